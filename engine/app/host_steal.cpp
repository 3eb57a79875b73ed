#include "app/host_steal.hpp"

#include <unistd.h>

#include <cstdio>
#include <string>

namespace echosim::app {

std::optional<double> parse_host_steal_s(std::string_view cpu_line, long ticks_per_s)
{
    // "cpu  user nice system idle iowait irq softirq steal guest guest_nice", in clock ticks
    if (ticks_per_s <= 0 || !cpu_line.starts_with("cpu ")) return std::nullopt;
    const std::string line(cpu_line.substr(4));
    unsigned long long v[8] = {};
    if (std::sscanf(line.c_str(), "%llu %llu %llu %llu %llu %llu %llu %llu", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &v[6], &v[7]) != 8)
        return std::nullopt;
    return double(v[7]) / double(ticks_per_s);
}

std::optional<double> host_steal_s()
{
    std::FILE* f = std::fopen("/proc/stat", "r");
    if (!f) return std::nullopt;
    char line[256] = {};
    const bool got = std::fgets(line, sizeof line, f) != nullptr;
    std::fclose(f);
    if (!got) return std::nullopt;
    return parse_host_steal_s(line, sysconf(_SC_CLK_TCK));
}

}  // namespace echosim::app

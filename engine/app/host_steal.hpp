// Host steal: the CPU time a hypervisor gave to other guests while this machine's CPUs had work to
// do. Inside a VM no priority prevents it, and it stalls a thread for as long as it lasts (up to
// tens of milliseconds on a busy shared host), so the timing of the haptic loop is read beside it
// (`echosim soak`, the haptics benchmark).
#pragma once

#include <optional>
#include <string_view>

namespace echosim::app {

// Since boot, all CPUs together [s]: the "steal" column of /proc/stat's first line, in clock ticks
// (10 ms on Debian's kernels), so a second's steal reads 0 until it adds up to a tick; 0 on bare
// metal; nullopt where it cannot be read.
std::optional<double> host_steal_s();
// The same from the text of that line and the clock ticks per second.
std::optional<double> parse_host_steal_s(std::string_view cpu_line, long ticks_per_s);

}  // namespace echosim::app

#include "fit/measurements.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include <glm/geometric.hpp>

#include "core/parse_number.hpp"
#include "io/text_fields.hpp"
#include "io/partial_file.hpp"

namespace echosim::fit {
namespace {

constexpr std::array<const char*, 10> kColumns = {"point", "probe", "x_mm", "y_mm", "z_mm", "nx", "ny", "nz",
                                                   "depth_mm", "force_N"};
enum Column { kPoint, kProbe, kX, kY, kZ, kNx, kNy, kNz, kDepth, kForce };

std::vector<std::string> split(const std::string& line)
{
    std::vector<std::string> out;
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, ',')) {
        const auto b = field.find_first_not_of(" \t\r"), e = field.find_last_not_of(" \t\r");
        out.push_back(b == std::string::npos ? std::string() : field.substr(b, e - b + 1));
    }
    if (!line.empty() && line.back() == ',') out.emplace_back();
    return out;
}

}  // namespace

const char* to_string(ProbeKind kind) { return kind == ProbeKind::indenter ? "indenter" : "probe"; }

int MeasurementSet::point_count() const
{
    int n = 0;
    for (const auto& s : samples) n = std::max(n, s.point + 1);
    return n;
}

MeasurementSet read_measurements(const std::filesystem::path& path)
{
    std::ifstream in = io::text::open_binary<MeasurementError>(path);  // refuses devices and FIFOs
    MeasurementSet set;
    std::array<int, kColumns.size()> where{};
    std::size_t width = 0;
    bool have_header = false;
    int line_no = 0;
    for (std::string line; std::getline(in, line);) {
        ++line_no;
        if (!line.empty() && line.back() == '\r') line.pop_back();
        if (line.find_first_not_of(" \t") == std::string::npos) continue;
        if (line[0] == '#') {
            set.comments.push_back(line.substr(1));
            continue;
        }
        const auto here = [&](const std::string& field) {
            return path.string() + ":" + std::to_string(line_no) + (field.empty() ? "" : ": field '" + field + "'");
        };
        const std::vector<std::string> fields = split(line);
        if (!have_header) {
            // the first non-comment line names the columns
            for (std::size_t c = 0; c < kColumns.size(); ++c) {
                const auto it = std::find(fields.begin(), fields.end(), kColumns[c]);
                if (it == fields.end())
                    throw MeasurementError(here("") + ": header lacks column '" + kColumns[c] +
                                           "' (expected point,probe,x_mm,y_mm,z_mm,nx,ny,nz,depth_mm,force_N)");
                where[c] = int(it - fields.begin());
            }
            width = fields.size();
            have_header = true;
            continue;
        }
        if (fields.size() != width)
            throw MeasurementError(here("") + ": " + std::to_string(fields.size()) + " fields, the header has " +
                                   std::to_string(width));
        auto number = [&](Column c) {
            const std::string& f = fields[std::size_t(where[c])];
            double v = 0;
            if (!parse_number(f, v) || !std::isfinite(v))
                throw MeasurementError(here(kColumns[c]) + ": not a finite number: '" + f + "'");
            return v;
        };
        Sample s;
        const double point = number(kPoint);
        if (point < 0 || point != std::floor(point) || point > 1e6)
            throw MeasurementError(here("point") + ": not a point index (a non-negative integer): '" +
                                   fields[std::size_t(where[kPoint])] + "'");
        s.point = int(point);
        const std::string& probe = fields[std::size_t(where[kProbe])];
        if (probe == "indenter")
            s.probe = ProbeKind::indenter;
        else if (probe == "probe")
            s.probe = ProbeKind::probe;
        else
            throw MeasurementError(here("probe") + ": unknown probe '" + probe + "' (expected indenter or probe)");
        s.position = {number(kX), number(kY), number(kZ)};
        s.normal = {number(kNx), number(kNy), number(kNz)};
        const double len = glm::length(s.normal);
        if (std::abs(len - 1.0) > 0.01)
            throw MeasurementError(here("nx,ny,nz") + ": the normal is not of unit length (|n| = " + std::to_string(len) + ")");
        s.normal /= len;
        s.depth_mm = number(kDepth);
        if (s.depth_mm < 0) throw MeasurementError(here("depth_mm") + ": negative depth " + std::to_string(s.depth_mm));
        s.force_N = number(kForce);
        if (s.force_N < 0) throw MeasurementError(here("force_N") + ": negative force " + std::to_string(s.force_N));
        set.samples.push_back(s);
    }
    if (!have_header) throw MeasurementError(path.string() + ": empty file (no header line)");
    if (set.samples.empty()) throw MeasurementError(path.string() + ": no samples after the header");
    return set;
}

void write_measurements(const std::filesystem::path& path, const MeasurementSet& set)
{
    io::PartialFile<std::runtime_error> out(path);
    for (const auto& c : set.comments) out.write("#" + c + "\n");
    out.write(std::string("point,probe,x_mm,y_mm,z_mm,nx,ny,nz,depth_mm,force_N\n"));
    char row[256];
    for (const Sample& s : set.samples) {
        const int n = std::snprintf(row, sizeof row, "%d,%s,%.3f,%.3f,%.3f,%.5f,%.5f,%.5f,%.2f,%.3f\n", s.point, to_string(s.probe),
                                    s.position.x, s.position.y, s.position.z, s.normal.x, s.normal.y, s.normal.z, s.depth_mm, s.force_N);
        out.write(row, std::size_t(n));
    }
    out.commit();
}

}  // namespace echosim::fit

#include "device/trajectory.hpp"

#include "core/pose.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "core/parse_number.hpp"
#include "core/printable_text.hpp"

namespace echosim::device {
namespace {

constexpr const char* kFields[] = {"t_s", "x_mm", "y_mm", "z_mm", "qw", "qx", "qy", "qz"};

std::string_view trim(std::string_view s)
{
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

}  // namespace

Trajectory Trajectory::parse(const std::string& text, const std::string& source)
{
    Trajectory traj;
    std::istringstream in(text);
    std::string line;
    int line_no = 0;
    bool header = false;
    while (std::getline(in, line)) {
        ++line_no;
        const std::string_view l = trim(line);
        if (l.empty() || l.front() == '#') continue;
        const std::string where = source + ":" + std::to_string(line_no);
        if (!header) {
            std::string squeezed;
            for (char c : l)
                if (c != ' ' && c != '\t') squeezed += c;
            if (squeezed != kHeader)
                throw std::invalid_argument(where + ": the header must be '" + kHeader + "', not '" + printable(l) + "'");
            header = true;
            continue;
        }
        double v[8];
        std::size_t field = 0, begin = 0;
        for (; field < 8; ++field) {
            const std::size_t comma = l.find(',', begin);
            if (field < 7 && comma == std::string_view::npos)
                throw std::invalid_argument(where + ": " + kFields[field + 1] + " is missing (a row has 8 fields)");
            const std::string_view token = trim(l.substr(begin, field < 7 ? comma - begin : std::string_view::npos));
            if (field == 7 && token.find(',') != std::string_view::npos)
                throw std::invalid_argument(where + ": more than 8 fields");
            if (!parse_number(token, v[field]) || !std::isfinite(v[field]))
                throw std::invalid_argument(where + ": " + kFields[field] + " '" + printable(token) + "' is not a finite number");
            if (field >= 1 && field <= 3 && std::abs(v[field]) > kMaxPoseCoordinateMm)
                throw std::invalid_argument(where + ": " + kFields[field] + " '" + printable(token) +
                                            "' is more than a kilometre from the origin (at most 1e6 mm)");
            begin = comma + 1;
        }
        TrajectoryRow r;
        r.t_s = v[0];
        r.position = {v[1], v[2], v[3]};
        r.orientation = Eigen::Quaterniond(v[4], v[5], v[6], v[7]);
        const double norm = r.orientation.norm();
        if (std::abs(norm - 1.0) > 0.01)
            throw std::invalid_argument(where + ": qw,qx,qy,qz is not a unit quaternion (norm " + std::to_string(norm) + ")");
        // a quaternion written to 17 digits reads back within an ulp or two of unit length: left as
        // written, so a trajectory plays exactly what its file says
        if (std::abs(norm - 1.0) > 1e-12) r.orientation.normalize();
        if (!traj.rows_.empty() && !(r.t_s > traj.rows_.back().t_s))
            throw std::invalid_argument(where + ": t_s " + std::to_string(r.t_s) + " does not increase (the row before is at " +
                                        std::to_string(traj.rows_.back().t_s) + " s)");
        traj.rows_.push_back(r);
    }
    if (!header) throw std::invalid_argument(source + ": empty: a trajectory starts with the header '" + std::string(kHeader) + "'");
    if (traj.rows_.empty()) throw std::invalid_argument(source + ": no rows after the header");
    return traj;
}

Trajectory Trajectory::load(const std::filesystem::path& file)
{
    std::error_code ec;
    if (!std::filesystem::is_regular_file(file, ec)) throw std::invalid_argument(file.string() + ": not a readable regular file");
    if (std::filesystem::file_size(file, ec) > (std::uintmax_t(256) << 20))
        throw std::invalid_argument(file.string() + ": larger than 256 MB, too large for a trajectory");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::invalid_argument(file.string() + ": cannot be opened");
    std::ostringstream text;
    text << in.rdbuf();
    return parse(text.str(), file.string());
}

TrajectoryRow Trajectory::at(double t_s) const
{
    if (!(t_s > rows_.front().t_s)) return rows_.front();
    if (t_s >= rows_.back().t_s) return rows_.back();
    const auto next = std::upper_bound(rows_.begin(), rows_.end(), t_s, [](double t, const TrajectoryRow& r) { return t < r.t_s; });
    const TrajectoryRow& a = *(next - 1);
    if (t_s == a.t_s) return a;
    const TrajectoryRow& b = *next;
    const double s = (t_s - a.t_s) / (b.t_s - a.t_s);
    TrajectoryRow r;
    r.t_s = t_s;
    r.position = a.position + s * (b.position - a.position);
    r.orientation = a.orientation.slerp(s, b.orientation);
    return r;
}

std::string format_trajectory(const std::vector<TrajectoryRow>& rows)
{
    std::string out = std::string(Trajectory::kHeader) + "\n";
    char line[320];
    for (const TrajectoryRow& r : rows) {
        std::snprintf(line, sizeof line, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", r.t_s, r.position.x(), r.position.y(),
                      r.position.z(), r.orientation.w(), r.orientation.x(), r.orientation.y(), r.orientation.z());
        out += line;
    }
    return out;
}

}  // namespace echosim::device

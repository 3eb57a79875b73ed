// A scripted probe trajectory (DESIGN.md §3): CSV rows `t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz`, the probe
// frame in world at each time, times strictly increasing. Between rows the pose is interpolated
// (position linearly, orientation by slerp); before the first row and after the last it holds. At a
// row's own time it is that row exactly, as read.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace echosim::device {

struct TrajectoryRow {
    double t_s = 0;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();                 // [mm]
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();    // unit
};

class Trajectory {
public:
    // Throws std::invalid_argument naming `source`, the line and the field when the header is not
    // the documented one, a field is missing or not a finite number, a quaternion is not of unit
    // length (within 1 %; beyond 1e-12 it is renormalised), the times do not increase, or there are no rows.
    static Trajectory parse(const std::string& text, const std::string& source);
    static Trajectory load(const std::filesystem::path& file);

    const std::vector<TrajectoryRow>& rows() const { return rows_; }
    double start_s() const { return rows_.front().t_s; }
    double end_s() const { return rows_.back().t_s; }

    // The pose at time t (no allocation).
    TrajectoryRow at(double t_s) const;

    static constexpr const char* kHeader = "t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz";

private:
    std::vector<TrajectoryRow> rows_;
};

// Writes rows in the same format (17 significant digits: read back, they are the same doubles).
std::string format_trajectory(const std::vector<TrajectoryRow>& rows);

}  // namespace echosim::device

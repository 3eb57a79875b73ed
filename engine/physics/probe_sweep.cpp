#include "physics/probe_sweep.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Core>

namespace echosim::physics {

contact::ProbeState swept_probe(const contact::ProbeState& now, const contact::ProbeState& commanded, double time_step,
                                double max_move_mm)
{
    if (!commanded.active) return commanded;
    contact::ProbeState from = now;
    if (!now.active) {
        from = commanded;
        from.position -= kProbeEntryMm * (commanded.orientation.normalized() * Eigen::Vector3d::UnitY());
    }
    // how far the face's farthest point would move: its centre's shift and the array's ends' arc
    const double reach = 0.5 * contact::ProbeGeometry{}.face_width;
    const double move = (commanded.position - from.position).norm() + from.orientation.angularDistance(commanded.orientation) * reach;
    if (move <= max_move_mm && now.active) return commanded;
    const double t = std::min(1.0, max_move_mm / move);
    contact::ProbeState next = commanded;
    next.position = from.position + t * (commanded.position - from.position);
    next.orientation = from.orientation.slerp(t, commanded.orientation);
    // the swept step's own velocity; the commanded one once it arrives
    if (t < 1.0) next.velocity = (next.position - from.position) / time_step;
    return next;
}

bool probe_clear_by(const contact::ProbeGeometry& g, const contact::ProbeState& probe, const Eigen::VectorXd& x, double clearance_mm)
{
    if (!probe.active) return true;
    const Eigen::Matrix3d to_local = probe.orientation.normalized().toRotationMatrix().transpose();
    const double hw = 0.5 * g.face_width + clearance_mm, ht = 0.5 * g.face_thickness + clearance_mm;
    for (Eigen::Index i = 0; i + 2 < x.size(); i += 3) {
        const Eigen::Vector3d p = to_local * (x.segment<3>(i) - probe.position);
        // local y: along the beam, the face at 0, the body behind it (negative)
        if (p.y() < clearance_mm && p.y() > -g.body_depth - clearance_mm && std::abs(p.x()) < hw && std::abs(p.z()) < ht) return false;
    }
    return true;
}

}  // namespace echosim::physics

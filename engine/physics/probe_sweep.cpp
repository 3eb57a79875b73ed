#include "physics/probe_sweep.hpp"

#include <algorithm>

namespace echosim::physics {

contact::ProbeState swept_probe(const contact::ProbeState& now, const contact::ProbeState& commanded, double time_step)
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
    if (move <= kMaxProbeMoveMm && now.active) return commanded;
    const double t = std::min(1.0, kMaxProbeMoveMm / move);
    contact::ProbeState next = commanded;
    next.position = from.position + t * (commanded.position - from.position);
    next.orientation = from.orientation.slerp(t, commanded.orientation);
    // the swept step's own velocity; the commanded one once it arrives
    if (t < 1.0) next.velocity = (next.position - from.position) / time_step;
    return next;
}

}  // namespace echosim::physics

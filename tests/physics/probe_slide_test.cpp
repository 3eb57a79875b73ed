// A pressed probe sliding over the thigh, the full dynamics: the skin stays out of the probe and
// the force changes smoothly, whichever edge leads. (With every edge of the face rounded, skin
// ahead of a long edge passed into the probe unpushed: at 6 mm, 13 nodes inside and steps of
// 0.29 N sliding along the thigh; at 12 mm, 47 and 0.71 N: bench/RESULTS.md "Settling".)
#include <gtest/gtest.h>

#include "physics/physics_fixture.hpp"
#include "physics/simulation.hpp"

namespace echosim::physics {
namespace {

struct Slide {
    int most_inside = 0;        // nodes more than 1.5 mm inside the probe's box, at the worst step
    double largest_step = 0;    // the largest change of the force from one step to the next [N]
    double force = 0;           // at the end [N]
};

// Pressed `press` mm in at (0.5, 0.4) of the patch, then moved a tenth of the patch along u (along
// the thigh, a long edge leading) or v (around it, an end leading) in 2 s.
Slide slide(double press, bool along_the_thigh)
{
    Simulation sim{compile_model(test::shipped_model(7), PhysicsOptions{})};
    TissueState& s = sim.state;
    const contact::ProbeGeometry g;
    const auto at = [&](double u, double v, double depth) {
        return contact::probe_at(pressed_along_beam(test::leg().probe_rest_pose(float(u), float(v)), depth));
    };
    for (int i = 1; i <= 100; ++i) {
        s.probe = at(0.5, 0.4, press * i / 100.0);
        sim.step();
    }
    for (int i = 0; i < 200; ++i) sim.step();
    Slide out;
    double last = s.last.probe_force_N;
    for (int i = 0; i <= 2000; ++i) {
        const double t = i / 2000.0;
        s.probe = along_the_thigh ? at(0.5 + 0.1 * t, 0.4, press) : at(0.5, 0.4 + 0.1 * t, press);
        sim.step();
        const Eigen::Matrix3d to_probe = s.probe.orientation.toRotationMatrix().transpose();
        int inside = 0;
        for (Eigen::Index k = 0; k < s.x.size() / 3; ++k) {
            const Eigen::Vector3d l = to_probe * (s.x.segment<3>(3 * k) - s.probe.position);
            inside += l.y() < -1.5 && l.y() > -g.body_depth && std::abs(l.x()) < g.face_width / 2 && std::abs(l.z()) < g.face_thickness / 2;
        }
        out.most_inside = std::max(out.most_inside, inside);
        out.largest_step = std::max(out.largest_step, std::abs(s.last.probe_force_N - last));
        last = s.last.probe_force_N;
    }
    out.force = s.last.probe_force_N;
    return out;
}

TEST(ProbeSlide, AtAnExaminingPressTheSkinStaysOutOfTheProbe)
{
    for (bool along : {true, false}) {
        const Slide r = slide(6.0, along);
        const char* how = along ? "along the thigh" : "around it";
        EXPECT_GT(r.force, 2.0) << how;  // still pressing
        EXPECT_LE(r.most_inside, 4) << how;                      // measured 2 and 2
        EXPECT_LT(r.largest_step, 0.01 * r.force) << how;       // measured 0.015 and 0.002 N of 3 N
    }
}

}  // namespace
}  // namespace echosim::physics

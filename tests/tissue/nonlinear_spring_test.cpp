#include "tissue/nonlinear_spring.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace echosim::tissue {
namespace {

TEST(NonlinearSpring, ForceAndAnalyticInverseAgree)
{
    const double a = 0.04, b = 0.9;  // 1/N, mm/N: bottoms out at 22.5 mm
    for (double f = 0.0; f < 200.0; f += 3.7) {
        const double c = spring_compression(f, a, b);
        EXPECT_LT(c, spring_limit(a, b));
        EXPECT_NEAR(spring_force(c, a, b), f, 1e-9 * (1 + f));
    }
}

TEST(NonlinearSpring, MatchesThePapersEquation)
{
    // the paper: f(x) = x / (a x + b), x the change of length (negative in compression);
    // ours is the magnitude at compression c = -x
    const double a = 0.03, b = 1.2;
    for (double c : {0.5, 4.0, 12.0, 30.0}) EXPECT_NEAR(spring_force(c, a, b), -(-c / (a * -c + b)), 1e-12);
    // rest stiffness 1/b, and the stiffness grows without bound towards b/a
    EXPECT_NEAR(spring_stiffness(0.0, a, b), 1.0 / b, 1e-12);
    EXPECT_GT(spring_stiffness(39.0, a, b), 100.0 * spring_stiffness(0.0, a, b));
}

TEST(NonlinearSpring, StiffnessIsTheDerivative)
{
    const double a = 0.05, b = 0.7, h = 1e-6;
    for (double c : {0.1, 5.0, 11.0}) {
        const double numeric = (spring_force(c + h, a, b) - spring_force(c - h, a, b)) / (2 * h);
        EXPECT_NEAR(spring_stiffness(c, a, b), numeric, 1e-5 * numeric);
    }
}

}  // namespace
}  // namespace echosim::tissue

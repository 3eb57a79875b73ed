#include "echo/phantom.hpp"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

namespace echosim::echo {
namespace {

const scene::LegModel& leg()
{
    static const scene::LegModel model;
    return model;
}

TEST(Phantom, LinesUpWithTheLegsSkin)
{
    const Phantom p(leg(), Case::healthy);
    for (float u : {0.1f, 0.5f, 0.9f})
        for (float v : {0.1f, 0.5f, 0.9f}) {
            const glm::dvec3 skin(leg().patch_point(u, v)), n(leg().patch_normal(u, v));
            EXPECT_NEAR(p.depth_at(skin), 0.0, 0.05);
            EXPECT_EQ(p.tissue_at(skin + 0.5 * n), Tissue::outside);
            EXPECT_EQ(p.tissue_at(skin - 0.5 * n), Tissue::skin);
        }
}

TEST(Phantom, FemoralVesselsHaveTheirSizeAndDepth)
{
    const Phantom p(leg(), Case::healthy);
    const double z = leg().patch_point(0.5f, 0.5f).z;
    const VesselSection a = p.artery(z), v = p.vein(z);
    EXPECT_NEAR(2 * a.lumen_radius, 7.5, 0.5);
    EXPECT_GE(2 * v.lumen_radius, 10.0);
    EXPECT_LE(2 * v.lumen_radius, 12.0);
    EXPECT_GE(p.depth_at(v.centre), 20.0);
    EXPECT_LE(p.depth_at(v.centre), 40.0);
    // the vein lies beside the artery and partly below it
    EXPECT_GT(p.depth_at(v.centre), p.depth_at(a.centre));
    EXPECT_GT(glm::length(v.centre - a.centre), a.lumen_radius + v.lumen_radius);
    EXPECT_EQ(p.tissue_at(v.centre), Tissue::vein_lumen);
    EXPECT_EQ(p.tissue_at(a.centre), Tissue::artery_lumen);
    EXPECT_EQ(p.tissue_at(p.saphenous(z).centre), Tissue::saphenous_lumen);
}

TEST(Phantom, CasesDifferInTheVein)
{
    const double z = -100.0;
    const Phantom healthy(leg(), Case::healthy), acute(leg(), Case::dvt_acute), chronic(leg(), Case::dvt_chronic);
    EXPECT_EQ(healthy.tissue_at(healthy.vein(z).centre), Tissue::vein_lumen);
    // acute: distended and full of clot
    EXPECT_GT(acute.vein(z).lumen_radius, healthy.vein(z).lumen_radius + 1.0);
    EXPECT_EQ(acute.tissue_at(acute.vein(z).centre), Tissue::thrombus);
    // chronic: a smaller lumen, a thicker wall, an organised clot with a residual channel
    const VesselSection c = chronic.vein(z);
    EXPECT_LT(c.lumen_radius, healthy.vein(z).lumen_radius - 1.0);
    EXPECT_GT(c.wall, healthy.vein(z).wall);
    EXPECT_EQ(chronic.tissue_at(c.thrombus_centre), Tissue::organised_thrombus);
    const glm::dvec3 channel = c.centre + (c.centre - c.thrombus_centre) / glm::length(c.centre - c.thrombus_centre) * (c.lumen_radius - 0.3);
    EXPECT_EQ(chronic.tissue_at(channel), Tissue::vein_lumen);
    // the clot starts below the groin: the common femoral vein is open in every case
    EXPECT_EQ(acute.tissue_at(acute.vein(-20.0).centre), Tissue::vein_lumen);
}

TEST(Phantom, CaseNamesParse)
{
    EXPECT_EQ(parse_case("dvt-acute"), Case::dvt_acute);
    EXPECT_THROW(parse_case("dvt"), std::invalid_argument);
}

}  // namespace
}  // namespace echosim::echo

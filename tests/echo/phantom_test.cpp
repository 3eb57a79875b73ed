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
    // under the exam patch's centre, where the session's probe rests: the femoral vein below the
    // bifurcation, its artery, the GSV medially in the fat
    const Phantom p(leg(), Case::healthy);
    const double s = p.deep_s_at(leg().patch_point(0.5f, 0.5f).z);
    ASSERT_GT(s, kBifurcation_cm + 1.0);
    const VesselSection v = p.vein(VeinSegment::fv, s);
    const VesselSection a = *p.artery(VeinSegment::fv, s);
    EXPECT_GE(2 * v.lumen_radius, kVeinCalibre_mm[std::size_t(VeinSegment::fv)].lo);
    EXPECT_LE(2 * v.lumen_radius, kVeinCalibre_mm[std::size_t(VeinSegment::fv)].hi);
    EXPECT_GE(2 * a.lumen_radius, kArteryCalibre_mm[std::size_t(VeinSegment::fv)].lo);
    EXPECT_LE(2 * a.lumen_radius, kArteryCalibre_mm[std::size_t(VeinSegment::fv)].hi);
    EXPECT_GE(p.depth_at(v.centre), 20.0);
    EXPECT_LE(p.depth_at(v.centre), 40.0);
    // the vein lies beside the artery and partly below it
    EXPECT_GT(p.depth_at(v.centre), p.depth_at(a.centre));
    EXPECT_GT(glm::length(v.centre - a.centre), a.lumen_radius + v.lumen_radius);
    EXPECT_EQ(p.tissue_at(v.centre), Tissue::vein_lumen);
    EXPECT_EQ(p.tissue_at(a.centre), Tissue::artery_lumen);
    EXPECT_EQ(p.tissue_at(p.vein(VeinSegment::gsv, p.deep_s_at(v.centre.z) - kSfj_cm).centre), Tissue::saphenous_lumen);
}

TEST(Phantom, CasesDifferInTheVein)
{
    const Phantom healthy(leg(), Case::healthy), acute(leg(), Case::dvt_acute), chronic(leg(), Case::dvt_chronic);
    const double s = healthy.deep_s_at(-100.0);
    EXPECT_EQ(healthy.tissue_at(healthy.vein(VeinSegment::fv, s).centre), Tissue::vein_lumen);
    // acute: distended and full of clot
    EXPECT_GT(acute.vein(VeinSegment::fv, s).lumen_radius, healthy.vein(VeinSegment::fv, s).lumen_radius + 0.8);
    EXPECT_EQ(acute.tissue_at(acute.vein(VeinSegment::fv, s).centre), Tissue::thrombus);
    // chronic: a smaller lumen, a thicker wall of its own code, an organised clot with a residual channel
    const VesselSection c = chronic.vein(VeinSegment::fv, s);
    EXPECT_LT(c.lumen_radius, healthy.vein(VeinSegment::fv, s).lumen_radius - 0.8);
    EXPECT_GT(c.wall, healthy.vein(VeinSegment::fv, s).wall);
    EXPECT_EQ(chronic.tissue_at(c.thrombus_centre), Tissue::organised_thrombus);
    const glm::dvec3 channel = c.centre + (c.centre - c.thrombus_centre) / glm::length(c.centre - c.thrombus_centre) * (c.lumen_radius - 0.3);
    EXPECT_EQ(chronic.tissue_at(channel), Tissue::vein_lumen);
    const glm::dvec3 wall = c.centre + (c.centre - c.thrombus_centre) / glm::length(c.centre - c.thrombus_centre) * (c.lumen_radius + 0.4);
    EXPECT_EQ(chronic.tissue_at(wall), Tissue::scarred_vein_wall);
    // the acute clot starts above the SFJ: the common femoral vein at the groin is open in every case
    EXPECT_EQ(acute.tissue_at(acute.vein(VeinSegment::cfv, 1.0).centre), Tissue::vein_lumen);
    EXPECT_EQ(acute.tissue_at(acute.vein(VeinSegment::cfv, kSfj_cm).centre), Tissue::thrombus);
}

TEST(Phantom, TissueCodesKeepTheirValues)
{
    // volumes and label maps on disk carry them: new codes come at the end
    EXPECT_EQ(int(Tissue::organised_thrombus), 13);
    EXPECT_EQ(int(Tissue::scarred_vein_wall), 14);
    EXPECT_EQ(int(Tissue::lymph_node), 15);
    EXPECT_EQ(kTissueCount, 16);
    EXPECT_STREQ(tissue_name(Tissue::lymph_node), "lymph node");
}

TEST(Phantom, CaseNamesParse)
{
    EXPECT_EQ(parse_case("dvt-acute"), Case::dvt_acute);
    EXPECT_THROW(parse_case("dvt"), std::invalid_argument);
}

}  // namespace
}  // namespace echosim::echo

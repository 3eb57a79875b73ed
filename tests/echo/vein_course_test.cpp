// The vein course the phantom builds (echo/phantom.hpp), measured from its labels as a sonographer
// would measure the anatomy from an image: each lumen's area and depth under the skin in the
// cross-section at a station, the levels where the vein divides, where a thrombus or a lymph node
// is, and where the transverse probe's beam meets the vein; all against echo/vein_course.hpp's
// constants (one source for those numbers).
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "echo/case_volume.hpp"
#include "echo/phantom.hpp"
#include "echo/vein_course.hpp"

namespace echosim::echo {
namespace {

const scene::LegModel& leg()
{
    static const scene::LegModel model;
    return model;
}

const Phantom& healthy()
{
    static const Phantom p(leg(), Anatomy{});
    return p;
}

bool is_lumen(Tissue t, bool vein)
{
    if (!vein) return t == Tissue::artery_lumen;
    return t == Tissue::vein_lumen || t == Tissue::saphenous_lumen || t == Tissue::thrombus || t == Tissue::organised_thrombus;
}

// The labels of the plane through `centre` square to `normal` (the cross-section across a vessel),
// `half` mm either side, at `pixel` mm: a grid to measure from.
struct Grid {
    glm::dvec3 origin, e1, e2;
    double px;
    int n;
    std::vector<Tissue> t;

    Grid(const Phantom& p, const glm::dvec3& centre, const glm::dvec3& normal, double half, double pixel)
        : e1(glm::normalize(glm::cross(normal, std::abs(normal.z) < 0.9 ? glm::dvec3(0, 0, 1) : glm::dvec3(1, 0, 0)))),
          e2(glm::cross(glm::normalize(normal), e1)), px(pixel), n(int(2 * half / pixel) + 1), t(std::size_t(n) * std::size_t(n))
    {
        origin = centre - half * e1 - half * e2;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) t[std::size_t(j * n + i)] = p.tissue_at(at(i, j));
    }
    glm::dvec3 at(int i, int j) const { return origin + (i * px) * e1 + (j * px) * e2; }
    Tissue operator()(int i, int j) const { return t[std::size_t(j * n + i)]; }

    // the connected region of pixels `in` holds, from the pixel nearest `seed`: its pixel count
    template <class In>
    int region(const glm::dvec3& seed, In&& in, std::vector<char>* mask = nullptr) const
    {
        std::vector<char> seen(t.size(), 0);
        const int si = int(std::lround(glm::dot(seed - origin, e1) / px)), sj = int(std::lround(glm::dot(seed - origin, e2) / px));
        if (si < 0 || sj < 0 || si >= n || sj >= n || !in((*this)(si, sj))) return 0;
        std::vector<int> stack{sj * n + si};
        seen[std::size_t(stack.back())] = 1;
        int count = 0;
        while (!stack.empty()) {
            const int k = stack.back();
            stack.pop_back();
            ++count;
            const int i = k % n, j = k / n;
            for (const auto& [di, dj] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
                const int a = i + di, b = j + dj;
                if (a < 0 || b < 0 || a >= n || b >= n) continue;
                const int kk = b * n + a;
                if (seen[std::size_t(kk)] || !in((*this)(a, b))) continue;
                seen[std::size_t(kk)] = 1;
                stack.push_back(kk);
            }
        }
        if (mask) *mask = std::move(seen);
        return count;
    }

    // how many separate regions of pixels `in` holds
    template <class In>
    int regions(In&& in) const
    {
        std::vector<char> seen(t.size(), 0);
        int count = 0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i < n; ++i) {
                if (seen[std::size_t(j * n + i)] || !in((*this)(i, j))) continue;
                std::vector<char> mask;
                region(at(i, j), in, &mask);
                for (std::size_t k = 0; k < mask.size(); ++k) seen[k] |= mask[k];
                ++count;
            }
        return count;
    }

    template <class In>
    int count(In&& in) const
    {
        int c = 0;
        for (Tissue x : t) c += in(x);
        return c;
    }
};

// The lumen's diameter as its area's equivalent circle [mm], measured in the labels across the
// vessel at `centre`, its direction `along`.
double lumen_diameter(const Phantom& p, const glm::dvec3& centre, const glm::dvec3& along, bool vein)
{
    const Grid g(p, centre, along, 12.0, 0.08);
    const int pixels = g.region(centre, [&](Tissue t) { return is_lumen(t, vein); });
    return 2.0 * std::sqrt(pixels * g.px * g.px / std::numbers::pi);
}

// Along the probe's beam from its face: how deep [mm] the first sample of `tissue` lies (-1: none
// within 90 mm), 0.05 mm steps.
template <class In>
double depth_along_beam(const Phantom& p, const Pose& probe, In&& in)
{
    const glm::dvec3 face(probe.position), beam(probe.axis_y());
    for (double d = 0; d < 90.0; d += 0.05)
        if (in(p.tissue_at(face + d * beam))) return d;
    return -1;
}

struct Station {
    VeinSegment segment;
    double s_cm;
};
const Station kStations[] = {{VeinSegment::cfv, 0.5},  {VeinSegment::cfv, 2.0},        {VeinSegment::cfv, 1.2},
                             {VeinSegment::fv, 7.0},   {VeinSegment::fv, 15.0},        {VeinSegment::fv, 25.0},
                             {VeinSegment::fv, 33.0},  {VeinSegment::popliteal, 39.0}, {VeinSegment::popliteal, 42.0},
                             {VeinSegment::popliteal, 46.0}, {VeinSegment::popliteal, 49.0}, {VeinSegment::gsv, 6.0},
                             {VeinSegment::gsv, 20.0}, {VeinSegment::gsv, 35.0},       {VeinSegment::dfv, 3.0},
                             {VeinSegment::dfv, 5.5}};

TEST(VeinCourse, LandmarksLieWhereTheExamFindsThem)
{
    const Phantom& p = healthy();
    const auto z = [&](double s) { return p.level_z(VeinSegment::cfv, s); };
    EXPECT_NEAR(z(kInguinalLigament_cm), kLigamentZ_mm, 0.5);
    // the SFJ 2 to 4 cm and the bifurcation 4 to 6 cm below the ligament
    EXPECT_LE(z(kSfj_cm), kLigamentZ_mm - 20.0);
    EXPECT_GE(z(kSfj_cm), kLigamentZ_mm - 40.0);
    EXPECT_LE(z(kBifurcation_cm), kLigamentZ_mm - 40.0);
    EXPECT_GE(z(kBifurcation_cm), kLigamentZ_mm - 60.0);
    // the adductor hiatus at the distal thigh, the fossa above the joint line, the trifurcation
    // about 5 cm below it
    EXPECT_LE(z(kAdductorHiatus_cm), -330.0);
    EXPECT_GE(z(kAdductorHiatus_cm), -360.0);
    EXPECT_LT(z(kPoplitealFossa_cm), z(kAdductorHiatus_cm) - 30.0);
    EXPECT_GT(z(kPoplitealFossa_cm), kKneeJointZ_mm);
    EXPECT_NEAR(z(kTrifurcation_cm), kKneeJointZ_mm - 50.0, 10.0);
    for (int l = 0; l < kLandmarkCount; ++l) {
        Landmark parsed;
        ASSERT_TRUE(parse_landmark(landmark_name(Landmark(l)), parsed));
        EXPECT_EQ(parsed, Landmark(l));
        const LandmarkSite site = landmark_site(Landmark(l));
        EXPECT_TRUE(p.modelled(site.segment, site.s_cm)) << landmark_name(Landmark(l));
    }
    Landmark none;
    EXPECT_FALSE(parse_landmark("knee", none));
}

TEST(VeinCourse, SegmentNamesParse)
{
    for (int s = 0; s < kVeinSegmentCount; ++s) {
        VeinSegment parsed;
        ASSERT_TRUE(parse_segment(segment_name(VeinSegment(s)), parsed));
        EXPECT_EQ(parsed, VeinSegment(s));
    }
    VeinSegment seg;
    EXPECT_FALSE(parse_segment("sfv", seg));
    ThrombusKind kind;
    ASSERT_TRUE(parse_thrombus_kind("chronic", kind));
    EXPECT_EQ(kind, ThrombusKind::chronic);
    EXPECT_FALSE(parse_thrombus_kind("subacute", kind));
    EXPECT_EQ(deep_segment_at(1.0), VeinSegment::cfv);
    EXPECT_EQ(deep_segment_at(20.0), VeinSegment::fv);
    EXPECT_EQ(deep_segment_at(45.0), VeinSegment::popliteal);
}

TEST(VeinCourse, CalibresMeasuredFromTheLabelsAreTheStatedOnes)
{
    const Phantom& p = healthy();
    for (const Station& st : kStations) {
        const VesselSection v = p.vein(st.segment, st.s_cm);
        const double stated = vein_diameter_mm(st.segment, st.s_cm);
        const glm::dvec3 along = p.vein_direction(st.segment, st.s_cm);
        const double measured = lumen_diameter(p, v.centre, along, true);
        std::printf("%-9s %4.1f cm: vein %.2f mm (stated %.2f)", segment_name(st.segment), st.s_cm, measured, stated);
        EXPECT_NEAR(measured, stated, 0.3) << segment_name(st.segment) << " at " << st.s_cm;
        const Range range = kVeinCalibre_mm[std::size_t(st.segment)];
        EXPECT_GE(measured, range.lo) << segment_name(st.segment) << " at " << st.s_cm;
        EXPECT_LE(measured, range.hi) << segment_name(st.segment) << " at " << st.s_cm;
        if (const auto a = p.artery(st.segment, st.s_cm)) {
            // across the artery's own direction (it turns about the vein at the hiatus)
            const auto a0 = p.artery(st.segment, st.s_cm - 0.05), a1 = p.artery(st.segment, st.s_cm + 0.05);
            const double artery = lumen_diameter(p, a->centre, glm::normalize(a1->centre - a0->centre), false);
            std::printf(", artery %.2f mm (stated %.2f)", artery, artery_diameter_mm(st.segment, st.s_cm));
            EXPECT_NEAR(artery, artery_diameter_mm(st.segment, st.s_cm), 0.3) << segment_name(st.segment) << " at " << st.s_cm;
            const Range range_a = kArteryCalibre_mm[std::size_t(st.segment)];
            EXPECT_GE(artery, range_a.lo);
            EXPECT_LE(artery, range_a.hi);
        } else {
            EXPECT_EQ(st.segment, VeinSegment::gsv);
        }
        std::printf("\n");
    }
    // the calibres narrow down the course
    EXPECT_GT(vein_diameter_mm(VeinSegment::cfv, 1.0), vein_diameter_mm(VeinSegment::fv, 10.0));
    EXPECT_GT(vein_diameter_mm(VeinSegment::fv, 10.0), vein_diameter_mm(VeinSegment::popliteal, 48.0));
}

TEST(VeinCourse, DepthsMeasuredAlongTheBeamAreTheStatedOnes)
{
    for (const double fat : {6.0, 12.0, 30.0, 45.0}) {
        Anatomy a;
        a.fat_mm = fat;
        const Phantom p(leg(), a);
        for (const Station& st : kStations) {
            const Pose probe = p.transverse_probe_pose(st.segment, st.s_cm);
            const VesselSection v = p.vein(st.segment, st.s_cm);
            // the vein's centre: halfway between the near and the far wall of the lumen the beam
            // crosses where the course says the vein is
            const glm::dvec3 face(probe.position), beam(probe.axis_y());
            const double stated = glm::length(v.centre - face);
            ASSERT_TRUE(is_lumen(p.tissue_at(face + stated * beam), true)) << segment_name(st.segment) << " at " << st.s_cm << " with fat " << fat;
            double near = stated, far = stated;
            while (is_lumen(p.tissue_at(face + (near - 0.05) * beam), true)) near -= 0.05;
            while (is_lumen(p.tissue_at(face + (far + 0.05) * beam), true)) far += 0.05;
            const double centre = (near + far) / 2;
            // the beam goes through the vein's centre, and the labels' lumen is its stated one
            EXPECT_NEAR(centre, glm::length(v.centre - face), 0.15) << segment_name(st.segment) << " at " << st.s_cm;
            EXPECT_NEAR(far - near, 2 * v.lumen_radius, 0.3) << segment_name(st.segment) << " at " << st.s_cm;
            if (fat == 12.0) {
                const Range range = kVeinDepth_mm[std::size_t(st.segment)];
                EXPECT_GE(centre, range.lo) << segment_name(st.segment) << " at " << st.s_cm;
                EXPECT_LE(centre, range.hi) << segment_name(st.segment) << " at " << st.s_cm;
            }
            // no bone within a millimetre of the vein's wall, whatever the fat
            int bone = 0;
            for (int k = 0; k < 360; ++k)
                for (const double r : {v.lumen_radius + v.wall + 0.5, v.lumen_radius + v.wall + 1.0}) {
                    const Tissue t = p.tissue_at(v.centre + r * glm::dvec3(std::cos(k * std::numbers::pi / 180), std::sin(k * std::numbers::pi / 180), 0));
                    bone += t == Tissue::bone_cortex || t == Tissue::bone_marrow;
                }
            EXPECT_EQ(bone, 0) << segment_name(st.segment) << " at " << st.s_cm << " with fat " << fat;
        }
        // the fat over the CFV at the groin is the anatomy's
        const Pose groin = p.transverse_probe_pose(VeinSegment::cfv, kInguinalLigament_cm);
        const double fat_top = depth_along_beam(p, groin, [](Tissue t) { return t == Tissue::fat; });
        const double fat_bottom = depth_along_beam(p, groin, [](Tissue t) { return t == Tissue::fascia; });
        std::printf("fat %4.1f mm: measured over the CFV %.2f mm, CFV centre %.1f mm deep\n", fat, fat_bottom - fat_top,
                    glm::length(p.vein(VeinSegment::cfv, 0.0).centre - glm::dvec3(groin.position)));
        // (the fat is the anatomy's along the limb's radius at the CFV's angle; the beam, square to
        // the vein, meets the skin a few degrees from there, where the fat is a little thinner)
        EXPECT_NEAR(fat_bottom - fat_top, fat, 0.3 + 0.04 * fat);
    }
}

TEST(VeinCourse, TheVeinDividesAtTheBifurcationAndTakesTheGsvAtTheSfj)
{
    const Phantom& p = healthy();
    // the deep veins' lumens (the GSV's is a code of its own) in the cross-section about the vein
    const auto deep_lumens = [&](double s) {
        const Grid g(p, p.vein(VeinSegment::cfv, s).centre, p.vein_direction(VeinSegment::cfv, s), 30.0, 0.25);
        return g.regions([](Tissue t) { return t == Tissue::vein_lumen; });
    };
    const auto arteries = [&](double s) {
        const Grid g(p, p.vein(VeinSegment::cfv, s).centre, p.vein_direction(VeinSegment::cfv, s), 30.0, 0.25);
        return g.regions([](Tissue t) { return t == Tissue::artery_lumen; });
    };
    // the first level, in mm steps down the vein, where each divides
    double vein_divides = -1, artery_divides = -1;
    for (double s = kBifurcation_cm - 2.0; s < kBifurcation_cm + 2.0 && (vein_divides < 0 || artery_divides < 0); s += 0.1) {
        if (vein_divides < 0 && deep_lumens(s) >= 2) vein_divides = s;
        if (artery_divides < 0 && arteries(s) >= 2) artery_divides = s;
    }
    std::printf("the vein divides at %.1f cm, the artery at %.1f cm\n", vein_divides, artery_divides);
    EXPECT_GE(vein_divides, kBifurcation_cm);
    EXPECT_LE(vein_divides, kBifurcation_cm + 1.0);
    EXPECT_GE(artery_divides, kArteryBifurcation_cm);
    EXPECT_LE(artery_divides, kArteryBifurcation_cm + 1.0);
    EXPECT_EQ(deep_lumens(kBifurcation_cm - 0.3), 1);
    EXPECT_EQ(deep_lumens(kBifurcation_cm + 1.5), 2);

    // the SFJ: no GSV above it; at it, the GSV's lumen opens into the CFV's (one region); 3 cm
    // below it, in the fat, apart from the CFV
    const auto gsv_at = [&](double s, bool joined) {
        const VesselSection v = p.vein(VeinSegment::cfv, s);
        const Grid g(p, v.centre, p.vein_direction(VeinSegment::cfv, s), 30.0, 0.25);
        if (joined) {
            std::vector<char> mask;
            g.region(v.centre, [](Tissue t) { return t == Tissue::vein_lumen || t == Tissue::saphenous_lumen; }, &mask);
            int saphenous = 0;
            for (std::size_t k = 0; k < mask.size(); ++k) saphenous += mask[k] && g.t[k] == Tissue::saphenous_lumen;
            return saphenous;
        }
        return g.count([](Tissue t) { return t == Tissue::saphenous_lumen; });
    };
    EXPECT_EQ(gsv_at(kSfj_cm - 0.3, false), 0);
    EXPECT_GT(gsv_at(kSfj_cm + 0.05, true), 50);
    EXPECT_EQ(gsv_at(kSfj_cm + 3.0, true), 0);
    EXPECT_GT(gsv_at(kSfj_cm + 3.0, false), 50);
    // and the GSV runs in the fat (between the skin and the fascia) below its first 2.5 cm
    for (const double s : {5.0, 15.0, 30.0}) {
        const VesselSection g = p.vein(VeinSegment::gsv, s);
        const Pose probe = p.transverse_probe_pose(VeinSegment::gsv, s);
        const double fascia = depth_along_beam(p, probe, [](Tissue t) { return t == Tissue::fascia || t == Tissue::muscle; });
        EXPECT_LT(glm::length(g.centre - glm::dvec3(probe.position)) + g.lumen_radius, fascia) << "GSV at " << s;
    }
}

TEST(VeinCourse, TheArteryLiesLateralAtTheGroinInFrontInTheCanalAndDeepInTheFossa)
{
    const Phantom& p = healthy();
    // in the probe's frame: x across (towards the patient's left on the thigh), y the depth
    const auto in_probe = [&](VeinSegment seg, double s) {
        const Pose probe = p.transverse_probe_pose(seg, s);
        const glm::dvec3 d = p.artery(seg, s)->centre - p.vein(seg, s).centre;
        return glm::dvec2(glm::dot(d, glm::dvec3(probe.axis_x())), glm::dot(d, glm::dvec3(probe.axis_y())));
    };
    const glm::dvec2 groin = in_probe(VeinSegment::cfv, 1.0), canal = in_probe(VeinSegment::fv, 32.0), fossa = in_probe(VeinSegment::popliteal, 44.0);
    // lateral: the patient's right, the image's left (-x); in front: shallower (-y)
    EXPECT_LT(groin.x, -8.0);
    EXPECT_LT(std::abs(canal.x), 4.0);
    EXPECT_LT(canal.y, -7.0);
    EXPECT_GT(fossa.y, 7.0);  // the vein superficial to the artery, seen from the back
}

Anatomy with(std::vector<Thrombus> thrombi)
{
    Anatomy a;
    a.thrombi = std::move(thrombi);
    return a;
}

// The thrombus's pixels and the lumen's in the vein's cross-section at s.
struct Clot {
    int clot = 0, lumen = 0, scarred = 0;
};
Clot clot_at(const Phantom& p, VeinSegment seg, double s)
{
    // in the vein's level (the plane of constant z through its centre: every point of it at the
    // same s, where an oblique vessel's section is an ellipse as long as 1 / cos of its slope)
    const VesselSection v = p.vein(seg, s);
    const Grid g(p, v.centre, glm::dvec3(0, 0, 1), 1.3 * v.lumen_radius + 3.0, 0.1);
    Clot c;
    c.clot = g.count([](Tissue t) { return t == Tissue::thrombus || t == Tissue::organised_thrombus; });
    c.lumen = g.count([](Tissue t) { return t == Tissue::vein_lumen || t == Tissue::saphenous_lumen; });
    c.scarred = g.count([](Tissue t) { return t == Tissue::scarred_vein_wall; });
    return c;
}

TEST(VeinCourse, AThrombusLiesExactlyOverItsStartAndExtent)
{
    for (const ThrombusKind kind : {ThrombusKind::acute, ThrombusKind::chronic}) {
        const Thrombus th{VeinSegment::fv, kind, 15.0, 6.0, 1.0};
        const Phantom p(leg(), with({th}));
        // every 2.5 mm, and the ends themselves (where the clot begins as a thread) 0.1 mm either side
        std::vector<double> levels{th.start_cm - 0.01, th.start_cm + 0.01, th.start_cm + th.extent_cm - 0.01, th.start_cm + th.extent_cm + 0.01};
        for (double s = 12.0; s <= 24.0; s += 0.25) levels.push_back(s);
        for (const double at : levels) {
            const bool inside = at >= th.start_cm && at <= th.start_cm + th.extent_cm;
            const Clot c = clot_at(p, VeinSegment::fv, at);
            EXPECT_EQ(c.clot > 0, inside) << thrombus_kind_name(kind) << " at " << at;
            EXPECT_EQ(p.thrombosed(VeinSegment::fv, at), inside) << at;
            if (kind == ThrombusKind::chronic) {
                EXPECT_EQ(c.scarred > 0, inside) << at;
            }
        }
        // its tip: a thread in the lumen, growing to fill it over 1.2 cm
        const Clot tip = clot_at(p, VeinSegment::fv, th.start_cm + 0.05), full = clot_at(p, VeinSegment::fv, th.start_cm + 2.0);
        EXPECT_LT(tip.clot, 0.1 * (tip.clot + tip.lumen));
        EXPECT_EQ(full.lumen, 0);
        // nowhere else: not in the other segments or the branches
        for (const Station& st : kStations)
            if (st.s_cm < th.start_cm || st.s_cm > th.start_cm + th.extent_cm || !on_deep_vein(st.segment)) {
                EXPECT_EQ(clot_at(p, st.segment, st.s_cm).clot, 0) << segment_name(st.segment) << " at " << st.s_cm;
                EXPECT_FALSE(p.thrombosed(st.segment, st.s_cm));
            }
    }
}

TEST(VeinCourse, AcuteThrombusDistendsChronicShrinksPartialLeavesAChannel)
{
    const double s = 20.0;
    const double healthy_r = healthy().vein(VeinSegment::fv, s).lumen_radius;
    const Phantom acute(leg(), with({{VeinSegment::fv, ThrombusKind::acute, 10.0, 20.0, 1.0}}));
    const Phantom chronic(leg(), with({{VeinSegment::fv, ThrombusKind::chronic, 10.0, 20.0, 0.6}}));
    const Phantom partial(leg(), with({{VeinSegment::fv, ThrombusKind::acute, 10.0, 20.0, 0.5}}));
    EXPECT_NEAR(acute.vein(VeinSegment::fv, s).lumen_radius, 1.2 * healthy_r, 0.05);
    EXPECT_NEAR(chronic.vein(VeinSegment::fv, s).lumen_radius, 0.8 * healthy_r, 0.05);
    EXPECT_EQ(acute.tissue_at(acute.vein(VeinSegment::fv, s).centre), Tissue::thrombus);
    const Clot a = clot_at(acute, VeinSegment::fv, s), c = clot_at(chronic, VeinSegment::fv, s), h = clot_at(partial, VeinSegment::fv, s);
    EXPECT_EQ(a.lumen, 0);
    EXPECT_GT(c.scarred, 0);
    EXPECT_NEAR(double(c.clot) / (c.clot + c.lumen), 0.6, 0.05);
    EXPECT_NEAR(double(h.clot) / (h.clot + h.lumen), 0.5, 0.05);
    // the partly occlusive clot lies against the deep wall: the channel is on the probe's side
    const Pose probe = partial.transverse_probe_pose(VeinSegment::fv, s);
    const double first = depth_along_beam(partial, probe, [](Tissue t) { return t == Tissue::vein_lumen || t == Tissue::thrombus; });
    EXPECT_EQ(partial.tissue_at(glm::dvec3(probe.position) + (first + 0.2) * glm::dvec3(probe.axis_y())), Tissue::vein_lumen);
    // a thrombus written as two segments' (CFV then FV) is one clot: no second tip at the bifurcation
    const Phantom two(leg(), anatomy_of(Case::dvt_acute));
    for (const double at : {kBifurcation_cm - 0.1, kBifurcation_cm + 0.1}) {
        const VesselSection v = two.vein(VeinSegment::fv, at);
        EXPECT_NEAR(v.thrombus_radius, v.lumen_radius, 1e-9) << at;
    }
    EXPECT_TRUE(two.thrombosed(VeinSegment::cfv, 3.0));
    EXPECT_FALSE(two.thrombosed(VeinSegment::cfv, 1.0));
}

TEST(VeinCourse, BranchThrombiStayInTheirBranch)
{
    const Phantom p(leg(), with({{VeinSegment::gsv, ThrombusKind::acute, 4.0, 10.0, 1.0}}));
    EXPECT_GT(clot_at(p, VeinSegment::gsv, 8.0).clot, 0);
    EXPECT_EQ(clot_at(p, VeinSegment::gsv, 2.0).clot, 0);
    EXPECT_EQ(clot_at(p, VeinSegment::fv, 8.0).clot, 0);
    EXPECT_TRUE(p.thrombosed(VeinSegment::gsv, 8.0));
    EXPECT_FALSE(p.thrombosed(VeinSegment::fv, 8.0));
}

TEST(VeinCourse, ALymphNodeIsThereOnlyWhenTheAnatomyHasOne)
{
    const auto node_pixels = [](const Phantom& p) {
        int n = 0;
        for (double s = 0.0; s <= 5.0; s += 0.1) {
            const Grid g(p, p.vein(VeinSegment::cfv, s).centre, p.vein_direction(VeinSegment::cfv, s), 30.0, 0.3);
            n += g.count([](Tissue t) { return t == Tissue::lymph_node; });
        }
        return n;
    };
    EXPECT_EQ(node_pixels(healthy()), 0);
    Anatomy a;
    a.lymph_nodes.push_back({1.0, 15.0});
    const Phantom p(leg(), a);
    EXPECT_GT(node_pixels(p), 500);
    // beside the CFV, in the fat: its hilum fat, its cortex the node's own code; within a probe's
    // half width of the vein across the image
    const glm::dvec3 c = p.lymph_node_centres().at(0);
    EXPECT_EQ(p.tissue_at(c), Tissue::fat);
    EXPECT_NEAR(c.z, p.level_z(VeinSegment::cfv, 1.0), 0.5);
    const Pose probe = p.transverse_probe_pose(VeinSegment::cfv, 1.0);
    const double across = glm::dot(c - glm::dvec3(probe.position), glm::dvec3(probe.axis_x()));
    EXPECT_GT(std::abs(across), 5.0);
    EXPECT_LT(std::abs(across), 18.0);
    EXPECT_EQ(p.tissue_at(c + glm::dvec3(0, 0, 6.5)), Tissue::lymph_node);  // the cortex along its long axis
}

TEST(VeinCourse, TheTransverseProbeRestsOnTheSkinAndLooksAtTheVein)
{
    const Phantom& p = healthy();
    for (const Station& st : kStations) {
        const Pose probe = p.transverse_probe_pose(st.segment, st.s_cm);
        const glm::dvec3 face(probe.position), x(probe.axis_x()), y(probe.axis_y()), dir = p.vein_direction(st.segment, st.s_cm);
        const VesselSection v = p.vein(st.segment, st.s_cm);
        // on the skin, the beam through the vein's centre
        EXPECT_NEAR(p.depth_at(face), 0.0, 0.05) << segment_name(st.segment) << " at " << st.s_cm;
        EXPECT_EQ(p.tissue_at(face - 0.3 * y), Tissue::outside);
        EXPECT_EQ(p.tissue_at(face + 0.3 * y), Tissue::skin);
        const glm::dvec3 to_vein = v.centre - face;
        EXPECT_LT(glm::length(to_vein - glm::dot(to_vein, y) * y), 0.05) << segment_name(st.segment) << " at " << st.s_cm;
        // nearly along the skin's inward normal: the face about flat on the skin (the normal from
        // the depth's gradient)
        const double h = 0.2;
        const glm::dvec3 inward = glm::normalize(glm::dvec3(p.depth_at(face + glm::dvec3(h, 0, 0)) - p.depth_at(face - glm::dvec3(h, 0, 0)),
                                                            p.depth_at(face + glm::dvec3(0, h, 0)) - p.depth_at(face - glm::dvec3(0, h, 0)),
                                                            p.depth_at(face + glm::dvec3(0, 0, h)) - p.depth_at(face - glm::dvec3(0, 0, h))));
        const double tilt = std::acos(std::min(1.0, glm::dot(inward, y))) * 180 / std::numbers::pi;
        std::printf("%-9s %4.1f cm: the face %.1f deg off the skin's plane, the vein %.1f mm deep\n", segment_name(st.segment), st.s_cm, tilt,
                    glm::length(to_vein));
        EXPECT_LT(tilt, st.segment == VeinSegment::dfv ? 30.0 : 12.0) << segment_name(st.segment) << " at " << st.s_cm;
        // the lumen met at its depth: its near wall, then the lumen
        const double wall = glm::length(to_vein) - v.lumen_radius;
        EXPECT_FALSE(is_lumen(p.tissue_at(face + (wall - 0.15) * y), true)) << segment_name(st.segment) << " at " << st.s_cm;
        EXPECT_TRUE(is_lumen(p.tissue_at(face + (wall + 0.15) * y), true)) << segment_name(st.segment) << " at " << st.s_cm;
        // transverse: the image plane square to the vein
        EXPECT_LT(std::abs(glm::dot(x, dir)), 1e-3);
        EXPECT_LT(std::abs(glm::dot(y, dir)), 1e-3);
        EXPECT_NEAR(glm::length(dir), 1.0, 1e-9);
        // the marker (-x) towards the patient's right: +x towards the patient's left (world +x)
        EXPECT_GE(x.x, 0.0) << segment_name(st.segment) << " at " << st.s_cm;
    }
    // the popliteal vein is reached from the posterior-medial skin: the beam towards anterior and lateral
    const Pose fossa = p.transverse_probe_pose(VeinSegment::popliteal, kPoplitealFossa_cm);
    EXPECT_LT(fossa.axis_y().y, -0.7);
    EXPECT_LT(fossa.axis_y().x, -0.2);
    EXPECT_THROW(p.vein(VeinSegment::cfv, kTrifurcation_cm + 1.0), std::out_of_range);
    EXPECT_THROW(p.vein(VeinSegment::dfv, -0.5), std::out_of_range);
}

TEST(VeinCourse, PresetCasesMapToTheirAnatomies)
{
    EXPECT_TRUE(anatomy_of(Case::healthy).thrombi.empty());
    const Phantom acute(leg(), Case::dvt_acute), chronic(leg(), Case::dvt_chronic);
    EXPECT_TRUE(acute.thrombosed(VeinSegment::cfv, kSfj_cm));
    EXPECT_TRUE(acute.thrombosed(VeinSegment::fv, 20.0));
    EXPECT_FALSE(acute.thrombosed(VeinSegment::popliteal, kPoplitealFossa_cm));
    EXPECT_FALSE(chronic.thrombosed(VeinSegment::cfv, kSfj_cm));
    EXPECT_TRUE(chronic.thrombosed(VeinSegment::fv, 20.0));
    EXPECT_EQ(chronic.tissue_at(chronic.vein(VeinSegment::fv, 20.0).thrombus_centre), Tissue::organised_thrombus);
}

TEST(VeinCourse, TheSweepFollowsTheCourse)
{
    const std::vector<Pose> poses = course_sweep_poses(healthy(), 200);
    ASSERT_EQ(poses.size(), 200u);
    // from the groin down the thigh, then over the fossa to below the trifurcation, never jumping
    // more than a few mm within a pass
    EXPECT_GT(poses.front().position.z, healthy().level_z(VeinSegment::cfv, 0.0) - 1.0);
    EXPECT_LT(poses.back().position.z, healthy().level_z(VeinSegment::cfv, kTrifurcation_cm) + 1.0);
    int jumps = 0;
    for (std::size_t i = 1; i < poses.size(); ++i) {
        const float step = glm::length(poses[i].position - poses[i - 1].position);
        if (step > 8.0f) std::printf("frame %zu: %.1f mm from the last\n", i, double(step));
        jumps += step > 8.0f;
    }
    EXPECT_EQ(jumps, 1);  // from the thigh's pass to the fossa's
}

}  // namespace
}  // namespace echosim::echo

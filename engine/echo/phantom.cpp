#include "echo/phantom.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace echosim::echo {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// the part of the exam limb the phantom covers [mm]: from under the drape above the groin to the
// calf below the trifurcation
constexpr double kTop = 40.0, kBottom = -560.0;
constexpr double kFascia = 0.8;           // the deep fascia's thickness [mm]
constexpr double kVeinWall = 0.6, kArteryWall = 0.8, kSaphenousWall = 0.4;  // [mm]
constexpr double kScarredWall = 1.6;      // a chronic vein's wall [mm]
constexpr double kTipCm = 1.2;            // a thrombus grows from its floating tip to full over this [cm]
constexpr double kTipRadius = 0.6;        // the tip's radius [mm]
constexpr double kFatCap = 0.6;           // the fat stays below this fraction of the limb's radius

// A smooth curve through knots (x increasing): monotone cubic (Fritsch-Carlson), so it neither
// overshoots nor rings between them; constant past the ends.
struct Curve {
    std::vector<double> x, y, m;

    Curve(std::initializer_list<std::pair<double, double>> knots)
    {
        for (const auto& [kx, ky] : knots) x.push_back(kx), y.push_back(ky);
        const std::size_t n = x.size();
        m.assign(n, 0.0);
        std::vector<double> d(n > 1 ? n - 1 : 0);
        for (std::size_t i = 0; i + 1 < n; ++i) d[i] = (y[i + 1] - y[i]) / (x[i + 1] - x[i]);
        for (std::size_t i = 1; i + 1 < n; ++i) m[i] = d[i - 1] * d[i] <= 0 ? 0.0 : (d[i - 1] + d[i]) / 2;
        if (n > 1) m[0] = d[0], m[n - 1] = d[n - 2];
        for (std::size_t i = 0; i + 1 < n; ++i) {
            if (d[i] == 0) {
                m[i] = m[i + 1] = 0;
                continue;
            }
            const double a = m[i] / d[i], b = m[i + 1] / d[i], h = a * a + b * b;
            if (h > 9) {
                const double t = 3 / std::sqrt(h);
                m[i] = t * a * d[i], m[i + 1] = t * b * d[i];
            }
        }
    }

    double operator()(double at) const
    {
        if (at <= x.front()) return y.front();
        if (at >= x.back()) return y.back();
        const std::size_t i = std::size_t(std::upper_bound(x.begin(), x.end(), at) - x.begin()) - 1;
        const double h = x[i + 1] - x[i], t = (at - x[i]) / h, t2 = t * t, t3 = t2 * t;
        return (2 * t3 - 3 * t2 + 1) * y[i] + (t3 - 2 * t2 + t) * h * m[i] + (-2 * t3 + 3 * t2) * y[i + 1] + (t3 - t2) * h * m[i + 1];
    }
};

// Curves along the limb are written by depth below the groin, -z [mm], so that x increases.
// The deep vein: its angle around the limb [deg, unwrapped: 365 is 5] and its centre's depth below
// the skin at that angle for the reference patient [mm].
const Curve kVeinTheta{{-40, 310}, {0, 312}, {60, 312}, {120, 314}, {200, 322}, {280, 336}, {330, 350}, {350, 365},
                       {370, 392}, {395, 418}, {430, 425}, {470, 425}, {500, 423}, {560, 420}};
const Curve kVeinDepth{{-40, 30}, {0, 29}, {60, 31}, {120, 34}, {200, 39}, {280, 44}, {330, 44}, {350, 39},
                       {370, 32}, {395, 28}, {430, 25}, {470, 24}, {500, 25}, {560, 27}};
// The artery's place around the vein [deg]: 0 superficial (towards the skin), -90 on the side of
// decreasing theta (lateral on the anterior-medial thigh), 180 deep. Lateral at the groin, crossing
// in front of the vein down the thigh, behind it (deep, seen from the back) in the fossa.
const Curve kArteryPsi{{-40, -80}, {0, -78}, {60, -70}, {120, -60}, {180, -40}, {250, -15}, {320, 0}, {345, 60}, {370, 140}, {395, 180}};
// the GSV in the fat: its angle [deg]
const Curve kGsvTheta{{0, 322}, {60, 326}, {150, 334}, {250, 345}, {330, 358}, {400, 380}, {470, 395}, {560, 398}};
// the sartorius: its angle [deg], from anterior-lateral at the groin over the canal to medial at the knee
const Curve kSartoriusTheta{{0, 255}, {100, 285}, {200, 318}, {280, 342}, {350, 365}, {420, 390}, {480, 400}};
// the femur: angle [deg], distance of its axis from the limb's [mm], radius [mm] (the condyles at the knee)
const Curve kFemurTheta{{-40, 270}, {150, 272}, {300, 272}, {385, 270}};
const Curve kFemurDistance{{-40, 25}, {150, 25}, {300, 16}, {385, 10}};
const Curve kFemurRadius{{-40, 13}, {385, 13}, {425, 21}, {445, 21}};
constexpr double kFemurEnd = -443.0, kTibiaTop = -446.0, kFibulaTop = -455.0;
const Curve kTibiaRadius{{446, 19}, {520, 14}, {560, 12}};
const Curve kTibiaDistance{{446, 12}, {520, 14}};

// Branch offsets from the deep vein in its local frame (out: towards the skin along the limb's
// radius; across: towards increasing theta) [mm], by the distance below the junction [mm].
struct Offset {
    Curve out, across;
    glm::dvec2 operator()(double below) const { return {out(below), across(below)}; }
};
// the DFV: leaving deep and a little lateral of the FV, diving behind it medial of the femur
const Offset kDfv{{{0, -6.6}, {15, -13}, {30, -24}, {45, -32}, {70, -38}, {150, -42}},
                  {{0, -1.2}, {15, 8}, {30, 14}, {45, 16}, {90, 16}, {150, 15}}};
// the deep femoral artery (from its own junction, 1 cm above): from the artery's deep-lateral side
// under the FV to lie deep of the DFV (the first knot is added to the artery's own offset)
const Offset kDfa{{{0, -4.3}, {12, -12}, {30, -24}, {50, -36}, {90, -44}, {150, -46}},
                  {{0, -1.2}, {12, -5}, {30, 4}, {50, 8}, {90, 8}, {150, 8}}};
// the calf vessels below the trifurcation, from the popliteal vein's end
const Offset kCalfVeins[3] = {
    {{{0, -2}, {30, -12}}, {{0, -3}, {30, -8}}},   // anterior tibial: deep and lateral
    {{{0, -1}, {30, -6}}, {{0, 3}, {30, 10}}},     // posterior tibial: medial
    {{{0, -3}, {30, -15}}, {{0, 0}, {30, 0}}},     // peroneal: deep
};
const Offset kCalfArteries[2] = {
    {{{0, -8.9}, {30, -18}}, {{0, -3}, {30, -14}}},  // anterior tibial
    {{{0, -8.9}, {30, -13}}, {{0, 3}, {30, 8}}},     // tibioperoneal trunk
};

double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }
double smooth(double e0, double e1, double x)
{
    const double t = clamp01((x - e0) / (e1 - e0));
    return t * t * (3 - 2 * t);
}
double mix(double a, double b, double w) { return a + (b - a) * w; }
glm::dvec2 mix(const glm::dvec2& a, const glm::dvec2& b, double w) { return a + (b - a) * w; }
glm::dvec2 radial(double theta) { return {std::cos(theta), std::sin(theta)}; }
glm::dvec2 around(double theta) { return {-std::sin(theta), std::cos(theta)}; }

// the reference fat [mm] before its scaling to 12 mm over the CFV at the groin: thicker medially
// and proximally
double fat_shape(double z, double theta) { return 10.0 + 4.0 * std::sin(theta * 2.0 + 0.7) + 3.0 * std::cos(z * 0.02); }
double skin_mm(double theta) { return 1.6 + 0.6 * (0.5 + 0.5 * std::sin(theta)); }

// the level where a table of s (increasing with the index) reaches s, as a fractional index
double index_of_s(const std::vector<double>& s, std::size_t first, double at)
{
    if (at <= s[first]) return double(first);
    const auto it = std::upper_bound(s.begin() + std::ptrdiff_t(first), s.end(), at);
    if (it == s.end()) return double(s.size() - 1);
    const std::size_t i = std::size_t(it - s.begin()) - 1;
    return double(i) + (at - s[i]) / (s[i + 1] - s[i]);
}

}  // namespace

const char* tissue_name(Tissue t)
{
    static const char* names[kTissueCount] = {"outside",         "skin",        "fat",         "fascia",
                                              "muscle",          "artery lumen", "artery wall", "vein lumen",
                                              "vein wall",       "thrombus",    "saphenous lumen", "bone cortex",
                                              "bone marrow",     "organised thrombus", "scarred vein wall", "lymph node"};
    const auto i = std::size_t(t);
    return i < std::size_t(kTissueCount) ? names[i] : "?";
}

const char* case_name(Case c)
{
    switch (c) {
    case Case::healthy: return "healthy";
    case Case::dvt_acute: return "dvt-acute";
    case Case::dvt_chronic: return "dvt-chronic";
    }
    return "?";
}

Case parse_case(const std::string& name)
{
    for (Case c : {Case::healthy, Case::dvt_acute, Case::dvt_chronic})
        if (name == case_name(c)) return c;
    throw std::invalid_argument("unknown case '" + name + "' (expected healthy, dvt-acute or dvt-chronic)");
}

Anatomy anatomy_of(Case c)
{
    Anatomy a;
    if (c == Case::dvt_acute) {
        a.thrombi.push_back({VeinSegment::cfv, ThrombusKind::acute, 2.0, kBifurcation_cm - 2.0, 1.0});
        a.thrombi.push_back({VeinSegment::fv, ThrombusKind::acute, kBifurcation_cm, 26.0 - kBifurcation_cm, 1.0});
    } else if (c == Case::dvt_chronic) {
        a.thrombi.push_back({VeinSegment::fv, ThrombusKind::chronic, 6.0, 20.0, 0.6});
    }
    return a;
}

Phantom::Phantom(const scene::LegModel& leg, Case c) : Phantom(leg, anatomy_of(c)) {}

Phantom::Phantom(const scene::LegModel& leg, const Anatomy& anatomy, const PhantomOptions& options)
    : anatomy_(anatomy), fat_scale_(anatomy.fat_mm / 12.0), z_top_(kTop), z_bottom_(kBottom), step_(options.step_mm)
{
    if (!(step_ > 0.05 && step_ <= 5.0)) throw std::invalid_argument("PhantomOptions::step_mm must be within 0.05 .. 5 mm");
    if (!(anatomy.fat_mm > 0 && anatomy.fat_mm <= 80)) throw std::invalid_argument("Anatomy::fat_mm must be within 0 .. 80 mm");
    // the limb's cross-sections by level: the tube runs along -z, so invert z(t) once
    const scene::Tube& limb = leg.exam_limb();
    const std::size_t n = std::size_t(std::floor((z_top_ - z_bottom_) / step_)) + 1;
    z_bottom_ = z_top_ - step_ * double(n - 1);
    double t = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double z = z_top_ - step_ * double(i);
        while (t < limb.t_max() && limb.at(float(t)).center.z > z) t += 1e-3;
        const scene::Station s = limb.at(float(t));
        limbs_.push_back({glm::dvec2(s.center.x, s.center.y), s.r_pos1, s.r_neg1, s.r_pos2, s.r_neg2, s.exponent});
    }
    const auto z_at = [&](std::size_t i) { return z_top_ - step_ * double(i); };

    // the reference patient's deep vein, its arc length s from the ligament
    std::vector<glm::dvec3> reference(n);
    for (std::size_t i = 0; i < n; ++i) {
        const double z = z_at(i), theta = kVeinTheta(-z) * kDeg;
        reference[i] = glm::dvec3(at_depth(limbs_[i], theta, kVeinDepth(-z)), z);
    }
    deep_s_.assign(n, 0.0);
    for (std::size_t i = 1; i < n; ++i) deep_s_[i] = deep_s_[i - 1] + glm::length(reference[i] - reference[i - 1]) / 10.0;
    const double at_ligament = index_at(kLigamentZ_mm);
    const std::size_t l0 = std::min(std::size_t(at_ligament), n - 2);
    const double s0 = mix(deep_s_[l0], deep_s_[l0 + 1], at_ligament - double(l0));
    for (double& s : deep_s_) s -= s0;
    const auto deep_z = [&](double s) { return z_top_ - step_ * index_of_s(deep_s_, 0, s); };
    z_sfj_ = deep_z(kSfj_cm);
    z_bifurcation_ = deep_z(kBifurcation_cm);
    z_artery_bifurcation_ = deep_z(kArteryBifurcation_cm);
    z_trifurcation_ = deep_z(kTrifurcation_cm);

    // the branches' own s, from the reference patient's course
    levels_.resize(n);
    for (std::size_t i = 0; i < n; ++i) levels_[i] = build_level(i, 1.0, nullptr);
    const auto branch_s = [&](Vessel v, double z_junction, std::vector<double>& s) {
        s.assign(n, -1.0);
        const std::size_t first = std::size_t(std::ceil((z_top_ - z_junction) / step_));
        if (first >= n) return;
        s[first] = 0;
        for (std::size_t i = first + 1; i < n; ++i)
            s[i] = s[i - 1] + glm::length(glm::dvec3(levels_[i].ring[v].c - levels_[i - 1].ring[v].c, -step_)) / 10.0;
    };
    branch_s(gsv, z_sfj_, gsv_s_);
    branch_s(dfv, z_bifurcation_, dfv_s_);

    // this patient's course, thrombi and all
    for (std::size_t i = 0; i < n; ++i) levels_[i] = build_level(i, fat_scale_, &anatomy_.thrombi);
    for (int v = 0; v < kVessels; ++v) {
        const auto present = [&](std::size_t i) { return levels_[i].ring[v].lumen > 0; };
        for (std::size_t i = 0; i < n; ++i) {
            Ring& r = levels_[i].ring[v];
            if (!present(i)) {
                // where a vessel begins or ends, its absent neighbour sits at its centre, so the
                // levels between them grow or shrink it in place
                if (i + 1 < n && present(i + 1)) r.c = levels_[i + 1].ring[v].c;
                else if (i > 0 && present(i - 1)) r.c = levels_[i - 1].ring[v].c;
                continue;
            }
            const std::size_t lo = i > 0 && present(i - 1) ? i - 1 : i, hi = i + 1 < n && present(i + 1) ? i + 1 : i;
            if (hi == lo) continue;
            r.slope = (levels_[hi].ring[v].c - levels_[lo].ring[v].c) / (levels_[hi].z - levels_[lo].z);
        }
    }
    place_bones();

    // the lymph nodes: in the deep fat 10 mm medial of the CFV
    for (const LymphNode& ln : anatomy_.lymph_nodes) {
        const double z = deep_z(ln.s_cm);
        const std::size_t i = std::min(std::size_t(std::lround(index_at(z))), n - 1);
        const Level& lv = levels_[i];
        Node node;
        node.along = ln.size_mm / 2;
        node.across = 0.3 * ln.size_mm;
        node.radial = 0.22 * ln.size_mm;
        // its depth at the vein's angle, then turned medially until it lies 10 mm across from the
        // vein (at its own radius)
        double theta = lv.theta_vein;
        const auto depth_at_theta = [&](double th) {
            const double fat = fat_mm(z, th, skin_radius(lv.limb, th)), skin = skin_mm(th);
            return std::max(skin + node.radial + 0.5, skin + fat - node.radial - 0.6);
        };
        for (int k = 0; k < 3; ++k) theta = lv.theta_vein + 10.0 / (skin_radius(lv.limb, theta) - depth_at_theta(theta));
        const double depth = depth_at_theta(theta);
        node.c = glm::dvec3(at_depth(lv.limb, theta, depth), z);
        node.dir = radial(theta);
        nodes_.push_back(node);
    }
}

double Phantom::index_at(double z) const
{
    return std::clamp((z_top_ - z) / step_, 0.0, double(limbs_.size() - 1));
}

double Phantom::fat_mm(double z, double theta, double radius) const
{
    // 12 mm over the CFV at the groin for the reference patient, scaled by the patient's fat
    static const double groin = fat_shape(kLigamentZ_mm, kVeinTheta(-kLigamentZ_mm) * kDeg);
    return std::min(fat_shape(z, theta) * 12.0 / groin * fat_scale_, kFatCap * radius);
}

Phantom::Level Phantom::build_level(std::size_t i, double fat_scale, const std::vector<Thrombus>* thrombi) const
{
    Level lv;
    const double z = z_top_ - step_ * double(i), below = -z;
    lv.z = z;
    lv.limb = limbs_[i];
    const Section& limb = lv.limb;
    const double s = deep_s_[i];

    // the deep vein: its reference place, then the muscle compartment shrunk or widened radially
    // by the fat's change
    const double theta = kVeinTheta(below) * kDeg;
    lv.theta_vein = theta;
    const double R = skin_radius(limb, theta);
    static const double groin = fat_shape(kLigamentZ_mm, kVeinTheta(-kLigamentZ_mm) * kDeg);
    const double fat_ref = fat_shape(z, theta) * 12.0 / groin;
    const double fat = std::min(fat_ref * fat_scale, kFatCap * R);
    const double inner_ref = R - skin_mm(theta) - fat_ref - kFascia, inner = R - skin_mm(theta) - fat - kFascia;
    const double ratio = inner / inner_ref;
    // the vein keeps its depth under the fascia (the muscle over it does not thin), as far as the
    // compartment holds it
    const double under_fascia = kVeinDepth(below) - (R - inner_ref);
    const double vein_depth = std::min(R - inner + under_fascia, R - 8.0);
    const glm::dvec2 out = radial(theta), across = around(theta);
    const glm::dvec2 vein_c = limb.centre + (R - vein_depth) * out;
    const auto local = [&](const glm::dvec2& o) { return vein_c + o.x * out + o.y * across; };
    lv.ratio = ratio;

    // the deep vein ends at the trifurcation, where the calf veins take over
    const double past_trifurcation = z_trifurcation_ - z;  // [mm], positive below it
    Ring& v = lv.ring[deep_vein];
    v.c = vein_c;
    const double r_vein = vein_diameter_mm(VeinSegment::cfv, s) / 2;
    v.lumen = r_vein * (1.0 - smooth(-2.0, 4.0, past_trifurcation));
    v.wall = kVeinWall;

    // its artery, far enough for the vein distended by a thrombus
    Ring& a = lv.ring[deep_artery];
    const double r_artery = artery_diameter_mm(VeinSegment::cfv, s) / 2;
    const double psi = kArteryPsi(below) * kDeg;
    const double gap = 1.25 * r_vein + kVeinWall + r_artery + kArteryWall + 0.7;
    const glm::dvec2 artery_offset = gap * glm::dvec2(std::cos(psi), std::sin(psi));
    a.c = local(artery_offset);
    a.lumen = r_artery * (1.0 - smooth(-3.0, 3.0, past_trifurcation));
    a.wall = kArteryWall;
    a.lumen_code = Tissue::artery_lumen;
    a.wall_code = Tissue::artery_wall;

    // the GSV: joining the CFV from medial and superficial at the SFJ, in the fat below it
    if (z <= z_sfj_) {
        Ring& g = lv.ring[gsv];
        const double sg = gsv_s_.empty() ? 0.0 : std::max(0.0, gsv_s_[i]);
        g.lumen = vein_diameter_mm(VeinSegment::gsv, sg) / 2;
        g.wall = kSaphenousWall;
        g.lumen_code = Tissue::saphenous_lumen;
        const double junction_psi = 38.0 * kDeg;
        const glm::dvec2 junction = local((r_vein + g.lumen - 1.0) * glm::dvec2(std::cos(junction_psi), std::sin(junction_psi)));
        const double theta_g = kGsvTheta(below) * kDeg;
        const double fat_g = std::min(fat_shape(z, theta_g) * 12.0 / groin * fat_scale, kFatCap * skin_radius(limb, theta_g));
        const glm::dvec2 in_fat = at_depth(limb, theta_g, skin_mm(theta_g) + 0.55 * fat_g);
        g.c = mix(junction, in_fat, smooth(0.0, 25.0, z_sfj_ - z));
    }

    // the DFV and the deep femoral artery, diving from the bifurcation
    if (z <= z_bifurcation_) {
        Ring& d = lv.ring[dfv];
        const double sd = dfv_s_.empty() ? 0.0 : std::max(0.0, dfv_s_[i]);
        d.c = local(kDfv(z_bifurcation_ - z));
        d.lumen = vein_diameter_mm(VeinSegment::dfv, sd) / 2;
        d.wall = kVeinWall;
    }
    if (z <= z_artery_bifurcation_) {
        Ring& d = lv.ring[dfa];
        const double down = z_artery_bifurcation_ - z;
        // from the artery's side at the junction, blending into the course written from the vein
        const glm::dvec2 start = artery_offset + kDfa(0.0);
        d.c = local(kDfa(down) + (start - kDfa(0.0)) * (1.0 - smooth(0.0, 15.0, down)));
        d.lumen = artery_diameter_mm(VeinSegment::dfv, down / 10.0) / 2;
        d.wall = kArteryWall;
        d.lumen_code = Tissue::artery_lumen;
        d.wall_code = Tissue::artery_wall;
    }

    // the calf vessels below the trifurcation
    if (past_trifurcation > -3.0) {
        const double grow = smooth(-3.0, 3.0, past_trifurcation) * (1.0 - smooth(40.0, 55.0, past_trifurcation));
        for (int k = 0; k < 3; ++k) {
            Ring& c = lv.ring[calf_vein0 + k];
            c.c = local(kCalfVeins[k](std::max(0.0, past_trifurcation)));
            c.lumen = 2.0 * grow;
            c.wall = kVeinWall;
        }
        for (int k = 0; k < 2; ++k) {
            Ring& c = lv.ring[calf_artery0 + k];
            c.c = local(kCalfArteries[k](std::max(0.0, past_trifurcation)));
            c.lumen = 1.8 * grow;
            c.wall = kArteryWall;
            c.lumen_code = Tissue::artery_lumen;
            c.wall_code = Tissue::artery_wall;
        }
    }

    // each vessel's own s, and its wall where no clot is
    for (int k = 0; k < kVessels; ++k) {
        Ring& r = lv.ring[k];
        r.s = k == deep_vein || k == deep_artery ? s
              : k == gsv                          ? (gsv_s_.empty() ? 0.0 : gsv_s_[i])
              : k == dfv                          ? (dfv_s_.empty() ? 0.0 : dfv_s_[i])
              : k == dfa                          ? (z_artery_bifurcation_ - z) / 10.0
                                                  : past_trifurcation / 10.0;
        r.plain_wall = r.wall;
        r.plain_wall_code = r.wall_code;
    }

    // thrombi: the deep vein by its s, the branches by theirs
    if (thrombi) {
        const glm::dvec2 deep_dir = -out;
        const auto clot = [&](Ring& r, bool deep, VeinSegment branch, double at) {
            for (const Thrombus& th : *thrombi) {
                if (deep ? !on_deep_vein(th.segment) : th.segment != branch) continue;
                const double into = at - th.start_cm;
                if (into < 0 || into > th.extent_cm || r.lumen <= 0) continue;
                // a proximal tip only where no other thrombus of this vein runs on into this one
                bool continued = false;
                for (const Thrombus& o : *thrombi)
                    if (&o != &th && (deep ? on_deep_vein(o.segment) : o.segment == branch) && o.start_cm < th.start_cm &&
                        o.start_cm + o.extent_cm >= th.start_cm - 0.05)
                        continued = true;
                const double grown = continued ? 1.0 : smooth(0.0, kTipCm, into);
                const double f = std::clamp(th.occlusion, 0.05, 1.0);
                if (th.kind == ThrombusKind::acute) {
                    r.lumen *= 1.0 + 0.2 * grown;  // distended
                    r.clot_code = Tissue::thrombus;
                } else {
                    r.lumen *= 1.0 - 0.2 * grown;  // shrunk, in a thick scarred wall
                    r.wall = mix(r.wall, kScarredWall, grown);
                    r.wall_code = Tissue::scarred_vein_wall;
                    r.irregular = true;
                    r.clot_code = Tissue::organised_thrombus;
                }
                const double full = r.lumen * std::sqrt(f);
                r.clot = mix(std::min(kTipRadius, full), full, grown);
                r.clot_c = r.c + deep_dir * (r.lumen - full) * grown;
                r.clot_from = th.start_cm;
                r.clot_to = th.start_cm + th.extent_cm;
            }
        };
        clot(lv.ring[deep_vein], true, VeinSegment::cfv, s);
        if (z <= z_sfj_ && !gsv_s_.empty()) clot(lv.ring[gsv], false, VeinSegment::gsv, gsv_s_[i]);
        if (z <= z_bifurcation_ && !dfv_s_.empty()) clot(lv.ring[dfv], false, VeinSegment::dfv, dfv_s_[i]);
    }

    // the bones, their places in the muscle compartment shrunk or widened as the vessels'
    if (z >= kFemurEnd) {
        const double t = kFemurTheta(below) * kDeg;
        lv.bone[0] = {limb.centre + kFemurDistance(below) * ratio * radial(t), kFemurRadius(below), below > 400 ? 3.0 : 4.0};
    }
    if (z <= kTibiaTop) lv.bone[1] = {limb.centre + kTibiaDistance(below) * ratio * radial(270.0 * kDeg), kTibiaRadius(below), 3.0};
    if (z <= kFibulaTop) lv.bone[2] = {limb.centre + 31.0 * ratio * radial(165.0 * kDeg), 6.5, 2.5};

    // the sartorius under the fascia, from the groin over the canal to the knee
    if (z < -20 && z > -480) {
        const double size = smooth(-20.0, -60.0, z) * (1.0 - smooth(-440.0, -478.0, z));
        const double t = kSartoriusTheta(below) * kDeg;
        const double fat_s = std::min(fat_shape(z, t) * 12.0 / groin * fat_scale, kFatCap * skin_radius(limb, t));
        lv.sartorius = {at_depth(limb, t, skin_mm(t) + fat_s + kFascia + 5.0), radial(t), 4.5 * size, 14.0 * size};
    }
    // the popliteal fossa's fat around its vessels
    if (z < -360 && z > -490) {
        const double size = smooth(-360.0, -385.0, z) * (1.0 - smooth(-470.0, -490.0, z));
        lv.fossa_fat = {(v.c + a.c) / 2.0, out, 13.0 * size, 15.0 * size};
    }
    return lv;
}

void Phantom::place_bones()
{
    // where a bone would cut into a vessel (a thick fat shrinks the muscle compartment), push it
    // away, then smooth the pushes along the limb so the bone stays straight
    const std::size_t n = levels_.size();
    for (int b = 0; b < 3; ++b) {
        std::vector<glm::dvec2> push(n, glm::dvec2(0.0));
        for (std::size_t i = 0; i < n; ++i) {
            Bone bone = levels_[i].bone[b];
            if (bone.r <= 0) continue;
            const glm::dvec2 start = bone.c;
            for (int pass = 0; pass < 4; ++pass)
                for (const Ring& r : levels_[i].ring) {
                    if (r.lumen <= 0) continue;
                    const double need = bone.r + r.lumen + 1.35 * r.wall + 1.0;
                    const glm::dvec2 d = bone.c - r.c;
                    const double dist = glm::length(d);
                    if (dist < need) bone.c += (dist > 1e-9 ? d / dist : glm::dvec2(0.0, -1.0)) * (need - dist);
                }
            push[i] = bone.c - start;
        }
        const int reach = int(std::lround(15.0 / step_));
        for (std::size_t i = 0; i < n; ++i) {
            if (levels_[i].bone[b].r <= 0) continue;
            glm::dvec2 most(0.0);
            for (int k = -reach; k <= reach; ++k) {
                const std::ptrdiff_t j = std::ptrdiff_t(i) + k;
                if (j < 0 || j >= std::ptrdiff_t(n)) continue;
                if (glm::length(push[std::size_t(j)]) > glm::length(most)) most = push[std::size_t(j)];
            }
            levels_[i].bone[b].c += most;
        }
    }
}

Phantom::Section Phantom::section(double z) const
{
    const double f = index_at(z);
    const std::size_t i = std::min(std::size_t(f), limbs_.size() - 2);
    const double w = f - double(i);
    const Section &a = limbs_[i], &b = limbs_[i + 1];
    return {mix(a.centre, b.centre, w), mix(a.r_pos1, b.r_pos1, w), mix(a.r_neg1, b.r_neg1, w),
            mix(a.r_pos2, b.r_pos2, w), mix(a.r_neg2, b.r_neg2, w), mix(a.exponent, b.exponent, w)};
}

double Phantom::skin_radius(const Section& s, double theta)
{
    // the same super-ellipse as scene::Tube::point
    const double c = std::cos(theta), sn = std::sin(theta);
    const double a1 = c >= 0 ? s.r_pos1 : s.r_neg1, a2 = sn >= 0 ? s.r_pos2 : s.r_neg2;
    if (s.exponent == 2.0) return 1.0 / std::sqrt((c / a1) * (c / a1) + (sn / a2) * (sn / a2));
    return std::pow(std::pow(std::abs(c) / a1, s.exponent) + std::pow(std::abs(sn) / a2, s.exponent), -1.0 / s.exponent);
}

glm::dvec2 Phantom::at_depth(const Section& s, double theta, double depth) const
{
    return s.centre + (skin_radius(s, theta) - depth) * radial(theta);
}

double Phantom::depth_at(const glm::dvec3& p) const
{
    const Section s = section(p.z);
    const glm::dvec2 d = glm::dvec2(p.x, p.y) - s.centre;
    return skin_radius(s, std::atan2(d.y, d.x)) - glm::length(d);
}

Phantom::Ring Phantom::blend(const Ring& a, const Ring& b, double w)
{
    // the level nearer, or the one where the vessel is
    const bool take_a = b.lumen <= 0 || (a.lumen > 0 && w < 0.5);
    Ring r = take_a ? a : b;
    r.c = mix(a.c, b.c, w);
    r.lumen = mix(a.lumen, b.lumen, w);
    if (a.lumen > 0 && b.lumen > 0) {
        r.s = mix(a.s, b.s, w);
        r.slope = mix(a.slope, b.slope, w);
    }
    // the clot where the level's s lies within its span, grown from its tip's place between levels
    const Ring& k = a.clot > 0 ? a : b;
    const bool clot = k.clot > 0 && r.s >= k.clot_from && r.s <= k.clot_to;
    r.clot = clot ? (a.clot > 0 && b.clot > 0 ? mix(a.clot, b.clot, w) : k.clot) : 0.0;
    r.clot_c = a.clot > 0 && b.clot > 0 ? mix(a.clot_c, b.clot_c, w) : k.clot_c;
    r.clot_code = k.clot_code;
    if (clot) {
        r.wall = mix(a.clot > 0 ? a.wall : a.plain_wall, b.clot > 0 ? b.wall : b.plain_wall, w);
        r.wall_code = k.wall_code;
        r.irregular = k.irregular;
    } else {
        r.wall = mix(a.plain_wall, b.plain_wall, w);
        r.wall_code = r.plain_wall_code;
        r.irregular = false;
    }
    return r;
}

// the distance of q (in a level's plane) from a tube's axis through c going `slope` sideways per mm
// of z: across the vessel, not along the level's plane
static double across_tube(const glm::dvec2& q, const glm::dvec2& c, const glm::dvec2& slope)
{
    const glm::dvec2 d = q - c;
    const double cross = d.x * slope.y - d.y * slope.x;
    return std::sqrt((glm::dot(d, d) + cross * cross) / (1.0 + glm::dot(slope, slope)));
}

Phantom::Ring Phantom::ring_at(Vessel v, double z) const
{
    const double f = index_at(z);
    const std::size_t i = std::min(std::size_t(f), levels_.size() - 2);
    return blend(levels_[i].ring[v], levels_[i + 1].ring[v], f - double(i));
}

Tissue Phantom::tissue_at(const glm::dvec3& p) const
{
    if (!(p.z <= z_top_ && p.z >= z_bottom_)) return Tissue::outside;
    const double f = (z_top_ - p.z) / step_;
    const std::size_t i = std::min(std::size_t(f), levels_.size() - 2);
    const double w = f - double(i);
    const Level &la = levels_[i], &lb = levels_[i + 1];
    const Section &sa = la.limb, &sb = lb.limb;
    const Section s{mix(sa.centre, sb.centre, w), mix(sa.r_pos1, sb.r_pos1, w), mix(sa.r_neg1, sb.r_neg1, w),
                    mix(sa.r_pos2, sb.r_pos2, w), mix(sa.r_neg2, sb.r_neg2, w), mix(sa.exponent, sb.exponent, w)};
    const glm::dvec2 q(p.x, p.y);
    const glm::dvec2 d = q - s.centre;
    const double theta = std::atan2(d.y, d.x);
    const double radius = skin_radius(s, theta), depth = radius - glm::length(d);
    if (depth < 0) return Tissue::outside;

    // vessels first: they cut through the layers; a lumen wins over another's wall, so lumens that
    // meet at a junction open into each other
    Tissue wall_hit = Tissue::outside;
    for (int v = 0; v < kVessels; ++v) {
        const Ring &a = la.ring[v], &b = lb.ring[v];
        if (a.lumen <= 0 && b.lumen <= 0) continue;
        // a cheap test first: the level's plane distance bounds the distance across the tube
        const glm::dvec2 c = mix(a.c, b.c, w);
        const double reach = mix(a.lumen, b.lumen, w) + 1.35 * std::max(std::max(a.wall, b.wall), std::max(a.plain_wall, b.plain_wall));
        const glm::dvec2 dc = q - c;
        const glm::dvec2 slope = a.lumen > 0 ? a.slope : b.slope;
        if (glm::dot(dc, dc) > reach * reach * (1.0 + glm::dot(slope, slope))) continue;
        const Ring r = blend(a, b, w);
        const double dist = across_tube(q, r.c, r.slope);
        if (dist <= r.lumen) {
            if (r.clot > 0 && across_tube(q, r.clot_c, r.slope) <= r.clot) return r.clot_code;
            return r.lumen_code;
        }
        if (wall_hit != Tissue::outside) continue;
        double thick = r.wall;
        if (r.irregular) thick *= 1.0 + 0.35 * std::sin(5.0 * std::atan2(dc.y, dc.x) + 0.08 * p.z);
        if (dist <= r.lumen + thick) wall_hit = r.wall_code;
    }
    if (wall_hit != Tissue::outside) return wall_hit;

    // lymph nodes: a hypo-echoic cortex around a fatty hilum indenting it from the deep side
    for (const Node& n : nodes_) {
        const double dz = (p.z - n.c.z) / n.along;
        if (std::abs(dz) > 1.0) continue;
        const glm::dvec2 dn = q - glm::dvec2(n.c);
        const double u = glm::dot(dn, n.dir), v = n.dir.x * dn.y - n.dir.y * dn.x;
        if ((u / n.radial) * (u / n.radial) + (v / n.across) * (v / n.across) + dz * dz > 1.0) continue;
        const double hu = (u + 0.35 * n.radial) / (0.5 * n.radial), hv = v / (0.45 * n.across), hz = dz / 0.6;
        return hu * hu + hv * hv + hz * hz <= 1.0 ? Tissue::fat : Tissue::lymph_node;
    }

    // bones
    for (int b = 0; b < 3; ++b) {
        const Bone &ba = la.bone[b], &bb = lb.bone[b];
        if (ba.r <= 0 || bb.r <= 0) continue;
        const double rb = glm::length(q - mix(ba.c, bb.c, w)), r = mix(ba.r, bb.r, w);
        if (rb < r - mix(ba.cortex, bb.cortex, w)) return Tissue::bone_marrow;
        if (rb < r) return Tissue::bone_cortex;
    }

    const double skin = skin_mm(theta);
    if (depth < skin) return Tissue::skin;
    const double fat = skin + fat_mm(p.z, theta, radius);
    if (depth < fat) return Tissue::fat;
    if (depth < fat + kFascia) return Tissue::fascia;
    // in the muscle: the sartorius' outline, the popliteal fossa's fat
    const auto inside = [&](const Ellipse& ea, const Ellipse& eb, double grow) {
        if (ea.radial <= 0 || eb.radial <= 0) return false;
        const glm::dvec2 de = q - mix(ea.c, eb.c, w);
        const double u = glm::dot(de, ea.dir), v = ea.dir.x * de.y - ea.dir.y * de.x;
        const double ru = mix(ea.radial, eb.radial, w) + grow, rv = mix(ea.across, eb.across, w) + grow;
        return ru > 0 && rv > 0 && (u / ru) * (u / ru) + (v / rv) * (v / rv) <= 1.0;
    };
    if (inside(la.sartorius, lb.sartorius, 0.35) && !inside(la.sartorius, lb.sartorius, -0.35)) return Tissue::fascia;
    if (inside(la.fossa_fat, lb.fossa_fat, 0.0)) return Tissue::fat;
    return Tissue::muscle;
}

// --- the course ---

bool Phantom::modelled(VeinSegment segment, double s_cm) const
{
    if (!std::isfinite(s_cm)) return false;
    switch (segment) {
    case VeinSegment::gsv: return s_cm >= 0 && s_cm <= gsv_s_.back();
    case VeinSegment::dfv: return s_cm >= 0 && s_cm <= kDfvModelled_cm;
    default: return s_cm >= kDeepVeinFrom_cm && s_cm <= kTrifurcation_cm;
    }
}

void Phantom::check_modelled(VeinSegment segment, double s_cm) const
{
    if (modelled(segment, s_cm)) return;
    char text[200];
    const double from = on_deep_vein(segment) ? kDeepVeinFrom_cm : 0.0;
    const double to = segment == VeinSegment::gsv ? gsv_s_.back() : segment == VeinSegment::dfv ? kDfvModelled_cm : kTrifurcation_cm;
    std::snprintf(text, sizeof text, "s = %g cm is off the modelled %s (%g .. %g cm)", s_cm, segment_name(segment), from, to);
    throw std::out_of_range(text);
}

double Phantom::z_of(VeinSegment segment, double s_cm) const
{
    const std::vector<double>& s = segment == VeinSegment::gsv ? gsv_s_ : segment == VeinSegment::dfv ? dfv_s_ : deep_s_;
    std::size_t first = 0;
    while (first < s.size() && s[first] < 0) ++first;
    if (on_deep_vein(segment)) first = 0;
    return z_top_ - step_ * index_of_s(s, first, s_cm);
}

double Phantom::level_z(VeinSegment segment, double s_cm) const
{
    check_modelled(segment, s_cm);
    return z_of(segment, s_cm);
}

double Phantom::deep_s_at(double z_mm) const
{
    const double f = index_at(z_mm);
    const std::size_t i = std::min(std::size_t(f), deep_s_.size() - 2);
    return mix(deep_s_[i], deep_s_[i + 1], f - double(i));
}

VesselSection Phantom::section_of(const Ring& r, double z) const
{
    VesselSection v;
    v.centre = glm::dvec3(r.c, z);
    v.lumen_radius = r.lumen;
    v.wall = r.wall;
    v.thrombus_radius = r.clot;
    v.thrombus_centre = r.clot > 0 ? glm::dvec3(r.clot_c, z) : v.centre;
    return v;
}

VesselSection Phantom::vein(VeinSegment segment, double s_cm) const
{
    check_modelled(segment, s_cm);
    const double z = z_of(segment, s_cm);
    const Vessel v = segment == VeinSegment::gsv ? gsv : segment == VeinSegment::dfv ? dfv : deep_vein;
    return section_of(ring_at(v, z), z);
}

std::optional<VesselSection> Phantom::artery(VeinSegment segment, double s_cm) const
{
    check_modelled(segment, s_cm);
    if (segment == VeinSegment::gsv) return std::nullopt;
    const double z = z_of(segment, s_cm);
    const Ring r = ring_at(segment == VeinSegment::dfv ? dfa : deep_artery, z);
    if (r.lumen <= 0) return std::nullopt;
    return section_of(r, z);
}

glm::dvec3 Phantom::vein_direction(VeinSegment segment, double s_cm) const
{
    check_modelled(segment, s_cm);
    const double h = 0.1;  // [cm]
    double lo = s_cm - h, hi = s_cm + h;
    if (!modelled(segment, lo)) lo = s_cm;
    if (!modelled(segment, hi)) hi = s_cm;
    const Vessel v = segment == VeinSegment::gsv ? gsv : segment == VeinSegment::dfv ? dfv : deep_vein;
    const auto centre = [&](double s) {
        const double z = z_of(segment, s);
        return glm::dvec3(ring_at(v, z).c, z);
    };
    return glm::normalize(centre(hi) - centre(lo));
}

Pose Phantom::transverse_probe_pose(VeinSegment segment, double s_cm) const
{
    const VesselSection v = vein(segment, s_cm);
    const glm::dvec3 tangent = vein_direction(segment, s_cm);
    // the transverse plane through the vein's centre: the skin along each ray from the centre in
    // it, the nearest taken (coarse, then finer about the best)
    const glm::dvec3 e1 = glm::normalize(std::abs(tangent.z) < 0.9 ? glm::cross(tangent, glm::dvec3(0, 0, 1)) : glm::cross(tangent, glm::dvec3(1, 0, 0)));
    const glm::dvec3 e2 = glm::cross(tangent, e1);
    const auto ray = [&](double phi) { return std::cos(phi) * e1 + std::sin(phi) * e2; };
    const auto skin_along = [&](double phi) {
        const glm::dvec3 d = ray(phi);
        double in = 0, out = 1.0;
        while (depth_at(v.centre + out * d) >= 0 && out < 400) in = out, out += 1.0;
        for (int k = 0; k < 40; ++k) {
            const double mid = (in + out) / 2;
            (depth_at(v.centre + mid * d) >= 0 ? in : out) = mid;
        }
        return (in + out) / 2;
    };
    double best_phi = 0, best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 360; ++k)
        if (const double r = skin_along(k * kDeg); r < best) best = r, best_phi = k * kDeg;
    for (const double step : {0.1, 0.01}) {
        const double centre = best_phi;
        for (int k = -12; k <= 12; ++k)
            if (const double r = skin_along(centre + k * step * kDeg); r < best) best = r, best_phi = centre + k * step * kDeg;
    }
    const glm::dvec3 face = v.centre + best * ray(best_phi);
    const glm::dvec3 beam = -ray(best_phi);
    // across the vein, the marker (-x) towards the patient's right: +x towards world +x
    glm::dvec3 x = glm::normalize(glm::cross(beam, tangent));
    if (x.x < 0) x = -x;
    return pose_from_axes(glm::vec3(face), glm::vec3(x), glm::vec3(beam));
}

bool Phantom::thrombosed(VeinSegment segment, double s_cm) const
{
    for (const Thrombus& th : anatomy_.thrombi) {
        const bool same = on_deep_vein(segment) ? on_deep_vein(th.segment) : th.segment == segment;
        if (same && s_cm >= th.start_cm && s_cm <= th.start_cm + th.extent_cm) return true;
    }
    return false;
}

std::vector<glm::dvec3> Phantom::lymph_node_centres() const
{
    std::vector<glm::dvec3> out;
    for (const Node& n : nodes_) out.push_back(n.c);
    return out;
}

}  // namespace echosim::echo

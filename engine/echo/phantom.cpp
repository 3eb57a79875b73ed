#include "echo/phantom.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <glm/geometric.hpp>

namespace echosim::echo {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// the thigh part of the exam limb the phantom covers [mm]
constexpr double kTop = 40.0, kBottom = -420.0, kStep = 0.5;

double fat_thickness(double z, double theta)
{
    // 6 to 18 mm, thicker medially and proximally, as the reference tissue of the measurements
    return 10.0 + 4.0 * std::sin(theta * 2.0 + 0.7) + 3.0 * std::cos(z * 0.02);
}

}  // namespace

const char* tissue_name(Tissue t)
{
    static const char* names[kTissueCount] = {"outside",    "skin",        "fat",         "fascia",        "muscle",
                                              "artery lumen", "artery wall", "vein lumen", "vein wall",     "thrombus",
                                              "saphenous lumen", "bone cortex", "bone marrow", "organised thrombus"};
    return names[int(t)];
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

Phantom::Phantom(const scene::LegModel& leg, Case c) : case_(c), z_top_(kTop), z_step_(kStep)
{
    // tabulate the limb's cross-sections by level: the tube runs along -z, so invert z(t) once
    const scene::Tube& limb = leg.exam_limb();
    double t = 0;
    for (double z = kTop; z >= kBottom; z -= kStep) {
        while (t < limb.t_max() && limb.at(float(t)).center.z > z) t += 1e-3;
        const scene::Station s = limb.at(float(t));
        table_.push_back({glm::dvec3(s.center.x, s.center.y, z), s.r_pos1, s.r_neg1, s.r_pos2, s.r_neg2, s.exponent});
    }
}

Phantom::Section Phantom::section(double z) const
{
    const double f = std::clamp((z_top_ - z) / z_step_, 0.0, double(table_.size() - 1));
    const std::size_t i = std::min(std::size_t(f), table_.size() - 2);
    const double w = f - double(i);
    const Section &a = table_[i], &b = table_[i + 1];
    auto mix = [w](double p, double q) { return p + (q - p) * w; };
    return {glm::dvec3(mix(a.centre.x, b.centre.x), mix(a.centre.y, b.centre.y), z), mix(a.r_pos1, b.r_pos1),
            mix(a.r_neg1, b.r_neg1),  mix(a.r_pos2, b.r_pos2), mix(a.r_neg2, b.r_neg2), mix(a.exponent, b.exponent)};
}

double Phantom::skin_radius(const Section& s, double theta)
{
    // the same super-ellipse as scene::Tube::point
    const double c = std::cos(theta), sn = std::sin(theta);
    const double a1 = c >= 0 ? s.r_pos1 : s.r_neg1, a2 = sn >= 0 ? s.r_pos2 : s.r_neg2;
    return std::pow(std::pow(std::abs(c) / a1, s.exponent) + std::pow(std::abs(sn) / a2, s.exponent), -1.0 / s.exponent);
}

glm::dvec3 Phantom::at_depth(double z, double theta, double depth) const
{
    const Section s = section(z);
    const double r = skin_radius(s, theta) - depth;
    return s.centre + glm::dvec3(r * std::cos(theta), r * std::sin(theta), 0.0);
}

double Phantom::depth_at(const glm::dvec3& p) const
{
    const Section s = section(p.z);
    const glm::dvec2 d(p.x - s.centre.x, p.y - s.centre.y);
    return skin_radius(s, std::atan2(d.y, d.x)) - glm::length(d);
}

VesselSection Phantom::open_vessel(double z, double theta_deg, double depth, double radius, double wall) const
{
    // the femoral vessels run from anterior at the groin towards medial and deeper down the thigh
    const double along = std::clamp(-z / 400.0, 0.0, 1.0);
    VesselSection v;
    v.centre = at_depth(z, (theta_deg + 14.0 * along) * kDeg, depth + 10.0 * along);
    v.lumen_radius = radius;
    v.wall = wall;
    v.thrombus_radius = 0;
    v.thrombus_centre = v.centre;
    return v;
}

VesselSection Phantom::artery(double z) const { return open_vessel(z, 298.0, 24.0, 3.75, 0.8); }

VesselSection Phantom::vein(double z) const
{
    // beside the artery, medial to it and partly below
    VesselSection v = open_vessel(z, 309.0, 31.0, 5.5, 0.6);
    // the thrombus occupies the femoral vein from 40 mm below the groin down
    const double in_clot = std::clamp((-z - 40.0) / 10.0, 0.0, 1.0);
    if (case_ == Case::dvt_acute) {
        v.lumen_radius = 5.5 + 1.5 * in_clot;  // distended
        v.thrombus_radius = v.lumen_radius * in_clot;
    } else if (case_ == Case::dvt_chronic) {
        v.lumen_radius = 5.5 - 1.5 * in_clot;  // retracted
        v.wall = 0.6 + 0.9 * in_clot;          // thickened
        // organised thrombus against one side, a residual channel on the other
        v.thrombus_radius = 3.2 * in_clot;
        v.thrombus_centre = v.centre + glm::dvec3(-1.8 * in_clot, 1.0 * in_clot, 0.0);
    }
    return v;
}

VesselSection Phantom::saphenous(double z) const
{
    // superficial, in the fat, medially; it keeps its course (no drift down the thigh)
    VesselSection v;
    v.centre = at_depth(z, 332.0 * kDeg, 6.5);
    v.lumen_radius = 2.0;
    v.wall = 0.3;
    v.thrombus_radius = 0;
    v.thrombus_centre = v.centre;
    return v;
}

Tissue Phantom::tissue_at(const glm::dvec3& p) const
{
    if (p.z > z_top_ || p.z < kBottom) return Tissue::outside;
    const Section s = section(p.z);
    const glm::dvec2 d(p.x - s.centre.x, p.y - s.centre.y);
    const double theta = std::atan2(d.y, d.x);
    const double depth = skin_radius(s, theta) - glm::length(d);
    if (depth < 0) return Tissue::outside;

    // vessels first: they cut through the layers
    auto in_vessel = [&](const VesselSection& v, Tissue lumen, Tissue wall) -> Tissue {
        const double r = glm::length(glm::dvec2(p.x - v.centre.x, p.y - v.centre.y));
        if (r > v.lumen_radius + v.wall) return Tissue::outside;
        if (r > v.lumen_radius) return wall;
        if (v.thrombus_radius > 0 &&
            glm::length(glm::dvec2(p.x - v.thrombus_centre.x, p.y - v.thrombus_centre.y)) <= v.thrombus_radius)
            return case_ == Case::dvt_chronic ? Tissue::organised_thrombus : Tissue::thrombus;
        return lumen;
    };
    for (const auto& [section_of, lumen, wall] :
         {std::tuple{&Phantom::vein, Tissue::vein_lumen, Tissue::vein_wall},
          std::tuple{&Phantom::artery, Tissue::artery_lumen, Tissue::artery_wall},
          std::tuple{&Phantom::saphenous, Tissue::saphenous_lumen, Tissue::vein_wall}}) {
        const Tissue t = in_vessel((this->*section_of)(p.z), lumen, wall);
        if (t != Tissue::outside) return t;
    }

    // the femur: 25 mm anterior of the limb's axis, a little lateral of the vessels, its
    // anterior cortex about 42 mm under the skin
    const glm::dvec2 femur = 25.0 * glm::dvec2(std::cos(285.0 * kDeg), std::sin(285.0 * kDeg));
    const double rf = glm::length(d - femur);
    if (rf < 9.0) return Tissue::bone_marrow;
    if (rf < 13.0) return Tissue::bone_cortex;

    const double skin = 1.6 + 0.6 * (0.5 + 0.5 * std::sin(theta));
    if (depth < skin) return Tissue::skin;
    const double fat = skin + fat_thickness(p.z, theta);
    if (depth < fat) return Tissue::fat;
    if (depth < fat + 0.8) return Tissue::fascia;
    return Tissue::muscle;
}

}  // namespace echosim::echo

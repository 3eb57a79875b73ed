#include "trainer/guidance.hpp"

#include <cmath>
#include <cstdio>

#include <glm/geometric.hpp>

#include "exam/scorer.hpp"

namespace echosim::trainer {
namespace {

constexpr double kRadToDeg = 57.29577951308232;
constexpr double kTiltAdviceDeg = 10;  // beyond this from the skin's normal: "level the probe"
constexpr double kSmallMm = 3;          // a slide shorter than this is not worth a word

glm::dvec3 d(glm::vec3 v) { return glm::dvec3(v); }

}  // namespace

Guidance guide(const Pose& probe, const exam::StationTruth& station, const exam::ScoringBands& bands)
{
    Guidance g;
    const glm::dvec3 p = d(probe.position);
    const glm::dvec3 target = d(station.ideal_probe.position);
    const glm::dvec3 delta = target - p;
    // along the vein, pointing to the head
    glm::dvec3 up = glm::normalize(station.vein.direction);
    if (up.z < 0) up = -up;
    // the along-distance measured where the scorer measures it: the face's foot on the vein's axis
    g.along_mm = glm::dot(station.vein.centre - p, up);
    const glm::dvec3 beam = glm::normalize(d(station.ideal_probe.axis_y()));
    const glm::dvec3 across = delta - glm::dot(delta, up) * up - glm::dot(delta, beam) * beam;
    g.across_mm = glm::dot(across, glm::normalize(d(probe.axis_x())));
    // the turn about the probe's own beam that brings its elevation axis along the vein
    const glm::dvec3 b = glm::normalize(d(probe.axis_y()));
    const glm::dvec3 z = glm::normalize(d(probe.axis_z()));
    glm::dvec3 v = up - glm::dot(up, b) * b;
    if (glm::length(v) > 1e-9) {
        v = glm::normalize(v);
        double t = std::atan2(glm::dot(glm::cross(z, v), b), glm::dot(z, v)) * kRadToDeg;
        if (t > 90) t -= 180;
        if (t < -90) t += 180;
        g.turn_deg = t;
    }
    g.tilt_deg = std::acos(std::min(1.0, std::abs(glm::dot(b, beam)))) * kRadToDeg;
    g.vein_far_mm = glm::dot(station.vein.centre - target, beam) + station.vein.radius_mm;
    g.there = std::abs(g.along_mm) <= exam::kAlongToleranceMm && std::abs(g.across_mm) <= bands.reach_mm &&
              std::abs(g.turn_deg) <= bands.transverse_deg;
    return g;
}

GuidanceLevel guidance_level(Difficulty d)
{
    switch (d) {
    case Difficulty::beginner: return {1.0f, true, true};
    case Difficulty::intermediate: return {0.45f, true, false};
    case Difficulty::expert: return {0.0f, false, false};
    }
    return {};
}

std::string guidance_text(const Guidance& g, const GuidanceLevel& level, double image_depth_mm)
{
    if (!level.text) return "";
    char buf[96];
    std::string deeper;
    if (g.vein_far_mm > image_depth_mm) {
        if (level.numbers) std::snprintf(buf, sizeof buf, " The vein lies %.0f mm deep: deepen the image (]).", g.vein_far_mm);
        else std::snprintf(buf, sizeof buf, " The vein lies below the image: deepen it (]).");
        deeper = buf;
    }
    if (g.there) return "At the station: press until the vein closes, then call." + deeper;
    std::string s;
    auto add = [&](const char* part) { s += (s.empty() ? "" : ", ") + std::string(part); };
    if (std::abs(g.along_mm) >= kSmallMm) {
        const char* way = g.along_mm > 0 ? "towards the groin" : "towards the knee";
        if (level.numbers) std::snprintf(buf, sizeof buf, "slide %.0f mm %s", std::abs(g.along_mm), way);
        else std::snprintf(buf, sizeof buf, "slide %s", way);
        add(buf);
    }
    if (std::abs(g.across_mm) >= kSmallMm) {
        const char* way = g.across_mm > 0 ? "towards the image's right edge" : "towards the image's left edge";
        if (level.numbers) std::snprintf(buf, sizeof buf, "%.0f mm %s", std::abs(g.across_mm), way);
        else std::snprintf(buf, sizeof buf, "across %s", way);
        add(buf);
    }
    if (std::abs(g.turn_deg) >= 5) {
        const char* way = g.turn_deg > 0 ? "clockwise" : "anticlockwise";
        if (level.numbers) std::snprintf(buf, sizeof buf, "turn %.0f deg %s", std::abs(g.turn_deg), way);
        else std::snprintf(buf, sizeof buf, "turn %s", way);
        add(buf);
    }
    if (g.tilt_deg > kTiltAdviceDeg) add("level the probe (R)");
    if (s.empty()) return "Almost there: centre the vein under the probe." + deeper;
    s[0] = char(std::toupper(static_cast<unsigned char>(s[0])));
    return s + "." + deeper;
}

}  // namespace echosim::trainer

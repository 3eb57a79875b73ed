#include "app/exam_volume.hpp"

#include <cstdint>
#include <cstdio>

#include "app/bmode_imager.hpp"
#include "echo/case_volume.hpp"
#include "scene/leg.hpp"

namespace echosim::app {

std::string anatomy_digest(const echo::Anatomy& a)
{
    std::string text;
    char number[40];
    auto add = [&](double x) {
        std::snprintf(number, sizeof number, "%.17g;", x);
        text += number;
    };
    add(a.fat_mm);
    for (const echo::Thrombus& t : a.thrombi) {
        text += echo::segment_name(t.segment);
        text += echo::thrombus_kind_name(t.kind);
        add(t.start_cm), add(t.extent_cm), add(t.occlusion);
    }
    text += "|";
    for (const echo::LymphNode& n : a.lymph_nodes) add(n.s_cm), add(n.size_mm);
    std::uint64_t h = 1469598103934665603ull;
    for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
    std::snprintf(number, sizeof number, "%016llx", static_cast<unsigned long long>(h));
    return number;
}

namespace {

// by the anatomy alone: cases that differ only in their stations or bands share one volume
std::string exam_entry(const exam::Scenario& scenario, bool coarse)
{
    return cache_entry_name("exam-" + anatomy_digest(scenario.anatomy).substr(0, 12) + (coarse ? "-coarse" : ""));
}

}  // namespace

bool exam_volume_cached(const exam::Scenario& scenario, bool coarse) { return volume_cached(exam_entry(scenario, coarse)); }

VolumePair exam_volume(const exam::Scenario& scenario, bool coarse, const gpu::ContextOptions& gpu,
                       const std::function<void(const std::string&, double)>& progress)
{
    echo::CaseVolumeOptions options = coarse ? echo::coarse_case_volume_options() : echo::CaseVolumeOptions{};
    options.imager = bmode_imager_factory(gpu, "echosim exam");
    return cached_volume(exam_entry(scenario, coarse), "case " + scenario.id + "'s volume", [&] {
        const scene::LegModel leg;
        return echo::make_case_volume(leg, scenario.anatomy, options, progress);
    }, progress);
}

}  // namespace echosim::app

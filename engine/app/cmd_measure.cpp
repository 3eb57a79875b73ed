#include <cstdio>

#include "app/commands.hpp"
#include "fit/reference_tissue.hpp"
#include "scene/leg.hpp"

namespace echosim::app {

int run_measure(const MeasureArgs& args)
{
    if (!output_path_usable("measure", "--out", args.out)) return kExitBadInput;
    const scene::LegModel leg;
    fit::CampaignOptions options;
    options.seed = args.seed;
    const fit::MeasurementSet set = fit::simulate_campaign(leg, fit::ReferenceTissue{}, options);
    fit::write_measurements(args.out, set);
    int indenter = 0;
    for (const auto& s : set.samples) indenter += s.probe == fit::ProbeKind::indenter;
    std::printf("echosim measure: wrote %s: %d points, %zu samples (%d indenter, %zu probe)\n", args.out.c_str(),
                set.point_count(), set.samples.size(), indenter, set.samples.size() - std::size_t(indenter));
    return kExitOk;
}

}  // namespace echosim::app

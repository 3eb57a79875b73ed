#include <cstdio>

#include <nlohmann/json.hpp>

#include "app/commands.hpp"
#include "app/haptics_demo.hpp"

namespace echosim::app {

int run_haptics_demo(const HapticsDemoArgs& args)
{
    std::fprintf(stderr, "echosim haptics-demo: sliding the probe across the thigh (haptic loop 1 kHz, physics %.0f Hz)...\n",
                 args.physics_hz);
    const Fig8Result r = run_fig8({}, args.physics_hz);
    write_fig8(r, args.out);
    const double ratio = r.local_model.max_jump_N > 0 ? r.held_physics.max_jump_N / r.local_model.max_jump_N : 0.0;
    if (args.json) {
        const nlohmann::json j = {{"local_model", {{"max_jump_N_per_ms", r.local_model.max_jump_N}, {"lost_contacts", r.local_model.lost_contacts}}},
                                  {"held_physics", {{"max_jump_N_per_ms", r.held_physics.max_jump_N}, {"lost_contacts", r.held_physics.lost_contacts}}},
                                  {"jump_ratio", ratio}};
        std::printf("%s\n", j.dump().c_str());
        return kExitOk;
    }
    std::printf("                                 largest jump in 1 ms   lost contacts on the skin\n");
    std::printf("with the local model             %10.4f N              %d\n", r.local_model.max_jump_N, r.local_model.lost_contacts);
    std::printf("without (physics force held)     %10.4f N              %d\n", r.held_physics.max_jump_N, r.held_physics.lost_contacts);
    std::printf("the local model's largest jump is %.1f times smaller\n", ratio);
    std::printf("wrote %s, %s, %s\n", (args.out / "force_log.csv").c_str(), (args.out / "force.png").c_str(), (args.out / "summary.json").c_str());
    return kExitOk;
}

}  // namespace echosim::app

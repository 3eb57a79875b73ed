#include <chrono>
#include <cstdio>
#include <exception>

#include "app/commands.hpp"
#include "app/gpu_args.hpp"
#include "app/headless.hpp"

namespace echosim::app {

int run_render(const RenderArgs& args)
{
    // check what the user gave before spending time on Vulkan
    const auto parent = args.out.has_parent_path() ? args.out.parent_path() : std::filesystem::path(".");
    if (!std::filesystem::is_directory(parent)) {
        std::fprintf(stderr, "echosim render: --out %s: folder %s does not exist\n", args.out.c_str(), parent.c_str());
        return kExitBadInput;
    }
    DefaultScene scene;
    if (!args.pose.empty()) {
        try {
            scene.probe_pose = parse_pose(args.pose);
        } catch (const std::invalid_argument& e) {
            std::fprintf(stderr, "echosim render: --pose: %s\n", e.what());
            return kExitBadInput;
        }
    }

    const auto start = std::chrono::steady_clock::now();
    const HeadlessFrame frame = render_headless(context_options(args.gpu), scene, args.width, args.height);
    io::write_png(args.out, frame.image);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("echosim render: wrote %s (%ux%u) on %s in %.0f ms\n", args.out.c_str(), frame.image.width,
                frame.image.height, frame.device.c_str(), ms);
    if (frame.validation_messages > 0) {
        std::fprintf(stderr, "echosim render: Vulkan validation reported %u message(s)\n", frame.validation_messages);
        return kExitValidation;
    }
    return kExitOk;
}

}  // namespace echosim::app

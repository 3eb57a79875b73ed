#include <chrono>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>
#include <cstdio>
#include <exception>

#include "app/commands.hpp"
#include "app/default_scene.hpp"
#include "app/gpu_args.hpp"
#include "app/headless.hpp"
#include "core/image_limits.hpp"
#include "core/parse_number.hpp"

namespace echosim::app {
namespace {

// "yaw,pitch,distance" or "yaw,pitch,distance,x,y,z" or "yaw,pitch,distance,probe"
void apply_camera(const std::string& text, DefaultScene& scene)
{
    std::vector<std::string> fields;
    std::stringstream in(text);
    for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
    if (fields.size() != 3 && fields.size() != 4 && fields.size() != 6)
        throw std::invalid_argument("expected yaw,pitch,distance[,x,y,z|,probe], got '" + text + "'");
    auto number = [&](std::size_t i, const char* name) {
        float v = 0;
        if (!parse_number(fields[i], v) || !std::isfinite(v))
            throw std::invalid_argument(std::string(name) + " is not a finite number: '" + fields[i] + "'");
        return v;
    };
    scene.camera.yaw = number(0, "yaw");
    scene.camera.pitch = number(1, "pitch");
    scene.camera.distance = number(2, "distance");
    if (!(scene.camera.distance > 0)) throw std::invalid_argument("distance must be positive");
    if (fields.size() == 4) {
        if (fields[3] != "probe") throw std::invalid_argument("the fourth field can only be 'probe'");
        scene.camera.target = scene.session.probe().rest.position;
    } else if (fields.size() == 6) {
        scene.camera.target = {number(3, "x"), number(4, "y"), number(5, "z")};
    }
}

}  // namespace

int run_render(const RenderArgs& args)
{
    // check what the user gave before spending time on Vulkan
    if (!output_path_usable("render", "--out", args.out) || !outputs_distinct("render", {{"--out", args.out}}, {{"--model", args.model}}))
        return kExitBadInput;
    if (std::uint64_t(args.width) * args.height > kMaxImagePixels) {
        std::fprintf(stderr, "echosim render: --width %u --height %u: more than %llu pixels (7680x4320, 8K UHD) in all\n", args.width,
                     args.height, static_cast<unsigned long long>(kMaxImagePixels));
        return kExitBadInput;
    }
    session::SessionOptions options;  // the lock-step clock: only what is asked of the session is simulated
    options.window_follows_probe = true;  // a --pose anywhere on the leg presses simulated tissue
    if (!read_model_option("render", args.model, options.tissue)) return kExitBadInput;
    DefaultScene scene(options);
    if (!args.pose.empty()) {
        try {
            scene.session.place_probe({parse_pose(args.pose), 0.0});
        } catch (const std::invalid_argument& e) {
            std::fprintf(stderr, "echosim render: --pose: %s\n", e.what());
            return kExitBadInput;
        }
    }
    if (!args.camera.empty()) {
        try {
            apply_camera(args.camera, scene);
        } catch (const std::invalid_argument& e) {
            std::fprintf(stderr, "echosim render: --camera: %s\n", e.what());
            return kExitBadInput;
        }
    }

    const auto start = std::chrono::steady_clock::now();
    session::SettleReport settle;
    if (args.press_mm >= 0) settle = scene.session.press_and_settle(scene.session.probe().rest, args.press_mm);
    const session::SessionView& state = scene.session.view();
    if (state.resets > 0) std::fprintf(stderr, "echosim render: the tissue simulation was reset %d times\n", state.resets);
    const HeadlessFrame frame = render_headless(context_options(args.gpu), scene.meshes(), scene.frame_view(), args.width, args.height);
    io::write_png(args.out, frame.image);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("echosim render: wrote %s (%ux%u) on %s in %.0f ms\n", args.out.c_str(), frame.image.width,
                frame.image.height, frame.device.c_str(), ms);
    if (args.press_mm >= 0 && !settle.settled) {
        // the image shows the tissue as it is; a force it has not reached is not reported
        std::fprintf(stderr, "echosim render: %s\n", session::not_settled_message(args.press_mm, settle).c_str());
        return kExitFailure;
    }
    if (args.press_mm >= 0)
        std::printf("echosim render: probe pressed %.1f mm, tissue pushes back %.2f N (settled after %.2f s; ripple +/- %.2f N)\n",
                    args.press_mm, settle.force_N, settle.seconds, settle.ripple_N);
    if (frame.validation_messages > 0) {
        std::fprintf(stderr, "echosim render: Vulkan validation reported %u message(s)\n", frame.validation_messages);
        return kExitValidation;
    }
    return kExitOk;
}

}  // namespace echosim::app

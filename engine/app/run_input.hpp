// What the window's loop takes from its input each frame, whoever produces it: the mouse and
// keyboard (window_input.hpp) or a script (exercise_script.hpp, the smoke test's). Sources are
// polled on the main thread, once a frame, after GLFW's events.
#pragma once

#include <optional>

#include <glm/vec2.hpp>

#include "device/mouse_keyboard_device.hpp"
#include "runner/scanner_controls.hpp"

namespace echosim::app {

struct RunInput {
    // the camera
    float orbit_yaw = 0, orbit_pitch = 0;  // [rad]
    float zoom = 1;                        // distance factor (< 1 closer)
    bool reset_camera = false;             // the default view again, still on the probe
    runner::ScannerInput scanner;          // gain, focus, freeze
    bool toggle_guides = false;            // the practice guides: the vessels and the image plane in the leg
    // the probe, for the mouse-and-keyboard device (device/mouse_keyboard_device.hpp): a slide
    // over the exam patch (fractions of its extent), a tilt, and a press along the beam
    device::SurfaceMotion probe;
    // the window
    bool toggle_fullscreen = false;
    std::optional<bool> fullscreen;
    std::optional<glm::ivec2> resize;  // [px]
    bool minimise = false, restore = false;
    bool quit = false;
};

class InputSource {
public:
    virtual ~InputSource() = default;
    // The input since the last poll; `dt` is the frame's duration [s].
    virtual RunInput poll(float dt) = 0;
};

}  // namespace echosim::app

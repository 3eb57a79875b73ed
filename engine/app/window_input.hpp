// The mouse and keyboard of the simulator's window: left-drag orbits the camera, the wheel zooms,
// right-drag or the arrow keys slide the probe over the patch, Q/E fan it and A/D rock it (30
// degrees a second), R sets it upright again, T turns it a quarter about its beam (transverse to
// longitudinal and back), ] and [ the depth, + and - the gain, Page Down and Page Up the focus, Space freezes, W/S or Shift+wheel press it in and out, V (or Home)
// gives the default view again, G shows or hides the practice guides (the vessels and the image
// plane in the leg), F11 (or F) toggles fullscreen, Esc quits. GLFW's callbacks collect what happened between two
// polls; main thread only (GLFW's rule).
#pragma once

#include "app/run_input.hpp"

namespace echosim::gpu {
class Window;
}

struct GLFWwindow;

namespace echosim::app {

class WindowInput : public InputSource {
public:
    explicit WindowInput(gpu::Window& window);  // installs the callbacks
    ~WindowInput() override;
    WindowInput(const WindowInput&) = delete;
    WindowInput& operator=(const WindowInput&) = delete;

    RunInput poll(float dt) override;

    // what the callbacks collect between polls
    struct Pending {
        bool dragging = false;        // left button: orbit the camera
        bool moving_probe = false;    // right button: slide the probe over the patch
        double last_x = 0, last_y = 0;
        double drag_x = 0, drag_y = 0;    // camera drag [px]
        double probe_x = 0, probe_y = 0;  // probe drag [px]
        double scroll = 0, press_scroll = 0;  // wheel notches: zoom, or with Shift the press
        bool toggle_fullscreen = false, quit = false, level = false, reset_camera = false, turn = false, toggle_guides = false;
        runner::ScannerInput scanner;
    };

private:
    GLFWwindow* window_;
    Pending pending_;
};

}  // namespace echosim::app

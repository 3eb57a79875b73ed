#include "app/window_input.hpp"

#include <cmath>

#include <GLFW/glfw3.h>

#include "gpu/window.hpp"

namespace echosim::app {
namespace {

WindowInput::Pending& pending_of(GLFWwindow* w) { return *static_cast<WindowInput::Pending*>(glfwGetWindowUserPointer(w)); }

bool pressed(GLFWwindow* w, int key) { return glfwGetKey(w, key) == GLFW_PRESS; }

}  // namespace

WindowInput::WindowInput(gpu::Window& window) : window_(window.handle())
{
    glfwSetWindowUserPointer(window_, &pending_);
    glfwSetMouseButtonCallback(window_, [](GLFWwindow* win, int button, int action, int) {
        Pending& k = pending_of(win);
        if (button == GLFW_MOUSE_BUTTON_LEFT) k.dragging = action == GLFW_PRESS;
        if (button == GLFW_MOUSE_BUTTON_RIGHT) k.moving_probe = action == GLFW_PRESS;
        glfwGetCursorPos(win, &k.last_x, &k.last_y);
    });
    glfwSetCursorPosCallback(window_, [](GLFWwindow* win, double x, double y) {
        Pending& k = pending_of(win);
        if (k.dragging) k.drag_x += x - k.last_x, k.drag_y += y - k.last_y;
        if (k.moving_probe) k.probe_x += x - k.last_x, k.probe_y += y - k.last_y;
        k.last_x = x;
        k.last_y = y;
    });
    glfwSetScrollCallback(window_, [](GLFWwindow* win, double, double dy) {
        Pending& k = pending_of(win);
        (pressed(win, GLFW_KEY_LEFT_SHIFT) || pressed(win, GLFW_KEY_RIGHT_SHIFT) ? k.press_scroll : k.scroll) += dy;
    });
    glfwSetKeyCallback(window_, [](GLFWwindow* win, int key, int, int action, int) {
        if (action != GLFW_PRESS) return;
        Pending& k = pending_of(win);
        if (key == GLFW_KEY_ESCAPE) k.quit = true;
        if (key == GLFW_KEY_F11 || (key == GLFW_KEY_F && !k.dragging)) k.toggle_fullscreen = true;
        if (key == GLFW_KEY_R) k.level = true;
        if (key == GLFW_KEY_T) k.turn = true;
        if (key == GLFW_KEY_G) k.toggle_guides = true;
        // the scanner: ] / [ the image deeper / shallower, + / - gain, Page Down / Page Up the focus
        // deeper / shallower, Space freezes
        if (key == GLFW_KEY_EQUAL || key == GLFW_KEY_KP_ADD) ++k.scanner.gain_steps;
        if (key == GLFW_KEY_MINUS || key == GLFW_KEY_KP_SUBTRACT) --k.scanner.gain_steps;
        if (key == GLFW_KEY_PAGE_DOWN) ++k.scanner.focus_steps;
        if (key == GLFW_KEY_PAGE_UP) --k.scanner.focus_steps;
        if (key == GLFW_KEY_RIGHT_BRACKET) ++k.scanner.depth_steps;
        if (key == GLFW_KEY_LEFT_BRACKET) --k.scanner.depth_steps;
        if (key == GLFW_KEY_SPACE) k.scanner.toggle_freeze = !k.scanner.toggle_freeze;
        if (key == GLFW_KEY_V || key == GLFW_KEY_HOME) k.reset_camera = true;
    });
}

WindowInput::~WindowInput()
{
    glfwSetMouseButtonCallback(window_, nullptr);
    glfwSetCursorPosCallback(window_, nullptr);
    glfwSetScrollCallback(window_, nullptr);
    glfwSetKeyCallback(window_, nullptr);
    glfwSetWindowUserPointer(window_, nullptr);
}

RunInput WindowInput::poll(float dt)
{
    Pending& k = pending_;
    RunInput in;
    in.orbit_yaw = float(k.drag_x) * -0.005f;
    in.orbit_pitch = float(k.drag_y) * 0.005f;
    in.zoom = float(std::pow(0.9, k.scroll));
    // arrows slide the probe over the patch at 0.4 of the patch a second; right-drag: down the
    // screen moves the probe down the thigh, across moves it around
    const float step = 0.4f * dt;
    device::SurfaceMotion& m = in.probe;
    m.du = step * float(pressed(window_, GLFW_KEY_DOWN) - pressed(window_, GLFW_KEY_UP)) + 0.002f * float(k.probe_y);
    m.dv = step * float(pressed(window_, GLFW_KEY_RIGHT) - pressed(window_, GLFW_KEY_LEFT)) + 0.002f * float(k.probe_x);
    // Q/E fan the image plane, A/D rock the probe heel to toe, at 30 degrees a second
    const double tilt = 0.5236 * dt;
    m.dfan_rad = tilt * double(pressed(window_, GLFW_KEY_E) - pressed(window_, GLFW_KEY_Q));
    m.drock_rad = tilt * double(pressed(window_, GLFW_KEY_D) - pressed(window_, GLFW_KEY_A));
    m.level = k.level;
    m.turn = k.turn;
    // W/S press the probe in and out at 15 mm/s; Shift+wheel 1 mm a notch
    m.dpress_mm = 15.0 * dt * double(pressed(window_, GLFW_KEY_W) - pressed(window_, GLFW_KEY_S)) + k.press_scroll;
    in.toggle_fullscreen = k.toggle_fullscreen;
    in.reset_camera = k.reset_camera;
    in.toggle_guides = k.toggle_guides;
    in.scanner = k.scanner;
    k.scanner = {};
    in.quit = k.quit;
    k.drag_x = k.drag_y = k.probe_x = k.probe_y = k.scroll = k.press_scroll = 0;
    k.toggle_fullscreen = k.quit = k.level = k.reset_camera = k.turn = k.toggle_guides = false;
    return in;
}

}  // namespace echosim::app

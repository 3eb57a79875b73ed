// What the trainee did to the UI since the last step, as plain values (issue 32): the mouse, the
// keys pressed and held, the characters typed. The window's GLFW callbacks (app/ui_window_input.hpp)
// and a test's script fill it alike; the UI pass (ui/ui_pass.hpp) hands it to Dear ImGui, and the
// trainer (trainer/trainer.hpp) reads its shortcut keys from it.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace echosim::ui {

// A key: a printable key by its upper-case ASCII code ('A'..'Z', '0'..'9', ' '), the others from
// 256 up. The letters and digits are GLFW's own key codes; the rest are mapped once (app).
enum class Key : int {
    none = 0,
    space = ' ',
    tab = 256,
    enter,
    escape,
    backspace,
    del,
    left,
    right,
    up,
    down,
    home,
    end,
    page_up,
    page_down,
    f1,
    f2,
    f3,
    f4,
    f5,
    f6,
    f7,
    f8,
    f9,
    f10,
    f11,
    f12,
    count
};
constexpr Key letter(char c) { return Key(int(c >= 'a' && c <= 'z' ? c - 'a' + 'A' : c)); }

struct UiInput {
    // the mouse in the frame's pixels (negative: not over the frame); a button down now, and a
    // button that went down since the last step (a click shorter than a step is not lost)
    float mouse_x = -1, mouse_y = -1;
    std::array<bool, 3> mouse_down{};      // left, right, middle
    std::array<bool, 3> mouse_clicked{};
    float wheel = 0;                       // notches, up positive
    std::vector<Key> pressed;              // went down since the last step (a repeat counts again)
    std::vector<Key> held;                 // down now
    std::u32string chars;                  // typed, in order
    bool ctrl = false, shift = false, alt = false;

    bool was_pressed(Key k) const { return std::find(pressed.begin(), pressed.end(), k) != pressed.end(); }
    bool is_held(Key k) const { return std::find(held.begin(), held.end(), k) != held.end(); }
    bool empty() const
    {
        return pressed.empty() && chars.empty() && wheel == 0 && !mouse_clicked[0] && !mouse_clicked[1] && !mouse_clicked[2];
    }
};

}  // namespace echosim::ui

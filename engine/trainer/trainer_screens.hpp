// The trainer's screens in Dear ImGui (issue 32), drawn by the UI pass's callback (ui/ui_pass.hpp)
// from the trainer's state (trainer/trainer.hpp); a button does what its shortcut key does.
//   start:  the trainee's name, the lesson, the case (or random) with its description, the
//           difficulty, Start; the shortcut keys listed.
//   exam:   a panel over the leg's view: case and lesson, the step (station k of n and its name),
//           the guidance sentence and the leg map (the stations by where they lie along the leg,
//           done / pending / wrong, the probe's place, the arrow to the next), the turn dial, the
//           force gauge (the live force, the patient's adequate band, the excessive limit), the
//           call buttons and Finish.
//   report: score against the pass mark and the conclusion, the station table or the stations'
//           images at their deepest press (I; the images drawn by StationSheetPass in the area the
//           screen leaves for them), the errors flagged, the force over the exam, the report's
//           folder, the trainee's earlier sessions from the records, New lesson.
#pragma once

#include <map>
#include <optional>
#include <string>

#include <vulkan/vulkan.h>

#include "session/session.hpp"
#include "trainer/caliper.hpp"
#include "trainer/trainer.hpp"
#include "ui/ui_pass.hpp"

namespace echosim::trainer {

// What the screens keep between frames: the screen drawn last (a screen just shown gives the
// trainee's name field the keyboard), and where each button was drawn [px], by name ("trainee",
// "start", "compressible", "not-compressible", "finish", "new-lesson"), for a test's script to click
// it as a trainee would.
struct ScreenState {
    Screen last = Screen::report;
    struct Rect {
        float x0 = 0, y0 = 0, x1 = 0, y1 = 0;
        float cx() const { return 0.5f * (x0 + x1); }
        float cy() const { return 0.5f * (y0 + y1); }
    };
    std::map<std::string, Rect> hotspots;
    // where the report screen left room for the stations' images [px] (StationSheetPass draws
    // them there), this frame; none when it shows the table or another screen
    std::optional<Rect> sheet_area;
    // the exam screen's panel over the leg's view [px], this frame (none on the other screens)
    std::optional<Rect> exam_panel;
};

// Draws the trainer's current screen into a frame of `extent` (ImGui's context current), the
// echographic image shown in `plane` (its depth the scanner's); returns what a clicked button asks
// of the driver.
Action draw_trainer(Trainer& trainer, const session::SessionView& view, const echo::ImagePlane& plane, VkExtent2D extent,
                    const ui::UiFonts& fonts, float scale, ScreenState& state);

// Draws the caliper over the frozen image (ImGui's context current, inside the draw callback):
// its points as crosses, the line between them, the distance by the second, and a line at the
// image's top saying the image is frozen and how to measure.
void draw_caliper(const Caliper& caliper, const ImagePanel& panel, const ui::UiFonts& fonts, float scale);

// Draws the scanner's marks over the image (ImGui's context current, inside the draw callback), as
// a scanner's screen shows them: each centimetre's tick (the post stage's major ticks,
// compute/post_bindings.h) numbered in cm beside it, the image's whole depth at its bottom right
// ("7.0 cm"), the orientation marker at its top left: the image's left is the side of the
// probe's marker (probe -x; scene::make_linear_probe colours it kMarkerColour), which the exam
// keeps towards the patient's right (echo::Phantom::transverse_probe_pose); and the scanner's
// settings at its top right ("gain +4 dB  focus 2.0 cm"), which a fullscreen kiosk has no title
// bar to show.
void draw_scanner_marks(const ImagePanel& panel, const echo::ScannerSettings& scanner, const ui::UiFonts& fonts, float scale);

}  // namespace echosim::trainer

// The trainer's screens in Dear ImGui (issue 32), drawn by the UI pass's callback (ui/ui_pass.hpp)
// from the trainer's state (trainer/trainer.hpp); a button does what its shortcut key does.
//   start:  the trainee's name, the lesson, the case (or random) with its description, the
//           difficulty, Start; the shortcut keys listed.
//   exam:   a panel over the leg's view: case and lesson, the step (station k of n and its name),
//           the guidance sentence and the leg map (the stations by where they lie along the leg,
//           done / pending / wrong, the probe's place, the arrow to the next), the turn dial, the
//           force gauge (the live force, the patient's adequate band, the excessive limit), the
//           call buttons and Finish.
//   report: score against the pass mark and the conclusion, the station table, the errors flagged,
//           the report's folder, the trainee's earlier sessions from the records, New lesson.
#pragma once

#include <vulkan/vulkan.h>

#include "session/session.hpp"
#include "trainer/trainer.hpp"
#include "ui/ui_pass.hpp"

namespace echosim::trainer {

// Draws the trainer's current screen into a frame of `extent` (ImGui's context current); returns
// what a clicked button asks of the driver.
Action draw_trainer(Trainer& trainer, const session::SessionView& view, VkExtent2D extent, const ui::UiFonts& fonts, float scale);

}  // namespace echosim::trainer

// The smoke test's scripted input (`echosim run --exercise`): at fixed loop iterations it resizes
// the window, minimises and restores it, goes fullscreen and back, while pressing the probe 12 mm
// in over the first 40 iterations; it quits after 10,000 iterations, in case a window system never
// shows the window and the requested frames never come.
#pragma once

#include <glm/vec2.hpp>

#include "app/run_input.hpp"

namespace echosim::app {

class ExerciseScript : public InputSource {
public:
    explicit ExerciseScript(glm::ivec2 window_size) : size_(window_size) {}
    RunInput poll(float dt) override;

private:
    glm::ivec2 size_;  // the window's size at the start [px]
    int iteration_ = 0;
};

}  // namespace echosim::app

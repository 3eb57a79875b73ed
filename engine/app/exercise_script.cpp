#include "app/exercise_script.hpp"

#include <algorithm>

#include <glm/common.hpp>

namespace echosim::app {

RunInput ExerciseScript::poll(float)
{
    RunInput in;
    switch (iteration_) {
    case 10: in.resize = glm::max(size_ / 2, glm::ivec2(64)); break;
    case 20: in.minimise = true; break;
    case 24: in.restore = true; break;
    case 30: in.fullscreen = true; break;
    case 40: in.fullscreen = false; break;
    case 50: in.resize = size_ + glm::ivec2(37, 21); break;
    default: break;
    }
    ++iteration_;
    in.probe.press_mm = 12.0 * std::min(1.0, iteration_ / 40.0);
    in.quit = iteration_ > 10000;
    return in;
}

}  // namespace echosim::app

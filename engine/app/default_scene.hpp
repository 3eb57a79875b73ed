// The scene every part draws by default lives with the runner (runner/default_scene.hpp), which
// owns it; the commands, tests and benches that drew it before the runner came name it here.
#pragma once

#include "runner/default_scene.hpp"

namespace echosim::app {
using runner::DefaultScene;
}  // namespace echosim::app

// Must not compile: the runner is below the UI pass (engine/CMakeLists.txt); a UI is one more pass a
// configuration adds to its frame, the runner knows nothing of Dear ImGui.
#include "runner/runner.hpp"
#include "ui/ui_pass.hpp"

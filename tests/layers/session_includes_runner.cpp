// Must not compile: the session is below the runner (engine/CMakeLists.txt); it knows nothing of the
// frame, the presenters or the observers that drive it: the runner steps it.
#include "session/session.hpp"
#include "runner/runner.hpp"

// Must not compile: the live link's layer links only core; it knows nothing of the session it
// serves (engine/CMakeLists.txt): the app makes the session's frames into live frames.
#include "igtl/server.hpp"
#include "session/session.hpp"

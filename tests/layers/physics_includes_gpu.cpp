// Must not compile: the physics layer does not link the gpu layer (engine/CMakeLists.txt).
#include "gpu/context.hpp"
#include "physics/step.hpp"

// Must not compile: the gpu layer does not link the scene layer; the scene is drawn by the render
// layer above both (engine/CMakeLists.txt).
#include "gpu/frame.hpp"
#include "scene/mesh.hpp"

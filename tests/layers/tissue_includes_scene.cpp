// Must not compile: the tissue layer does not link the scene layer (engine/CMakeLists.txt).
#include "scene/leg.hpp"
#include "tissue/tissue_model.hpp"

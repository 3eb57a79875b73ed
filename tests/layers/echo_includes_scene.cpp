// Must compile: the echo layer links the scene layer. The control for the layer tests, so that a
// refused include is known to fail for the layer and not for a broken build.
#include "echo/phantom.hpp"
#include "scene/leg.hpp"

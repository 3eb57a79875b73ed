// Must not compile: the CPU echo layer does not link the gpu layer (engine/CMakeLists.txt).
#include "echo/log_compress.hpp"
#include "gpu/compute.hpp"

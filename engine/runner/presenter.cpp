#include "runner/presenter.hpp"

#include <GLFW/glfw3.h>

namespace echosim::runner {

bool OffscreenOutput::present(const gpu::FramePasses& passes, io::RgbaImage* pixels)
{
    presenter_.render(passes, pixels);
    return true;
}

bool WindowOutput::present(const gpu::FramePasses& passes, io::RgbaImage*)
{
    if (presenter_.draw(passes)) return true;
    glfwWaitEventsTimeout(0.05);  // minimised: do not spin
    return false;
}

}  // namespace echosim::runner

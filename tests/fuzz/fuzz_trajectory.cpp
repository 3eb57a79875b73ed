// Fuzz target: the scripted trajectory CSV (device::Trajectory::load), which refuses with
// std::invalid_argument.
#include <cstddef>
#include <cstdint>

#include <stdexcept>

#include "device/trajectory.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace echosim;
    fuzz::refusing<std::invalid_argument>([&] { device::Trajectory::load(fuzz::input_file(data, size, "trajectory.csv")); });
    return 0;
}

// Fuzz target: the PLUS device-set configuration XML (io::read_plus_config; tinyxml2 underneath).
#include <cstddef>
#include <cstdint>

#include "io/plus_config.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace echosim;
    fuzz::refusing<io::PlusConfigError>([&] { io::read_plus_config(fuzz::input_file(data, size, "PlusDeviceSet.xml")); });
    return 0;
}

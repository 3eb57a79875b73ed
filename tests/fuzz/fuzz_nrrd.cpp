// Fuzz target: NRRD volumes (io::read_nrrd) with a modest memory budget: the header and data paths.
#include <cstddef>
#include <cstdint>

#include "io/nrrd.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace echosim;
    fuzz::refusing<io::NrrdError>([&] { io::read_nrrd(fuzz::input_file(data, size, "volume.nrrd"), fuzz::fuzz_memory_budget); });
    return 0;
}

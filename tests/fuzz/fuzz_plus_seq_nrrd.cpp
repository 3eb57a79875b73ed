// Fuzz target: a PLUS .seq.nrrd sequence with a modest memory budget, read and resolved
// (plus_recording.hpp).
#include <cstddef>
#include <cstdint>

#include "input_file.hpp"
#include "plus_recording.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace echosim;
    fuzz::read_and_resolve(fuzz::input_file(data, size, "Sweep.seq.nrrd"), fuzz::fuzz_memory_budget);
    return 0;
}

// Fuzz target: a PLUS sequence of either kind (told apart by content) with the DEFAULT memory budget
// (8 GiB), read and resolved (plus_recording.hpp), so that a header claiming gigabytes over a tiny
// payload surfaces as an allocation over libFuzzer's -malloc_limit_mb.
#include <cstddef>
#include <cstdint>

#include "input_file.hpp"
#include "plus_recording.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace echosim;
    fuzz::read_and_resolve(fuzz::input_file(data, size, "Sweep.mha"), io::default_sweep_memory_budget);
    return 0;
}

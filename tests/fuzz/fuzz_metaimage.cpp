// Fuzz target: MetaImage volumes (io::read_metaimage_volume) with a modest memory budget; the
// header's ElementDataFile may name any file (a detached .raw, itself, a device).
#include <cstddef>
#include <cstdint>

#include "io/metaimage.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace echosim;
    fuzz::refusing<io::MetaImageError>(
        [&] { io::read_metaimage_volume(fuzz::input_file(data, size, "volume.mha"), fuzz::fuzz_memory_budget); });
    return 0;
}

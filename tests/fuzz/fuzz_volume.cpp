// Fuzz target: either volume format, told apart by content (io::read_volume), with the DEFAULT
// memory budget (8 GiB): a header claiming gigabytes over a tiny payload must be refused before the
// memory is taken (libFuzzer's -malloc_limit_mb turns any such allocation into a finding).
#include <cstddef>
#include <cstdint>

#include "io/volume_file.hpp"
#include "input_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
    using namespace echosim;
    fuzz::refusing<io::NrrdError, io::MetaImageError, io::VolumeFileError>(
        [&] { io::read_volume(fuzz::input_file(data, size, "volume.nrrd")); });
    return 0;
}

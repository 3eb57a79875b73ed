// What the PLUS sequence targets do with a file: read the recording and resolve it to a sweep as
// `echosim reconstruct` does without a configuration (default_reference_frame, then resolve_sweep),
// so the transforms' checks and chaining are fuzzed too, not only the header and pixels.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>

#include "io/plus_sequence.hpp"
#include "input_file.hpp"

namespace echosim::fuzz {

inline void read_and_resolve(const std::filesystem::path& path, std::uint64_t budget)
{
    refusing<io::PlusSequenceError>([&] {
        io::PlusRecording recording = io::read_plus_recording(path, budget);
        const std::string reference = io::default_reference_frame(recording);
        io::resolve_sweep(path, std::move(recording), {}, "Image", reference);
    });
}

}  // namespace echosim::fuzz

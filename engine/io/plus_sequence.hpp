// Tracked ultrasound sweeps as PLUS toolkit sequence files (DESIGN.md §3), the way PLUS and 3D Slicer
// write them: a MetaImage `.mha` (text header, then the pixels in the same file) or a `.seq.nrrd`.
// A sweep is N greyscale frames of W x H pixels and, per frame, the transform from image pixels to
// the reference (tracker, world) frame in mm, a timestamp and whether the transform is valid.
//
// Reading resolves each frame's transform from the first of these the file holds:
//   Seq_FrameNNNN_ImageToReferenceTransform, Seq_FrameNNNN_ImageToTrackerTransform,
//   ProbeToReference * ImageToProbe, ProbeToTracker * ImageToProbe,
// where ImageToProbe is the frame's own or, failing that, a file-wide `ImageToProbeTransform` field.
// A frame is valid when every transform used says OK (a missing status field counts as OK) and its
// ImageStatus, when given, is OK. Errors name the file, the frame (as written, e.g. Seq_Frame0002)
// and the field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

namespace echosim::io {

class PlusSequenceError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// 8 GiB of pixels at most, refused before any allocation.
inline constexpr std::uint64_t default_sweep_memory_budget = std::uint64_t(8) << 30;

struct TrackedFrame {
    double timestamp = 0;                // [s]
    glm::dmat4 image_to_reference{1.0};  // pixel (column, row, 0, 1) -> reference [mm]
    bool valid = true;                   // false: the tracker reported INVALID, MISSING, ... for it
};

struct Sweep {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::vector<std::uint8_t> pixels;  // frame after frame, row-major, top row first
    std::vector<TrackedFrame> frames;
    std::string orientation = "MF";    // PLUS UltrasoundImageOrientation of the pixels as stored

    std::size_t frame_bytes() const { return std::size_t(width) * height; }
    const std::uint8_t* frame_pixels(std::size_t frame) const { return pixels.data() + frame * frame_bytes(); }
};

// Throws PlusSequenceError naming the file when the sweep is inconsistent (pixel count, no frames,
// non-finite or non-affine transform, unknown orientation) or cannot be written; writes FILE.partial
// and renames it, so a failed write leaves nothing at `path`. `compressed`: zlib-deflated pixels.
void write_plus_mha(const std::filesystem::path& path, const Sweep& sweep, bool compressed);

// A `.mha` (header and data in one file) or `.seq.nrrd`, told apart by the file's first bytes.
// Throws PlusSequenceError naming the file, the frame and the field.
Sweep read_plus_sequence(const std::filesystem::path& path, std::uint64_t memory_budget_bytes = default_sweep_memory_budget);

}  // namespace echosim::io

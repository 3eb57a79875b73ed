// Tracked ultrasound sweeps as PLUS toolkit sequence files (DESIGN.md §3), the way PLUS and 3D Slicer
// write them: a MetaImage `.mha` / `.igs.mha` (text header, then the pixels in the same file) or a
// `.seq.nrrd` / `.igs.nrrd`. A recording is N greyscale frames of W x H pixels and, per frame, the
// transforms the tracker gave (`Seq_FrameNNNN_<From>To<To>Transform`, with its `...TransformStatus`),
// a timestamp and the image's status.
//
// Reading converts the pixels to PLUS's MF orientation (x toward the probe's marked side, y away
// from the transducer), whatever the file's UltrasoundImageOrientation (two letters, or three: the
// third is the volume axis and means nothing for a 2D frame), as PLUS does on reading: its `Image`
// frame, the one calibrations (ImageToProbe) are for, is the MF image's pixel (column, row, 0).
// A sweep is the recording resolved to one transform per frame, ImageToReference, by chaining the
// frame's transforms with those of a PLUS configuration (io/transform_repository.hpp). A frame whose
// image or any transform of its chain is not OK is kept but marked not valid; transforms that are
// not on the chain (a stylus, a needle) are not looked at. Errors name the file, the frame (as
// written, e.g. Seq_Frame0002) and the field.
// Budget (issue 34): the header at most 1 MiB plus 4 KiB for each frame its sizes allow, checked in
// one pass that keeps nothing before it is parsed; parsed, it holds 8 to 15 times its size (each
// field kept twice, as the MetaImage/NRRD header and by frame; 15 for the shortest fields). The
// pixels within the memory budget (8 GiB by default), checked against the header and the file
// before allocating, and held twice for a moment when the file counts its frames on another axis
// than the last (they are reordered); compressed ones grow with the stream (io/zlib_stream.hpp).
// Time: linear in the file, plus a copy and a search of the transforms for each of at most 64
// different sets of transform names the frames hold (resolve_sweep).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>

#include "core/printable_text.hpp"
#include "io/nrrd.hpp"
#include "io/transform_repository.hpp"

namespace echosim::io {

class PlusSequenceError : public InputFileError {  // its message escaped (core/printable_text.hpp)
public:
    using InputFileError::InputFileError;
};

// 8 GiB of pixels at most, refused before any allocation.
inline constexpr std::uint64_t default_sweep_memory_budget = std::uint64_t(8) << 30;

struct TrackedFrame {
    double timestamp = 0;                // [s]
    glm::dmat4 image_to_reference{1.0};  // pixel (column, row, 0, 1) -> reference [mm]
    bool valid = true;                   // false: the image or a transform of its chain is not OK
    bool image_valid = true;             // false: the image itself is not OK (ImageStatus)
};

struct Sweep {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    VoxelType pixel_type = VoxelType::uint8;
    std::vector<std::uint8_t> pixels;  // frame after frame, row-major, top row first, little-endian
    std::vector<TrackedFrame> frames;
    std::string orientation = "MF";    // PLUS UltrasoundImageOrientation of the pixels as stored

    std::size_t frame_bytes() const { return std::size_t(width) * height * voxel_size(pixel_type); }
    const std::uint8_t* frame_pixels(std::size_t frame) const { return pixels.data() + frame * frame_bytes(); }
};

// A transform as the recording gives it: `valid` false when its status is not OK (the matrix is
// then whatever the tracker left there, and is not used).
struct RecordedTransform {
    std::string from, to;
    glm::dmat4 matrix{1.0};
    bool valid = true;
};

struct RecordedFrame {
    std::string label;  // "Seq_Frame0002", as the file spells it
    double timestamp = 0;
    bool image_valid = true;
    std::vector<RecordedTransform> transforms;
};

struct PlusRecording {
    Sweep images;  // the pixels (MF), sizes and timestamps; its frames' transforms not yet resolved
    std::string orientation_in_file;  // as written, e.g. "MFA"
    std::vector<RecordedFrame> frames;
    std::vector<RecordedTransform> file_transforms;  // file-wide, e.g. ImageToProbeTransform
};

// The recording, pixels converted to MF. Throws PlusSequenceError naming the file, the frame and
// the field.
PlusRecording read_plus_recording(const std::filesystem::path& path,
                                  std::uint64_t memory_budget_bytes = default_sweep_memory_budget);

// Each frame's ImageToReference, from its transforms, the file-wide ones and `config` (which the
// recording's own take precedence over); the recording's pixels move into the sweep. Throws
// PlusSequenceError naming the file, the frame and the missing transform when a frame has no chain
// from `image_frame` to `reference_frame`, or the singular one when a valid link of it is singular
// (TransformRepository::product), or when the frames name more than 64 different sets of transforms.
// Time: each frame's own transforms and its chain's length, plus a copy and a search of all the
// transforms for each different set of transform names the frames hold (64 at most).
Sweep resolve_sweep(const std::filesystem::path& path, PlusRecording recording, const TransformRepository& config,
                    const std::string& image_frame = "Image", const std::string& reference_frame = "Reference");

// A transform of the configuration that the recording holds too (either way round), as the
// recording names it: file-wide (frames 0) or in `frames` of its frames. resolve_sweep uses the
// recording's; a caller says so.
struct AlsoRecorded {
    std::string from, to;
    std::size_t frames = 0;
};
std::vector<AlsoRecorded> transforms_also_recorded(const PlusRecording& recording, const TransformRepository& config);

// The frame a recording is reconstructed in when nothing says: Reference, as PLUS's tools default
// to, unless the recording's first frame names only the tracker's frame (then Tracker).
std::string default_reference_frame(const PlusRecording& recording);

// Throws PlusSequenceError naming the file when the sweep is inconsistent (pixel count, no frames,
// non-finite or non-affine transform, unknown orientation) or cannot be written; writes FILE.partial
// and renames it, so a failed write leaves nothing at `path`. `compressed`: zlib-deflated pixels.
void write_plus_mha(const std::filesystem::path& path, const Sweep& sweep, bool compressed);

// A `.mha` (header and data in one file) or `.seq.nrrd`, told apart by the file's first bytes,
// resolved to Reference (or, when the recording has no chain to it, to Tracker) with the
// recording's own transforms. Throws PlusSequenceError naming the file, the frame and the field.
Sweep read_plus_sequence(const std::filesystem::path& path, std::uint64_t memory_budget_bytes = default_sweep_memory_budget);

}  // namespace echosim::io

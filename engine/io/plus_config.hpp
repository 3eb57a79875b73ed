// The PLUS toolkit's device-set configuration file (PlusDeviceSet*.xml), the parts a volume
// reconstruction needs: the transforms of `CoordinateDefinitions` (the probe calibration
// ImageToProbe, usually) and the `VolumeReconstruction` element's settings, as PLUS's
// VolumeReconstructor reads them. Everything else in the file (devices, data collection, fCal's
// settings) belongs to acquisition and is not looked at; what the VolumeReconstruction element
// asks for that echosim does not do is listed in `warnings`, each naming the line and attribute,
// never silently dropped. Errors (PlusConfigError) name the file, the line and the attribute.
// Budget: a configuration of at most 1 MiB (PLUS's own are 5 to 60 KiB), refused by its size before
// it is read, and at most 256 attributes on an element (tinyxml2 checks each against those before
// it), refused by a scan of the text before parsing; parsing then holds at most about 40 MiB
// (tinyxml2's nodes for the densest file) and takes time O(n log n) in its n elements and
// attributes (0.15 s at the cap).
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include "core/printable_text.hpp"

namespace echosim::io {

class PlusConfigError : public InputFileError {  // its message escaped (core/printable_text.hpp)
public:
    using InputFileError::InputFileError;
};

enum class PlusInterpolation { nearest_neighbor, linear };
enum class PlusCompounding { mean, maximum, latest };

// The VolumeReconstruction element; what the file leaves out stays empty, for the caller's own
// defaults (and command-line options) to fill.
struct PlusReconstructionSettings {
    std::optional<glm::dvec3> output_spacing;              // [mm]
    std::optional<glm::dvec3> output_origin;               // centre of voxel (0, 0, 0) in the reference frame [mm]
    std::optional<std::array<int, 6>> output_extent;       // first and last voxel index on each axis
    std::optional<std::array<int, 2>> clip_origin;         // [pixels] of the MF-oriented image
    std::optional<std::array<int, 2>> clip_size;           // [pixels]
    std::optional<PlusInterpolation> interpolation;
    std::optional<PlusCompounding> compounding;
    std::optional<bool> fill_holes;
    std::optional<double> pixel_rejection_threshold;       // pixels below it are not pasted
    std::string image_frame = "Image";
    std::string reference_frame = "Reference";
    int line = 0;                                          // where the element is, for messages
};

struct PlusConfigTransform {
    std::string from, to;
    glm::dmat4 matrix{1.0};
    bool valid = true;  // Valid="FALSE" in the file
    int line = 0;
};

struct PlusConfig {
    std::vector<PlusConfigTransform> transforms;
    std::optional<PlusReconstructionSettings> reconstruction;
    std::vector<std::string> warnings;  // "FILE:LINE: VolumeReconstruction: FanAnglesDeg ... not supported: ...";
                                        // 100 at most, then one saying how many more
};

// Throws PlusConfigError naming the file (and line and attribute) when it is not a regular file,
// is over 1 MiB, has an element of more than 256 attributes, is not well-formed XML, or a value is
// malformed.
PlusConfig read_plus_config(const std::filesystem::path& path);

}  // namespace echosim::io

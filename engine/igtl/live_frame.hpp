// One frame of the live link to 3D Slicer (DESIGN.md §4, `echosim run --igtl`): the echographic
// image as the trainee sees it, where it lies, and the probe's pose, all from one session snapshot.
//
// What goes on the wire for each frame, as PlusServer sends it (OpenIGTLink protocol 2):
//   IMAGE     "Image_Reference"   the image, 8-bit scalar, columns x rows x 1, with its placement
//                                 in Reference (PLUS's name for an image sent with its
//                                 image-to-reference transform embedded);
//   TRANSFORM "ProbeToReference"  the probe's frame (DESIGN.md §2) to Reference [mm];
//   TRANSFORM "ImageToReference"  pixel (column, row, 0) to Reference [mm], at pixel centres, as in
//                                 a PLUS sequence file (so it scales: pixels in, millimetres out).
//
// The Reference frame is echosim's world, patient space in millimetres, but in RAS: world is LPS
// (DESIGN.md §2), and RAS = diag(-1, -1, 1) LPS. 3D Slicer works in RAS and places whatever
// OpenIGTLinkIF receives in RAS; and it converts the volumes we write (NRRD, `space:
// left-posterior-superior`) to RAS when it loads them. Sent in RAS, the live image therefore lands
// inside the case's volume loaded into the same scene, with no transform to add.
//
// The IMAGE message's placement (igtlImageMessage.cxx, and OpenIGTLinkIO's
// igtlioConverterUtilities.cxx, which Slicer's OpenIGTLinkIF uses to read it): the matrix's first
// three columns are the unit directions of the pixel axes i (columns), j (rows) and k, the spacing
// travels apart, and the translation is the *centre* of the pixel grid, not its first pixel:
// Slicer puts pixel (0, 0, 0)'s centre at centre - R S (size - 1) / 2. Here k is the elevational
// axis and its spacing the slice thickness the frame gives (image_to_world's third column).
//
// Timestamps: the wall clock (seconds since the UNIX epoch, UTC) at the moment the session snapshot
// was taken, as PLUS stamps its messages with the system time.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/mat4x4.hpp>

namespace echosim::igtl {

inline constexpr int kDefaultPort = 18944;  // PLUS's and SlicerIGT's
inline constexpr const char* kImageName = "Image_Reference";
inline constexpr const char* kProbeToReferenceName = "ProbeToReference";
inline constexpr const char* kImageToReferenceName = "ImageToReference";

struct LiveFrame {
    std::uint32_t columns = 0, rows = 0;
    std::vector<std::uint8_t> pixels;  // columns x rows grey levels, row-major, row 0 at the probe's face
    // pixel (column, row, 0, 1) to world (LPS mm) at pixel centres; its third column is the
    // elevational direction scaled by the slice's thickness [mm]
    glm::dmat4 image_to_world{1.0};
    glm::dmat4 probe_to_world{1.0};  // the probe's frame to world (LPS mm)
    double timestamp_s = 0;          // wall clock [s since the UNIX epoch] when the snapshot was taken
};

// World (LPS) to Reference (RAS): x and y negated.
inline glm::dmat4 reference_from_world()
{
    glm::dmat4 m(1.0);
    m[0][0] = -1.0;
    m[1][1] = -1.0;
    return m;
}

}  // namespace echosim::igtl

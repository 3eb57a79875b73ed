// The stations' images at their deepest press as one sheet of thumbnails, each captioned with its
// station and, under it, what was left of the vein's lumen at the deepest press (per cent of its
// area at rest, as the report table's "vein closed to") and the peak force ("2 %  13.3 N"): what summary.png shows at its foot, and what
// the trainer's report screen shows in the window (one picture, one textured quad to draw).
#pragma once

#include <filesystem>

#include "exam/exam_report.hpp"
#include "io/bitmap_font.hpp"
#include "io/png.hpp"

namespace echosim::exam {

struct SheetStyle {
    int width = 1552;      // [px] the sheet's
    int max_height = 0;    // [px] 0: as tall as its thumbnails; else they shrink to fit it (width fixed)
    int thumb_width = 296; // [px] the widest a thumbnail is
    int thumb_max_height = 0;  // [px] the tallest (0: as its width and the image's aspect make it)
    int gap = 16;          // [px] between thumbnails
    int caption_scale = 2; // the bitmap font's
    io::Rgba paper{255, 255, 255, 255}, ink{33, 33, 33, 255}, muted{117, 117, 117, 255}, placeholder{238, 238, 238, 255};
    bool status_frames = false;  // a frame round each thumbnail in its station's status colour (covered, skipped, wrong)
};

// The sheet of `report`'s station images, read from the report's folder `dir`; a station without
// an image is left out, one that cannot be read keeps its place with why. Empty (0 x 0) when no
// station has an image.
io::RgbaImage station_sheet(const ExamReport& report, const std::filesystem::path& dir, const SheetStyle& style = {});

}  // namespace echosim::exam

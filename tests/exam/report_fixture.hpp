// A hand-made exam report for the report and records tests: four stations, one of each outcome
// (covered, wrong call, skipped, and a covered thrombosed one), flagged errors, a force trace, and
// station images that the test writes as solid-colour PNGs.
#pragma once

#include <cmath>
#include <filesystem>
#include <string>

#include "exam/exam_report.hpp"
#include "io/png.hpp"

namespace echosim::exam::test {

inline ExamReport make_report()
{
    ExamReport r;
    r.trainee = "Ada Lovelace";
    r.case_id = "fv-isolated-acute";
    r.case_title = "Isolated acute clot of the femoral vein";
    r.protocol = "extended";
    r.pass_mark = 0.8;
    r.score = 0.625;
    r.passed = false;
    r.conclusion = "DVT not excluded: the femoral vein at 6 cm does not compress";
    r.dvt_present = true;
    r.adequate_force_N = 9;
    r.excessive_force_N = 30;

    StationResult cfv;
    cfv.name = "CFV";
    cfv.segment = "cfv";
    cfv.s_cm = 1.0;
    cfv.reached = true;
    cfv.reached_at_s = 2.0;
    cfv.offset_mm = 1.234;
    cfv.angle_deg = 3.5;
    cfv.peak_force_N = 14.25;
    cfv.deepest_press_at_s = 4.0;
    cfv.lumen_rest_mm2 = 95.5;
    cfv.lumen_pressed_mm2 = 2.125;
    cfv.collapse_ratio = 0.02225;
    cfv.artery_area_ratio = 0.93;
    cfv.call = Call::compressible;
    cfv.call_correct = true;
    cfv.image_png = "stations/cfv.png";

    StationResult sfj = cfv;
    sfj.name = "SFJ";
    sfj.s_cm = 2.5;
    sfj.reached_at_s = 7.0;
    sfj.deepest_press_at_s = 9.0;
    sfj.peak_force_N = 6.0;  // too little: flagged below
    sfj.collapse_ratio = 0.6;
    sfj.call = Call::not_compressible;
    sfj.call_correct = false;
    sfj.image_png = "stations/sfj.png";

    StationResult fv2 = cfv;
    fv2.name = "FV 2 cm";
    fv2.segment = "fv";
    fv2.s_cm = 6.0;
    fv2.reached = false;
    fv2.reached_at_s = -1;
    fv2.deepest_press_at_s = -1;
    fv2.peak_force_N = 0;
    fv2.call = Call::none;
    fv2.call_correct = false;
    fv2.image_png = "";

    StationResult fv6 = cfv;
    fv6.name = "FV 6 cm";
    fv6.segment = "fv";
    fv6.s_cm = 10.0;
    fv6.reached_at_s = 12.0;
    fv6.deepest_press_at_s = 14.5;
    fv6.peak_force_N = 18.0;
    fv6.collapse_ratio = 0.97;
    fv6.thrombosed = true;
    fv6.call = Call::not_compressible;
    fv6.call_correct = true;
    fv6.image_png = "stations/fv6.png";

    r.stations = {cfv, sfj, fv2, fv6};
    r.errors = {{ErrorKind::too_little_pressure, "SFJ", 9.0, "peak 6.0 N, adequate from 9.0 N"},
                {ErrorKind::wrong_call, "SFJ", 9.5, "called not compressible; the vein is patent"},
                {ErrorKind::skipped_station, "FV 2 cm", 16.0, "never reached"}};
    r.motion = {16.0, 312.5, 4.25, 11.0};
    r.osaus = {3, 2.5, 3};
    for (int i = 0; i <= 1600; ++i) {
        const double t = i * 0.01;
        r.force_trace.push_back({t, 10 + 8 * std::sin(t)});
    }
    return r;
}

// A solid-colour PNG of w x h at `path` (its folder made).
inline void write_solid_png(const std::filesystem::path& path, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint32_t w = 160,
                            std::uint32_t h = 120)
{
    std::filesystem::create_directories(path.parent_path());
    io::RgbaImage img;
    img.width = w;
    img.height = h;
    img.pixels.resize(std::size_t(w) * h * 4);
    for (std::size_t i = 0; i < img.pixels.size(); i += 4) {
        img.pixels[i] = r;
        img.pixels[i + 1] = g;
        img.pixels[i + 2] = b;
        img.pixels[i + 3] = 255;
    }
    io::write_png(path, img);
}

// The three station images of make_report() in `dir`: magenta, cyan and yellow.
inline void write_station_images(const std::filesystem::path& dir)
{
    write_solid_png(dir / "stations/cfv.png", 255, 0, 255);
    write_solid_png(dir / "stations/sfj.png", 0, 255, 255);
    write_solid_png(dir / "stations/fv6.png", 255, 255, 0);
}

}  // namespace echosim::exam::test

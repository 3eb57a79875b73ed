// Reconstruction of recordings written the way the PLUS toolkit writes them: a three-letter
// orientation, the tracker's transforms per frame (ProbeToTracker, ReferenceToTracker, a stylus the
// tracker lost), the calibration only in the device-set configuration, frames whose image or
// transform is INVALID. Checked against expectations made here, not by the reader: a tiny sweep's
// voxels against nearest-neighbour means worked out by hand, and a known object's position and size.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/matrix.hpp>

#include <gtest/gtest.h>

#include "app/commands.hpp"
#include "io/text_fields.hpp"
#include "io/volume_file.hpp"
#include "test_files.hpp"

namespace echosim::app {
namespace {

std::filesystem::path temp(const std::string& name) { return test::temp_path("plus_reconstruct", name); }

std::string row_major(const glm::dmat4& m)
{
    std::string s;
    for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) s += (s.empty() ? "" : " ") + io::text::format_double(m[c][r]);
    return s;
}

// The tracker's view of a frame: where the probe and the reference marker were, or that it lost one.
struct RecordedFrame {
    glm::dmat4 probe_to_tracker{1.0};
    glm::dmat4 reference_to_tracker{1.0};
    bool probe_ok = true;
    bool image_ok = true;
    std::vector<std::uint8_t> pixels;  // width x height, as the file stores them
};

// A sequence file as PLUS's vtkPlusMetaImageSequenceIO writes one.
void write_plus_recording(const std::filesystem::path& path, int width, int height, const std::string& orientation,
                          const std::vector<RecordedFrame>& frames)
{
    std::string h = "ObjectType = Image\nNDims = 3\nAnatomicalOrientation = RAI\nBinaryData = True\nBinaryDataByteOrderMSB = False\n"
                    "CenterOfRotation = 0 0 0\nCompressedData = False\n";
    h += "DimSize = " + std::to_string(width) + " " + std::to_string(height) + " " + std::to_string(frames.size()) + "\n";
    h += "ElementNumberOfChannels = 1\nElementSpacing = 1 1 1\nKinds = domain domain list                      \nOffset = 0 0 0\n"
         "TransformMatrix = 1 0 0 0 1 0 0 0 1\nUltrasoundImageOrientation = " + orientation + "\nUltrasoundImageType = BRIGHTNESS\n";
    std::string data;
    for (std::size_t f = 0; f < frames.size(); ++f) {
        char label[32];
        std::snprintf(label, sizeof label, "Seq_Frame%04zu_", f);
        const RecordedFrame& fr = frames[f];
        h += label + std::string("FrameNumber = ") + std::to_string(f) + "\n";
        h += label + std::string("ImageStatus = ") + (fr.image_ok ? "OK" : "INVALID") + "\n";
        h += label + std::string("ProbeToTrackerTransform = ") + row_major(fr.probe_to_tracker) + "\n";
        h += label + std::string("ProbeToTrackerTransformStatus = ") + (fr.probe_ok ? "OK" : "INVALID") + "\n";
        h += label + std::string("ReferenceToTrackerTransform = ") + row_major(fr.reference_to_tracker) + "\n";
        h += label + std::string("ReferenceToTrackerTransformStatus = OK\n");
        h += label + std::string("StylusToTrackerTransform = 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0\n");  // another tool, lost
        h += label + std::string("StylusToTrackerTransformStatus = INVALID\n");
        h += label + std::string("Timestamp = ") + std::to_string(100.0 + 0.033 * double(f)) + "\n";
        h += label + std::string("UnfilteredTimestamp = ") + std::to_string(100.0 + 0.033 * double(f)) + "\n";
        data.append(fr.pixels.begin(), fr.pixels.end());
    }
    h += "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n";
    test::write_bytes(path, h + data);
}

std::string plus_config(const glm::dmat4& image_to_probe, const std::string& reconstruction)
{
    return "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n<PlusConfiguration version=\"2.1\">\n"
           "  <DataCollection StartupDelaySec=\"1.0\"><DeviceSet Name=\"test\" Description=\"a saved sweep\"/></DataCollection>\n"
           "  <CoordinateDefinitions>\n"
           "    <Transform From=\"Image\" To=\"Probe\" Matrix=\"" + row_major(image_to_probe) + "\" Error=\"0.5\" Date=\"2026.11.23\"/>\n"
           "  </CoordinateDefinitions>\n  " + reconstruction + "\n</PlusConfiguration>\n";
}

// Rigid motions the frames' transforms are made of: none is a simple axis step, so a reader that
// took a transform the wrong way round, or one of the wrong tool, lands voxels elsewhere.
glm::dmat4 rigid(double angle, const glm::dvec3& axis, const glm::dvec3& move)
{
    return glm::translate(glm::dmat4(1.0), move) * glm::rotate(glm::dmat4(1.0), angle, axis);
}

// ProbeToTracker that makes the chain (ReferenceToTracker)^-1 * ProbeToTracker * ImageToProbe equal
// the wanted ImageToReference.
glm::dmat4 probe_to_tracker_for(const glm::dmat4& image_to_reference, const glm::dmat4& reference_to_tracker,
                                const glm::dmat4& image_to_probe)
{
    return reference_to_tracker * image_to_reference * glm::inverse(image_to_probe);
}

io::Volume reconstruct(const std::filesystem::path& sweep, const std::filesystem::path& config, const std::string& out_name,
                       const std::function<void(ReconstructArgs&)>& more = {})
{
    ReconstructArgs args;
    args.sweep = sweep;
    args.config = config;
    args.out = temp(out_name);
    if (more) more(args);
    EXPECT_EQ(run_reconstruct(args), kExitOk);
    io::Volume v = io::read_volume(args.out);
    std::filesystem::remove(args.out);
    return v;
}

// Three frames of 3 x 2 pixels, 0.4 mm apart in x and y from (0.05, 0.05); frames at z = 0.05, 0.35
// and 0.85 mm; a 1 mm grid. Nearest voxel of pixel (c, r): x 0.05, 0.45, 0.85 -> 0, 0, 1; y 0.05,
// 0.45 -> 0, 0; z 0.05, 0.35 -> 0 and 0.85 -> 1 (no position on a half, where rounding would hang
// on the last bit of the chain's arithmetic). Two more frames lie on voxel (0, 0, 0) with 255s, one with its image INVALID, one with
// the probe's transform INVALID: they must not count.
TEST(PlusReconstruction, TinySweepVoxelsAreTheNearestNeighbourMeans)
{
    const glm::dmat4 image_to_probe = rigid(0.4, {1, 1, 0}, {-12, 3, 40}) * glm::scale(glm::dmat4(1.0), glm::dvec3(0.4, 0.4, 0.4));
    const auto frame_at = [&](double z, std::vector<std::uint8_t> pixels, int k) {
        RecordedFrame f;
        f.reference_to_tracker = rigid(0.3 + 0.1 * k, {0.2, 1, 0.3}, {200, -50, 1000 + k});  // the patient breathes
        const glm::dmat4 image_to_reference = glm::translate(glm::dmat4(1.0), glm::dvec3(0.05, 0.05, z)) *
                                              glm::scale(glm::dmat4(1.0), glm::dvec3(0.4, 0.4, 1));
        f.probe_to_tracker = probe_to_tracker_for(image_to_reference, f.reference_to_tracker, image_to_probe);
        f.pixels = std::move(pixels);
        return f;
    };
    std::vector<RecordedFrame> frames = {
        frame_at(0.05, {10, 20, 100, 30, 40, 110}, 0),
        frame_at(0.35, {50, 60, 120, 70, 80, 130}, 1),
        frame_at(0.85, {1, 3, 200, 5, 7, 220}, 2),
        frame_at(0.05, {255, 255, 255, 255, 255, 255}, 3),
        frame_at(0.15, {255, 255, 255, 255, 255, 255}, 4),
    };
    frames[3].image_ok = false;
    frames[4].probe_ok = false;
    const auto sweep = temp("tiny.igs.mha");
    const auto config = temp("tiny.xml");
    write_plus_recording(sweep, 3, 2, "MFA", frames);
    test::write_bytes(config, plus_config(image_to_probe, R"(<VolumeReconstruction OutputSpacing="1 1 1"
        Interpolation="NEAREST_NEIGHBOR" CompoundingMode="MEAN" FillHoles="OFF" Optimization="FULL" NumberOfThreads="1"/>)"));

    const io::Volume v = reconstruct(sweep, config, "tiny.nrrd");
    // PLUS's grid: origin floor(0.05 / 1) * 1 = 0; last index ceil(0.85) = 1, ceil(0.45) = 1, ceil(0.85) = 1
    ASSERT_EQ(v.size, (std::array<std::size_t, 3>{2, 2, 2}));
    EXPECT_NEAR(glm::length(v.origin), 0.0, 1e-9);
    EXPECT_NEAR(v.directions[0][0], 1.0, 1e-12);
    const std::uint8_t* g = v.as<const std::uint8_t>();
    EXPECT_EQ(g[v.index(0, 0, 0)], (10 + 20 + 30 + 40 + 50 + 60 + 70 + 80) / 8);  // 45
    EXPECT_EQ(g[v.index(1, 0, 0)], (100 + 110 + 120 + 130) / 4);                  // 115
    EXPECT_EQ(g[v.index(0, 0, 1)], (1 + 3 + 5 + 7) / 4);                          // 4
    EXPECT_EQ(g[v.index(1, 0, 1)], (200 + 220) / 2);                              // 210
    for (std::size_t i = 0; i < 2; ++i)
        for (std::size_t k = 0; k < 2; ++k) EXPECT_EQ(g[v.index(i, 1, k)], 0) << "no pixel reaches y = 1";

    // the same recording with its pixels stored upside down (MN): PLUS turns them back to MF
    for (RecordedFrame& f : frames) std::swap_ranges(f.pixels.begin(), f.pixels.begin() + 3, f.pixels.begin() + 3);
    write_plus_recording(sweep, 3, 2, "MND", frames);
    const io::Volume flipped = reconstruct(sweep, config, "tiny_mn.mha");
    EXPECT_EQ(flipped.data, v.data);
    std::filesystem::remove(sweep);
    std::filesystem::remove(config);
}

// A bright ball in a dim medium, swept by 0.25 mm-apart frames under an oblique calibration, the
// tracker's reference moving frame to frame: the ball must come back where it is and as big as it
// is, in PLUS's grid; without the configuration the calibration is missing and the error says so.
TEST(PlusReconstruction, AKnownObjectLandsAtItsTruePositionAndSize)
{
    const glm::dvec3 centre(21.3, 14.7, 9.6);
    const double radius = 4.0;                    // [mm]
    const int width = 120, height = 100;          // 0.25 mm pixels: 30 x 25 mm frames
    const glm::dmat4 image_to_probe = rigid(-0.3, {0, 0, 1}, {-15, 2, 5}) * glm::scale(glm::dmat4(1.0), glm::dvec3(0.25, 0.25, 1));
    std::vector<RecordedFrame> frames;
    for (int k = 0; k < 80; ++k) {
        // frames tilted about y a little, stepping 0.25 mm along their normal
        const glm::dmat4 image_to_reference = glm::translate(glm::dmat4(1.0), glm::dvec3(5, 2, 0.25 * k)) *
                                              glm::rotate(glm::dmat4(1.0), 0.05, glm::dvec3(0, 1, 0)) *
                                              glm::scale(glm::dmat4(1.0), glm::dvec3(0.25, 0.25, 1));
        RecordedFrame f;
        f.reference_to_tracker = rigid(0.02 * k, {0, 1, 0.2}, {300, 40, 900 - k});
        f.probe_to_tracker = probe_to_tracker_for(image_to_reference, f.reference_to_tracker, image_to_probe);
        f.pixels.resize(std::size_t(width * height));
        for (int r = 0; r < height; ++r)
            for (int c = 0; c < width; ++c) {
                const glm::dvec3 p(image_to_reference * glm::dvec4(c, r, 0, 1));
                f.pixels[std::size_t(r * width + c)] = glm::length(p - centre) <= radius ? 200 : 20;
            }
        frames.push_back(std::move(f));
    }
    frames[10].probe_ok = false;  // a blink of the tracker
    const auto sweep = temp("ball.igs.mha");
    const auto config = temp("ball.xml");
    write_plus_recording(sweep, width, height, "MFA", frames);
    test::write_bytes(config, plus_config(image_to_probe, R"(<VolumeReconstruction OutputSpacing="0.5 0.5 0.5"
        Interpolation="LINEAR" CompoundingMode="MEAN" FillHoles="ON" ReferenceCoordinateFrame="Reference" ImageCoordinateFrame="Image"/>)"));

    const io::Volume v = reconstruct(sweep, config, "ball.mha");
    // the ball's voxels: their centroid and extent along each axis
    glm::dvec3 sum(0.0), lo(1e9), hi(-1e9);
    double n = 0;
    const std::uint8_t* g = v.as<const std::uint8_t>();
    for (std::size_t k = 0; k < v.size[2]; ++k)
        for (std::size_t j = 0; j < v.size[1]; ++j)
            for (std::size_t i = 0; i < v.size[0]; ++i)
                if (g[v.index(i, j, k)] > 110) {
                    const glm::dvec3 p = v.origin + v.directions * glm::dvec3(double(i), double(j), double(k));
                    sum += p, n += 1;
                    lo = glm::min(lo, p), hi = glm::max(hi, p);
                }
    ASSERT_GT(n, 0);
    const glm::dvec3 found = sum / n;
    EXPECT_NEAR(found.x, centre.x, 0.25);
    EXPECT_NEAR(found.y, centre.y, 0.25);
    EXPECT_NEAR(found.z, centre.z, 0.25);
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(hi[a] - lo[a], 2 * radius, 1.0) << "diameter along axis " << a;
    // its volume: 4/3 pi r^3 = 268 mm^3, at 0.125 mm^3 a voxel
    EXPECT_NEAR(n * 0.125, 4.0 / 3.0 * M_PI * radius * radius * radius, 0.1 * 268);
    // PLUS's grid: axis-aligned, the origin on a whole multiple of the spacing
    EXPECT_EQ(v.directions, glm::dmat3(0.5));
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(std::remainder(v.origin[a], 0.5), 0.0, 1e-9) << a;

    // without the configuration: no calibration, and the message says which transform is missing
    ReconstructArgs args;
    args.sweep = sweep;
    args.out = temp("ball_nocalibration.nrrd");
    EXPECT_EQ(run_reconstruct(args), kExitBadInput);
    EXPECT_FALSE(std::filesystem::exists(args.out));
    std::filesystem::remove(sweep);
    std::filesystem::remove(config);
}

// ---- issue 34: collapsed or empty volumes are refused, the command line overrides the file ------

// A run's exit status and what it said on stderr.
struct Outcome {
    int rc = -1;
    std::string err;
};
Outcome run_captured(const ReconstructArgs& args)
{
    testing::internal::CaptureStderr();
    Outcome r;
    r.rc = run_reconstruct(args);
    r.err = testing::internal::GetCapturedStderr();
    return r;
}

// Ten frames of 8 x 6 pixels at 0.5 mm, 1 mm apart along z, through ImageToProbe from a
// configuration (`transform`: its Transform element's attributes) and `reconstruction`.
struct SmallCase {
    std::filesystem::path sweep, config;
    ReconstructArgs args(const std::string& out) const
    {
        ReconstructArgs a;
        a.sweep = sweep;
        a.config = config;
        a.out = temp(out);
        return a;
    }
};
SmallCase small_case(const std::string& name, const std::string& image_to_probe_matrix, const std::string& reconstruction,
                     const std::function<glm::dmat4(int)>& probe_to_tracker = {})
{
    std::vector<RecordedFrame> frames;
    for (int k = 0; k < 10; ++k) {
        RecordedFrame f;
        f.probe_to_tracker = probe_to_tracker ? probe_to_tracker(k) : glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, k));
        f.pixels.assign(48, std::uint8_t(100 + k));
        frames.push_back(std::move(f));
    }
    SmallCase c{temp(name + ".igs.mha"), temp(name + ".xml")};
    write_plus_recording(c.sweep, 8, 6, "MF", frames);
    test::write_bytes(c.config,
                      "<PlusConfiguration version=\"2.1\">\n<CoordinateDefinitions>\n"
                      "  <Transform From=\"Image\" To=\"Probe\" Matrix=\"" + image_to_probe_matrix + "\"/>\n"
                      "</CoordinateDefinitions>\n" + reconstruction + "\n</PlusConfiguration>\n");
    return c;
}
const std::string kHalfMillimetre = "0.5 0 0 0  0 0.5 0 0  0 0 0.5 0  0 0 0 1";

void expect_refused(const Outcome& r, const ReconstructArgs& args, std::initializer_list<const char*> words)
{
    EXPECT_EQ(r.rc, kExitBadInput) << r.err;
    for (const char* w : words) EXPECT_NE(r.err.find(w), std::string::npos) << "'" << w << "' not in:\n" << r.err;
    EXPECT_FALSE(std::filesystem::exists(args.out)) << "a volume was written";
    std::filesystem::remove(args.out);
}

// The same small case is reconstructed (exit 0) when nothing is wrong with it: what the refusals
// below change is only the one thing they name.
TEST(PlusReconstructionChecks, TheSmallCaseItselfReconstructs)
{
    const SmallCase c = small_case("fine", kHalfMillimetre, "<VolumeReconstruction OutputSpacing=\"0.5 0.5 0.5\"/>");
    const ReconstructArgs args = c.args("fine.nrrd");
    const Outcome r = run_captured(args);
    EXPECT_EQ(r.rc, kExitOk) << r.err;
    const io::Volume v = io::read_volume(args.out);
    EXPECT_EQ(v.size, (std::array<std::size_t, 3>{8, 6, 19}));  // 3.5 x 2.5 x 9 mm at 0.5 mm
    std::filesystem::remove(args.out);
}

// Every frame at the identity (the probe never moved, a recording of ImageToReference = 1), and the
// reference frame named as the image's own: all frames in one plane, refused.
TEST(PlusReconstructionChecks, FramesInOnePlaneAreRefused)
{
    const SmallCase still = small_case("still", kHalfMillimetre, "", [](int) { return glm::dmat4(1.0); });
    ReconstructArgs args = still.args("still.nrrd");
    expect_refused(run_captured(args), args, {"one plane", "the same ImageToReference"});

    // sliding within the frames' own plane spans no volume either
    const SmallCase sliding = small_case("sliding", kHalfMillimetre, "",
                                         [](int k) { return glm::translate(glm::dmat4(1.0), glm::dvec3(k, 0.5 * k, 0)); });
    args = sliding.args("sliding.nrrd");
    expect_refused(run_captured(args), args, {"one plane", "move only within it"});

    // one valid frame: the others' probe transforms INVALID
    const SmallCase one = small_case("one", kHalfMillimetre, "");
    std::string text = test::read_bytes(one.sweep);
    for (int k = 1; k < 10; ++k) {
        char field[80];
        std::snprintf(field, sizeof field, "Seq_Frame%04d_ProbeToTrackerTransformStatus = OK", k);
        text = test::with(text, field, std::string(field, std::strlen(field) - 2) + "INVALID");
    }
    test::write_bytes(one.sweep, text);
    args = one.args("one.nrrd");
    expect_refused(run_captured(args), args, {"one frame has a valid image and transform"});

    const SmallCase fine = small_case("itself", kHalfMillimetre, "");
    args = fine.args("itself.nrrd");
    args.image_to_reference = "Image";
    expect_refused(run_captured(args), args, {"both Image", "one plane"});
}

// Issue 34: names from the configuration are printed escaped, as the readers' errors are: a frame
// named with a terminal's escape sequence (tinyxml2 turns &#x1b; into the byte) and an element
// whose name holds a lone 0x9b (an 8-bit terminal's CSI) reach stderr as \x1b, \x07 and \x9b.
TEST(PlusReconstructionChecks, NamesFromTheConfigurationArePrintedEscaped)
{
    const SmallCase c = small_case("escape", kHalfMillimetre,
                                   "<VolumeReconstruction OutputSpacing=\"0.5 0.5 0.5\" ImageCoordinateFrame=\"&#x1b;]0;owned&#x07;\" "
                                   "ReferenceCoordinateFrame=\"&#x1b;]0;owned&#x07;\"/>");
    ReconstructArgs args = c.args("escape.nrrd");
    Outcome r = run_captured(args);
    expect_refused(r, args, {"both \\x1b]0;owned\\x07", "one plane"});
    for (const char raw : {'\x1b', '\x07'}) EXPECT_EQ(r.err.find(raw), std::string::npos) << r.err;

    // a warning naming an element the reconstruction does not know, in a run that succeeds
    const SmallCase odd = small_case("odd", kHalfMillimetre, "<VolumeReconstruction OutputSpacing=\"0.5 0.5 0.5\"><Odd\x9b" "Element/></VolumeReconstruction>");
    args = odd.args("odd.nrrd");
    r = run_captured(args);
    EXPECT_EQ(r.rc, kExitOk) << r.err;
    EXPECT_NE(r.err.find("Odd\\x9bElement"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('\x9b'), std::string::npos) << r.err;
    std::filesystem::remove(args.out);
}

// A calibration that flattens the image to a line, and a tracker transform that is singular.
TEST(PlusReconstructionChecks, ASingularCalibrationOrChainIsRefusedByName)
{
    // ImageToProbe's columns 0 and 1 parallel: every pixel of a row and a column on one line
    const SmallCase line = small_case("line", "0.5 0.5 0 0  0 0 0 0  0 0 0.5 0  0 0 0 1", "");
    ReconstructArgs args = line.args("line.nrrd");
    expect_refused(run_captured(args), args, {"ImageToProbe", "singular", "Seq_Frame0000"});

    // ProbeToTracker of frame 3 scaled to nothing along z
    const SmallCase flat = small_case("flat", kHalfMillimetre, "", [](int k) {
        glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, k));
        if (k == 3) m[1] = glm::dvec4(0, 0, 0, 0);
        return m;
    });
    args = flat.args("flat.nrrd");
    expect_refused(run_captured(args), args, {"Seq_Frame0003", "ProbeToTracker", "singular"});
}

// ClipRectangleOrigin past the frames: refused before any memory is taken for a grid (it spanned
// from the frames to the clip corner: gigabytes).
TEST(PlusReconstructionChecks, AClipRectangleOutsideTheFramesIsRefused)
{
    const SmallCase c = small_case("clip", kHalfMillimetre,
                                   "<VolumeReconstruction OutputSpacing=\"0.5 0.5 0.5\" ClipRectangleOrigin=\"4000 3000\" "
                                   "ClipRectangleSize=\"10 10\"/>");
    const ReconstructArgs args = c.args("clip.nrrd");
    expect_refused(run_captured(args), args, {"ClipRectangleOrigin 4000 3000", "outside the frames of 8 x 6", "clip.xml:"});

    // one that starts inside and reaches past them is cut to them, and said
    const SmallCase past = small_case("clip_past", kHalfMillimetre,
                                      "<VolumeReconstruction OutputSpacing=\"0.5 0.5 0.5\" ClipRectangleOrigin=\"2 2\" "
                                      "ClipRectangleSize=\"100 100\"/>");
    const ReconstructArgs cut = past.args("clip_past.nrrd");
    const Outcome r = run_captured(cut);
    EXPECT_EQ(r.rc, kExitOk) << r.err;
    EXPECT_NE(r.err.find("the clip rectangle reaches past the frames of 8 x 6 pixels"), std::string::npos) << r.err;
    EXPECT_EQ(io::read_volume(cut.out).size, (std::array<std::size_t, 3>{6, 4, 19}));  // pixels 2..7, 2..5: 2.5 x 1.5 mm
    std::filesystem::remove(cut.out);
}

// OutputOrigin/OutputExtent 1 m away from every frame: refused; and with --grid sweep the frames'
// own grid is used instead, as the README says of command-line options, with a warning.
TEST(PlusReconstructionChecks, AnOutputGridNoFrameReachesIsRefusedAndGridOverridesIt)
{
    const SmallCase c = small_case("away", kHalfMillimetre,
                                   "<VolumeReconstruction OutputSpacing=\"0.5 0.5 0.5\" OutputOrigin=\"1000 0 0\" "
                                   "OutputExtent=\"0 9 0 9 0 9\"/>");
    ReconstructArgs args = c.args("away.nrrd");
    expect_refused(run_captured(args), args, {"OutputOrigin and OutputExtent", "reached by none of the 10 frames"});

    for (const char* grid : {"sweep", "plus"}) {
        args.grid = grid;
        const Outcome r = run_captured(args);
        ASSERT_EQ(r.rc, kExitOk) << r.err;
        EXPECT_NE(r.err.find(std::string("not used: --grid ") + grid), std::string::npos) << r.err;
        const io::Volume v = io::read_volume(args.out);
        EXPECT_LT(v.origin.x, 10.0) << grid << ": the frames' grid, not the configuration's at x = 1000 mm";
        std::filesystem::remove(args.out);
    }
}

// Each command-line option over its configuration field (README: "Command-line options override
// the file"): the configuration asks for nearest neighbour, maximum, no hole filling, 1 mm voxels
// and PLUS's frame names; the command line for trilinear, mean, holes filled, 0.5 mm, and the
// tracker's frame. The run's summary line says what was used.
TEST(PlusReconstructionChecks, EachOptionOverridesItsConfigurationField)
{
    const SmallCase c = small_case("override", kHalfMillimetre,
                                   "<VolumeReconstruction OutputSpacing=\"1 1 1\" Interpolation=\"NEAREST_NEIGHBOR\" "
                                   "CompoundingMode=\"MAXIMUM\" FillHoles=\"OFF\" ImageCoordinateFrame=\"Image\" "
                                   "ReferenceCoordinateFrame=\"Reference\"/>");
    ReconstructArgs args = c.args("override.nrrd");
    testing::internal::CaptureStdout();
    EXPECT_EQ(run_reconstruct(args), kExitOk);
    std::string said = testing::internal::GetCapturedStdout();
    EXPECT_NE(said.find("nearest neighbour interpolation, maximum compounding, holes left empty; PLUS's grid"), std::string::npos) << said;
    EXPECT_NE(said.find("of 1 x 1 x 1 mm in Reference"), std::string::npos) << said;

    args.splat = "trilinear";
    args.compound = "mean";
    args.fill_holes = "on";
    args.voxel_mm = 0.5;
    args.image_to_reference = "Tracker";
    testing::internal::CaptureStdout();
    EXPECT_EQ(run_reconstruct(args), kExitOk);
    said = testing::internal::GetCapturedStdout();
    EXPECT_NE(said.find("trilinear interpolation, mean compounding, holes filled; PLUS's grid"), std::string::npos) << said;
    EXPECT_NE(said.find("of 0.5 x 0.5 x 0.5 mm in Tracker"), std::string::npos) << said;
    std::filesystem::remove(args.out);
}

// The recording holds ImageToProbe too (file-wide): the recording's is used, and the
// configuration's is named in a warning, not replaced unsaid.
TEST(PlusReconstructionChecks, AConfigurationTransformTheRecordingAlsoHoldsIsNamed)
{
    const SmallCase c = small_case("twice", kHalfMillimetre, "<VolumeReconstruction OutputSpacing=\"0.5 0.5 0.5\"/>");
    std::string recording = test::read_bytes(c.sweep);
    recording = test::with(recording, "ElementType = MET_UCHAR",
                           "ImageToProbeTransform = 0.5 0 0 0 0 0.5 0 0 0 0 0.5 0 0 0 0 1\nElementType = MET_UCHAR");
    test::write_bytes(c.sweep, recording);
    const ReconstructArgs args = c.args("twice.nrrd");
    const Outcome r = run_captured(args);
    EXPECT_EQ(r.rc, kExitOk) << r.err;
    EXPECT_NE(r.err.find("twice.xml:3: Transform: ImageToProbe is also in"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("the recording's is used"), std::string::npos) << r.err;
    std::filesystem::remove(args.out);
}

// --budget-mb values whose bytes wrap past 64 bits (2^44 MiB is 2^64 bytes: 0 once shifted) or
// exceed any machine's memory are refused naming the option.
TEST(PlusReconstructionChecks, BudgetsThatWrapOrExceedTheMachineAreRefused)
{
    const SmallCase c = small_case("budget", kHalfMillimetre, "");
    ReconstructArgs args = c.args("budget.nrrd");
    for (const std::uint64_t mb : {std::uint64_t(1) << 44, (std::uint64_t(1) << 44) + 16, std::uint64_t(1) << 40, UINT64_MAX,
                                   std::uint64_t(0)}) {
        args.budget_mb = mb;
        expect_refused(run_captured(args), args, {"--budget-mb"});
    }
}

}  // namespace
}  // namespace echosim::app

#include "io/plus_sequence.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>

#include <unistd.h>

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include "io/partial_left.hpp"
#include "test_files.hpp"
#include <zlib.h>

namespace echosim::io {
namespace {

using test::read_bytes;
using test::with;
using test::write_bytes;

std::filesystem::path temp(const std::string& name) { return test::temp_path("plus_test", name); }

// `text` with the whole line starting with `start` replaced by `line` (empty: removed).
std::string with_line(std::string text, const std::string& start, const std::string& line)
{
    const auto at = text.find("\n" + start);
    EXPECT_NE(at, std::string::npos) << "no line '" << start << "' in the test file";
    if (at == std::string::npos) return text;
    const auto end = text.find('\n', at + 1);
    text.replace(at + 1, end - at, line.empty() ? "" : line + "\n");
    return text;
}

// `text` without any line starting with `start`.
std::string without_lines(std::string text, const std::string& start)
{
    for (auto at = text.find("\n" + start); at != std::string::npos; at = text.find("\n" + start))
        text.erase(at + 1, text.find('\n', at + 1) - at);
    return text;
}

// glm from 16 numbers row by row, as PLUS writes them.
glm::dmat4 row_major(std::initializer_list<double> v)
{
    glm::dmat4 m{0.0};
    int i = 0;
    for (const double x : v) {
        m[i % 4][i / 4] = x;
        ++i;
    }
    return m;
}

// A sweep of `n` frames with a different pose per frame; frame 2 (when there) has an invalid transform.
Sweep make_sweep(std::uint32_t width, std::uint32_t height, std::size_t n)
{
    Sweep s;
    s.width = width;
    s.height = height;
    s.pixels.resize(std::size_t(width) * height * n);
    for (std::size_t i = 0; i < s.pixels.size(); ++i) s.pixels[i] = std::uint8_t((i * 31 + i / 7) & 0xff);
    for (std::size_t f = 0; f < n; ++f) {
        TrackedFrame frame;
        frame.timestamp = 12.5 + double(f) / 3.0;
        const double d = double(f);
        frame.image_to_reference = glm::scale(glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(1.5 * d, -2.0, 30.25)),
                                                          0.1 * d + 0.05, glm::dvec3(0.3, 1.0, -0.2)),
                                              glm::dvec3(0.1, 0.1, 1.0));
        frame.valid = f != 2;
        s.frames.push_back(frame);
    }
    return s;
}

void expect_same_sweep(const Sweep& back, const Sweep& s)
{
    EXPECT_EQ(back.width, s.width);
    EXPECT_EQ(back.height, s.height);
    EXPECT_EQ(back.orientation, s.orientation);
    EXPECT_EQ(back.pixels, s.pixels);
    ASSERT_EQ(back.frames.size(), s.frames.size());
    for (std::size_t f = 0; f < s.frames.size(); ++f) {
        EXPECT_EQ(back.frames[f].timestamp, s.frames[f].timestamp) << f;
        EXPECT_EQ(back.frames[f].image_to_reference, s.frames[f].image_to_reference) << f;  // shortest round-trip text
        EXPECT_EQ(back.frames[f].valid, s.frames[f].valid) << f;
    }
}

// read_plus_sequence(path) must throw a PlusSequenceError naming the file and every one of `words`.
void expect_plus_error(const std::filesystem::path& path, std::initializer_list<const char*> words,
                       std::uint64_t budget = default_sweep_memory_budget)
{
    try {
        read_plus_sequence(path, budget);
        ADD_FAILURE() << "no error reading " << path;
    } catch (const PlusSequenceError& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find(path.string()), std::string::npos) << message;
        for (const char* word : words) EXPECT_NE(message.find(word), std::string::npos) << "no '" << word << "' in: " << message;
    }
}

// A 3-frame raw .mha as the writer makes it, to be spoiled by each bad-input case.
std::string good_mha()
{
    const auto path = temp("good.mha");
    write_plus_mha(path, make_sweep(4, 3, 3), false);
    std::string text = read_bytes(path);
    std::filesystem::remove(path);
    return text;
}

void expect_mha_error(const std::string& name, const std::string& file, std::initializer_list<const char*> words)
{
    const auto path = temp(name);
    write_bytes(path, file);
    expect_plus_error(path, words);
    std::filesystem::remove(path);
}

std::string gzip(const std::string& data)
{
    z_stream z{};
    EXPECT_EQ(deflateInit2(&z, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
    std::string out(data.size() + 64, '\0');
    z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
    z.avail_in = uInt(data.size());
    z.next_out = reinterpret_cast<Bytef*>(out.data());
    z.avail_out = uInt(out.size());
    EXPECT_EQ(deflate(&z, Z_FINISH), Z_STREAM_END);
    out.resize(z.total_out);
    deflateEnd(&z);
    return out;
}

TEST(PlusSequence, RoundTripsRawEveryPixelAndPose)
{
    const Sweep s = make_sweep(7, 5, 4);
    const auto path = temp("raw.mha");
    write_plus_mha(path, s, false);
    EXPECT_FALSE(test::partial_left_beside(path));

    const std::string bytes = read_bytes(path);
    const std::string head = "ObjectType = Image\nNDims = 3\nAnatomicalOrientation = RAI\nBinaryData = True\n"
                             "BinaryDataByteOrderMSB = False\nCenterOfRotation = 0 0 0\nCompressedData = False\nDimSize = 7 5 4\n";
    EXPECT_EQ(bytes.substr(0, head.size()), head);
    for (const char* line : {"\nElementNumberOfChannels = 1\n", "\nElementSpacing = 1 1 1\n", "\nOffset = 0 0 0\n",
                             "\nTransformMatrix = 1 0 0 0 1 0 0 0 1\n", "\nUltrasoundImageOrientation = MF\n",
                             "\nUltrasoundImageType = BRIGHTNESS\n", "\nSeq_Frame0000_ImageToReferenceTransform = ",
                             "\nSeq_Frame0000_ImageToReferenceTransformStatus = OK\n", "\nSeq_Frame0000_Timestamp = 12.5\n",
                             "\nSeq_Frame0002_ImageToReferenceTransformStatus = INVALID\n", "\nSeq_Frame0003_Timestamp = 13.5\n"})
        EXPECT_NE(bytes.find(line), std::string::npos) << line;
    const std::string tail = "\nElementType = MET_UCHAR\nElementDataFile = LOCAL\n";
    const auto data_at = bytes.find(tail) + tail.size();
    EXPECT_EQ(bytes.substr(data_at), std::string(s.pixels.begin(), s.pixels.end()));  // raw pixels right after the header

    expect_same_sweep(read_plus_sequence(path), s);
    std::filesystem::remove(path);
}

TEST(PlusSequence, RoundTripsCompressedEveryPixelAndPose)
{
    Sweep s = make_sweep(64, 48, 5);
    s.orientation = "UF";
    const auto path = temp("compressed.mha");
    write_plus_mha(path, s, true);
    const std::string bytes = read_bytes(path);
    EXPECT_NE(bytes.find("\nCompressedData = True\n"), std::string::npos);
    const auto size_at = bytes.find("\nCompressedDataSize = ");
    ASSERT_NE(size_at, std::string::npos);
    const std::string tail = "ElementDataFile = LOCAL\n";
    const auto data_at = bytes.find(tail) + tail.size();
    EXPECT_EQ(std::stoul(bytes.substr(size_at + 22)), bytes.size() - data_at);
    EXPECT_LT(bytes.size() - data_at, s.pixels.size());

    // read as PLUS reads it: turned to MF, each row mirrored (UF's x runs toward the unmarked side)
    Sweep mf = s;
    mf.orientation = "MF";
    for (std::size_t row = 0; row < mf.pixels.size() / mf.width; ++row)
        for (std::size_t c = 0; c < mf.width; ++c) mf.pixels[row * mf.width + c] = s.pixels[row * s.width + s.width - 1 - c];
    expect_same_sweep(read_plus_sequence(path), mf);
    std::filesystem::remove(path);
}

TEST(PlusSequence, ComposesProbeToTrackerWithImageToProbe)
{
    // as PLUS writes a tracked sweep without a reference tool: per frame the probe pose and the calibration
    const std::string image_to_probe = "0.1 0 0 -0.15 0 0.1 0 0 0 0 0.1 0 0 0 0 1";  // 0.1 mm pixels, centred array
    const std::string probe_to_tracker_0 = "0 -1 0 10 1 0 0 20 0 0 1 30 0 0 0 1";     // 90 degrees about z, moved
    const std::string probe_to_tracker_1 = "1 0 0 -5 0 0 -1 2.5 0 1 0 7 0 0 0 1";     // 90 degrees about x, moved
    std::string header = "ObjectType = Image\nNDims = 3\nAnatomicalOrientation = RAI\nBinaryData = True\n"
                         "BinaryDataByteOrderMSB = False\nCenterOfRotation = 0 0 0\nCompressedData = False\nDimSize = 3 2 2\n"
                         "ElementNumberOfChannels = 1\nElementSpacing = 1 1 1\nKinds = domain domain list\nOffset = 0 0 0\n"
                         "TransformMatrix = 1 0 0 0 1 0 0 0 1\nUltrasoundImageOrientation = MF\nUltrasoundImageType = BRIGHTNESS\n";
    header += "Seq_Frame0000_FrameNumber = 0\n"
              "Seq_Frame0000_ImageToProbeTransform = " + image_to_probe + "\n"
              "Seq_Frame0000_ImageToProbeTransformStatus = OK\n"
              "Seq_Frame0000_ProbeToTrackerTransform = " + probe_to_tracker_0 + "\n"
              "Seq_Frame0000_ProbeToTrackerTransformStatus = OK\n"
              "Seq_Frame0000_Timestamp = 1.25\n"
              "Seq_Frame0000_UnfilteredTimestamp = 1.2\n"
              "Seq_Frame0000_ImageStatus = OK\n"
              "Seq_Frame0001_FrameNumber = 1\n"
              "Seq_Frame0001_ImageToProbeTransform = " + image_to_probe + "\n"
              "Seq_Frame0001_ImageToProbeTransformStatus = OK\n"
              "Seq_Frame0001_ProbeToTrackerTransform = " + probe_to_tracker_1 + "\n"
              "Seq_Frame0001_ProbeToTrackerTransformStatus = MISSING\n"
              "Seq_Frame0001_Timestamp = 1.3\n"
              "Seq_Frame0001_ImageStatus = OK\n"
              "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n";
    const std::string pixels = "abcdefghijkl";
    const auto path = temp("probe_to_tracker.mha");
    write_bytes(path, header + pixels);

    const Sweep s = read_plus_sequence(path);
    EXPECT_EQ(s.width, 3u);
    EXPECT_EQ(s.height, 2u);
    EXPECT_EQ(std::string(s.pixels.begin(), s.pixels.end()), pixels);
    ASSERT_EQ(s.frames.size(), 2u);
    EXPECT_EQ(s.frames[0].timestamp, 1.25);
    EXPECT_EQ(s.frames[1].timestamp, 1.3);
    EXPECT_TRUE(s.frames[0].valid);
    EXPECT_FALSE(s.frames[1].valid);  // the tracker lost the probe

    const glm::dmat4 calibration = row_major({0.1, 0, 0, -0.15, 0, 0.1, 0, 0, 0, 0, 0.1, 0, 0, 0, 0, 1});
    const glm::dmat4 expected0 = row_major({0, -1, 0, 10, 1, 0, 0, 20, 0, 0, 1, 30, 0, 0, 0, 1}) * calibration;
    const glm::dmat4 expected1 = row_major({1, 0, 0, -5, 0, 0, -1, 2.5, 0, 1, 0, 7, 0, 0, 0, 1}) * calibration;
    EXPECT_EQ(s.frames[0].image_to_reference, expected0);
    EXPECT_EQ(s.frames[1].image_to_reference, expected1);
    // pixel (2, 1) of frame 0: (0.05, 0.1, 0) on the probe, turned about z and moved
    const glm::dvec4 p = s.frames[0].image_to_reference * glm::dvec4(2, 1, 0, 1);
    EXPECT_NEAR(p.x, 10 - 0.1, 1e-12);
    EXPECT_NEAR(p.y, 20 + 0.05, 1e-12);
    EXPECT_NEAR(p.z, 30, 1e-12);
    std::filesystem::remove(path);
}

TEST(PlusSequence, ReadsAFileWideCalibrationAnyPaddingAndCrLf)
{
    std::string header = "ObjectType = Image\r\nNDims = 3\r\nBinaryData = True\r\nCompressedData = False\r\nDimSize = 2 2 2\r\n"
                         "ImageToProbeTransform = 2 0 0 1 0 2 0 0 0 0 2 0 0 0 0 1   \r\n"
                         "Seq_Frame0_ProbeToReferenceTransform = 1 0 0 100 0 1 0 0 0 0 1 0 0 0 0 1\r\n"
                         "Seq_Frame0_ProbeToReferenceTransformStatus = OK\r\n"
                         "Seq_Frame0_Timestamp = 0\r\n"
                         "Seq_Frame00001_ProbeToReferenceTransform = 1 0 0 0 0 1 0 200 0 0 1 0 0 0 0 1\r\n"
                         "Seq_Frame00001_ProbeToReferenceTransformStatus = OK\r\n"
                         "Seq_Frame00001_Timestamp = 0.04\r\n"
                         "ElementType = MET_UCHAR\r\nElementDataFile = LOCAL\r\n";
    const auto path = temp("file_wide.mha");
    write_bytes(path, header + "\r\n\r\n\r\n\r\n");  // the pixels may well look like line ends
    const Sweep s = read_plus_sequence(path);
    EXPECT_EQ(std::string(s.pixels.begin(), s.pixels.end()), "\r\n\r\n\r\n\r\n");
    EXPECT_EQ(s.orientation, "MF");
    ASSERT_EQ(s.frames.size(), 2u);
    const glm::dmat4 calibration = row_major({2, 0, 0, 1, 0, 2, 0, 0, 0, 0, 2, 0, 0, 0, 0, 1});
    EXPECT_EQ(s.frames[0].image_to_reference, row_major({1, 0, 0, 100, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}) * calibration);
    EXPECT_EQ(s.frames[1].image_to_reference, row_major({1, 0, 0, 0, 0, 1, 0, 200, 0, 0, 1, 0, 0, 0, 0, 1}) * calibration);
    EXPECT_EQ(s.frames[1].timestamp, 0.04);
    std::filesystem::remove(path);
}

// A .seq.nrrd as PLUS writes it for a 2D sweep (sizes W H N, per-frame key/values).
std::string seq_nrrd_header(const std::string& encoding)
{
    return "NRRD0004\n# Complete NRRD file format specification at:\n# http://teem.sourceforge.net/nrrd/format.html\n"
           "dimension: 3\nencoding: " + encoding + "\nendian: little\nkinds: domain domain list\nsizes: 3 2 2\n"
           "space dimension: 2\nspace directions: (1,0) (0,1) none\nspace origin: (0,0)\ntype: unsigned char\n"
           "ultrasound image orientation:=MF\nultrasound image type:=BRIGHTNESS\n"
           "Seq_Frame0000_ImageToReferenceTransform:=0.2 0 0 5 0 0.2 0 6 0 0 0.2 7 0 0 0 1\n"
           "Seq_Frame0000_ImageToReferenceTransformStatus:=OK\n"
           "Seq_Frame0000_Timestamp:=100.5\n"
           "Seq_Frame0001_ImageToReferenceTransform:=0.2 0 0 5 0 0.2 0 6 0 0 0.2 9 0 0 0 1\n"
           "Seq_Frame0001_ImageToReferenceTransformStatus:=INVALID\n"
           "Seq_Frame0001_Timestamp:=100.55\n"
           "\n";
}

TEST(PlusSequence, ReadsSeqNrrdRawAndGzip)
{
    const std::string pixels = "ABCDEFabcdef";
    const auto path = temp("sweep.seq.nrrd");
    for (const bool gz : {false, true}) {
        write_bytes(path, seq_nrrd_header(gz ? "gz" : "raw") + (gz ? gzip(pixels) : pixels));
        const Sweep s = read_plus_sequence(path);
        EXPECT_EQ(s.width, 3u);
        EXPECT_EQ(s.height, 2u);
        EXPECT_EQ(std::string(s.pixels.begin(), s.pixels.end()), pixels);
        ASSERT_EQ(s.frames.size(), 2u);
        EXPECT_EQ(s.frames[0].image_to_reference, row_major({0.2, 0, 0, 5, 0, 0.2, 0, 6, 0, 0, 0.2, 7, 0, 0, 0, 1}));
        EXPECT_EQ(s.frames[1].image_to_reference[3], glm::dvec4(5, 6, 9, 1));
        EXPECT_EQ(s.frames[1].timestamp, 100.55);
        EXPECT_TRUE(s.frames[0].valid);
        EXPECT_FALSE(s.frames[1].valid);
    }
    // Slicer's 4D layout: sizes W H 1 N
    write_bytes(path, with(with(seq_nrrd_header("raw"), "sizes: 3 2 2", "sizes: 3 2 1 2"), "kinds: domain domain list",
                           "kinds: domain domain domain list") +
                          pixels);
    EXPECT_THROW(read_plus_sequence(path), PlusSequenceError);  // dimension 3 with 4 sizes
    write_bytes(path, with(with(with(seq_nrrd_header("raw"), "sizes: 3 2 2", "sizes: 3 2 1 2"), "kinds: domain domain list",
                                "kinds: domain domain domain list"),
                           "dimension: 3", "dimension: 4") +
                          pixels);
    EXPECT_EQ(read_plus_sequence(path).frames.size(), 2u);
    std::filesystem::remove(path);
}

TEST(PlusSequence, RejectsBadSeqNrrd)
{
    const auto path = temp("bad.seq.nrrd");
    write_bytes(path, seq_nrrd_header("raw") + "ABCDEFabcde");
    expect_plus_error(path, {"truncated", "11 bytes"});
    write_bytes(path, with(seq_nrrd_header("raw"), "type: unsigned char", "type: double") + std::string(96, 'x'));
    expect_plus_error(path, {"type", "double"});
    write_bytes(path, with(seq_nrrd_header("raw"), "Transform:=0.2 0 0 5 0 0.2 0 6 0 0 0.2 9", "Transform:=0.2 0 0 x 0 0.2 0 6 0 0 0.2 9") +
                          "ABCDEFabcdef");
    expect_plus_error(path, {"Seq_Frame0001_ImageToReferenceTransform", "'x'", "not a number"});
    write_bytes(path, seq_nrrd_header("gzip") + gzip("ABCDEFabcdef").substr(0, 12));
    expect_plus_error(path, {"truncated", "gzip"});
    std::filesystem::remove(path);
}

TEST(PlusSequence, RejectsBadMhaNamingFrameAndField)
{
    const std::string good = good_mha();
    const std::string header_end = "ElementDataFile = LOCAL\n";
    const std::string header = good.substr(0, good.find(header_end) + header_end.size());
    const std::string f2 = "Seq_Frame0002_ImageToReferenceTransform = ";

    expect_mha_error("truncated.mha", good.substr(0, good.size() - 1), {"ElementDataFile", "truncated", "35 bytes", "36"});
    expect_mha_error("noheaderend.mha", header.substr(0, header.size() - header_end.size()), {"truncated header", "ElementDataFile"});
    expect_mha_error("garbage.mha", "\x89PNG\r\n\x1a\n\x00\x00", {"not 'Name = Value'"});
    expect_mha_error("more_frames.mha", with(good, "DimSize = 4 3 3", "DimSize = 4 3 2"), {"Seq_Frame0002", "DimSize"});
    expect_mha_error("fewer_frames.mha", without_lines(with(good, "DimSize = 4 3 3", "DimSize = 4 3 4"), "Seq_Frame0002"),
                     {"Seq_Frame0002", "DimSize"});
    expect_mha_error("no_transform.mha", with_line(good, "Seq_Frame0001_ImageToReferenceTransform =", ""),
                     {"Seq_Frame0001", "no chain of transforms from Image to Reference", "ImageToReference"});
    const std::string f1 = "Seq_Frame0001_ImageToReferenceTransform = ";
    expect_mha_error("nan.mha", with_line(good, f1, f1 + "1 0 0 0 0 1 0 0 0 0 1 nan 0 0 0 1"),
                     {"Seq_Frame0001_ImageToReferenceTransform", "entry 11", "not finite"});
    expect_mha_error("text.mha", with_line(good, f2, f2 + "1 0 0 0 0 1 abc 0 0 0 1 0 0 0 0 1"),
                     {"Seq_Frame0002_ImageToReferenceTransform", "'abc'", "not a number"});
    expect_mha_error("twelve.mha", with_line(good, f2, f2 + "1 0 0 0 0 1 0 0 0 0 1 0"),
                     {"Seq_Frame0002_ImageToReferenceTransform", "16 numbers", "found 12"});
    expect_mha_error("projective.mha", with_line(good, f1, f1 + "1 0 0 0 0 1 0 0 0 0 1 0 0 0 0.5 1"),
                     {"Seq_Frame0001_ImageToReferenceTransform", "affine"});
    expect_mha_error("status.mha", with(good, "0001_ImageToReferenceTransformStatus = OK", "0001_ImageToReferenceTransformStatus = MAYBE"),
                     {"Seq_Frame0001_ImageToReferenceTransformStatus", "'MAYBE'"});
    expect_mha_error("timestamp.mha", with_line(good, "Seq_Frame0001_Timestamp", ""), {"Seq_Frame0001_Timestamp", "missing"});
    expect_mha_error("twice.mha", with(good, "Seq_Frame0001_Timestamp", "Seq_Frame1_Timestamp = 3\nSeq_Frame0001_Timestamp"),
                     {"Seq_Frame0001_Timestamp", "twice"});
    expect_mha_error("double.mha", with(good, "ElementType = MET_UCHAR", "ElementType = MET_DOUBLE"), {"ElementType", "'MET_DOUBLE'", "MET_UCHAR"});
    expect_mha_error("rgb.mha", with(good, "ElementNumberOfChannels = 1", "ElementNumberOfChannels = 3"), {"ElementNumberOfChannels"});
    expect_mha_error("detached.mha", with(good, "ElementDataFile = LOCAL", "ElementDataFile = sweep.raw"), {"ElementDataFile", "detached"});
    expect_mha_error("nodims.mha", with_line(good, "DimSize", ""), {"DimSize", "missing"});
    expect_mha_error("baddims.mha", with(good, "DimSize = 4 3 3", "DimSize = 4 three 3"), {"DimSize", "'three'"});
    expect_mha_error("orientation.mha", with(good, "UltrasoundImageOrientation = MF", "UltrasoundImageOrientation = XY"),
                     {"UltrasoundImageOrientation", "'XY'"});
    expect_mha_error("framename.mha", with(good, "Seq_Frame0001_Timestamp", "Seq_FrameX_Timestamp = 1\nSeq_Frame0001_Timestamp"),
                     {"Seq_FrameX_Timestamp", "malformed"});

    // ProbeToTracker with no calibration anywhere
    std::string probe = good;
    const std::string frame = "Seq_Frame000";
    for (int f = 0; f < 3; ++f)
        probe = with(probe, frame + std::to_string(f) + "_ImageToReferenceTransform", frame + std::to_string(f) + "_ProbeToTrackerTransform");
    expect_mha_error("nocalibration.mha", probe, {"Seq_Frame0000", "no chain of transforms from Image to Tracker", "ImageToProbe"});
}

// A tracker that lost the probe may leave anything in the matrix: the frame is skipped, not the file.
TEST(PlusSequence, AnInvalidTransformMayHoldAnything)
{
    const std::string f2 = "Seq_Frame0002_ImageToReferenceTransform = ";
    for (const char* junk : {"0 0 0 0 0 0 0 0 0 0 0 0 0 0 0 0", "nan nan nan nan nan nan nan nan nan nan nan nan nan nan nan nan"}) {
        const auto path = temp("junk.mha");
        write_bytes(path, with_line(good_mha(), f2, f2 + junk));
        const Sweep s = read_plus_sequence(path);
        ASSERT_EQ(s.frames.size(), 3u);
        EXPECT_TRUE(s.frames[1].valid);
        EXPECT_FALSE(s.frames[2].valid);
        std::filesystem::remove(path);
    }
}

TEST(PlusSequence, RejectsCorruptCompressedData)
{
    const Sweep s = make_sweep(32, 32, 3);
    const auto path = temp("corrupt.mha");
    write_plus_mha(path, s, true);
    const std::string good = read_bytes(path);
    const std::string header_end = "ElementDataFile = LOCAL\n";
    const std::size_t data_at = good.find(header_end) + header_end.size();

    std::string bad = good;
    for (std::size_t i = data_at; i < data_at + 8; ++i) bad[i] = char(0xff);
    write_bytes(path, bad);
    expect_plus_error(path, {"CompressedData", "fails to inflate"});
    bad = good;
    bad[bad.size() - 2] = char(bad[bad.size() - 2] ^ 0x21);  // the adler-32 checksum
    write_bytes(path, bad);
    expect_plus_error(path, {"CompressedData", "fails to inflate"});
    write_bytes(path, good.substr(0, good.size() - 10));
    expect_plus_error(path, {"CompressedDataSize", "truncated"});
    write_bytes(path, with(good, "DimSize = 32 32 3", "DimSize = 32 31 3"));
    expect_plus_error(path, {"CompressedData", "do not end"});
    std::filesystem::remove(path);
}

TEST(PlusSequence, InflatesNoMoreThanCompressedDataSizeAnnounces)
{
    const Sweep s = make_sweep(32, 32, 3);
    const auto path = temp("announced.mha");
    write_plus_mha(path, s, true);
    const std::string good = read_bytes(path);
    const auto size_at = good.find("\nCompressedDataSize = ") + 1;
    const std::string size_line = good.substr(size_at, good.find('\n', size_at) - size_at);
    const std::uint64_t packed = std::stoull(size_line.substr(21));

    // more bytes after the stream than the header announces: they are not the pixels' business
    write_bytes(path, good + "trailing bytes");
    expect_same_sweep(read_plus_sequence(path), s);
    // an announced size that stops inside the checksum, or halfway through the stream
    write_bytes(path, with(good, size_line, "CompressedDataSize = " + std::to_string(packed - 2)));
    expect_plus_error(path, {"CompressedData", "do not end", "cut stream"});
    write_bytes(path, with(good, size_line, "CompressedDataSize = " + std::to_string(packed / 2)));
    expect_plus_error(path, {"CompressedData", "fails to inflate", "ends after"});
    std::filesystem::remove(path);
}

TEST(PlusSequence, RejectsPixelsBeyondTheMemoryBudget)
{
    const auto path = temp("budget.mha");
    write_plus_mha(path, make_sweep(4, 3, 3), false);
    expect_plus_error(path, {"DimSize", "36 bytes", "memory budget of 35 bytes"}, 35);
    EXPECT_EQ(read_plus_sequence(path, 36).pixels.size(), 36u);
    write_bytes(path, with(read_bytes(path), "DimSize = 4 3 3", "DimSize = 4294967295 4294967295 4294967295"));
    expect_plus_error(path, {"DimSize", "overflow"});
    std::filesystem::remove(path);
}

TEST(PlusSequence, FailedWriteLeavesNoFile)
{
    const auto path = temp("failed.mha");
    Sweep s = make_sweep(4, 3, 3);
    s.frames[1].image_to_reference[3][2] = std::nan("");
    try {
        write_plus_mha(path, s, false);
        ADD_FAILURE() << "no error";
    } catch (const PlusSequenceError& e) {
        EXPECT_NE(std::string(e.what()).find("Seq_Frame0001_ImageToReferenceTransform"), std::string::npos) << e.what();
    }
    s = make_sweep(4, 3, 3);
    s.pixels.pop_back();
    EXPECT_THROW(write_plus_mha(path, s, true), PlusSequenceError);
    s = make_sweep(4, 3, 3);
    s.orientation = "up";
    EXPECT_THROW(write_plus_mha(path, s, false), PlusSequenceError);
    s = make_sweep(4, 3, 0);
    EXPECT_THROW(write_plus_mha(path, s, false), PlusSequenceError);
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_FALSE(test::partial_left_beside(path));

    const auto nowhere = std::filesystem::path("/nonexistent-echosim-folder/x.mha");
    EXPECT_THROW(write_plus_mha(nowhere, make_sweep(4, 3, 3), false), PlusSequenceError);
    EXPECT_FALSE(std::filesystem::exists(nowhere));
}


// `kinds: list domain domain`: the frame axis first, so the file interleaves the frames' pixels;
// pixel (x, y) of frame f is byte f + 2 * (x + 3 * y) here. Read wherever the axis stands.
TEST(PlusSequence, ReadsTheFrameAxisWhereverItStands)
{
    const std::string header = with(with(seq_nrrd_header("raw"), "kinds: domain domain list", "kinds: list domain domain"), "sizes: 3 2 2",
                                    "sizes: 2 3 2");
    std::string data(12, '\0');
    for (int f = 0; f < 2; ++f)
        for (int y = 0; y < 2; ++y)
            for (int x = 0; x < 3; ++x) data[std::size_t(f + 2 * (x + 3 * y))] = char('A' + 6 * f + 3 * y + x);
    const auto path = temp("list_first.seq.nrrd");
    write_bytes(path, header + data);
    const Sweep s = read_plus_sequence(path);
    EXPECT_EQ(s.width, 3u);
    EXPECT_EQ(s.height, 2u);
    EXPECT_EQ(std::string(s.pixels.begin(), s.pixels.end()), "ABCDEFGHIJKL");  // frame after frame, row after row
    std::filesystem::remove(path);
}

// Issue 13's finding: a compressed sweep whose DimSize claims gigabytes (within the budget) over a few
// bytes of payload made the reader reserve them all before finding the stream short. Now refused first.
TEST(PlusSequence, RefusesACompressedSweepClaimingMoreThanItCouldHold)
{
    const auto path = temp("claims_huge.mha");
    write_plus_mha(path, make_sweep(4, 3, 3), true);
    write_bytes(path, with(read_bytes(path), "DimSize = 4 3 3", "DimSize = 65536 16384 3"));
    expect_plus_error(path, {"CompressedData", "DimSize", "3221225472 bytes cannot come from", "1032"});
    std::filesystem::remove(path);
}

TEST(PlusSequence, RefusesWhatIsNotARegularFile)
{
    test::expect_special_files_refused<PlusSequenceError>("plus_test", [](const std::filesystem::path& p) { read_plus_recording(p); });
}

// Issue 13 (fuzzing): a transform from a frame to itself (ImageToImageTransform) escaped as a
// TransformError from default_reference_frame; the reader refuses it by name, in a frame or file-wide.
TEST(PlusSequence, RefusesATransformFromAFrameToItself)
{
    const std::string identity = " = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n";
    const std::string f1 = "Seq_Frame0001_ImageToReferenceTransform";
    expect_mha_error("itself.mha", with(good_mha(), f1, "Seq_Frame0001_ImageToImageTransform" + identity + f1),
                     {"Seq_Frame0001_ImageToImageTransform", "to itself"});
    expect_mha_error("itself_file.mha", with(good_mha(), "ElementType", "ProbeToProbeTransform" + identity + "ElementType"),
                     {"ProbeToProbeTransform", "to itself"});
}

// Issue 13 (fuzzing): a singular transform on the only chain, to be inverted (ReferenceToImage with a
// zero row), escaped as a TransformError from default_reference_frame; it is refused naming the frame.
TEST(PlusSequence, RefusesASingularTransformItWouldInvertNamingTheFrame)
{
    const std::string singular = "Seq_Frame0000_ReferenceToImageTransform = 0 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1";
    expect_mha_error("singular.mha", with_line(good_mha(), "Seq_Frame0000_ImageToReferenceTransform = ", singular),
                     {"Seq_Frame0000", "ReferenceToImage", "singular"});
}

// Issue 34: a 169 MB header of file-wide fields took 3.8 GB to parse. A header may hold 1 MiB and
// 4 KiB for each frame its sizes allow; past that it is refused before it is parsed. Here: 1.1 MiB
// of file-wide fields over a 4 x 3 x 3 sweep (4 KiB frames of allowance each: 1 MiB + 16 KiB), then
// the same fields spread over 400 frames of their own (1 MiB + 1.6 MiB allowed), which is read.
TEST(PlusSequence, RefusesAHeaderPastWhatItsFramesNeed)
{
    std::string junk;
    for (int i = 0; junk.size() < (std::size_t(11) << 20) / 10; ++i)
        junk += "Note" + std::to_string(i) + " = " + std::string(100, 'x') + "\n";
    expect_mha_error("long_header.mha", with(good_mha(), "\nElementType", "\n" + junk + "ElementType"),
                     {"header runs past", "more than a sequence of 4 frames needs", "1 MiB, and 4 KiB a frame"});

    const Sweep many = make_sweep(1, 1, 400);
    const auto path = temp("many_frames.mha");
    write_plus_mha(path, many, false);
    std::string text = read_bytes(path);
    std::string fields;
    for (std::size_t f = 0; f < 400; ++f) {
        char label[32];
        std::snprintf(label, sizeof label, "Seq_Frame%04zu_", f);
        fields += label + std::string("Note = ") + std::string(2900, 'y') + "\n";
    }
    text = with(text, "\nElementType", "\n" + fields + "ElementType");
    ASSERT_GT(text.size(), std::size_t(1) << 20);
    write_bytes(path, text);
    EXPECT_EQ(read_plus_sequence(path).frames.size(), 400u);
    std::filesystem::remove(path);
}

// Issue 34: a chain through a singular transform named the frame only when it had to be inverted;
// one used forward collapsed the frame with no word.
TEST(PlusSequence, RefusesASingularTransformOnTheChainNamingTheFrame)
{
    std::string text = good_mha();
    const std::string singular = "Seq_Frame0001_ImageToReferenceTransform = 0.3 0.6 0 1 0 0 0 2 0 0 1 3 0 0 0 1";
    text = with_line(text, "Seq_Frame0001_ImageToReferenceTransform =", singular);
    expect_mha_error("singular.mha", text, {"Seq_Frame0001", "ImageToReference is singular", "onto a line"});
}

// Issue 34: frames that each name a transform of their own made each frame copy and search every
// transform (frames x transforms). A recording's frames may name at most 64 different sets of
// transforms (a tracker's name the same ones in every frame); 64 are read, 65 refused.
TEST(PlusSequence, RefusesFramesNamingMoreThan64SetsOfTransforms)
{
    for (const std::size_t sets : {64u, 65u}) {
        const Sweep s = make_sweep(1, 1, sets);
        const auto path = temp("sets.mha");
        write_plus_mha(path, s, false);
        std::string text = read_bytes(path);
        std::string fields;
        for (std::size_t f = 0; f < sets; ++f) {
            char label[32];
            std::snprintf(label, sizeof label, "Seq_Frame%04zu_", f);
            fields += label + std::string("Tool") + std::to_string(f) + "ToStylusTransform = 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\n";
        }
        write_bytes(path, with(text, "\nElementType", "\n" + fields + "ElementType"));
        if (sets == 64) EXPECT_EQ(read_plus_sequence(path).frames.size(), 64u);
        else expect_plus_error(path, {"Seq_Frame0064", "more than 64 different sets of transforms"});
        std::filesystem::remove(path);
    }
}

}  // namespace
}  // namespace echosim::io

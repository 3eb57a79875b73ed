#include "io/nrrd.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <string>

#include <unistd.h>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include "io/partial_left.hpp"
#include "test_files.hpp"
#include "volume_samples.hpp"

namespace echosim::io {
namespace {

using test::read_bytes;
using test::with;
using test::write_bytes;

std::filesystem::path temp(const std::string& name) { return test::temp_path("nrrd_test", name); }

// The header 3D Slicer writes for a 4 x 3 x 2 unsigned char volume.
const std::string slicer_header =
    "NRRD0004\n"
    "# Complete NRRD file format specification at:\n"
    "# http://teem.sourceforge.net/nrrd/format.html\n"
    "type: unsigned char\n"
    "dimension: 3\n"
    "space: left-posterior-superior\n"
    "sizes: 4 3 2\n"
    "space directions: (0.5,0,0) (0,0.5,0) (0,0,2)\n"
    "kinds: domain domain domain\n"
    "endian: little\n"
    "encoding: raw\n"
    "space origin: (-10,20,5)\n"
    "\n";

std::string slicer_data()
{
    std::string data(24, '\0');
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = char(i * 10 + 1);
    return data;
}

// read_nrrd(path) must throw a NrrdError naming the file and every one of `words`.
void expect_nrrd_error(const std::filesystem::path& path, std::initializer_list<const char*> words,
                       std::uint64_t budget = default_nrrd_memory_budget)
{
    test::expect_error_naming<NrrdError>(path, words, [&] { read_nrrd(path, budget); });
}

void expect_header_error(const std::string& name, const std::string& header, std::initializer_list<const char*> words)
{
    const auto path = temp(name);
    write_bytes(path, header + slicer_data());
    expect_nrrd_error(path, words);
    std::filesystem::remove(path);
}

// The shared oblique volume, with a key/value needing escapes.
Volume oblique_volume(VoxelType type)
{
    Volume v = test::oblique_volume(type);
    v.key_values["note"] = "two\nlines \\ and a backslash";
    return v;
}

void expect_same_volume(const Volume& back, const Volume& v)
{
    EXPECT_EQ(back.size, v.size);
    EXPECT_EQ(back.type, v.type);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_EQ(back.directions[c][r], v.directions[c][r]) << c << "," << r;  // shortest round-trip text
    EXPECT_EQ(back.origin, v.origin);
    EXPECT_EQ(back.data, v.data);
    EXPECT_EQ(back.key_values, v.key_values);
}

TEST(Nrrd, RoundTripsRawEveryVoxelAndTheGeometry)
{
    const Volume v = oblique_volume(VoxelType::uint16);  // voxel i holds i * 997 + 3
    const auto path = temp("raw.nrrd");
    write_nrrd(path, v, false);
    EXPECT_FALSE(test::partial_left_beside(path));
    const std::string bytes = read_bytes(path);
    EXPECT_EQ(bytes.rfind("NRRD0004\n", 0), 0u);
    EXPECT_NE(bytes.find("space: left-posterior-superior\n"), std::string::npos);
    EXPECT_NE(bytes.find("encoding: raw\n"), std::string::npos);
    EXPECT_EQ(bytes.size() - bytes.find("\n\n") - 2, v.data.size());  // raw voxels right after the blank line

    const Volume back = read_nrrd(path);
    expect_same_volume(back, v);
    EXPECT_EQ(back.as<std::uint16_t>()[back.index(4, 3, 2)], std::uint16_t(59 * 997 + 3));
    std::filesystem::remove(path);
}

TEST(Nrrd, RoundTripsGzipEveryVoxelAndTheGeometry)
{
    const Volume v = oblique_volume(VoxelType::float32);
    const auto path = temp("gzip.nrrd");
    write_nrrd(path, v, true);
    const std::string bytes = read_bytes(path);
    EXPECT_NE(bytes.find("encoding: gzip\n"), std::string::npos);
    const auto data_at = bytes.find("\n\n") + 2;
    EXPECT_EQ(std::uint8_t(bytes[data_at]), 0x1f);  // the gzip magic, as teem writes it
    EXPECT_EQ(std::uint8_t(bytes[data_at + 1]), 0x8b);
    expect_same_volume(read_nrrd(path), v);
    std::filesystem::remove(path);
}

TEST(Nrrd, RoundTripsALabelMapOfManyVoxelsThroughGzip)
{
    // larger than zlib's and the reader's chunks, so the streaming loops turn over
    Volume v = make_volume({256, 128, 80}, VoxelType::uint8);
    for (std::size_t k = 0; k < 80; ++k)
        for (std::size_t j = 0; j < 128; ++j)
            for (std::size_t i = 0; i < 256; ++i) v.data[v.index(i, j, k)] = std::uint8_t((i / 16 + j / 8 + k) % 7);
    v.key_values["label_1"] = "skin";
    const auto path = temp("labels.nrrd");
    write_nrrd(path, v, true);
    EXPECT_LT(std::filesystem::file_size(path), v.data.size() / 10);
    EXPECT_EQ(read_nrrd(path).data, v.data);
    std::filesystem::remove(path);
}

TEST(Nrrd, RoundTripsOneImageAsSizesWxHx1)
{
    // an echographic image placed in the volume's space: lateral and depth steps, elevational normal
    Volume image = make_volume({6, 4, 1}, VoxelType::uint8);
    for (std::size_t i = 0; i < image.data.size(); ++i) image.data[i] = std::uint8_t(255 - i);
    image.directions = glm::dmat3(glm::dvec3(0.2, 0, 0), glm::dvec3(0, 0, -0.2), glm::dvec3(0, 1, 0));
    image.origin = {1, 2, 3};
    const auto path = temp("image.nrrd");
    write_nrrd(path, image, false);
    EXPECT_NE(read_bytes(path).find("sizes: 6 4 1\n"), std::string::npos);
    const Volume back = read_nrrd(path);
    expect_same_volume(back, image);
    const glm::dvec3 corner = back.index_to_world({5, 3, 0});
    EXPECT_DOUBLE_EQ(corner.x, 2.0);
    EXPECT_DOUBLE_EQ(corner.y, 2.0);
    EXPECT_DOUBLE_EQ(corner.z, 3.0 - 0.6);
    std::filesystem::remove(path);
}

TEST(Nrrd, ReadsTheHeaderSlicerWrites)
{
    const auto path = temp("slicer.nrrd");
    write_bytes(path, slicer_header + slicer_data());
    const Volume v = read_nrrd(path);
    EXPECT_EQ(v.size, (std::array<std::size_t, 3>{4, 3, 2}));
    EXPECT_EQ(v.type, VoxelType::uint8);
    EXPECT_EQ(v.directions, glm::dmat3(glm::dvec3(0.5, 0, 0), glm::dvec3(0, 0.5, 0), glm::dvec3(0, 0, 2)));
    EXPECT_EQ(v.origin, glm::dvec3(-10, 20, 5));
    EXPECT_EQ(std::string(v.data.begin(), v.data.end()), slicer_data());
    EXPECT_TRUE(v.key_values.empty());

    // voxel (3, 2, 1): the last of the second slice
    EXPECT_EQ(v.as<std::uint8_t>()[v.index(3, 2, 1)], 23 * 10 + 1);
    const glm::dvec3 world = v.index_to_world({3, 2, 1});
    EXPECT_DOUBLE_EQ(world.x, -8.5);
    EXPECT_DOUBLE_EQ(world.y, 21.0);
    EXPECT_DOUBLE_EQ(world.z, 7.0);
    const glm::dvec3 index = v.world_to_index(world);
    EXPECT_NEAR(index.x, 3.0, 1e-12);
    EXPECT_NEAR(index.y, 2.0, 1e-12);
    EXPECT_NEAR(index.z, 1.0, 1e-12);
    std::filesystem::remove(path);
}

TEST(Nrrd, ReadsFieldsInAnyOrderSynonymsAndKeyValues)
{
    const auto path = temp("reordered.nrrd");
    const std::string header = "NRRD0005\r\n"
                               "space origin: ( -10, 20, 5 )\r\n"
                               "encoding: raw\r\n"
                               "Segment1_Name:=femoral artery\r\n"
                               "space directions: (0.5, 0, 0) (0, 0.5, 0) (0, 0, 2)\r\n"
                               "sizes: 4 3 2\r\n"
                               "space: LPS\r\n"
                               "type: uchar\r\n"
                               "dimension: 3\r\n"
                               "\r\n";
    write_bytes(path, header + slicer_data());
    const Volume v = read_nrrd(path);
    EXPECT_EQ(v.origin, glm::dvec3(-10, 20, 5));
    EXPECT_EQ(v.directions[2], glm::dvec3(0, 0, 2));
    EXPECT_EQ(v.key_values.at("Segment1_Name"), "femoral artery");
    EXPECT_EQ(std::string(v.data.begin(), v.data.end()), slicer_data());

    for (const char* name : {"uchar", "unsigned char", "uint8", "UCHAR"}) {
        write_bytes(path, with(slicer_header, "type: unsigned char", std::string("type: ") + name) + slicer_data());
        EXPECT_EQ(read_nrrd(path).type, VoxelType::uint8) << name;
    }
    for (const char* name : {"ushort", "unsigned short", "uint16"}) {
        const std::string ushort_header = with(slicer_header, "type: unsigned char", std::string("type: ") + name);
        write_bytes(path, with(ushort_header, "sizes: 4 3 2", "sizes: 4 3 1") + slicer_data());  // 24 bytes: 12 voxels
        const Volume u = read_nrrd(path);
        EXPECT_EQ(u.type, VoxelType::uint16) << name;
        EXPECT_EQ(u.as<std::uint16_t>()[1], std::uint16_t(21 + 31 * 256)) << name;  // little endian
    }
    for (const char* name : {"short", "signed short", "short int", "int16"}) {
        const std::string short_header = with(slicer_header, "type: unsigned char", std::string("type: ") + name);
        write_bytes(path, with(short_header, "sizes: 4 3 2", "sizes: 4 3 1") + slicer_data());
        const Volume s = read_nrrd(path);
        EXPECT_EQ(s.type, VoxelType::int16) << name;
        EXPECT_EQ(s.as<std::int16_t>()[1], std::int16_t(21 + 31 * 256)) << name;
    }
    write_bytes(path, with(with(slicer_header, "type: unsigned char", "type: float"), "sizes: 4 3 2", "sizes: 3 2 1") + slicer_data());
    EXPECT_EQ(read_nrrd(path).type, VoxelType::float32);
    std::filesystem::remove(path);
}

TEST(Nrrd, ReadsGzAsGzip)
{
    Volume v = make_volume({4, 3, 2}, VoxelType::uint8);
    for (std::size_t i = 0; i < v.data.size(); ++i) v.data[i] = std::uint8_t(i + 40);
    const auto path = temp("gz.nrrd");
    write_nrrd(path, v, true);
    write_bytes(path, with(read_bytes(path), "encoding: gzip\n", "encoding: gz\n"));
    EXPECT_EQ(read_nrrd(path).data, v.data);
    std::filesystem::remove(path);
}

TEST(Nrrd, ConvertsRasToLps)
{
    const auto path = temp("ras.nrrd");
    std::string ras = with(slicer_header, "space: left-posterior-superior", "space: right-anterior-superior");
    ras = with(ras, "(0.5,0,0) (0,0.5,0) (0,0,2)", "(-0.5,0.1,0) (0,-0.5,0) (0.25,0.5,2)");
    ras = with(ras, "space origin: (-10,20,5)", "space origin: (10,-20,5)");
    for (const std::string& header : {ras, with(ras, "right-anterior-superior", "RAS")}) {
        write_bytes(path, header + slicer_data());
        const Volume v = read_nrrd(path);
        EXPECT_EQ(v.directions[0], glm::dvec3(0.5, -0.1, 0));
        EXPECT_EQ(v.directions[1], glm::dvec3(0, 0.5, 0));
        EXPECT_EQ(v.directions[2], glm::dvec3(-0.25, -0.5, 2));
        EXPECT_EQ(v.origin, glm::dvec3(-10, 20, 5));
        const glm::dvec3 world = v.index_to_world({1, 1, 1});
        EXPECT_DOUBLE_EQ(world.x, -10 + 0.5 - 0.25);
        EXPECT_DOUBLE_EQ(world.y, 20 - 0.1 + 0.5 - 0.5);
        EXPECT_DOUBLE_EQ(world.z, 7);
    }
    std::filesystem::remove(path);
}

TEST(Nrrd, IndexAndWorldAreInverse)
{
    const Volume v = oblique_volume(VoxelType::uint8);
    const glm::dvec3 ijk(2.5, 1.25, 0.75);
    const glm::dvec3 world = v.index_to_world(ijk);
    EXPECT_NEAR(glm::length(world - (v.origin + 2.5 * v.directions[0] + 1.25 * v.directions[1] + 0.75 * v.directions[2])), 0, 1e-12);
    EXPECT_NEAR(glm::length(v.world_to_index(world) - ijk), 0, 1e-12);
}

TEST(Nrrd, TypedAccessChecksTheVoxelType)
{
    Volume v = make_volume({2, 2, 2}, VoxelType::uint16);
    EXPECT_EQ(v.data.size(), 16u);
    EXPECT_NO_THROW(v.as<std::uint16_t>());
    EXPECT_THROW(v.as<float>(), std::logic_error);
    const Volume& cv = v;
    EXPECT_THROW(cv.as<const std::uint8_t>(), std::logic_error);
}

TEST(Nrrd, RejectsBadHeadersNamingFileAndField)
{
    expect_header_error("magic.nrrd", with(slicer_header, "NRRD0004", "NRRB0004"), {"magic"});
    expect_header_error("nosizes.nrrd", with(slicer_header, "sizes: 4 3 2\n", ""), {"'sizes'", "missing"});
    expect_header_error("badsizes.nrrd", with(slicer_header, "sizes: 4 3 2", "sizes: 4 x 2"), {"'sizes'", "'x'", "positive integer"});
    expect_header_error("zerosize.nrrd", with(slicer_header, "sizes: 4 3 2", "sizes: 4 0 2"), {"'sizes'", "positive integer"});
    expect_header_error("fewsizes.nrrd", with(slicer_header, "sizes: 4 3 2", "sizes: 4 3"), {"'sizes'", "dimension 3"});
    expect_header_error("hugesize.nrrd", with(slicer_header, "sizes: 4 3 2", "sizes: 4 3 99999999999999999999999"), {"'sizes'", "overflow"});
    expect_header_error("product.nrrd", with(slicer_header, "sizes: 4 3 2", "sizes: 4294967296 4294967296 2"), {"'sizes'", "overflow"});
    expect_header_error("budget.nrrd", with(slicer_header, "sizes: 4 3 2", "sizes: 4096 4096 1024"), {"'sizes'", "memory budget"});
    expect_header_error("nandir.nrrd", with(slicer_header, "(0,0.5,0)", "(0,nan,0)"), {"'space directions'", "non-finite"});
    expect_header_error("infdir.nrrd", with(slicer_header, "(0,0,2)", "(0,0,inf)"), {"'space directions'", "non-finite"});
    expect_header_error("nanorigin.nrrd", with(slicer_header, "(-10,20,5)", "(-10,NaN,5)"), {"'space origin'", "non-finite"});
    expect_header_error("textdir.nrrd", with(slicer_header, "(0,0,2)", "(0,zero,2)"), {"'space directions'", "'zero'", "not a number"});
    expect_header_error("shortdir.nrrd", with(slicer_header, "(0,0,2)", "(0,2)"), {"'space directions'", "components"});
    expect_header_error("singular.nrrd", with(slicer_header, "(0,0.5,0)", "(1,0,0)"), {"'space directions'", "singular"});
    expect_header_error("big.nrrd", with(with(slicer_header, "endian: little", "endian: big"), "type: unsigned char", "type: ushort"),
                        {"'endian'", "big-endian"});
    expect_header_error("detached.nrrd", with(slicer_header, "encoding: raw\n", "encoding: raw\ndata file: volume.raw\n"),
                        {"'data file'", "detached"});
    expect_header_error("int.nrrd", with(slicer_header, "type: unsigned char", "type: int"), {"'type'", "'int'", "not supported"});
    expect_header_error("text.nrrd", with(slicer_header, "encoding: raw", "encoding: ascii"), {"'encoding'", "not supported"});
    expect_header_error("dim2.nrrd", with(with(slicer_header, "dimension: 3", "dimension: 2"), "sizes: 4 3 2", "sizes: 4 6"),
                        {"'dimension'", "2D image"});
    expect_header_error("space.nrrd", with(slicer_header, "left-posterior-superior", "scanner-xyz"), {"'space'", "'scanner-xyz'"});
    expect_header_error("vector.nrrd", with(slicer_header, "kinds: domain domain domain", "kinds: vector domain domain"), {"'kinds'", "scalar"});
    expect_header_error("twice.nrrd", with(slicer_header, "encoding: raw\n", "encoding: raw\nencoding: gzip\n"), {"'encoding'", "twice"});
    expect_header_error("garbage.nrrd", with(slicer_header, "kinds: domain domain domain\n", "kinds domain domain domain\n"),
                        {"neither 'field: value' nor 'key:=value'"});
}

TEST(Nrrd, RejectsAHeaderWithoutItsBlankLine)
{
    const auto path = temp("noblank.nrrd");
    write_bytes(path, slicer_header.substr(0, slicer_header.size() - 1));
    expect_nrrd_error(path, {"blank line", "truncated"});
    std::filesystem::remove(path);
}

// Issue 34: a header of megabytes (here 1.5 MiB of comments, then key/values) is junk, refused as it
// is read instead of kept line by line (a 169 MB one took 3.8 GB); one just under 1 MiB is read.
TEST(Nrrd, RejectsAHeaderLongerThanAVolumeNeeds)
{
    const std::string comments = [] {
        std::string c;
        for (int i = 0; i < 1500; ++i) c += "# " + std::string(1022, 'x') + "\n";
        return c;
    }();
    const auto at = slicer_header.find('\n') + 1;
    expect_header_error("long_header.nrrd", slicer_header.substr(0, at) + comments + slicer_header.substr(at),
                        {"the header runs past 1048576 bytes", "not a volume's header"});
    const auto path = temp("long_ok.nrrd");
    write_bytes(path, slicer_header.substr(0, at) + comments.substr(0, 1000 * 1025) + slicer_header.substr(at) + slicer_data());
    EXPECT_NO_THROW(read_nrrd(path));
    std::filesystem::remove(path);
}

TEST(Nrrd, RejectsDataBeyondTheMemoryBudget)
{
    const auto path = temp("budget.nrrd");
    write_bytes(path, slicer_header + slicer_data());
    expect_nrrd_error(path, {"'sizes'", "24 bytes", "memory budget of 23 bytes"}, 23);
    EXPECT_NO_THROW(read_nrrd(path, 24));
    std::filesystem::remove(path);
}

TEST(Nrrd, RejectsTruncatedRawData)
{
    const auto path = temp("truncated.nrrd");
    write_bytes(path, slicer_header + slicer_data().substr(0, 23));
    expect_nrrd_error(path, {"truncated", "23 bytes", "24"});
    std::filesystem::remove(path);
}

TEST(Nrrd, RejectsTruncatedAndCorruptGzip)
{
    Volume v = make_volume({64, 64, 16}, VoxelType::uint8);
    for (std::size_t i = 0; i < v.data.size(); ++i) v.data[i] = std::uint8_t((i * 7919) >> 5);
    const auto path = temp("corrupt.nrrd");
    write_nrrd(path, v, true);
    const std::string good = read_bytes(path);
    const std::size_t data_at = good.find("\n\n") + 2;

    // cut in the middle of the deflate stream
    write_bytes(path, good.substr(0, data_at + (good.size() - data_at) / 2));
    expect_nrrd_error(path, {"truncated", "gzip"});
    // cut off only the checksum at the end: every voxel is there, but the data cannot be trusted
    write_bytes(path, good.substr(0, good.size() - 8));
    expect_nrrd_error(path, {"truncated gzip", "checksum"});
    // a wrong checksum
    std::string bad = good;
    bad[bad.size() - 8] = char(bad[bad.size() - 8] ^ 0x5a);
    write_bytes(path, bad);
    expect_nrrd_error(path, {"'encoding'", "corrupt gzip"});
    // garbage in place of the gzip header
    bad = good;
    for (std::size_t i = data_at; i < data_at + 16; ++i) bad[i] = char(0xff);
    write_bytes(path, bad);
    expect_nrrd_error(path, {"'encoding'", "corrupt gzip"});
    std::filesystem::remove(path);
}

TEST(Nrrd, FailedWriteLeavesNoFile)
{
    const auto path = temp("failed.nrrd");
    Volume v = make_volume({4, 4, 4}, VoxelType::uint8);
    v.data.pop_back();
    EXPECT_THROW(write_nrrd(path, v, false), NrrdError);
    v.data.push_back(0);
    v.directions[1] = v.directions[0];
    EXPECT_THROW(write_nrrd(path, v, true), NrrdError);
    v.directions = glm::dmat3(1.0);
    v.origin.y = std::nan("");
    EXPECT_THROW(write_nrrd(path, v, false), NrrdError);
    v.origin.y = 0;
    for (const char* key : {"", "# comment", "a:=b", "type: float"}) {
        Volume keyed = v;
        keyed.key_values[key] = "x";
        EXPECT_THROW(write_nrrd(path, keyed, false), NrrdError) << key;
    }
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_FALSE(test::partial_left_beside(path));

    v.origin.y = 0;
    const auto nowhere = std::filesystem::path("/nonexistent-echosim-folder/x.nrrd");
    try {
        write_nrrd(nowhere, v, false);
        ADD_FAILURE() << "no error";
    } catch (const NrrdError& e) {
        EXPECT_NE(std::string(e.what()).find(nowhere.string()), std::string::npos) << e.what();
    }
    EXPECT_FALSE(std::filesystem::exists(nowhere));
}

// Sizes within the budget but beyond what the gzip data could inflate to (issue 13: 4 GiB claimed
// over 1 KB of zeros) are refused before the memory is taken.
TEST(Nrrd, RefusesGzipDataClaimingMoreThanItCouldHold)
{
    const auto path = temp("claims_huge.nrrd");
    Volume small = make_volume({10, 10, 10}, VoxelType::uint8);
    write_nrrd(path, small, true);
    write_bytes(path, with(read_bytes(path), "sizes: 10 10 10", "sizes: 2048 2048 1024"));
    expect_nrrd_error(path, {"'sizes'", "4294967296 bytes cannot come from", "1032"});
    std::filesystem::remove(path);
}

TEST(Nrrd, RefusesWhatIsNotARegularFile)
{
    test::expect_special_files_refused<NrrdError>("nrrd_test", [](const std::filesystem::path& p) { read_nrrd(p); });
}

}  // namespace
}  // namespace echosim::io

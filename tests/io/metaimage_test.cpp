#include "io/metaimage.hpp"
#include "io/volume_file.hpp"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <initializer_list>
#include <string>

#include <glm/geometric.hpp>

#include <gtest/gtest.h>
#include <zlib.h>

#include "io/partial_left.hpp"
#include "test_files.hpp"
#include "volume_samples.hpp"

namespace echosim::io {
namespace {

using test::oblique_volume;
using test::read_bytes;
using test::with;
using test::write_bytes;

std::filesystem::path temp(const std::string& name) { return test::temp_path("metaimage_test", name); }

// The header ITK (and so 3D Slicer) writes for a 4 x 3 x 2 unsigned char volume whose i axis runs
// along +y (posterior), j along -x (right) and k along +z, with anisotropic voxels.
const std::string itk_header =
    "ObjectType = Image\n"
    "NDims = 3\n"
    "BinaryData = True\n"
    "BinaryDataByteOrderMSB = False\n"
    "CompressedData = False\n"
    "TransformMatrix = 0 1 0 -1 0 0 0 0 1\n"
    "Offset = -10 20 5\n"
    "CenterOfRotation = 0 0 0\n"
    "AnatomicalOrientation = ALI\n"
    "ElementSpacing = 0.5 0.25 2\n"
    "DimSize = 4 3 2\n"
    "ElementType = MET_UCHAR\n"
    "ElementDataFile = LOCAL\n";

std::string itk_data()
{
    std::string data(24, '\0');
    for (std::size_t i = 0; i < data.size(); ++i) data[i] = char(i * 10 + 1);
    return data;
}

// read_metaimage_volume(path) must throw a MetaImageError naming the file and every one of `words`.
void expect_error(const std::filesystem::path& path, std::initializer_list<const char*> words,
                  std::uint64_t budget = default_metaimage_memory_budget)
{
    test::expect_error_naming<MetaImageError>(path, words, [&] { read_metaimage_volume(path, budget); });
}

void expect_file_error(const std::string& name, const std::string& file, std::initializer_list<const char*> words)
{
    const auto path = temp(name);
    write_bytes(path, file);
    expect_error(path, words);
    std::filesystem::remove(path);
}

std::string zlib(const std::string& data)
{
    uLongf size = compressBound(uLong(data.size()));
    std::string out(size, '\0');
    EXPECT_EQ(compress(reinterpret_cast<Bytef*>(out.data()), &size, reinterpret_cast<const Bytef*>(data.data()), uLong(data.size())), Z_OK);
    out.resize(size);
    return out;
}

// Voxels and key/values bit-exact; geometry to 1e-12 mm: the file keeps each axis as its unit
// direction and its spacing, so the step comes back as their product, to within a rounding.
void expect_same_volume(const Volume& back, const Volume& v)
{
    EXPECT_EQ(back.size, v.size);
    EXPECT_EQ(back.type, v.type);
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(back.directions[c][r], v.directions[c][r], 1e-12) << c << "," << r;
    EXPECT_EQ(back.origin, v.origin);  // written as is, shortest round-trip text
    EXPECT_EQ(back.data, v.data);
    EXPECT_EQ(back.key_values, v.key_values);
}

TEST(MetaImage, RoundTripsEveryVoxelTypeRawAndCompressed)
{
    for (const VoxelType type : {VoxelType::uint8, VoxelType::uint16, VoxelType::int16, VoxelType::float32}) {
        for (const bool compressed : {false, true}) {
            SCOPED_TRACE(std::string(to_string(type)) + (compressed ? ", compressed" : ", raw"));
            const Volume v = oblique_volume(type);
            const auto path = temp("oblique.mha");
            write_metaimage_volume(path, v, compressed);
            EXPECT_FALSE(test::partial_left_beside(path));
            const std::string bytes = read_bytes(path);
            EXPECT_EQ(bytes.rfind("ObjectType = Image\nNDims = 3\n", 0), 0u);
            EXPECT_NE(bytes.find(compressed ? "CompressedData = True\nCompressedDataSize = " : "CompressedData = False\n"), std::string::npos);
            EXPECT_NE(bytes.find("Segment0_Name = femoral vein\n"), std::string::npos);
            const std::string end = "ElementDataFile = LOCAL\n";
            ASSERT_NE(bytes.find(end), std::string::npos);
            if (!compressed) {
                EXPECT_EQ(bytes.size() - bytes.find(end) - end.size(), v.data.size());  // the voxels right after
            }
            expect_same_volume(read_metaimage_volume(path), v);
            std::filesystem::remove(path);
        }
    }
}

TEST(MetaImage, WritesTheElementTypeAndOrientationItkWould)
{
    const auto path = temp("types.mha");
    for (const auto& [type, name] : {std::pair{VoxelType::uint8, "MET_UCHAR"}, std::pair{VoxelType::uint16, "MET_USHORT"},
                                     std::pair{VoxelType::int16, "MET_SHORT"}, std::pair{VoxelType::float32, "MET_FLOAT"}}) {
        write_metaimage_volume(path, make_volume({2, 2, 2}, type), false);
        const std::string bytes = read_bytes(path);
        EXPECT_NE(bytes.find(std::string("ElementType = ") + name + "\nElementDataFile = LOCAL\n"), std::string::npos) << name;
        // identity directions: ITK's "RAI" (each axis named by the side it comes from: LPS)
        EXPECT_NE(bytes.find("TransformMatrix = 1 0 0 0 1 0 0 0 1\n"), std::string::npos);
        EXPECT_NE(bytes.find("AnatomicalOrientation = RAI\n"), std::string::npos);
    }
    Volume v = make_volume({2, 2, 2}, VoxelType::uint8);
    v.directions = glm::dmat3(glm::dvec3(0, 0.5, 0), glm::dvec3(-0.25, 0, 0), glm::dvec3(0, 0, 2));
    write_metaimage_volume(path, v, false);
    const std::string bytes = read_bytes(path);
    EXPECT_NE(bytes.find("TransformMatrix = 0 1 0 -1 0 0 0 0 1\n"), std::string::npos) << bytes;
    EXPECT_NE(bytes.find("ElementSpacing = 0.5 0.25 2\n"), std::string::npos) << bytes;
    EXPECT_NE(bytes.find("AnatomicalOrientation = ALI\n"), std::string::npos) << bytes;
    std::filesystem::remove(path);
}

TEST(MetaImage, ReadsTheHeaderItkWrites)
{
    const auto path = temp("itk.mha");
    write_bytes(path, itk_header + itk_data());
    const Volume v = read_metaimage_volume(path);
    EXPECT_EQ(v.size, (std::array<std::size_t, 3>{4, 3, 2}));
    EXPECT_EQ(v.type, VoxelType::uint8);
    EXPECT_EQ(std::string(v.data.begin(), v.data.end()), itk_data());
    EXPECT_TRUE(v.key_values.empty());  // CenterOfRotation, AnatomicalOrientation: MetaIO's own

    // by hand, from the ITK convention: the triples (0 1 0), (-1 0 0), (0 0 1) are the unit
    // directions of i, j, k in LPS; times the spacings 0.5, 0.25, 2; Offset is voxel (0, 0, 0)
    EXPECT_EQ(v.directions[0], glm::dvec3(0, 0.5, 0));
    EXPECT_EQ(v.directions[1], glm::dvec3(-0.25, 0, 0));
    EXPECT_EQ(v.directions[2], glm::dvec3(0, 0, 2));
    EXPECT_EQ(v.origin, glm::dvec3(-10, 20, 5));
    // voxel (3, 2, 1), the last: 3 steps of 0.5 mm posterior, 2 of 0.25 mm to the right, 1 of 2 mm up
    EXPECT_EQ(v.as<std::uint8_t>()[v.index(3, 2, 1)], 23 * 10 + 1);
    const glm::dvec3 world = v.index_to_world({3, 2, 1});
    EXPECT_DOUBLE_EQ(world.x, -10.0 - 2 * 0.25);
    EXPECT_DOUBLE_EQ(world.y, 20.0 + 3 * 0.5);
    EXPECT_DOUBLE_EQ(world.z, 5.0 + 1 * 2.0);
    std::filesystem::remove(path);
}

TEST(MetaImage, ReadsSynonymsATwoDimensionalImageAndBigEndianData)
{
    const auto path = temp("synonyms.mha");
    // Position and Orientation for Offset and TransformMatrix; ElementSize standing in for spacing;
    // CRLF line ends; fields MetaIO does not know kept as key/values
    std::string header = "NDims = 3\r\nDimSize = 4 3 2\r\nPosition = 1 2 3\r\nOrientation = 0 1 0 -1 0 0 0 0 1\r\n"
                         "ElementSize = 0.5 0.25 2\r\nlabel_1 = skin\r\nElementType = MET_UCHAR\r\nElementDataFile = LOCAL\r\n";
    write_bytes(path, header + itk_data());
    Volume v = read_metaimage_volume(path);
    EXPECT_EQ(v.origin, glm::dvec3(1, 2, 3));
    EXPECT_EQ(v.directions[1], glm::dvec3(-0.25, 0, 0));
    EXPECT_EQ(v.key_values.at("label_1"), "skin");
    EXPECT_EQ(v.key_values.size(), 1u);

    // a 2D image: one slice, its normal +z at 1 mm, as ITK reads a 2D file into a 3D image
    header = "NDims = 2\nDimSize = 4 6\nOffset = 1 2\nTransformMatrix = 0 1 1 0\nElementSpacing = 0.5 0.25\n"
             "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n";
    write_bytes(path, header + itk_data());
    v = read_metaimage_volume(path);
    EXPECT_EQ(v.size, (std::array<std::size_t, 3>{4, 6, 1}));
    EXPECT_EQ(v.directions, glm::dmat3(glm::dvec3(0, 0.5, 0), glm::dvec3(0.25, 0, 0), glm::dvec3(0, 0, 1)));
    EXPECT_EQ(v.origin, glm::dvec3(1, 2, 0));

    // big-endian shorts, byte-swapped; zlib-compressed, without CompressedDataSize
    header = "NDims = 3\nDimSize = 2 2 1\nBinaryDataByteOrderMSB = True\nCompressedData = True\nElementType = MET_SHORT\n"
             "ElementDataFile = LOCAL\n";
    write_bytes(path, header + zlib(std::string("\x01\x02\xff\xfe\x80\x00\x00\x07", 8)));
    v = read_metaimage_volume(path);
    ASSERT_EQ(v.type, VoxelType::int16);
    EXPECT_EQ(v.as<std::int16_t>()[0], 0x0102);
    EXPECT_EQ(v.as<std::int16_t>()[1], -2);
    EXPECT_EQ(v.as<std::int16_t>()[2], -32768);
    EXPECT_EQ(v.as<std::int16_t>()[3], 7);
    std::filesystem::remove(path);
}

TEST(MetaImage, ReadsAndWritesADetachedDataFile)
{
    // .mhd: the header, and the voxels beside it in .raw (.zraw compressed), named relative to it
    for (const bool compressed : {false, true}) {
        const Volume v = oblique_volume(VoxelType::uint16);
        const auto path = temp("detached.mhd");
        const auto data = temp(compressed ? "detached.zraw" : "detached.raw");
        write_volume(path, v, compressed);
        EXPECT_TRUE(std::filesystem::exists(data));
        EXPECT_NE(read_bytes(path).find("ElementDataFile = " + data.filename().string() + "\n"), std::string::npos);
        expect_same_volume(read_volume(path), v);
        if (!compressed) {
            EXPECT_EQ(std::filesystem::file_size(data), v.data.size());
        }
        std::filesystem::remove(path);
        std::filesystem::remove(data);
    }

    // as ITK writes one, into a folder of its own; then with the data file gone
    const auto folder = temp("mhd_folder");
    std::filesystem::create_directories(folder / "data");
    write_bytes(folder / "volume.mhd", with(itk_header, "ElementDataFile = LOCAL", "ElementDataFile = data/volume.raw"));
    write_bytes(folder / "data" / "volume.raw", itk_data());
    EXPECT_EQ(read_metaimage_volume(folder / "volume.mhd").as<std::uint8_t>()[23], 231);
    std::filesystem::remove(folder / "data" / "volume.raw");
    expect_error(folder / "volume.mhd", {"ElementDataFile (line 13)", "data/volume.raw", "cannot be opened"});
    std::filesystem::remove_all(folder);
}

TEST(MetaImage, RejectsBadHeadersNamingFileAndField)
{
    const std::string good = itk_header + itk_data();
    expect_file_error("nodims.mha", with(good, "DimSize = 4 3 2\n", ""), {"DimSize", "missing"});
    expect_file_error("baddims.mha", with(good, "DimSize = 4 3 2", "DimSize = 4 three 2"), {"DimSize (line 11)", "'three'"});
    expect_file_error("ndims.mha", with(good, "DimSize = 4 3 2", "DimSize = 4 3"), {"DimSize (line 11)", "NDims (line 2)"});
    expect_file_error("int.mha", with(good, "MET_UCHAR", "MET_INT"),
                      {"ElementType (line 12)", "'MET_INT'", "MET_UCHAR, MET_CHAR, MET_USHORT, MET_SHORT, MET_FLOAT, MET_DOUBLE"});
    expect_file_error("char.mha", with(good, "MET_UCHAR", "MET_CHAR"), {"ElementType", "'MET_CHAR' volumes are not supported"});
    expect_file_error("double.mha", with(good, "MET_UCHAR", "MET_DOUBLE"), {"ElementType", "'MET_DOUBLE' volumes are not supported"});
    expect_file_error("truncated.mha", good.substr(0, good.size() - 1), {"ElementDataFile", "truncated", "23 bytes", "24"});
    expect_file_error("noend.mha", itk_header.substr(0, itk_header.size() - 24), {"truncated header", "ElementDataFile"});
    // a header that undercounts its data (a DimSize of 4 3 1 over 4 x 3 x 2 voxels) would read a
    // slice of it as the whole image
    expect_file_error("longer.mha", with(good, "DimSize = 4 3 2", "DimSize = 4 3 1"),
                      {"ElementDataFile", "12 bytes more", "(12 bytes)"});
    expect_file_error("onemore.mha", good + "x", {"ElementDataFile", "1 byte more", "(24 bytes)"});
    // a header of megabytes is junk, refused as it is read (a 169 MB one was kept field by field: 3.8 GB)
    std::string fields;
    for (int i = 0; i < 1100; ++i) fields += "Field" + std::to_string(i) + " = " + std::string(1000, 'x') + "\n";
    expect_file_error("longheader.mha", fields + good, {"the header runs past 1048576 bytes", "not a volume's header"});
    expect_file_error("garbage.mha", "\x89PNG\r\n\x1a\n\x00\x00", {"line 1", "not 'Name = Value'"});
    expect_file_error("twice.mha", with(good, "Offset = -10 20 5\n", "Offset = -10 20 5\nOffset = 1 2 3\n"),
                      {"Offset (line 8)", "twice", "line 7"});
    expect_file_error("synonyms.mha", with(good, "Offset = -10 20 5\n", "Offset = -10 20 5\nOrigin = 1 2 3\n"),
                      {"Origin (line 8)", "Offset (line 7)", "synonym"});
    expect_file_error("nanoffset.mha", with(good, "Offset = -10 20 5", "Offset = -10 nan 5"), {"Offset (line 7)", "'nan'", "not finite"});
    expect_file_error("shortmatrix.mha", with(good, "0 1 0 -1 0 0 0 0 1", "0 1 0 -1 0 0"), {"TransformMatrix (line 6)", "expected 9"});
    expect_file_error("singular.mha", with(good, "0 1 0 -1 0 0 0 0 1", "0 1 0 0 1 0 0 0 1"), {"TransformMatrix", "singular"});
    expect_file_error("zerospacing.mha", with(good, "0.5 0.25 2", "0.5 0 2"), {"ElementSpacing (line 10)", "zero"});
    expect_file_error("msb.mha", with(good, "BinaryDataByteOrderMSB = False", "BinaryDataByteOrderMSB = Maybe"),
                      {"BinaryDataByteOrderMSB (line 4)", "'Maybe'"});
    expect_file_error("ascii.mha", with(good, "BinaryData = True", "BinaryData = False"), {"BinaryData (line 3)", "text"});
    expect_file_error("skip.mha", with(good, "DimSize", "HeaderSize = 16\nDimSize"), {"HeaderSize", "skipping"});
    expect_file_error("list.mha", with(good, "ElementDataFile = LOCAL", "ElementDataFile = LIST"),
                      {"ElementDataFile", "'LIST'", "list of files"});
    expect_file_error("pattern.mha", with(good, "ElementDataFile = LOCAL", "ElementDataFile = slice%03d.raw 1 2 1"),
                      {"ElementDataFile", "list of files"});
    expect_file_error("units.mha", with(good, "DimSize", "DistanceUnits = cm\nDimSize"), {"DistanceUnits", "'cm'", "millimetres"});
    expect_file_error("rgb.mha", with(good, "DimSize", "ElementNumberOfChannels = 3\nDimSize"), {"ElementNumberOfChannels", "one channel"});
    expect_file_error("sequence.mha", with(good, "DimSize", "Kinds = domain domain list\nDimSize"), {"Kinds", "'list'", "reconstruct"});
    expect_file_error("4d.mha", with(with(good, "NDims = 3", "NDims = 4"), "DimSize = 4 3 2", "DimSize = 4 3 2 1"),
                      {"DimSize", "4 dimensions"});
    expect_file_error("huge.mha", with(good, "DimSize = 4 3 2", "DimSize = 4294967296 4294967296 2"), {"DimSize", "overflows 64 bits"});
}

TEST(MetaImage, RefusesACompressedPayloadClaimingAHugeSizeBeforeInflating)
{
    const auto path = temp("huge.mha");
    // a few bytes of zlib that claim, through DimSize, 64 GiB of voxels
    const std::string payload = zlib(std::string(1000, '\0'));
    const std::string huge = with(with(itk_header, "CompressedData = False", "CompressedData = True\nCompressedDataSize = " +
                                                                                 std::to_string(payload.size())),
                                  "DimSize = 4 3 2", "DimSize = 4096 4096 4096");
    write_bytes(path, huge + payload);
    expect_error(path, {"DimSize (line 12)", "68719476736 bytes", "memory budget of 8589934592 bytes"});
    // the budget is the caller's: 24 bytes of data fit 24, not 23
    write_bytes(path, itk_header + itk_data());
    expect_error(path, {"DimSize", "24 bytes", "memory budget of 23 bytes"}, 23);
    EXPECT_NO_THROW(read_metaimage_volume(path, 24));
    std::filesystem::remove(path);
}

TEST(MetaImage, RejectsTruncatedAndCorruptCompressedData)
{
    Volume v = make_volume({64, 64, 16}, VoxelType::uint8);
    for (std::size_t i = 0; i < v.data.size(); ++i) v.data[i] = std::uint8_t((i * 7919) >> 5);
    const auto path = temp("corrupt.mha");
    write_metaimage_volume(path, v, true);
    const std::string good = read_bytes(path);
    const std::string end = "ElementDataFile = LOCAL\n";
    const std::size_t data_at = good.find(end) + end.size();

    write_bytes(path, good.substr(0, good.size() - 10));
    expect_error(path, {"CompressedDataSize", "truncated"});
    std::string bad = good;
    for (std::size_t i = data_at; i < data_at + 8; ++i) bad[i] = char(0xff);
    write_bytes(path, bad);
    expect_error(path, {"CompressedData", "fails to inflate"});
    write_bytes(path, with(good, "DimSize = 64 64 16", "DimSize = 64 64 15"));
    expect_error(path, {"CompressedData", "do not end"});
    write_bytes(path, with(good, "DimSize = 64 64 16", "DimSize = 64 64 17"));
    expect_error(path, {"CompressedData", "inflate to 65536 bytes", "DimSize needs 69632"});
    std::filesystem::remove(path);
}

TEST(MetaImage, RoundTripsALabelMapsTissueCodes)
{
    // as echosim writes label maps: the codes, and what each means in key/values
    Volume labels = make_volume({16, 8, 4}, VoxelType::uint8);
    for (std::size_t i = 0; i < labels.data.size(); ++i) labels.data[i] = std::uint8_t(i % 14);
    const char* names[] = {"outside", "skin", "fat", "fascia", "muscle", "artery lumen", "artery wall", "vein lumen"};
    for (int t = 0; t < 8; ++t) labels.key_values["label_" + std::to_string(t)] = names[t];
    labels.key_values["case"] = "dvt-acute";
    const auto path = temp("labels.mha");
    write_volume(path, labels, true);
    EXPECT_NE(read_bytes(path).find("label_5 = artery lumen\n"), std::string::npos);
    const Volume back = read_volume(path);
    EXPECT_EQ(back.key_values, labels.key_values);
    EXPECT_EQ(back.data, labels.data);
    std::filesystem::remove(path);
}

TEST(MetaImage, FailedWriteLeavesNoFile)
{
    const auto path = temp("failed.mha");
    const auto detached = temp("failed.mhd");
    Volume v = make_volume({4, 4, 4}, VoxelType::uint8);
    v.data.pop_back();
    EXPECT_THROW(write_metaimage_volume(path, v, false), MetaImageError);
    EXPECT_THROW(write_metaimage_volume(detached, v, true), MetaImageError);
    v.data.push_back(0);
    v.directions[1] = v.directions[0];
    EXPECT_THROW(write_metaimage_volume(path, v, true), MetaImageError);
    v.directions = glm::dmat3(1.0);
    for (const auto& [key, value] : {std::pair{"", "x"}, std::pair{"two words", "x"}, std::pair{"a=b", "x"}, std::pair{"DimSize", "1 1 1"},
                                     std::pair{"ElementDataFile", "x"}, std::pair{"note", "two\nlines"}, std::pair{"note", " padded"}}) {
        Volume keyed = v;
        keyed.key_values[key] = value;
        try {
            write_metaimage_volume(path, keyed, false);
            ADD_FAILURE() << "no error for key '" << key << "'";
        } catch (const MetaImageError& e) {
            EXPECT_NE(std::string(e.what()).find(std::string("'") + key + "'"), std::string::npos) << e.what();
        }
    }
    for (const auto& p : {path, detached, temp("failed.raw"), temp("failed.zraw")}) {
        EXPECT_FALSE(std::filesystem::exists(p)) << p;
        EXPECT_FALSE(test::partial_left_beside(p)) << p;
    }
    const auto nowhere = std::filesystem::path("/nonexistent-echosim-folder/x.mha");
    EXPECT_THROW(write_metaimage_volume(nowhere, v, false), MetaImageError);
}

TEST(VolumeFile, ReadsTheSameVolumeFromNrrdAndMetaImage)
{
    const Volume v = oblique_volume(VoxelType::int16);
    const auto nrrd = temp("same.nrrd"), mha = temp("same.mha"), renamed = temp("same.dat");
    write_volume(nrrd, v, true);
    write_volume(mha, v, false);
    EXPECT_EQ(read_bytes(nrrd).rfind("NRRD0004\n", 0), 0u);
    EXPECT_EQ(read_bytes(mha).rfind("ObjectType = Image\n", 0), 0u);
    const Volume from_nrrd = read_volume(nrrd), from_mha = read_volume(mha);
    expect_same_volume(from_nrrd, v);
    expect_same_volume(from_mha, from_nrrd);
    // the content decides, not the name
    std::filesystem::rename(mha, renamed);
    expect_same_volume(read_volume(renamed), v);

    EXPECT_THROW(write_volume(temp("same.png"), v, false), VolumeFileError);
    try {
        write_volume(temp("same.nhdr"), v, false);
        ADD_FAILURE() << "no error";
    } catch (const VolumeFileError& e) {
        EXPECT_NE(std::string(e.what()).find(".nrrd, .mha (MetaImage) or .mhd"), std::string::npos) << e.what();
    }
    write_bytes(renamed, "\x89PNG\r\n\x1a\n\x00\x00");
    try {
        read_volume(renamed);
        ADD_FAILURE() << "no error";
    } catch (const VolumeFileError& e) {
        EXPECT_NE(std::string(e.what()).find(renamed.string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("neither a NRRD file"), std::string::npos) << e.what();
    }
    for (const auto& p : {nrrd, renamed}) std::filesystem::remove(p);
}

// A DimSize within the budget but beyond what the compressed data could inflate to (issue 13: 4 GiB
// claimed over a few bytes of zlib) is refused before the memory is taken.
TEST(MetaImage, RefusesCompressedDataClaimingMoreThanItCouldHold)
{
    const auto path = temp("claims_huge.mha");
    const std::string payload = zlib(std::string(1000, '\0'));
    const std::string header = with(with(itk_header, "CompressedData = False", "CompressedData = True\nCompressedDataSize = " +
                                                                                   std::to_string(payload.size())),
                                    "DimSize = 4 3 2", "DimSize = 2048 2048 1024");
    write_bytes(path, header + payload);
    expect_error(path, {"CompressedData", "DimSize", "4294967296 bytes cannot come from", "1032"});
    // without CompressedDataSize, the rest of the file is the bound
    write_bytes(path, with(header, "CompressedDataSize = " + std::to_string(payload.size()) + "\n", "") + payload);
    expect_error(path, {"CompressedData", "4294967296 bytes cannot come from"});
    std::filesystem::remove(path);
}

TEST(MetaImage, RefusesWhatIsNotARegularFileAsHeaderOrData)
{
    test::expect_special_files_refused<MetaImageError>("metaimage_test", [](const std::filesystem::path& p) { read_metaimage_volume(p); });
    test::expect_special_files_refused<VolumeFileError>("volume_file_test", [](const std::filesystem::path& p) { read_volume(p); });
    // a header naming a device as its data file: refused by name, never read
    const auto path = temp("device_data.mhd");
    write_bytes(path, with(itk_header, "ElementDataFile = LOCAL", "ElementDataFile = /dev/zero"));
    expect_error(path, {"ElementDataFile", "/dev/zero", "not a regular file"});
    std::filesystem::remove(path);
}

// Issue 13 (fuzzing): a header whose last line (ElementDataFile = LOCAL) ends the file, without a
// newline, left the stream at its end, where tellg() fails; the bytes left were taken as unknown and
// the 4 GiB DimSize claimed was allocated (and zeroed) before the read found nothing.
TEST(MetaImage, RefusesRawDataClaimedByAHeaderThatEndsTheFile)
{
    const auto path = temp("ends_at_header.mha");
    std::string header = with(itk_header, "DimSize = 4 3 2", "DimSize = 2048 2048 1024");
    header.pop_back();  // no newline after ElementDataFile = LOCAL
    write_bytes(path, header);
    expect_error(path, {"ElementDataFile", "truncated data: 0 bytes", "4294967296"});
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace echosim::io

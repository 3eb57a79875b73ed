#include "io/plus_config.hpp"

#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "test_files.hpp"

namespace echosim::io {
namespace {

using test::with;
using test::write_bytes;

std::filesystem::path temp(const std::string& name) { return test::temp_path("plus_config_test", name); }

// A device-set configuration as PLUS ships them (a saved-data source, fCal's settings, the
// calibration in CoordinateDefinitions, the VolumeReconstructor's element).
const std::string kConfig = R"(<?xml version="1.0" encoding="utf-8"?>
<PlusConfiguration version="2.1">
  <DataCollection StartupDelaySec="1.0">
    <DeviceSet Name="PlusServer: Saved data, thigh sweep" Description="Replays a recording" />
    <Device Id="TrackedVideoDevice" Type="SavedDataSource" SequenceFile="Sweep.igs.mha" UseData="IMAGE_AND_TRANSFORM">
      <DataSources><DataSource Type="Video" Id="Video" /></DataSources>
      <OutputChannels><OutputChannel Id="TrackedVideoStream" VideoDataSourceId="Video" /></OutputChannels>
    </Device>
  </DataCollection>
  <CoordinateDefinitions>
    <Transform From="Image" To="Probe"
      Matrix="0.107535 0.00094824 0.0044213 -65.0343
              -0.0044901 0.0262413 0.102654 -42.5561
              -0.00000 -0.106198 0.0271362 -7.24144
              0 0 0 1"
      Error="0.582241" Date="2011.12.06 17:57:00" />
    <Transform From="TransducerOriginPixel" To="TransducerOrigin"
      Matrix="1 0 0 -410 0 1 0 5 0 0 1 0 0 0 0 1" Date="2011.12.06 17:57:00" />
  </CoordinateDefinitions>
  <VolumeReconstruction OutputSpacing="0.5 0.5 0.5"
    ClipRectangleOrigin="27 27" ClipRectangleSize="766 562"
    Interpolation="LINEAR" Optimization="FULL" CompoundingMode="MEAN" FillHoles="OFF" NumberOfThreads="2"
    ReferenceCoordinateFrame="Reference" ImageCoordinateFrame="Image" />
</PlusConfiguration>
)";

PlusConfig read_text(const std::string& text, const std::string& name = "config.xml")
{
    const auto path = temp(name);
    write_bytes(path, text);
    PlusConfig c = read_plus_config(path);
    std::filesystem::remove(path);
    return c;
}

std::string error_of(const std::string& text)
{
    const auto path = temp("bad.xml");
    write_bytes(path, text);
    try {
        read_plus_config(path);
    } catch (const PlusConfigError& e) {
        std::filesystem::remove(path);
        return e.what();
    }
    std::filesystem::remove(path);
    ADD_FAILURE() << "accepted";
    return {};
}

TEST(PlusConfig, ReadsTheCalibrationAndTheReconstructionSettings)
{
    const PlusConfig c = read_text(kConfig);
    ASSERT_EQ(c.transforms.size(), 2u);
    EXPECT_EQ(c.transforms[0].from, "Image");
    EXPECT_EQ(c.transforms[0].to, "Probe");
    EXPECT_EQ(c.transforms[0].line, 11);
    // row by row in the file: row 0 is 0.107535 0.00094824 0.0044213 -65.0343
    EXPECT_DOUBLE_EQ(c.transforms[0].matrix[0][0], 0.107535);
    EXPECT_DOUBLE_EQ(c.transforms[0].matrix[1][0], 0.00094824);
    EXPECT_DOUBLE_EQ(c.transforms[0].matrix[3][0], -65.0343);
    EXPECT_DOUBLE_EQ(c.transforms[0].matrix[1][2], -0.106198);
    EXPECT_DOUBLE_EQ(c.transforms[0].matrix[3][2], -7.24144);

    ASSERT_TRUE(c.reconstruction);
    const PlusReconstructionSettings& r = *c.reconstruction;
    EXPECT_EQ(*r.output_spacing, glm::dvec3(0.5));
    EXPECT_FALSE(r.output_origin);
    EXPECT_FALSE(r.output_extent);
    EXPECT_EQ(*r.clip_origin, (std::array<int, 2>{27, 27}));
    EXPECT_EQ(*r.clip_size, (std::array<int, 2>{766, 562}));
    EXPECT_EQ(*r.interpolation, PlusInterpolation::linear);
    EXPECT_EQ(*r.compounding, PlusCompounding::mean);
    EXPECT_EQ(*r.fill_holes, false);
    EXPECT_EQ(r.image_frame, "Image");
    EXPECT_EQ(r.reference_frame, "Reference");
    EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
}

TEST(PlusConfig, NamesWhatItDoesNotDo)
{
    const std::string text = with(kConfig, R"(NumberOfThreads="2")",
                                  R"(NumberOfThreads="2" FanAnglesDeg="-30 30" Sharpness="3")");
    const PlusConfig c = read_text(text);
    ASSERT_EQ(c.warnings.size(), 2u);
    EXPECT_NE(c.warnings[0].find(":20: VolumeReconstruction: FanAnglesDeg: '-30 30' is not supported"), std::string::npos) << c.warnings[0];
    EXPECT_NE(c.warnings[1].find("Sharpness: '3' is not an attribute echosim knows"), std::string::npos) << c.warnings[1];
}

TEST(PlusConfig, OlderAttributesAndTheOutputBox)
{
    const std::string text = with(with(kConfig, R"(CompoundingMode="MEAN")", R"(Compounding="ON" Calculation="MAXIMUM")"),
                                  R"(OutputSpacing="0.5 0.5 0.5")",
                                  R"(OutputSpacing="0.5 0.5 1" OutputOrigin="-10 -20.5 30" OutputExtent="0 99 0 49 0 9")");
    const PlusReconstructionSettings r = *read_text(text).reconstruction;
    EXPECT_EQ(*r.compounding, PlusCompounding::maximum);
    EXPECT_EQ(*r.output_spacing, glm::dvec3(0.5, 0.5, 1));
    EXPECT_EQ(*r.output_origin, glm::dvec3(-10, -20.5, 30));
    EXPECT_EQ(*r.output_extent, (std::array<int, 6>{0, 99, 0, 49, 0, 9}));
}

TEST(PlusConfig, ErrorsNameTheLineAndAttribute)
{
    EXPECT_NE(error_of(with(kConfig, R"(-7.24144)", "seven")).find(":11: Transform: Matrix: 'seven' is not a number"), std::string::npos);
    EXPECT_NE(error_of(with(kConfig, R"(0 0 0 1")", R"(0 0 0 1 5")")).find("Matrix: "), std::string::npos);
    EXPECT_NE(error_of(with(kConfig, R"(From="Image")", "")).find(":11: Transform: From: missing"), std::string::npos);
    EXPECT_NE(error_of(with(kConfig, R"("LINEAR")", R"("CUBIC")")).find("Interpolation: 'CUBIC' is not NEAREST_NEIGHBOR or LINEAR"),
              std::string::npos);
    EXPECT_NE(error_of(with(kConfig, R"("MEAN")", R"("IMPORTANCE_MASK")")).find("CompoundingMode: IMPORTANCE_MASK is not supported"),
              std::string::npos);
    EXPECT_NE(error_of(with(kConfig, R"(OutputSpacing="0.5 0.5 0.5")", R"(OutputSpacing="0.5 0 0.5")")).find("OutputSpacing"),
              std::string::npos);
    EXPECT_NE(error_of(with(kConfig, R"(OutputSpacing="0.5 0.5 0.5")", R"(OutputSpacing="0.5 0.5 0.5" OutputOrigin="0 0 0")"))
                  .find("OutputExtent: missing"),
              std::string::npos);
    EXPECT_NE(error_of(with(kConfig, "</CoordinateDefinitions>", "</CoordinateDefinition>")).find("not well-formed XML"), std::string::npos);
    EXPECT_NE(error_of("<Configuration/>").find("not PlusConfiguration"), std::string::npos);
    // the same calibration twice, even the other way round
    EXPECT_NE(error_of(with(kConfig, "</CoordinateDefinitions>",
                            R"(<Transform From="Probe" To="Image" Matrix="1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"/></CoordinateDefinitions>)"))
                  .find("ProbeToImage is defined already, on line 11"),
              std::string::npos);
}

TEST(PlusConfig, RefusesWhatIsNotARegularFile)
{
    try {
        read_plus_config(std::filesystem::temp_directory_path());
        FAIL() << "read a folder";
    } catch (const PlusConfigError& e) {
        EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
    EXPECT_THROW(read_plus_config(temp("missing.xml")), PlusConfigError);
}

// Issue 34: a 60 MiB configuration took 4.8 GB to parse, and 80,000 transforms were checked for
// repeats each against all before it. A configuration is at most 1 MiB (PLUS's are 5 to 60 KiB),
// refused by its size; within it, 10,000 transforms are read, and a repeat among them still found.
TEST(PlusConfig, RefusesAConfigurationPastOneMebibyteAndReadsManyTransforms)
{
    const std::string padding = "<!--" + std::string(std::size_t(1) << 20, '-') + "-->\n";
    EXPECT_NE(error_of(with(kConfig, "</CoordinateDefinitions>", "</CoordinateDefinitions>" + padding)).find("larger than 1 MiB"),
              std::string::npos);

    std::string many;
    for (int i = 0; i < 10000; ++i)
        many += "<Transform From=\"A" + std::to_string(i) + "\" To=\"B" + std::to_string(i) + "\" Matrix=\"1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1\"/>\n";
    const std::string text = with(kConfig, "</CoordinateDefinitions>", many + "</CoordinateDefinitions>");
    ASSERT_LT(text.size(), std::size_t(1) << 20);
    const auto path = temp("many.xml");
    write_bytes(path, text);
    EXPECT_EQ(read_plus_config(path).transforms.size(), 10002u);  // and the two of kConfig
    std::filesystem::remove(path);
    EXPECT_NE(error_of(with(text, "</CoordinateDefinitions>",
                            R"(<Transform From="B9999" To="A9999" Matrix="1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1"/></CoordinateDefinitions>)"))
                  .find("B9999ToA9999 is defined already"),
              std::string::npos);
}

// Issue 34: tinyxml2 checks each attribute against those before it on its element, so 50,000
// attributes on one (half a megabyte) took 10 s. An element of more than 256 attributes is refused
// by a scan of the text before parsing, naming its line; '=' in comments, CDATA and quoted values
// does not count.
TEST(PlusConfig, RefusesAnElementOfMoreThan256Attributes)
{
    const auto attributes = [](int n) {
        std::string a;
        for (int i = 0; i < n; ++i) a += " A" + std::to_string(i) + "=\"x\"";
        return a;
    };
    const std::string many = with(kConfig, "<VolumeReconstruction", "<VolumeReconstruction\n" + attributes(257));
    const std::string m = error_of(many);
    EXPECT_NE(m.find("an element with more than 256 attributes"), std::string::npos) << m;
    const auto line = kConfig.substr(0, kConfig.find("<VolumeReconstruction"));
    EXPECT_NE(m.find(":" + std::to_string(std::count(line.begin(), line.end(), '\n') + 1) + ": "), std::string::npos) << m;

    // 200 more are parsed (each an unknown attribute, warned about); '=' elsewhere is not an attribute
    const std::string equals(1000, '=');
    const std::string fine = with(kConfig, "<VolumeReconstruction",
                                  "<!--" + equals + "-->\n<![CDATA[" + equals + "]]>\n<VolumeReconstruction Note=\"" + equals +
                                      ">\"" + attributes(200));
    const auto path = temp("attributes.xml");
    write_bytes(path, fine);
    const PlusConfig c = read_plus_config(path);  // the 200 and Note, each an unknown attribute
    ASSERT_EQ(c.warnings.size(), 101u);              // 100 listed, the rest counted
    EXPECT_NE(c.warnings.back().find(": 101 more warnings like these, not listed"), std::string::npos) << c.warnings.back();
    std::filesystem::remove(path);
}

}  // namespace
}  // namespace echosim::io

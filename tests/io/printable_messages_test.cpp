// The readers' messages carry no terminal escape sequence (issue 34): a file whose field holds
// "\x1b]0;owned\x07" (OSC 0: set the terminal's title, ended by BEL) is refused with the field
// quoted as \x1b]0;owned\x07, readable and inert, by each reader that quotes what it refuses
// (core/printable_text.hpp: InputFileError, the base of the readers' errors; the trajectory's own).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "device/trajectory.hpp"
#include "io/metaimage.hpp"
#include "io/nrrd.hpp"
#include "test_files.hpp"
#include "tissue/tissue_json.hpp"

namespace echosim {
namespace {

const std::string kOwned = "\x1b]0;owned\x07";
const std::string kShown = "\\x1b]0;owned\\x07";

// `message` holds no byte a terminal acts on (C0 controls, DEL, C1 in either form) and shows `kShown`
void expect_inert(const std::string& message)
{
    for (std::size_t i = 0; i < message.size(); ++i) {
        const auto b = static_cast<unsigned char>(message[i]);
        EXPECT_FALSE(b < 0x20 || b == 0x7f || (b >= 0x80 && b < 0xa0 && (i == 0 || static_cast<unsigned char>(message[i - 1]) != 0xc2)) ||
                     (b == 0xc2 && i + 1 < message.size() && static_cast<unsigned char>(message[i + 1]) < 0xa0))
            << "raw byte 0x" << std::hex << int(b) << " at " << std::dec << i << " of: " << message;
    }
}

template <class Error, class Read>
std::string message_of(Read&& read)
{
    try {
        read();
    } catch (const Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error";
    return {};
}

TEST(PrintableMessages, NrrdQuotesAFieldsEscapeSequenceEscaped)
{
    const auto path = test::temp_path("printable", "owned.nrrd");
    test::write_bytes(path, "NRRD0004\ntype: " + kOwned + "\ndimension: 3\nsizes: 1 1 1\nencoding: raw\n\n" + std::string(1, '\0'));
    const std::string m = message_of<io::NrrdError>([&] { io::read_nrrd(path); });
    std::filesystem::remove(path);
    expect_inert(m);
    EXPECT_NE(m.find(kShown), std::string::npos) << m;
}

TEST(PrintableMessages, MetaImageQuotesAFieldsEscapeSequenceEscaped)
{
    const auto path = test::temp_path("printable", "owned.mha");
    test::write_bytes(path, "ObjectType = Image\nNDims = 3\nDimSize = 1 1 1\nElementType = " + kOwned + "\nElementDataFile = LOCAL\n" +
                                std::string(1, '\0'));
    const std::string m = message_of<io::MetaImageError>([&] { io::read_metaimage_volume(path); });
    std::filesystem::remove(path);
    expect_inert(m);
    EXPECT_NE(m.find(kShown), std::string::npos) << m;
}

TEST(PrintableMessages, TrajectoryQuotesAFieldsEscapeSequenceEscaped)
{
    const std::string m = message_of<std::invalid_argument>([&] {
        device::Trajectory::parse("t_s,x_mm,y_mm,z_mm,qw,qx,qy,qz\n0," + kOwned + ",0,0,1,0,0,0\n", "owned.csv");
    });
    expect_inert(m);
    EXPECT_NE(m.find(kShown), std::string::npos) << m;
}

TEST(PrintableMessages, TissueModelParseErrorsCarryNoRawControlBytes)
{
    // JSON's own error quotes the text it stopped at; C1 CSI (0x9b) and DEL are not JSON controls,
    // so the parser's message would carry them raw
    const auto path = test::temp_path("printable", "owned.json");
    test::write_bytes(path, "{\"format\": \x9b" "2J\x7f" + kOwned + "}");
    const std::string m = message_of<tissue::ModelFileError>([&] { tissue::read_tissue_model(path); });
    std::filesystem::remove(path);
    expect_inert(m);
}

TEST(PrintableMessages, TheErrorBaseEscapesWhateverItIsGiven)
{
    const io::NrrdError e("file.nrrd: field 'x': " + kOwned + " \xc2\x9b" "31m");
    EXPECT_EQ(std::string(e.what()), "file.nrrd: field 'x': " + kShown + " \\xc2\\x9b31m");
}

}  // namespace
}  // namespace echosim

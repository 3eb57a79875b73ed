#include "io/metaimage.hpp"

#include "core/parse_number.hpp"
#include "io/partial_file.hpp"
#include "io/text_fields.hpp"
#include "io/zlib_stream.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <istream>
#include <limits>
#include <span>
#include <system_error>
#include <utility>

#include <glm/geometric.hpp>

namespace echosim::io {
namespace {

using text::format_double;
using text::quote_text;
using text::split_whitespace;
using text::upper;

constexpr std::array<MetElementType, 6> all_element_types = {MetElementType::met_uchar, MetElementType::met_char,
                                                             MetElementType::met_ushort, MetElementType::met_short,
                                                             MetElementType::met_float, MetElementType::met_double};

// The fields MetaIO defines for an image (metaObject.cxx and metaImage.cxx, M_SetupReadFields):
// what a volume does not interpret of these is dropped; every other field is a key/value.
constexpr std::array<std::string_view, 41> metaio_fields = {
    "Comment", "AcquisitionDate", "ObjectType", "ObjectSubType", "TransformType", "NDims", "Name", "ID", "ParentID",
    "CompressedData", "CompressedDataSize", "BinaryData", "BinaryDataByteOrderMSB", "ElementByteOrderMSB", "Color",
    "Position", "Origin", "Offset", "TransformMatrix", "Rotation", "Orientation", "CenterOfRotation", "DistanceUnits",
    "AnatomicalOrientation", "ElementSpacing", "DimSize", "HeaderSize", "Modality", "ImagePosition", "SequenceID",
    "ElementMin", "ElementMax", "ElementNumberOfChannels", "ElementSize", "ElementNBits",
    "ElementToIntensityFunctionSlope", "ElementToIntensityFunctionOffset", "ElementType", "ElementDataFile",
    "Kinds",  // not MetaIO's: PLUS sequences' axis kinds
    "ParentName"};

bool is_metaio_field(std::string_view name)
{
    return std::find(metaio_fields.begin(), metaio_fields.end(), name) != metaio_fields.end();
}

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& why) { text::fail<MetaImageError>(path, why); }

std::string field_label(const MetaImageField& f) { return f.name + " (line " + std::to_string(f.line) + ")"; }

// MetaIO writes big-endian data when BinaryDataByteOrderMSB = True; the volume keeps little endian.
void swap_bytes(std::vector<std::uint8_t>& data, std::size_t element)
{
    for (auto at = data.begin(); data.end() - at >= std::ptrdiff_t(element); at += std::ptrdiff_t(element))
        std::reverse(at, at + std::ptrdiff_t(element));
}

// The file ElementDataFile names: relative to the header's folder unless absolute (as MetaIO).
std::filesystem::path data_file_path(const MetaImageHeader& header, const MetaImageField& field)
{
    if (upper(field.value) == "LIST" || field.value.find('%') != std::string::npos)
        header.fail(field.name, quote_text(field.value) +
                                    ": data split over a list of files is not supported; keep the data in one file (LOCAL, or one .raw)");
    const std::filesystem::path named(field.value);
    return named.is_absolute() ? named : header.path().parent_path() / named;
}

}  // namespace

std::size_t element_size(MetElementType type)
{
    switch (type) {
    case MetElementType::met_uchar:
    case MetElementType::met_char: return 1;
    case MetElementType::met_ushort:
    case MetElementType::met_short: return 2;
    case MetElementType::met_float: return 4;
    case MetElementType::met_double: return 8;
    }
    return 1;
}

const char* to_string(MetElementType type)
{
    switch (type) {
    case MetElementType::met_uchar: return "MET_UCHAR";
    case MetElementType::met_char: return "MET_CHAR";
    case MetElementType::met_ushort: return "MET_USHORT";
    case MetElementType::met_short: return "MET_SHORT";
    case MetElementType::met_float: return "MET_FLOAT";
    case MetElementType::met_double: return "MET_DOUBLE";
    }
    return "?";
}

// ---- header ------------------------------------------------------------------------------------

void MetaImageHeader::add(MetaImageField field)
{
    if (const MetaImageField* before = find(field.name))
        io::fail(path_, field_label(field) + ": given twice (first on line " + std::to_string(before->line) + ")");
    index_.emplace(field.name, fields_.size());
    fields_.push_back(std::move(field));
}

const MetaImageField* MetaImageHeader::find(std::string_view name) const
{
    const auto it = index_.find(name);
    return it == index_.end() ? nullptr : &fields_[it->second];
}

const MetaImageField& MetaImageHeader::require(std::string_view name) const
{
    if (const MetaImageField* f = find(name)) return *f;
    fail(name, "missing");
}

const MetaImageField* MetaImageHeader::find_one_of(std::initializer_list<std::string_view> names) const
{
    const MetaImageField* found = nullptr;
    for (const std::string_view name : names) {
        const MetaImageField* f = find(name);
        if (f && found)
            fail(f->name, "given together with " + field_label(*found) + ", its synonym: give one of them");
        if (f) found = f;
    }
    return found;
}

void MetaImageHeader::fail(std::string_view name, const std::string& why) const
{
    const MetaImageField* f = find(name);
    io::fail(path_, (f ? field_label(*f) : std::string(name)) + ": " + why);
}

MetElementType MetaImageHeader::element_type() const
{
    const std::string& type = require("ElementType").value;
    for (const MetElementType t : all_element_types)
        if (type == to_string(t)) return t;
    std::string supported;
    for (const MetElementType t : all_element_types) supported += std::string(supported.empty() ? "" : ", ") + to_string(t);
    fail("ElementType", quote_text(type) + " is not supported (" + supported + ")");
}

std::vector<std::uint64_t> MetaImageHeader::dim_size() const
{
    const auto tokens = split_whitespace(require("DimSize").value);
    if (tokens.empty()) fail("DimSize", "no sizes");
    if (const MetaImageField* ndims = find("NDims")) {
        std::uint64_t n = 0;
        if (!parse_number(ndims->value, n) || n == 0 || n > 16) fail("NDims", quote_text(ndims->value) + " is not a dimension from 1 to 16");
        if (n != tokens.size())
            fail("DimSize", std::to_string(tokens.size()) + " sizes, but NDims (line " + std::to_string(ndims->line) + ") is " + ndims->value);
    }
    std::vector<std::uint64_t> sizes;
    for (const std::string_view token : tokens) {
        std::uint64_t s = 0;
        const ParsedNumber parsed = parse_number(token, s);
        if (parsed.out_of_range()) fail("DimSize", quote_text(token) + " overflows a 64-bit size");
        if (!parsed || s == 0) fail("DimSize", quote_text(token) + " is not a positive integer");
        sizes.push_back(s);
    }
    return sizes;
}

std::uint64_t MetaImageHeader::channels() const
{
    const MetaImageField* f = find("ElementNumberOfChannels");
    if (!f) return 1;
    std::uint64_t n = 0;
    if (!parse_number(f->value, n) || n == 0 || n > 1024) fail(f->name, quote_text(f->value) + " is not a channel count from 1 to 1024");
    return n;
}

bool MetaImageHeader::flag(std::string_view name, bool absent) const
{
    const MetaImageField* f = find(name);
    if (!f) return absent;
    const std::string v = upper(f->value);
    if (v == "TRUE" || v == "1") return true;
    if (v == "FALSE" || v == "0") return false;
    fail(name, quote_text(f->value) + " is neither True nor False");
}

std::vector<double> MetaImageHeader::numbers(const MetaImageField& field, std::size_t count) const
{
    const auto tokens = split_whitespace(field.value);
    if (tokens.size() != count)
        fail(field.name, std::to_string(tokens.size()) + " numbers, expected " + std::to_string(count) + ": " + quote_text(field.value));
    std::vector<double> out;
    for (const std::string_view token : tokens) {
        double x = 0;
        if (!parse_number(token, x)) fail(field.name, quote_text(token) + " is not a number");
        if (!std::isfinite(x)) fail(field.name, quote_text(token) + " is not finite");
        out.push_back(x);
    }
    return out;
}

MetaImageHeader read_metaimage_header(std::istream& in, const std::filesystem::path& path, std::uint64_t max_header_bytes)
{
    MetaImageHeader header(path);
    std::string line;
    std::uint64_t bytes = 0;
    for (std::size_t number = 1;; ++number) {
        if (!text::read_header_line<MetaImageError>(in, line, path, "MetaImage"))
            fail(path, "truncated header: the file ends before ElementDataFile, the header's last field");
        text::count_header_bytes<MetaImageError>(bytes, line, max_header_bytes, path);
        if (text::trim(line).empty()) continue;
        const auto eq = line.find('=');
        const std::string_view name = text::trim(std::string_view(line).substr(0, std::min(eq, line.size())));
        if (eq == std::string::npos || name.empty())
            fail(path, "header line " + std::to_string(number) + " is not 'Name = Value': " + quote_text(line) +
                           " (not a MetaImage file?)");
        header.add({std::string(name), std::string(text::trim(std::string_view(line).substr(eq + 1))), number});
        if (name == "ElementDataFile") return header;
    }
}

// ---- element data --------------------------------------------------------------------------------

std::uint64_t metaimage_data_bytes(const MetaImageHeader& header, std::uint64_t memory_budget_bytes)
{
    std::uint64_t bytes = element_size(header.element_type());
    const std::uint64_t channels = header.channels();
    std::vector<std::uint64_t> factors = header.dim_size();
    factors.push_back(channels);
    for (const std::uint64_t f : factors) {
        if (bytes > std::numeric_limits<std::uint64_t>::max() / f) header.fail("DimSize", "the data size overflows 64 bits");
        bytes *= f;
    }
    if (bytes > memory_budget_bytes || bytes > std::numeric_limits<std::size_t>::max())
        header.fail("DimSize", std::to_string(bytes) + " bytes of data exceed the memory budget of " +
                                   std::to_string(memory_budget_bytes) + " bytes");
    return bytes;
}

std::vector<std::uint8_t> inflate_metaimage_data(const std::filesystem::path& path, std::istream& in, std::uint64_t bytes,
                                                 std::uint64_t packed, std::string_view sizes_field)
{
    const auto fail_compressed = [&](const std::string& why) { fail(path, "CompressedData: " + why); };
    const std::string sizes_give = std::to_string(bytes) + " bytes " + std::string(sizes_field) + " gives";
    const std::string corrupt = "the compressed data fails to inflate (corrupt or truncated): ";
    Inflated data;
    try {
        data = inflate_exactly(in, bytes, packed);
    } catch (const ZlibError& e) {
        const std::string produced = std::to_string(e.produced());
        if (e.kind() == ZlibError::Kind::too_large)
            fail_compressed("truncated data or a wrong " + std::string(sizes_field) + ": " + e.what());
        if (e.kind() == ZlibError::Kind::ended_early)
            fail_compressed("the compressed data inflate to " + produced + " bytes, " + std::string(sizes_field) + " needs " +
                            std::to_string(bytes));
        if (e.kind() == ZlibError::Kind::input_ended && e.produced() == bytes)
            fail_compressed("the compressed data do not end after the " + sizes_give + " (more data, or a cut stream)");
        if (e.kind() == ZlibError::Kind::input_ended) fail_compressed(corrupt + "the data ends after " + produced + " of the " + sizes_give);
        if (e.kind() == ZlibError::Kind::corrupt) fail_compressed(corrupt + e.what());
        fail_compressed(e.what());
    }
    return std::move(data.data);
}

std::vector<std::uint8_t> read_metaimage_data(std::istream& in, const MetaImageHeader& header, std::uint64_t memory_budget_bytes)
{
    // what the data are, refused by name before anything is read
    const std::uint64_t bytes = metaimage_data_bytes(header, memory_budget_bytes);
    if (!header.flag("BinaryData", true)) header.fail("BinaryData", "text (ASCII) element data is not supported: only binary");
    if (const MetaImageField* skip = header.find("HeaderSize"); skip && skip->value != "0")
        header.fail("HeaderSize", quote_text(skip->value) + ": skipping into the data file is not supported");
    const std::size_t element = element_size(header.element_type());
    const MetaImageField* msb = header.find_one_of({"BinaryDataByteOrderMSB", "ElementByteOrderMSB"});
    const bool big_endian = msb && header.flag(msb->name, false);
    const bool compressed = header.flag("CompressedData", false);

    // where they are: after the header, or in the file it names
    const MetaImageField& where = header.require("ElementDataFile");
    std::ifstream detached;
    std::istream* data_in = &in;
    std::filesystem::path data_path = header.path();
    if (upper(where.value) != "LOCAL") {
        data_path = data_file_path(header, where);
        if (text::is_special_file(data_path))
            header.fail(where.name, "the data file " + data_path.string() + " is " + text::not_regular_file + ": refusing to read it");
        detached.open(data_path, std::ios::binary);
        if (!detached)
            header.fail(where.name, "the data file " + data_path.string() + " cannot be opened: " +
                                        std::generic_category().message(errno));
        data_in = &detached;
    }

    std::vector<std::uint8_t> data;
    if (!compressed) {
        std::uint64_t found = 0;
        auto raw = text::read_exactly(*data_in, bytes, found);
        if (!raw)
            header.fail(where.name, "truncated data: " + std::to_string(found) + " bytes in " + data_path.string() +
                                        (data_in == &in ? " after the header" : "") + ", DimSize and ElementType need " +
                                        std::to_string(bytes));
        // more data than the header gives is a header that does not describe its data (a wrong
        // DimSize or ElementType): read as it says, the image would be silently wrong
        if (data_in->peek() != std::char_traits<char>::eof()) {
            const std::uint64_t more = text::bytes_left(*data_in);  // unknown (the maximum) on a pipe
            header.fail(where.name, "the data in " + data_path.string() + " hold " +
                                        (more == std::numeric_limits<std::uint64_t>::max() ? std::string("more") : std::to_string(more) + (more == 1 ? " byte more" : " bytes more")) +
                                        " than DimSize and ElementType give (" + std::to_string(bytes) + " bytes)");
        }
        data = std::move(*raw);
    } else {
        const std::uint64_t left = text::bytes_left(*data_in);
        std::uint64_t packed = left;
        if (const MetaImageField* size = header.find("CompressedDataSize")) {
            std::uint64_t n = 0;
            if (!parse_number(size->value, n) || n == 0) header.fail(size->name, quote_text(size->value) + " is not a positive integer");
            if (n > left)
                header.fail(size->name, "truncated data: " + size->value + " compressed bytes announced, " + std::to_string(left) +
                                            " left in " + data_path.string());
            packed = n;
        }
        data = inflate_metaimage_data(header.path(), *data_in, bytes, packed);
    }
    if (big_endian && element > 1) swap_bytes(data, element);
    return data;
}

std::optional<VoxelType> exact_voxel_type(MetElementType type)
{
    switch (type) {
    case MetElementType::met_uchar: return VoxelType::uint8;
    case MetElementType::met_ushort: return VoxelType::uint16;
    case MetElementType::met_short: return VoxelType::int16;
    case MetElementType::met_float: return VoxelType::float32;
    case MetElementType::met_char:
    case MetElementType::met_double: break;
    }
    return std::nullopt;
}

MetElementType element_type_of(VoxelType type)
{
    switch (type) {
    case VoxelType::uint8: return MetElementType::met_uchar;
    case VoxelType::uint16: return MetElementType::met_ushort;
    case VoxelType::int16: return MetElementType::met_short;
    case VoxelType::float32: return MetElementType::met_float;
    }
    return MetElementType::met_uchar;
}

// ---- volumes -------------------------------------------------------------------------------------

namespace {

VoxelType voxel_type(const MetaImageHeader& header)
{
    if (const auto type = exact_voxel_type(header.element_type())) return *type;
    header.fail("ElementType", quote_text(header.require("ElementType").value) +
                                   " volumes are not supported (MET_UCHAR, MET_USHORT, MET_SHORT or MET_FLOAT); convert the "
                                   "volume, e.g. with 3D Slicer's Cast Scalar Volume");
}

// The acronym ITK writes in AnatomicalOrientation: per axis, the side it comes from (R for an axis
// running towards L, A towards P, I towards S), for the pairing of axes with the anatomical
// directions closest to the direction cosines.
std::string orientation_acronym(const glm::dmat3& directions)
{
    static constexpr std::array<std::array<int, 3>, 6> pairings = {{{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}}};
    static constexpr char from_positive[3] = {'R', 'A', 'I'}, from_negative[3] = {'L', 'P', 'S'};
    const std::array<int, 3>* best = &pairings[0];
    double best_score = -1;
    for (const auto& p : pairings) {
        double score = 0;
        for (int a = 0; a < 3; ++a) score += std::abs(glm::normalize(directions[a])[p[std::size_t(a)]]);
        if (score > best_score) best_score = score, best = &p;
    }
    std::string acronym;
    for (int a = 0; a < 3; ++a) {
        const int lps = (*best)[std::size_t(a)];
        acronym += directions[a][lps] >= 0 ? from_positive[lps] : from_negative[lps];
    }
    return acronym;
}

void check_volume(const std::filesystem::path& path, const Volume& v)
{
    if (const std::string defect = volume_defect(v); !defect.empty()) fail(path, defect);
    for (const auto& [key, value] : v.key_values) {
        if (key.empty() || key.find_first_of(" \t\r\n=") != std::string::npos)
            fail(path, "key " + quote_text(key) + " is empty or holds blanks or '=', which a MetaImage field name cannot");
        if (is_metaio_field(key) || key.starts_with("Seq_Frame"))
            fail(path, "key " + quote_text(key) + " is a MetaImage field of its own: it cannot be a key/value");
        if (value.find_first_of("\r\n") != std::string::npos || (!value.empty() && text::trim(value).size() != value.size()))
            fail(path, "key " + quote_text(key) + ": its value holds a line break or blanks at either end, which a MetaImage "
                                                  "header cannot keep");
    }
}

std::string numbers_text(std::initializer_list<double> values)
{
    std::string out;
    for (const double v : values) out += (out.empty() ? "" : " ") + format_double(v);
    return out;
}

}  // namespace

Volume read_metaimage_volume(const std::filesystem::path& path, std::uint64_t memory_budget_bytes)
{
    std::ifstream in = text::open_binary<MetaImageError>(path);
    const MetaImageHeader header = read_metaimage_header(in, path);

    // what the file holds
    if (const MetaImageField* object = header.find("ObjectType"); object && upper(object->value) != "IMAGE")
        header.fail("ObjectType", quote_text(object->value) + ": not an image");
    if (const MetaImageField* kinds = header.find("Kinds"))
        for (const std::string_view kind : split_whitespace(kinds->value))
            if (upper(kind) != "DOMAIN" && upper(kind) != "SPACE")
                header.fail("Kinds", "a " + quote_text(kind) + " axis: this is a sequence of frames (a PLUS recording?), "
                                     "not a volume; reconstruct it first (echosim reconstruct)");
    if (header.channels() != 1) header.fail("ElementNumberOfChannels", "only scalar volumes (one channel) are supported");
    Volume v;
    v.type = voxel_type(header);
    const std::vector<std::uint64_t> sizes = header.dim_size();
    const std::size_t n = sizes.size();
    if (n != 2 && n != 3)
        header.fail("DimSize", std::to_string(n) + " dimensions: only 3D volumes (or 2D images, read as one slice) are supported");
    if (const MetaImageField* units = header.find("DistanceUnits"); units && units->value != "mm" && units->value != "?")
        header.fail("DistanceUnits", quote_text(units->value) + ": only millimetres are supported");

    // geometry, in the file's n dimensions, then embedded in 3 (a 2D image's k axis: 1 mm along z)
    std::vector<double> spacing(n, 1.0), offset(n, 0.0), matrix(n * n, 0.0);
    for (std::size_t a = 0; a < n; ++a) matrix[a * n + a] = 1.0;
    if (const MetaImageField* f = header.find("ElementSpacing") ? header.find("ElementSpacing") : header.find("ElementSize")) {
        spacing = header.numbers(*f, n);
        for (const double s : spacing)
            if (s == 0) header.fail(f->name, "a zero spacing");
    }
    if (const MetaImageField* f = header.find_one_of({"Offset", "Position", "Origin", "ImagePosition"})) offset = header.numbers(*f, n);
    const MetaImageField* rotation = header.find_one_of({"TransformMatrix", "Rotation", "Orientation"});
    if (rotation) matrix = header.numbers(*rotation, n * n);
    v.directions = glm::dmat3(1.0);
    for (std::size_t a = 0; a < n; ++a) {
        v.origin[int(a)] = offset[a];
        for (std::size_t r = 0; r < n; ++r) v.directions[int(a)][int(r)] = matrix[a * n + r] * spacing[a];  // triple a: axis a
    }
    if (is_singular(v.directions))
        header.fail(rotation ? rotation->name : "ElementSpacing", "singular: the axes do not span 3D space");

    v.data = read_metaimage_data(in, header, memory_budget_bytes);
    for (std::size_t a = 0; a < 3; ++a) v.size[a] = a < n ? std::size_t(sizes[a]) : 1;
    for (const MetaImageField& f : header.fields())
        if (!is_metaio_field(f.name)) v.key_values.emplace(f.name, f.value);
    return v;
}

std::vector<std::uint8_t> deflate_metaimage_data(const std::filesystem::path& path, std::span<const std::uint8_t> data)
{
    std::vector<std::uint8_t> packed;
    try {
        deflate_stream(data, ZlibWrapper::zlib,  // the zlib format, as MetaIO and PLUS write
                       [&](std::span<const std::uint8_t> s) { packed.insert(packed.end(), s.begin(), s.end()); });
    } catch (const ZlibError& e) {
        fail(path, "compressing the element data: " + std::string(e.what()));
    }
    return packed;
}

void write_metaimage_volume(const std::filesystem::path& path, const Volume& volume, bool compressed)
{
    check_volume(path, volume);
    // compressed first: the header gives the compressed size
    const std::vector<std::uint8_t> packed = compressed ? deflate_metaimage_data(path, volume.data) : std::vector<std::uint8_t>();
    const std::vector<std::uint8_t>& data = compressed ? packed : volume.data;
    const bool detached = text::lower(path.extension().string()) == ".mhd";
    std::filesystem::path data_path = path;
    data_path.replace_extension(compressed ? ".zraw" : ".raw");

    // the header, in the order ITK writes it; key/values before ElementType and ElementDataFile
    const glm::dmat3& d = volume.directions;
    const glm::dvec3 spacing(glm::length(d[0]), glm::length(d[1]), glm::length(d[2]));
    const glm::dmat3 unit(d[0] / spacing.x, d[1] / spacing.y, d[2] / spacing.z);
    std::string h = "ObjectType = Image\nNDims = 3\nBinaryData = True\nBinaryDataByteOrderMSB = False\n";
    h += std::string("CompressedData = ") + (compressed ? "True" : "False") + "\n";
    if (compressed) h += "CompressedDataSize = " + std::to_string(packed.size()) + "\n";
    h += "TransformMatrix = " +
         numbers_text({unit[0].x, unit[0].y, unit[0].z, unit[1].x, unit[1].y, unit[1].z, unit[2].x, unit[2].y, unit[2].z}) + "\n";
    h += "Offset = " + numbers_text({volume.origin.x, volume.origin.y, volume.origin.z}) + "\n";
    h += "CenterOfRotation = 0 0 0\nAnatomicalOrientation = " + orientation_acronym(d) + "\n";
    h += "ElementSpacing = " + numbers_text({spacing.x, spacing.y, spacing.z}) + "\n";
    h += "DimSize = " + std::to_string(volume.size[0]) + " " + std::to_string(volume.size[1]) + " " +
         std::to_string(volume.size[2]) + "\n";
    for (const auto& [key, value] : volume.key_values) h += key + " = " + value + "\n";
    h += std::string("ElementType = ") + to_string(element_type_of(volume.type)) + "\n";
    h += "ElementDataFile = " + (detached ? data_path.filename().string() : std::string("LOCAL")) + "\n";

    PartialFile<MetaImageError> out(path);
    out.write(h);
    if (!detached) {
        out.write(data.data(), data.size());
        out.commit();
        return;
    }
    // the data file first: a header never names a data file that is not there
    PartialFile<MetaImageError> data_out(data_path);
    data_out.write(data.data(), data.size());
    data_out.commit();
    try {
        out.commit();
    } catch (...) {
        std::error_code ec;
        std::filesystem::remove(data_path, ec);
        throw;
    }
}

}  // namespace echosim::io

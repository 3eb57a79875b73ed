#include "io/plus_sequence.hpp"

#include "core/parse_number.hpp"
#include "io/metaimage.hpp"
#include "io/nrrd.hpp"
#include "io/partial_file.hpp"
#include "io/text_fields.hpp"
#include "io/zlib_stream.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <istream>
#include <limits>
#include <map>
#include <optional>
#include <string_view>
#include <utility>

namespace echosim::io {
namespace {

using text::bytes_left;
using text::format_double;
using text::quote_text;
using text::split_whitespace;
using text::trim;
using text::upper;

constexpr std::string_view frame_prefix = "Seq_Frame";

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& why) { text::fail<PlusSequenceError>(path, why); }

// `field` is the name as the file spells it, e.g. Seq_Frame0002_ImageToReferenceTransform.
[[noreturn]] void fail_field(const std::filesystem::path& path, std::string_view field, const std::string& why)
{
    fail(path, std::string(field) + ": " + why);
}

std::string frame_label(std::size_t frame)
{
    char digits[24];
    std::snprintf(digits, sizeof digits, "%04zu", frame);
    return std::string(frame_prefix) + digits;
}

bool read_line(std::istream& in, std::string& line, const std::filesystem::path& path)
{
    return text::read_header_line<PlusSequenceError>(in, line, path, "sequence");
}

using FieldMap = std::map<std::string, std::string, std::less<>>;

// The header's fields, whatever the container: file-wide ones, and per frame (Seq_FrameNNNN_Name).
struct FrameFields {
    std::string label;  // "Seq_Frame0002" as the file spells it
    FieldMap fields;    // "Timestamp", "ImageToReferenceTransform", ...
};
struct SequenceHeader {
    FieldMap file;
    std::map<std::uint64_t, FrameFields> frames;

    const std::string* file_field(std::string_view name) const
    {
        const auto it = file.find(name);
        return it == file.end() ? nullptr : &it->second;
    }
};

void add_field(const std::filesystem::path& path, SequenceHeader& header, std::string_view name, std::string value)
{
    if (!name.starts_with(frame_prefix)) {
        if (!header.file.emplace(std::string(name), std::move(value)).second) fail_field(path, name, "given twice");
        return;
    }
    const std::string_view rest = name.substr(frame_prefix.size());
    const std::size_t digits = std::min(rest.find_first_not_of("0123456789"), rest.size());
    std::uint64_t frame = 0;
    if (!parse_number(rest.substr(0, digits), frame) || digits >= rest.size() || rest[digits] != '_' || digits + 1 == rest.size())
        fail_field(path, name, "malformed frame field name (expected Seq_FrameNNNN_Name)");
    FrameFields& f = header.frames[frame];
    if (f.label.empty()) f.label = std::string(name.substr(0, frame_prefix.size() + digits));
    if (!f.fields.emplace(std::string(rest.substr(digits + 1)), std::move(value)).second)
        fail_field(path, name, "given twice for this frame");
}

glm::dmat4 parse_matrix(const std::filesystem::path& path, std::string_view field, std::string_view text)
{
    const auto tokens = split_whitespace(text);
    if (tokens.size() != 16)
        fail_field(path, field, "expected 16 numbers (a 4x4 matrix, row by row), found " + std::to_string(tokens.size()));
    glm::dmat4 m{1.0};
    for (std::size_t i = 0; i < 16; ++i) {
        double x = 0;
        if (!parse_number(tokens[i], x))
            fail_field(path, field, "entry " + std::to_string(i) + " " + quote_text(tokens[i]) + " is not a number");
        if (!std::isfinite(x))
            fail_field(path, field, "entry " + std::to_string(i) + " " + quote_text(tokens[i]) + " is not finite");
        m[int(i % 4)][int(i / 4)] = x;  // glm is column-major, the file row-major
    }
    if (m[0][3] != 0 || m[1][3] != 0 || m[2][3] != 0 || m[3][3] != 1)
        fail_field(path, field, "the last row is not 0 0 0 1: not an affine transform");
    return m;
}

// OK is valid; the other statuses PLUS writes mark a transform the tracker could not give.
bool parse_status(const std::filesystem::path& path, std::string_view field, std::string_view text)
{
    const std::string s = upper(text);
    if (s == "OK") return true;
    for (const char* invalid : {"INVALID", "MISSING", "OUT_OF_VIEW", "OUT_OF_VOLUME", "REQ_TIMEOUT", "UNKNOWN"})
        if (s == invalid) return false;
    fail_field(path, field, quote_text(text) + " is not a transform status (OK, INVALID, MISSING)");
}

struct Transform {
    glm::dmat4 matrix{1.0};
    bool ok = true;
};

TrackedFrame resolve_frame(const std::filesystem::path& path, const SequenceHeader& header, const FrameFields& frame)
{
    // a transform of this frame, with its status; nullopt when the frame does not have it
    const auto frame_transform = [&](std::string_view name) -> std::optional<Transform> {
        const std::string field = std::string(name) + "Transform";
        const auto it = frame.fields.find(field);
        if (it == frame.fields.end()) return std::nullopt;
        const std::string full = frame.label + "_" + field;
        Transform t{parse_matrix(path, full, it->second), true};
        if (const auto status = frame.fields.find(field + "Status"); status != frame.fields.end())
            t.ok = parse_status(path, full + "Status", status->second);
        return t;
    };
    // the calibration: per frame, else once for the whole file
    const auto image_to_probe = [&]() -> std::optional<Transform> {
        if (auto t = frame_transform("ImageToProbe")) return t;
        const std::string* text = header.file_field("ImageToProbeTransform");
        if (!text) return std::nullopt;
        Transform t{parse_matrix(path, "ImageToProbeTransform", *text), true};
        if (const std::string* status = header.file_field("ImageToProbeTransformStatus"))
            t.ok = parse_status(path, "ImageToProbeTransformStatus", *status);
        return t;
    };

    std::optional<Transform> image_to_reference = frame_transform("ImageToReference");
    if (!image_to_reference) image_to_reference = frame_transform("ImageToTracker");
    for (const char* reference : {"Reference", "Tracker"}) {
        if (image_to_reference) break;
        const auto probe = frame_transform(std::string("ProbeTo") + reference);
        if (!probe) continue;
        const auto calibration = image_to_probe();
        if (!calibration)
            fail_field(path, frame.label + "_ImageToProbeTransform",
                       std::string("missing: ProbeTo") + reference +
                           "Transform needs it, per frame or as a file-wide ImageToProbeTransform");
        image_to_reference = Transform{probe->matrix * calibration->matrix, probe->ok && calibration->ok};
    }
    if (!image_to_reference)
        fail_field(path, frame.label + "_ImageToReferenceTransform",
                   "missing: the frame has no ImageToReference or ImageToTracker transform, nor ProbeToReference or "
                   "ProbeToTracker with ImageToProbe");

    TrackedFrame out;
    out.image_to_reference = image_to_reference->matrix;
    out.valid = image_to_reference->ok;
    for (const char* image_status : {"ImageStatus", "Status"})
        if (const auto it = frame.fields.find(image_status); it != frame.fields.end() && upper(it->second) != "OK")
            out.valid = false;

    const auto timestamp = frame.fields.find("Timestamp");
    if (timestamp == frame.fields.end()) fail_field(path, frame.label + "_Timestamp", "missing");
    if (!parse_number(timestamp->second, out.timestamp) || !std::isfinite(out.timestamp))
        fail_field(path, frame.label + "_Timestamp", quote_text(timestamp->second) + " is not a finite number");
    return out;
}

// Frames 0 to count-1 must all be there, and no others; `count_field` is where the file gives count.
std::vector<TrackedFrame> resolve_frames(const std::filesystem::path& path, const SequenceHeader& header,
                                         std::uint64_t count, std::string_view count_field)
{
    if (!header.frames.empty() && header.frames.rbegin()->first >= count)
        fail_field(path, header.frames.rbegin()->second.label,
                   "the header has fields for this frame, but " + std::string(count_field) + " gives only " +
                       std::to_string(count) + " frames");
    std::vector<TrackedFrame> frames;
    frames.reserve(header.frames.size());  // not count: a lying header fails below before costing memory
    for (std::uint64_t i = 0; i < count; ++i) {
        const auto it = header.frames.find(i);
        if (it == header.frames.end())
            fail_field(path, frame_label(std::size_t(i)),
                       "no transform: " + std::string(count_field) + " gives " + std::to_string(count) +
                           " frames, the header has fields for " + std::to_string(header.frames.size()));
        frames.push_back(resolve_frame(path, header, it->second));
    }
    return frames;
}

constexpr const char* orientation_help = " is not a PLUS orientation (MF, MN, UF, UN, FM, FU, NM, NU)";

bool valid_orientation(std::string_view o)
{
    static constexpr std::array<std::string_view, 8> codes = {"MF", "MN", "UF", "UN", "FM", "FU", "NM", "NU"};
    return std::find(codes.begin(), codes.end(), o) != codes.end();
}

struct FrameGeometry {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint64_t count = 0;
};

// W H N, or W H 1 N; with kinds, the list (or time) axis holds the frames wherever it is.
FrameGeometry frame_geometry(const std::filesystem::path& path, std::string_view sizes_field, std::string_view sizes_text,
                             std::string_view kinds_field, const std::string* kinds_text)
{
    std::vector<std::uint64_t> sizes;
    for (const std::string_view token : split_whitespace(sizes_text)) {
        std::uint64_t s = 0;
        if (!parse_number(token, s) || s == 0) fail_field(path, sizes_field, quote_text(token) + " is not a positive integer");
        sizes.push_back(s);
    }
    std::vector<std::uint64_t> spatial;
    std::optional<std::uint64_t> count;
    if (kinds_text) {
        const auto kinds = split_whitespace(*kinds_text);
        if (kinds.size() != sizes.size())
            fail_field(path, kinds_field, std::to_string(kinds.size()) + " kinds for " + std::to_string(sizes.size()) + " sizes");
        for (std::size_t a = 0; a < kinds.size(); ++a) {
            const std::string kind = upper(kinds[a]);
            if (kind == "DOMAIN" || kind == "SPACE") spatial.push_back(sizes[a]);
            else if ((kind == "LIST" || kind == "TIME") && !count) count = sizes[a];
            else fail_field(path, kinds_field, quote_text(kinds[a]) + " axis: frames must be single-channel 2D images in a list");
        }
    } else if (sizes.size() == 3 || sizes.size() == 4) {
        spatial.assign(sizes.begin(), sizes.end() - 1);
        count = sizes.back();
    }
    if (!count || spatial.size() < 2 || spatial.size() > 3 || (spatial.size() == 3 && spatial[2] != 1))
        fail_field(path, sizes_field, quote_text(sizes_text) + ": expected W H N (or W H 1 N) for N frames of W x H pixels");
    if (spatial[0] > std::numeric_limits<std::uint32_t>::max() || spatial[1] > std::numeric_limits<std::uint32_t>::max())
        fail_field(path, sizes_field, "a frame wider or taller than 2^32 pixels");
    return {std::uint32_t(spatial[0]), std::uint32_t(spatial[1]), *count};
}

std::uint64_t pixel_bytes(const std::filesystem::path& path, std::string_view sizes_field, const FrameGeometry& g,
                          std::uint64_t budget)
{
    const std::uint64_t frame = std::uint64_t(g.width) * g.height;  // < 2^64: both below 2^32
    if (g.count > std::numeric_limits<std::uint64_t>::max() / frame)
        fail_field(path, sizes_field, "the pixel count overflows 64 bits");
    const std::uint64_t bytes = frame * g.count;
    if (bytes > budget || bytes > std::numeric_limits<std::size_t>::max())
        fail_field(path, sizes_field, std::to_string(bytes) + " bytes of pixels exceed the memory budget of " +
                                          std::to_string(budget) + " bytes");
    return bytes;
}

// The pixels from a zlib stream of at most `packed` bytes (io/metaimage.hpp's, in our error type).
std::vector<std::uint8_t> inflate_pixels(const std::filesystem::path& path, std::istream& in, std::uint64_t bytes,
                                         std::uint64_t packed)
{
    try {
        return inflate_metaimage_data(path, in, bytes, packed, "DimSize");
    } catch (const MetaImageError& e) {
        throw PlusSequenceError(e.what());  // the message already names file and field
    }
}

Sweep read_mha(const std::filesystem::path& path, std::istream& in, std::uint64_t budget)
{
    // the text header, up to ElementDataFile: the last field, after which the pixels start
    SequenceHeader header;
    std::string line;
    for (std::size_t number = 1;; ++number) {
        if (!read_line(in, line, path)) fail(path, "truncated header: the file ends before 'ElementDataFile = LOCAL'");
        if (trim(line).empty()) continue;
        const auto eq = line.find('=');
        if (eq == std::string::npos)
            fail(path, "header line " + std::to_string(number) + " is not 'Name = Value': " + quote_text(line) +
                           " (not a MetaImage sequence file?)");
        const std::string_view name = trim(std::string_view(line).substr(0, eq));
        const std::string_view value = trim(std::string_view(line).substr(eq + 1));
        if (name == "ElementDataFile") {
            if (upper(value) != "LOCAL")
                fail_field(path, name, "detached pixel data (" + quote_text(value) +
                                           ") is not supported: use a .mha with ElementDataFile = LOCAL");
            break;
        }
        add_field(path, header, name, std::string(value));
    }

    // what the pixels are
    const auto require = [&](std::string_view name) -> const std::string& {
        if (const std::string* v = header.file_field(name)) return *v;
        fail_field(path, name, "missing");
    };
    const auto expect = [&](std::string_view name, std::string_view wanted, const std::string& why) {
        if (const std::string* v = header.file_field(name); v && upper(*v) != upper(wanted))
            fail_field(path, name, quote_text(*v) + ": " + why);
    };
    expect("ObjectType", "Image", "not an image sequence");
    expect("BinaryData", "True", "only binary pixel data is supported");
    expect("ElementNumberOfChannels", "1", "only single-channel (greyscale) frames are supported");
    if (const std::string& type = require("ElementType"); type != "MET_UCHAR")
        fail_field(path, "ElementType", quote_text(type) + " is not supported: only MET_UCHAR (8-bit greyscale)");
    const std::string& dims = require("DimSize");
    if (const std::string* ndims = header.file_field("NDims")) {
        std::uint64_t n = 0;
        if (!parse_number(*ndims, n) || n != split_whitespace(dims).size())
            fail_field(path, "NDims", quote_text(*ndims) + " does not match DimSize " + quote_text(dims));
    }
    const FrameGeometry geometry = frame_geometry(path, "DimSize", dims, "Kinds", header.file_field("Kinds"));
    bool compressed = false;
    if (const std::string* c = header.file_field("CompressedData")) {
        if (upper(*c) != "TRUE" && upper(*c) != "FALSE")
            fail_field(path, "CompressedData", quote_text(*c) + " is neither True nor False");
        compressed = upper(*c) == "TRUE";
    }

    Sweep sweep;
    sweep.width = geometry.width;
    sweep.height = geometry.height;
    if (const std::string* o = header.file_field("UltrasoundImageOrientation")) sweep.orientation = *o;
    if (!valid_orientation(sweep.orientation))
        fail_field(path, "UltrasoundImageOrientation", quote_text(sweep.orientation) + orientation_help);
    const std::uint64_t bytes = pixel_bytes(path, "DimSize", geometry, budget);
    sweep.frames = resolve_frames(path, header, geometry.count, "DimSize");

    // the pixels, checked against what is left of the file before allocating
    if (!compressed) {
        std::uint64_t found = 0;
        auto pixels = text::read_exactly(in, bytes, found);
        if (!pixels)
            fail_field(path, "ElementDataFile", "truncated pixel data: " + std::to_string(found) +
                                                    " bytes after the header, DimSize needs " + std::to_string(bytes));
        sweep.pixels = std::move(*pixels);
        return sweep;
    }
    const std::uint64_t left = bytes_left(in);
    std::uint64_t packed = left;
    if (const std::string* size = header.file_field("CompressedDataSize")) {
        std::uint64_t n = 0;
        if (!parse_number(*size, n) || n == 0)
            fail_field(path, "CompressedDataSize", quote_text(*size) + " is not a positive integer");
        if (n > left)
            fail_field(path, "CompressedDataSize", "truncated pixel data: " + *size + " compressed bytes announced, " +
                                                       std::to_string(left) + " left in the file");
        packed = n;
    }
    sweep.pixels = inflate_pixels(path, in, bytes, packed);
    return sweep;
}

Sweep read_seq_nrrd(const std::filesystem::path& path, std::istream& in, std::uint64_t budget)
{
    const NrrdHeader nrrd = read_nrrd_header(in, path);
    if (nrrd.type() != VoxelType::uint8) nrrd.fail("type", "only unsigned char (8-bit greyscale) frames are supported");
    SequenceHeader header;
    for (const auto& [key, value] : nrrd.key_values) add_field(path, header, key, value);
    nrrd.sizes();  // checks sizes against dimension
    const FrameGeometry geometry = frame_geometry(path, "sizes", nrrd.require("sizes"), "kinds", nrrd.find("kinds"));

    Sweep sweep;
    sweep.width = geometry.width;
    sweep.height = geometry.height;
    if (const std::string* o = header.file_field("ultrasound image orientation")) sweep.orientation = *o;
    else if (const std::string* f = nrrd.find("ultrasound image orientation")) sweep.orientation = *f;
    if (!valid_orientation(sweep.orientation))
        fail_field(path, "ultrasound image orientation", quote_text(sweep.orientation) + orientation_help);
    pixel_bytes(path, "sizes", geometry, budget);
    sweep.frames = resolve_frames(path, header, geometry.count, "sizes");
    sweep.pixels = read_nrrd_data(in, nrrd, budget);
    return sweep;
}

void check_sweep(const std::filesystem::path& path, const Sweep& sweep)
{
    if (sweep.width == 0 || sweep.height == 0 || sweep.frames.empty()) fail(path, "refusing to write an empty sweep");
    if (sweep.pixels.size() / sweep.frame_bytes() != sweep.frames.size() || sweep.pixels.size() % sweep.frame_bytes() != 0)
        fail(path, "pixels hold " + std::to_string(sweep.pixels.size()) + " bytes, " + std::to_string(sweep.frames.size()) +
                       " frames of " + std::to_string(sweep.width) + " x " + std::to_string(sweep.height) + " need " +
                       std::to_string(sweep.frame_bytes() * sweep.frames.size()));
    if (!valid_orientation(sweep.orientation))
        fail_field(path, "UltrasoundImageOrientation", quote_text(sweep.orientation) + orientation_help);
    for (std::size_t i = 0; i < sweep.frames.size(); ++i) {
        const TrackedFrame& f = sweep.frames[i];
        if (!std::isfinite(f.timestamp)) fail_field(path, frame_label(i) + "_Timestamp", "not finite");
        const glm::dmat4& m = f.image_to_reference;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r)
                if (!std::isfinite(m[c][r])) fail_field(path, frame_label(i) + "_ImageToReferenceTransform", "not finite");
        if (m[0][3] != 0 || m[1][3] != 0 || m[2][3] != 0 || m[3][3] != 1)
            fail_field(path, frame_label(i) + "_ImageToReferenceTransform",
                       "the last row is not 0 0 0 1: not an affine transform");
    }
}

}  // namespace

void write_plus_mha(const std::filesystem::path& path, const Sweep& sweep, bool compressed)
{
    check_sweep(path, sweep);
    // compressed first: the header gives the compressed size
    std::vector<std::uint8_t> packed;
    if (compressed) {
        try {
            deflate_stream(sweep.pixels, ZlibWrapper::zlib,  // the zlib format, as PLUS writes
                           [&](std::span<const std::uint8_t> s) { packed.insert(packed.end(), s.begin(), s.end()); });
        } catch (const ZlibError& e) {
            fail(path, "compressing the pixels: " + std::string(e.what()));
        }
    }

    const std::string frame_count = std::to_string(sweep.frames.size());
    std::string h = "ObjectType = Image\nNDims = 3\nAnatomicalOrientation = RAI\nBinaryData = True\n"
                    "BinaryDataByteOrderMSB = False\nCenterOfRotation = 0 0 0\n";
    h += std::string("CompressedData = ") + (compressed ? "True" : "False") + "\n";
    if (compressed) h += "CompressedDataSize = " + std::to_string(packed.size()) + "\n";
    h += "DimSize = " + std::to_string(sweep.width) + " " + std::to_string(sweep.height) + " " + frame_count + "\n";
    h += "ElementNumberOfChannels = 1\nElementSpacing = 1 1 1\nKinds = domain domain list\nOffset = 0 0 0\n"
         "TransformMatrix = 1 0 0 0 1 0 0 0 1\n";
    h += "UltrasoundImageOrientation = " + sweep.orientation + "\nUltrasoundImageType = BRIGHTNESS\n";
    for (std::size_t i = 0; i < sweep.frames.size(); ++i) {
        const TrackedFrame& f = sweep.frames[i];
        const std::string label = frame_label(i);
        h += label + "_ImageToReferenceTransform =";
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) h += " " + format_double(f.image_to_reference[c][r]);  // row by row
        h += "\n" + label + "_ImageToReferenceTransformStatus = " + (f.valid ? "OK" : "INVALID") + "\n";
        h += label + "_Timestamp = " + format_double(f.timestamp) + "\n";
    }
    h += "ElementType = MET_UCHAR\nElementDataFile = LOCAL\n";

    PartialFile<PlusSequenceError> out(path);
    out.write(h.data(), h.size());
    if (compressed) out.write(packed.data(), packed.size());
    else out.write(sweep.pixels.data(), sweep.pixels.size());
    out.commit();
}

Sweep read_plus_sequence(const std::filesystem::path& path, std::uint64_t memory_budget_bytes)
{
    std::ifstream in = text::open_binary<PlusSequenceError>(path);
    char magic[4] = {};
    in.read(magic, sizeof magic);
    in.clear();
    in.seekg(0);
    if (std::string_view(magic, sizeof magic) != "NRRD") return read_mha(path, in, memory_budget_bytes);
    try {
        return read_seq_nrrd(path, in, memory_budget_bytes);
    } catch (const NrrdError& e) {
        throw PlusSequenceError(e.what());  // one error type for callers; the message already names file and field
    }
}

}  // namespace echosim::io

#include "io/plus_sequence.hpp"

#include "core/parse_number.hpp"
#include "io/metaimage.hpp"
#include "io/nrrd.hpp"
#include "io/partial_file.hpp"
#include "io/text_fields.hpp"

#include <algorithm>
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

using text::format_double;
using text::quote_text;
using text::split_whitespace;
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

// `usable`: the matrix is used, so it must be finite and affine; a transform the tracker marked
// invalid only has to be 16 numbers (trackers leave zeros or NaN there).
glm::dmat4 parse_matrix(const std::filesystem::path& path, std::string_view field, std::string_view text, bool usable = true)
{
    const auto tokens = split_whitespace(text);
    if (tokens.size() != 16)
        fail_field(path, field, "expected 16 numbers (a 4x4 matrix, row by row), found " + std::to_string(tokens.size()));
    glm::dmat4 m{1.0};
    for (std::size_t i = 0; i < 16; ++i) {
        double x = 0;
        if (!parse_number(tokens[i], x))
            fail_field(path, field, "entry " + std::to_string(i) + " " + quote_text(tokens[i]) + " is not a number");
        if (!std::isfinite(x) && usable)
            fail_field(path, field, "entry " + std::to_string(i) + " " + quote_text(tokens[i]) + " is not finite");
        m[int(i % 4)][int(i / 4)] = x;  // glm is column-major, the file row-major
    }
    // an unusable one is kept as written when it is a transform at all, for what writes it back
    if (!usable) return is_affine(m) && all_finite(m) ? m : glm::dmat4(1.0);
    if (!is_affine(m))
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

// Every `<From>To<To>Transform` among `fields` (a frame's, or the file's), with its status (none
// given: OK). An invalid transform's matrix is not checked: trackers leave anything there.
std::vector<RecordedTransform> recorded_transforms(const std::filesystem::path& path, const FieldMap& fields,
                                                   const std::string& prefix)
{
    constexpr std::string_view suffix = "Transform";
    std::vector<RecordedTransform> out;
    for (const auto& [name, value] : fields) {
        if (!std::string_view(name).ends_with(suffix)) continue;
        const auto frames = split_transform_name(std::string_view(name).substr(0, name.size() - suffix.size()));
        if (!frames) continue;  // not a transform PLUS could name either
        const std::string field = prefix + name;
        if (frames->first == frames->second) fail_field(path, field, "a transform from a frame to itself");
        RecordedTransform t{frames->first, frames->second, glm::dmat4(1.0), true};
        if (const auto status = fields.find(name + "Status"); status != fields.end())
            t.valid = parse_status(path, field + "Status", status->second);
        t.matrix = parse_matrix(path, field, value, t.valid);
        out.push_back(std::move(t));
    }
    return out;
}

RecordedFrame record_frame(const std::filesystem::path& path, const FrameFields& frame)
{
    RecordedFrame out;
    out.label = frame.label;
    out.transforms = recorded_transforms(path, frame.fields, frame.label + "_");
    // ImageStatus in .mha, Status in .seq.nrrd
    for (const char* image_status : {"ImageStatus", "Status"})
        if (const auto it = frame.fields.find(image_status); it != frame.fields.end() && upper(it->second) != "OK")
            out.image_valid = false;
    const auto timestamp = frame.fields.find("Timestamp");
    if (timestamp == frame.fields.end()) fail_field(path, frame.label + "_Timestamp", "missing");
    if (!parse_number(timestamp->second, out.timestamp) || !std::isfinite(out.timestamp))
        fail_field(path, frame.label + "_Timestamp", quote_text(timestamp->second) + " is not a finite number");
    return out;
}

// Frames 0 to count-1 must all be there, and no others; `count_field` is where the file gives count.
std::vector<RecordedFrame> record_frames(const std::filesystem::path& path, const SequenceHeader& header, std::uint64_t count,
                                         std::string_view count_field)
{
    if (!header.frames.empty() && header.frames.rbegin()->first >= count)
        fail_field(path, header.frames.rbegin()->second.label,
                   "the header has fields for this frame, but " + std::string(count_field) + " gives only " +
                       std::to_string(count) + " frames");
    std::vector<RecordedFrame> frames;
    frames.reserve(header.frames.size());  // not count: a lying header fails below before costing memory
    for (std::uint64_t i = 0; i < count; ++i) {
        const auto it = header.frames.find(i);
        if (it == header.frames.end())
            fail_field(path, frame_label(std::size_t(i)),
                       "no fields: " + std::string(count_field) + " gives " + std::to_string(count) +
                           " frames, the header has fields for " + std::to_string(header.frames.size()));
        frames.push_back(record_frame(path, it->second));
    }
    return frames;
}

// PLUS's orientations of an image: the letters of its x and y axes (M or U: toward the probe's
// marked or unmarked side; F or N: away from or toward the transducer), and for a volume a third
// letter for its z axis (A or D: ascending or descending), which a 2D frame has no use for.
struct Orientation {
    char x = 'M', y = 'F';
};

constexpr const char* orientation_help =
    " is not a PLUS orientation of 2D frames (MF, MN, UF, UN, FM, FU, NM, NU, each with or without A or D)";

std::optional<Orientation> parse_orientation(std::string_view text)
{
    const std::string o = upper(text);
    if (o.size() != 2 && !(o.size() == 3 && (o[2] == 'A' || o[2] == 'D'))) return std::nullopt;
    const auto lateral = [](char c) { return c == 'M' || c == 'U'; };
    const auto beam = [](char c) { return c == 'F' || c == 'N'; };
    if ((lateral(o[0]) && beam(o[1])) || (beam(o[0]) && lateral(o[1]))) return Orientation{o[0], o[1]};
    return std::nullopt;
}

// The frames turned to MF, as PLUS's reader does (its FlipImage; it leaves the transposed FM, FU,
// NM and NU to RF data, which echosim turns as well): sizes come back as the MF image's.
void orient_to_mf(Sweep& sweep, Orientation o)
{
    if (o.x == 'M' && o.y == 'F') return;
    const std::size_t w = sweep.width, h = sweep.height, es = voxel_size(sweep.pixel_type);
    const bool transposed = o.x == 'F' || o.x == 'N';
    const std::size_t out_w = transposed ? h : w, out_h = transposed ? w : h;
    std::vector<std::uint8_t> frame(w * h * es);
    for (std::size_t f = 0; f < sweep.frames.size(); ++f) {
        std::uint8_t* pixels = sweep.pixels.data() + f * w * h * es;
        std::copy(pixels, pixels + frame.size(), frame.begin());
        for (std::size_t j = 0; j < h; ++j)
            for (std::size_t i = 0; i < w; ++i) {
                // where pixel (i, j) lies across (lateral) and along (depth) the beam
                std::size_t lateral, depth;
                if (!transposed) {
                    lateral = o.x == 'M' ? i : w - 1 - i;
                    depth = o.y == 'F' ? j : h - 1 - j;
                } else {
                    depth = o.x == 'F' ? i : w - 1 - i;
                    lateral = o.y == 'M' ? j : h - 1 - j;
                }
                std::copy_n(frame.data() + (j * w + i) * es, es, pixels + (depth * out_w + lateral) * es);
            }
    }
    sweep.width = std::uint32_t(out_w);
    sweep.height = std::uint32_t(out_h);
}

struct FrameGeometry {
    std::uint32_t width = 0;
    std::uint32_t height = 0;
    std::uint64_t count = 0;
    std::vector<std::uint64_t> sizes;  // as the file gives them
    std::size_t list_axis = 0;         // the one that counts the frames
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
    std::size_t list_axis = sizes.empty() ? 0 : sizes.size() - 1;
    if (kinds_text) {
        const auto kinds = split_whitespace(*kinds_text);
        if (kinds.size() != sizes.size())
            fail_field(path, kinds_field, std::to_string(kinds.size()) + " kinds for " + std::to_string(sizes.size()) + " sizes");
        for (std::size_t a = 0; a < kinds.size(); ++a) {
            const std::string kind = upper(kinds[a]);
            if (kind == "DOMAIN" || kind == "SPACE") spatial.push_back(sizes[a]);
            else if ((kind == "LIST" || kind == "TIME") && !count) count = sizes[a], list_axis = a;
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
    return {std::uint32_t(spatial[0]), std::uint32_t(spatial[1]), *count, sizes, list_axis};
}

// The pixels frame after frame, whichever axis of the file counts the frames (`kinds: list domain
// domain` puts them first: pixel (x, y) of frame f then lies at f + N * (x + W * y)).
void frames_last(Sweep& sweep, const FrameGeometry& g)
{
    if (g.list_axis + 1 == g.sizes.size() || g.count == 1) return;
    std::vector<std::uint64_t> stride(g.sizes.size(), 1);
    for (std::size_t a = 1; a < g.sizes.size(); ++a) stride[a] = stride[a - 1] * g.sizes[a - 1];
    std::vector<std::size_t> spatial;  // the axes of x and y, in order
    for (std::size_t a = 0; a < g.sizes.size(); ++a)
        if (a != g.list_axis) spatial.push_back(a);
    const std::size_t es = voxel_size(sweep.pixel_type);
    std::vector<std::uint8_t> out(sweep.pixels.size());
    std::size_t at = 0;
    for (std::uint64_t f = 0; f < g.count; ++f)
        for (std::uint64_t y = 0; y < g.height; ++y)
            for (std::uint64_t x = 0; x < g.width; ++x, at += es) {
                const std::uint64_t from = f * stride[g.list_axis] + x * stride[spatial[0]] + y * stride[spatial[1]];
                std::copy_n(sweep.pixels.data() + from * es, es, out.data() + at);
            }
    sweep.pixels.swap(out);
}

std::uint64_t pixel_bytes(const std::filesystem::path& path, std::string_view sizes_field, const FrameGeometry& g,
                          std::size_t element_bytes, std::uint64_t budget)
{
    std::uint64_t frame = std::uint64_t(g.width) * g.height;  // < 2^64: both below 2^32
    if (frame > std::numeric_limits<std::uint64_t>::max() / element_bytes) fail_field(path, sizes_field, "the pixel count overflows 64 bits");
    frame *= element_bytes;
    if (g.count > std::numeric_limits<std::uint64_t>::max() / frame)
        fail_field(path, sizes_field, "the pixel count overflows 64 bits");
    const std::uint64_t bytes = frame * g.count;
    if (bytes > budget || bytes > std::numeric_limits<std::size_t>::max())
        fail_field(path, sizes_field, std::to_string(bytes) + " bytes of pixels exceed the memory budget of " +
                                          std::to_string(budget) + " bytes");
    return bytes;
}

// What the header says of the images, before any pixel is read: sizes, type, the file's
// orientation (none given: MF, as PLUS assumes) and the file-wide transforms.
PlusRecording start_recording(const std::filesystem::path& path, const SequenceHeader& header, const FrameGeometry& geometry,
                              std::string_view orientation_field, const std::string* orientation, VoxelType type)
{
    PlusRecording r;
    r.images.width = geometry.width;
    r.images.height = geometry.height;
    r.images.pixel_type = type;
    r.orientation_in_file = orientation ? *orientation : "MF";
    if (!parse_orientation(r.orientation_in_file)) {
        if (upper(r.orientation_in_file) == "AMF")
            fail_field(path, orientation_field, "'AMF' orients volumes (x across the frames), not a sequence of 2D frames");
        fail_field(path, orientation_field, quote_text(r.orientation_in_file) + orientation_help);
    }
    r.file_transforms = recorded_transforms(path, header.file, "");
    return r;
}

// The frames' pixel type, from a MetaImage ElementType.
VoxelType sweep_pixel_type(const MetaImageHeader& meta)
{
    if (const auto type = exact_voxel_type(meta.element_type())) return *type;
    meta.fail("ElementType", quote_text(meta.require("ElementType").value) +
                                 " frames are not supported: MET_UCHAR, MET_USHORT, MET_SHORT or MET_FLOAT");
}

PlusRecording read_mha(const std::filesystem::path& path, std::istream& in, std::uint64_t budget)
{
    const MetaImageHeader meta = read_metaimage_header(in, path, text::unbounded_header_bytes);  // check_header_size bounded it
    SequenceHeader header;
    for (const MetaImageField& f : meta.fields())
        if (f.name != "ElementDataFile") add_field(path, header, f.name, f.value);

    // what the pixels are
    if (const auto* o = meta.find("ObjectType"); o && upper(o->value) != "IMAGE")
        meta.fail("ObjectType", quote_text(o->value) + ": not an image sequence");
    if (meta.channels() != 1) meta.fail("ElementNumberOfChannels", "only single-channel (greyscale) frames are supported");
    const VoxelType type = sweep_pixel_type(meta);
    const std::string& dims = meta.require("DimSize").value;
    meta.dim_size();  // checks DimSize against NDims
    const FrameGeometry geometry = frame_geometry(path, "DimSize", dims, "Kinds", header.file_field("Kinds"));
    PlusRecording recording = start_recording(path, header, geometry, "UltrasoundImageOrientation",
                                              header.file_field("UltrasoundImageOrientation"), type);
    pixel_bytes(path, "DimSize", geometry, voxel_size(type), budget);
    recording.frames = record_frames(path, header, geometry.count, "DimSize");
    // the pixels, their size checked against the budget and the file before allocating
    recording.images.pixels = read_metaimage_data(in, meta, budget);
    frames_last(recording.images, geometry);
    return recording;
}

PlusRecording read_seq_nrrd(const std::filesystem::path& path, std::istream& in, std::uint64_t budget)
{
    const NrrdHeader nrrd = read_nrrd_header(in, path, text::unbounded_header_bytes);  // check_header_size bounded it
    const VoxelType type = nrrd.type();
    SequenceHeader header;
    for (const auto& [key, value] : nrrd.key_values) add_field(path, header, key, value);
    nrrd.sizes();  // checks sizes against dimension
    const FrameGeometry geometry = frame_geometry(path, "sizes", nrrd.require("sizes"), "kinds", nrrd.find("kinds"));

    const std::string* orientation = header.file_field("ultrasound image orientation");
    if (!orientation) orientation = nrrd.find("ultrasound image orientation");
    PlusRecording recording = start_recording(path, header, geometry, "ultrasound image orientation", orientation, type);
    pixel_bytes(path, "sizes", geometry, voxel_size(type), budget);
    recording.frames = record_frames(path, header, geometry.count, "sizes");
    recording.images.pixels = read_nrrd_data(in, nrrd, budget);
    frames_last(recording.images, geometry);
    return recording;
}

// A sequence header grows with its frames: PLUS writes, per frame, FrameNumber, ImageStatus,
// Timestamp, UnfilteredTimestamp and each tool's transform and status (about 600 bytes with three
// tools). The header may take 1 MiB for its file-wide fields and 4 KiB for each frame its sizes
// allow (room for some 25 tools): a header past that is refused before it is parsed, read once line
// by line and nothing kept (a 169 MB header of one frame's fields took 3.8 GB: issue 34).
constexpr std::uint64_t header_base_bytes = std::uint64_t(1) << 20;
constexpr std::uint64_t header_frame_bytes = std::uint64_t(4) << 10;

// The frames a header's sizes allow: the largest of them (the frames may be counted on any axis).
std::uint64_t largest_size(std::string_view sizes)
{
    std::uint64_t most = 0;
    for (const std::string_view token : split_whitespace(sizes)) {
        std::uint64_t n = 0;
        if (parse_number(token, n)) most = std::max(most, n);
    }
    return most;
}

// Throws naming the file when the header runs past its allowance; leaves `in` at the file's start.
void check_header_size(const std::filesystem::path& path, std::istream& in, bool nrrd)
{
    std::string line;
    std::uint64_t bytes = 0, frames = 0;
    const std::uint64_t most_frames = (std::numeric_limits<std::uint64_t>::max() - header_base_bytes) / header_frame_bytes;
    for (bool first = true; text::read_header_line<PlusSequenceError>(in, line, path, nrrd ? "NRRD" : "MetaImage"); first = false) {
        bytes += line.size() + 1;
        const std::string_view l = line;
        if (nrrd && !first && text::trim(l).empty()) break;  // NRRD's header ends at its first blank line
        const auto sep = l.find(nrrd ? ':' : '=');
        const std::string_view name = text::trim(l.substr(0, std::min(sep, l.size())));
        if (!nrrd && name == "ElementDataFile") break;
        if (sep != std::string_view::npos && l.substr(sep, 2) != ":=" && (nrrd ? name == "sizes" : name == "DimSize"))
            frames = std::min(largest_size(l.substr(sep + 1)), most_frames);
        if (bytes > header_base_bytes + header_frame_bytes * frames)
            fail(path, "the header runs past " + std::to_string(bytes - line.size() - 1) + " bytes, more than a sequence of " +
                           std::to_string(frames) + " frames needs (1 MiB, and 4 KiB a frame: " +
                           std::to_string(header_base_bytes + header_frame_bytes * frames) + " bytes)");
    }
    in.clear();
    in.seekg(0);
}

void check_sweep(const std::filesystem::path& path, const Sweep& sweep)
{
    if (sweep.width == 0 || sweep.height == 0 || sweep.frames.empty()) fail(path, "refusing to write an empty sweep");
    if (sweep.pixels.size() / sweep.frame_bytes() != sweep.frames.size() || sweep.pixels.size() % sweep.frame_bytes() != 0)
        fail(path, "pixels hold " + std::to_string(sweep.pixels.size()) + " bytes, " + std::to_string(sweep.frames.size()) +
                       " frames of " + std::to_string(sweep.width) + " x " + std::to_string(sweep.height) + " need " +
                       std::to_string(sweep.frame_bytes() * sweep.frames.size()));
    if (!parse_orientation(sweep.orientation))
        fail_field(path, "UltrasoundImageOrientation", quote_text(sweep.orientation) + orientation_help);
    for (std::size_t i = 0; i < sweep.frames.size(); ++i) {
        const TrackedFrame& f = sweep.frames[i];
        if (!std::isfinite(f.timestamp)) fail_field(path, frame_label(i) + "_Timestamp", "not finite");
        const glm::dmat4& m = f.image_to_reference;
        if (!all_finite(m)) fail_field(path, frame_label(i) + "_ImageToReferenceTransform", "not finite");
        if (!is_affine(m))
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
            packed = deflate_metaimage_data(path, sweep.pixels);
        } catch (const MetaImageError& e) {
            throw PlusSequenceError(e.what());
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
    h += std::string("ElementType = ") + to_string(element_type_of(sweep.pixel_type)) + "\nElementDataFile = LOCAL\n";

    PartialFile<PlusSequenceError> out(path);
    out.write(h.data(), h.size());
    if (compressed) out.write(packed.data(), packed.size());
    else out.write(sweep.pixels.data(), sweep.pixels.size());
    out.commit();
}

PlusRecording read_plus_recording(const std::filesystem::path& path, std::uint64_t memory_budget_bytes)
{
    std::ifstream in = text::open_binary<PlusSequenceError>(path);
    char magic[4] = {};
    in.read(magic, sizeof magic);
    in.clear();
    in.seekg(0);
    const bool nrrd = std::string_view(magic, sizeof magic) == "NRRD";
    check_header_size(path, in, nrrd);
    PlusRecording r;
    if (!nrrd) {
        try {
            r = read_mha(path, in, memory_budget_bytes);
        } catch (const MetaImageError& e) {
            throw PlusSequenceError(e.what());  // one error type for callers; the message already names file and field
        }
    } else {
        try {
            r = read_seq_nrrd(path, in, memory_budget_bytes);
        } catch (const NrrdError& e) {
            throw PlusSequenceError(e.what());  // one error type for callers; the message already names file and field
        }
    }
    r.images.frames.resize(r.frames.size());
    orient_to_mf(r.images, *parse_orientation(r.orientation_in_file));
    r.images.orientation = "MF";
    for (std::size_t f = 0; f < r.frames.size(); ++f) {
        r.images.frames[f].timestamp = r.frames[f].timestamp;
        r.images.frames[f].image_valid = r.frames[f].image_valid;
        r.images.frames[f].valid = false;  // until resolved
    }
    return r;
}

namespace {

// The transforms a frame can chain through: the configuration's, the file's, then the frame's own.
TransformRepository frame_repository(const PlusRecording& recording, std::size_t f, const TransformRepository& config)
{
    TransformRepository repo = config;
    for (const auto* list : {&recording.file_transforms, &recording.frames[f].transforms})
        for (const RecordedTransform& t : *list) repo.set(t.from, t.to, t.matrix, t.valid);
    return repo;
}

// Frames naming the same transforms share one chain; this many different sets at most.
constexpr std::size_t max_transform_name_sets = 64;

// Which transforms a frame names, as written: frames naming the same ones share one chain.
std::vector<std::pair<std::string, std::string>> transform_names(const RecordedFrame& frame)
{
    std::vector<std::pair<std::string, std::string>> names;
    names.reserve(frame.transforms.size());
    for (const RecordedTransform& t : frame.transforms) names.emplace_back(t.from, t.to);
    std::sort(names.begin(), names.end());
    return names;
}

}  // namespace

Sweep resolve_sweep(const std::filesystem::path& path, PlusRecording recording, const TransformRepository& config,
                    const std::string& image_frame, const std::string& reference_frame)
{
    Sweep sweep = std::move(recording.images);
    // The chain is searched once for each set of transform names the frames hold (one set, in what
    // trackers write), its repository kept and each frame's matrices set into it: a frame costs its
    // own transforms and the chain's length, not a copy of every transform and a search (issue 34).
    struct Shared {
        TransformRepository repo;
        std::optional<std::vector<TransformRepository::Step>> chain;
    };
    std::map<std::vector<std::pair<std::string, std::string>>, Shared> by_names;
    for (std::size_t f = 0; f < recording.frames.size(); ++f) {
        const RecordedFrame& frame = recording.frames[f];
        try {
            auto [at, added] = by_names.try_emplace(transform_names(frame));
            Shared& shared = at->second;
            // each new set costs a copy and a search of every transform: bounded, so frames that
            // each name transforms of their own cannot make the work frames x transforms
            if (added && by_names.size() > max_transform_name_sets)
                fail_field(path, frame.label,
                           "the frames name more than " + std::to_string(max_transform_name_sets) +
                               " different sets of transforms (a tracker writes the same ones in every frame, its "
                               "status saying when one is missing)");
            if (added) {
                shared.repo = frame_repository(recording, f, config);
                shared.chain = shared.repo.chain(image_frame, reference_frame);
                if (!shared.chain) shared.repo.get(image_frame, reference_frame);  // throws, saying what is missing
            } else {
                for (const RecordedTransform& t : frame.transforms) shared.repo.set(t.from, t.to, t.matrix, t.valid);
            }
            const FrameTransform t = shared.repo.product(*shared.chain);
            sweep.frames[f].image_to_reference = t.matrix;
            sweep.frames[f].valid = t.valid && frame.image_valid;
        } catch (const TransformError& e) {
            fail_field(path, frame.label, e.what());
        }
    }
    return sweep;
}

std::vector<AlsoRecorded> transforms_also_recorded(const PlusRecording& recording, const TransformRepository& config)
{
    std::vector<AlsoRecorded> out;
    std::map<std::pair<std::string, std::string>, std::size_t> in_frames;  // name as written -> frames holding it
    for (const RecordedFrame& frame : recording.frames)
        for (const RecordedTransform& t : frame.transforms) ++in_frames[{t.from, t.to}];
    for (const RecordedTransform& t : recording.file_transforms)
        if (config.held(t.from, t.to)) out.push_back({t.from, t.to, 0});
    for (const auto& [name, frames] : in_frames)
        if (config.held(name.first, name.second)) out.push_back({name.first, name.second, frames});
    return out;
}

std::string default_reference_frame(const PlusRecording& recording)
{
    if (recording.frames.empty()) return "Reference";
    const TransformRepository first = frame_repository(recording, 0, {});
    try {
        if (!first.find("Image", "Reference") && (first.find("Image", "Tracker") || (!first.knows("Reference") && first.knows("Tracker"))))
            return "Tracker";
    } catch (const TransformError&) {
        // a chain through a singular transform it would have to invert: resolve_sweep names it, with the file and frame
    }
    return "Reference";
}

Sweep read_plus_sequence(const std::filesystem::path& path, std::uint64_t memory_budget_bytes)
{
    PlusRecording recording = read_plus_recording(path, memory_budget_bytes);
    const std::string reference = default_reference_frame(recording);
    return resolve_sweep(path, std::move(recording), {}, "Image", reference);
}

}  // namespace echosim::io

#include "io/nrrd.hpp"

#include "core/parse_number.hpp"
#include "io/partial_file.hpp"
#include "io/text_fields.hpp"
#include "io/zlib_stream.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <istream>
#include <limits>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

namespace echosim::io {
namespace {

using text::format_double;
using text::lower;
using text::quote_text;
using text::split_whitespace;
using text::trim;

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& why) { text::fail<NrrdError>(path, why); }

// NRRD key/value escaping: a backslash and a newline are written as \\ and \n.
std::string escape(std::string_view s)
{
    std::string out;
    for (const char c : s) {
        if (c == '\\') out += "\\\\";
        else if (c == '\n') out += "\\n";
        else out += c;
    }
    return out;
}

std::string unescape(std::string_view s)
{
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '\\' && i + 1 < s.size() && (s[i + 1] == '\\' || s[i + 1] == 'n')) {
            out += s[i + 1] == 'n' ? '\n' : '\\';
            ++i;
        } else {
            out += s[i];
        }
    }
    return out;
}

bool read_line(std::istream& in, std::string& line, const std::filesystem::path& path)
{
    return text::read_header_line<NrrdError>(in, line, path, "NRRD");
}

// The field names the spec allows in two spellings, mapped to one.
std::string canonical_field(std::string name)
{
    if (name == "datafile") return "data file";
    if (name == "lineskip") return "line skip";
    if (name == "byteskip") return "byte skip";
    if (name == "centerings") return "centers";
    return name;
}

// The voxels from a gzip (or zlib) stream, its failures told in the header's fields.
std::vector<std::uint8_t> inflate_data(std::istream& in, const NrrdHeader& header, std::uint64_t bytes)
{
    try {
        // a stream that holds more than the voxels is refused (ZlibError::Kind::too_long)
        return inflate_exactly(in, bytes, text::bytes_left(in)).data;
    } catch (const ZlibError& e) {
        const std::string sizes_say = " bytes, sizes say " + std::to_string(bytes);
        if (e.kind() == ZlibError::Kind::too_large) header.fail("sizes", std::string("truncated data: ") + e.what());
        if (e.kind() == ZlibError::Kind::ended_early)
            header.fail("sizes", "truncated data: the gzip data holds " + std::to_string(e.produced()) + sizes_say);
        if (e.kind() == ZlibError::Kind::input_ended && e.produced() < bytes)
            header.fail("sizes", "truncated data: the gzip data ends after " + std::to_string(e.produced()) + sizes_say);
        if (e.kind() == ZlibError::Kind::input_ended)
            header.fail("encoding", "truncated gzip data: the file ends before the stream's checksum");
        if (e.kind() == ZlibError::Kind::corrupt) header.fail("encoding", std::string("corrupt gzip data: ") + e.what());
        header.fail("encoding", e.what());
    }
}

std::vector<std::uint8_t> read_raw(std::istream& in, const NrrdHeader& header, std::uint64_t bytes)
{
    std::uint64_t found = 0;
    auto data = text::read_exactly(in, bytes, found);
    if (!data)
        header.fail("sizes", "truncated data: " + std::to_string(found) + " bytes follow the header, sizes say " +
                                 std::to_string(bytes));
    return std::move(*data);
}

// "(x,y,z)" with optional blanks; "none" gives an empty vector.
std::vector<double> parse_vector(const NrrdHeader& header, std::string_view field, std::string_view token, std::size_t n)
{
    if (token == "none") return {};
    if (token.size() < 2 || token.front() != '(' || token.back() != ')')
        header.fail(field, "expected a vector like (1,0,0), found " + quote_text(token));
    std::vector<double> v;
    std::string_view rest = token.substr(1, token.size() - 2);
    for (;;) {
        const auto comma = rest.find(',');
        const std::string_view part = trim(rest.substr(0, comma));
        double x = 0;
        if (!parse_number(part, x)) header.fail(field, quote_text(part) + " in " + quote_text(token) + " is not a number");
        if (!std::isfinite(x)) header.fail(field, "non-finite number " + quote_text(part) + " in " + quote_text(token));
        v.push_back(x);
        if (comma == std::string_view::npos) break;
        rest.remove_prefix(comma + 1);
    }
    if (v.size() != n)
        header.fail(field, quote_text(token) + " has " + std::to_string(v.size()) + " components, expected " + std::to_string(n));
    return v;
}

// Vectors in space directions may hold blanks inside the brackets: "(0.5, 0, 0) (0, 0.5, 0)".
std::vector<std::string_view> split_vectors(std::string_view s)
{
    std::vector<std::string_view> out;
    std::size_t pos = 0;
    while ((pos = s.find_first_not_of(" \t", pos)) != std::string_view::npos) {
        std::size_t end = s[pos] == '(' ? s.find(')', pos) : s.find_first_of(" \t", pos);
        end = end == std::string_view::npos ? s.size() : end + (s[pos] == '(' ? 1 : 0);
        out.push_back(s.substr(pos, end - pos));
        pos = end;
    }
    return out;
}

void check_volume(const std::filesystem::path& path, const Volume& v)
{
    if (const std::string defect = volume_defect(v); !defect.empty()) fail(path, defect);
    // a key must not read back as a comment or a field
    for (const auto& [key, value] : v.key_values)
        if (key.empty() || key[0] == '#' || key.find(":=") != std::string::npos || key.find(": ") != std::string::npos)
            fail(path, "key " + quote_text(key) + " is empty, starts with '#' or holds ':=' or ': ', which NRRD cannot store");
}

std::string vector_string(const glm::dvec3& v)
{
    return "(" + format_double(v.x) + "," + format_double(v.y) + "," + format_double(v.z) + ")";
}

}  // namespace

std::size_t voxel_size(VoxelType type)
{
    switch (type) {
    case VoxelType::uint8: return 1;
    case VoxelType::uint16: return 2;
    case VoxelType::float32: return 4;
    case VoxelType::int16: return 2;
    }
    return 1;
}

const char* to_string(VoxelType type)
{
    switch (type) {
    case VoxelType::uint8: return "unsigned char";
    case VoxelType::uint16: return "unsigned short";
    case VoxelType::float32: return "float";
    case VoxelType::int16: return "short";
    }
    return "?";
}

glm::dvec3 Volume::world_to_index(const glm::dvec3& world) const { return glm::inverse(directions) * (world - origin); }

double Volume::finest_spacing_mm() const
{
    return std::min({glm::length(directions[0]), glm::length(directions[1]), glm::length(directions[2])});
}

void Volume::check_type(VoxelType wanted) const
{
    if (wanted != type)
        throw std::logic_error(std::string("Volume holds ") + to_string(type) + " voxels, not " + to_string(wanted));
}

Volume make_volume(std::array<std::size_t, 3> size, VoxelType type)
{
    Volume v;
    v.size = size;
    v.type = type;
    v.data.assign(v.voxel_count() * voxel_size(type), 0);
    return v;
}

bool is_singular(const glm::dmat3& m)
{
    const double scale = glm::length(m[0]) * glm::length(m[1]) * glm::length(m[2]);
    return !(std::abs(glm::determinant(m)) > 1e-12 * scale);
}

std::string volume_defect(const Volume& v)
{
    std::uint64_t count = 1;
    for (const std::size_t s : v.size) {
        if (s == 0) return "refusing to write a volume with a zero size";
        if (count > std::numeric_limits<std::uint64_t>::max() / s) return "the volume's voxel count overflows";
        count *= s;
    }
    if (count > std::numeric_limits<std::uint64_t>::max() / voxel_size(v.type) || v.data.size() != count * voxel_size(v.type))
        return "data holds " + std::to_string(v.data.size()) + " bytes, size and type need " + std::to_string(count * voxel_size(v.type));
    for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r)
            if (!std::isfinite(v.directions[c][r])) return "directions (the voxel steps): non-finite component";
    if (is_singular(v.directions)) return "directions (the voxel steps): singular, the axes do not span 3D space";
    if (!std::isfinite(v.origin.x) || !std::isfinite(v.origin.y) || !std::isfinite(v.origin.z))
        return "origin: non-finite component";
    return {};
}

// ---- header layer ----------------------------------------------------------------------------------

const std::string* NrrdHeader::find(std::string_view field) const
{
    const auto it = fields.find(field);
    return it == fields.end() ? nullptr : &it->second;
}

const std::string& NrrdHeader::require(std::string_view field) const
{
    if (const std::string* v = find(field)) return *v;
    fail(field, "missing field");
}

void NrrdHeader::fail(std::string_view field, const std::string& why) const
{
    throw NrrdError(path.string() + ": field '" + std::string(field) + "': " + why);
}

VoxelType NrrdHeader::type() const
{
    const std::string t = lower(require("type"));
    if (t == "uchar" || t == "unsigned char" || t == "uint8" || t == "uint8_t") return VoxelType::uint8;
    if (t == "ushort" || t == "unsigned short" || t == "unsigned short int" || t == "uint16" || t == "uint16_t")
        return VoxelType::uint16;
    if (t == "short" || t == "short int" || t == "signed short" || t == "signed short int" || t == "int16" || t == "int16_t")
        return VoxelType::int16;
    if (t == "float") return VoxelType::float32;
    fail("type", quote_text(t) + " is not supported (unsigned char, unsigned short, short or float)");
}

std::vector<std::uint64_t> NrrdHeader::sizes() const
{
    const std::string& dim_text = require("dimension");
    std::uint64_t dimension = 0;
    if (!parse_number(trim(dim_text), dimension) || dimension == 0 || dimension > 16)
        fail("dimension", quote_text(dim_text) + " is not a dimension from 1 to 16");
    const auto tokens = split_whitespace(require("sizes"));
    if (tokens.size() != dimension)
        fail("sizes", std::to_string(tokens.size()) + " sizes for dimension " + std::to_string(dimension));
    std::vector<std::uint64_t> out;
    for (const std::string_view token : tokens) {
        std::uint64_t s = 0;
        const ParsedNumber parsed = parse_number(token, s);
        if (parsed.out_of_range()) fail("sizes", quote_text(token) + " overflows a 64-bit size");
        if (!parsed || s == 0) fail("sizes", quote_text(token) + " is not a positive integer");
        out.push_back(s);
    }
    return out;
}

NrrdHeader read_nrrd_header(std::istream& in, const std::filesystem::path& path, std::uint64_t max_header_bytes)
{
    NrrdHeader header;
    header.path = path;
    std::string line;
    if (!read_line(in, line, path) || line.size() != 8 || !line.starts_with("NRRD000") || line[7] < '1' || line[7] > '5')
        fail(path, "not a NRRD file: the first line is not the magic 'NRRD0001' to 'NRRD0005'");
    std::uint64_t bytes = line.size() + 1;
    for (std::size_t number = 2;; ++number) {
        if (!read_line(in, line, path)) fail(path, "the header ends without the blank line before the data (truncated file?)");
        text::count_header_bytes<NrrdError>(bytes, line, max_header_bytes, path);
        if (line.empty()) break;
        if (line[0] == '#') continue;
        const auto kv = line.find(":=");
        const auto colon = line.find(": ");
        if (kv != std::string::npos && (colon == std::string::npos || kv < colon)) {
            std::string key = unescape(std::string_view(line).substr(0, kv));
            if (key.empty()) fail(path, "header line " + std::to_string(number) + ": key/value with an empty key");
            if (!header.key_values.emplace(key, unescape(std::string_view(line).substr(kv + 2))).second)
                fail(path, "key " + quote_text(key) + " given twice");
        } else if (colon != std::string::npos || line.back() == ':') {
            const auto end = colon != std::string::npos ? colon : line.size() - 1;
            std::string name = canonical_field(lower(trim(std::string_view(line).substr(0, end))));
            const std::string value(trim(std::string_view(line).substr(std::min(end + 2, line.size()))));
            if (!header.fields.emplace(name, value).second) header.fail(name, "given twice");
        } else {
            fail(path, "header line " + std::to_string(number) + " is neither 'field: value' nor 'key:=value': " +
                           quote_text(line));
        }
    }
    return header;
}

std::vector<std::uint8_t> read_nrrd_data(std::istream& in, const NrrdHeader& header, std::uint64_t memory_budget_bytes)
{
    if (const std::string* file = header.find("data file"))
        header.fail("data file",
                    "detached data (" + quote_text(*file) + ") is not supported: keep header and data in one .nrrd file");
    for (const char* skip : {"line skip", "byte skip"})
        if (const std::string* v = header.find(skip); v && *v != "0")
            header.fail(skip, "skipping into the data is not supported");
    const VoxelType type = header.type();
    const std::vector<std::uint64_t> sizes = header.sizes();

    // the byte count, refused before any allocation when it overflows or exceeds the budget
    std::uint64_t bytes = voxel_size(type);
    for (const std::uint64_t s : sizes) {
        if (bytes > std::numeric_limits<std::uint64_t>::max() / s) header.fail("sizes", "the data size overflows 64 bits");
        bytes *= s;
    }
    if (bytes > memory_budget_bytes || bytes > std::numeric_limits<std::size_t>::max())
        header.fail("sizes", std::to_string(bytes) + " bytes of data exceed the memory budget of " +
                                 std::to_string(memory_budget_bytes) + " bytes");

    if (voxel_size(type) > 1) {
        const std::string endian = lower(header.require("endian"));
        if (endian == "big")
            header.fail("endian", "big-endian data is not supported; convert the file to little endian (e.g. 'unu endian')");
        if (endian != "little") header.fail("endian", quote_text(endian) + " is neither little nor big");
    }
    const std::string encoding = lower(header.require("encoding"));
    if (encoding == "raw") return read_raw(in, header, bytes);
    if (encoding == "gzip" || encoding == "gz") return inflate_data(in, header, bytes);
    header.fail("encoding", quote_text(encoding) + " is not supported (raw or gzip)");
}

// ---- volumes -------------------------------------------------------------------------------------

void write_nrrd(const std::filesystem::path& path, const Volume& volume, bool gzip)
{
    check_volume(path, volume);
    std::string h = "NRRD0004\n# Complete NRRD file format specification at:\n# http://teem.sourceforge.net/nrrd/format.html\n";
    h += std::string("type: ") + to_string(volume.type) + "\n";
    h += "dimension: 3\nspace: left-posterior-superior\n";
    h += "sizes: " + std::to_string(volume.size[0]) + " " + std::to_string(volume.size[1]) + " " +
         std::to_string(volume.size[2]) + "\n";
    h += "space directions: " + vector_string(volume.directions[0]) + " " + vector_string(volume.directions[1]) + " " +
         vector_string(volume.directions[2]) + "\n";
    h += "kinds: domain domain domain\nendian: little\n";
    h += std::string("encoding: ") + (gzip ? "gzip" : "raw") + "\n";
    h += "space origin: " + vector_string(volume.origin) + "\n";
    for (const auto& [key, value] : volume.key_values) h += escape(key) + ":=" + escape(value) + "\n";
    h += "\n";

    PartialFile<NrrdError> out(path);
    out.write(h.data(), h.size());
    if (gzip) {
        try {
            deflate_stream(volume.data, ZlibWrapper::gzip, [&](std::span<const std::uint8_t> s) { out.write(s.data(), s.size()); });
        } catch (const ZlibError& e) {
            fail(path, e.what());
        }
    } else {
        out.write(volume.data.data(), volume.data.size());
    }
    out.commit();
}

Volume read_nrrd(const std::filesystem::path& path, std::uint64_t memory_budget_bytes)
{
    std::ifstream in = text::open_binary<NrrdError>(path);
    const NrrdHeader header = read_nrrd_header(in, path);

    Volume v;
    v.type = header.type();
    const std::vector<std::uint64_t> sizes = header.sizes();
    if (sizes.size() != 3)
        header.fail("dimension", "only 3D volumes are read (a 2D image is stored as sizes W H 1), found dimension " +
                                     std::to_string(sizes.size()));
    if (const std::string* kinds = header.find("kinds")) {
        const auto tokens = split_whitespace(*kinds);
        if (tokens.size() != 3) header.fail("kinds", "expected 3 kinds, found " + std::to_string(tokens.size()));
        for (const std::string_view k : tokens)
            if (const std::string kind = lower(k); kind != "domain" && kind != "space" && kind != "???")
                header.fail("kinds", quote_text(k) + " axis: only scalar volumes (domain axes) are supported");
    }

    // space: anatomical frames other than LPS differ from it by the signs of x and y
    glm::dvec3 to_lps{1.0};
    const std::string* space = header.find("space");
    if (space) {
        const std::string s = lower(*space);
        if (s == "right-anterior-superior" || s == "ras") to_lps = {-1.0, -1.0, 1.0};
        else if (s == "left-anterior-superior" || s == "las") to_lps = {1.0, -1.0, 1.0};
        else if (s != "left-posterior-superior" && s != "lps")
            header.fail("space", quote_text(*space) + " is not supported (left-posterior-superior, right-anterior-superior, "
                                                      "left-anterior-superior or their initials)");
    } else if (const std::string* dims = header.find("space dimension")) {
        if (trim(*dims) != "3") header.fail("space dimension", quote_text(*dims) + ": only 3D space is supported");
        space = dims;  // unnamed 3D space: taken as LPS
    }
    if (const std::string* units = header.find("space units"))
        for (const std::string_view u : split_whitespace(*units))
            if (u != "\"mm\"" && u != "mm") header.fail("space units", quote_text(u) + ": only millimetres are supported");

    if (const std::string* dirs = header.find("space directions")) {
        if (!space) header.fail("space directions", "given without a 'space' field");
        const auto tokens = split_vectors(*dirs);
        if (tokens.size() != 3) header.fail("space directions", "expected 3 vectors, found " + std::to_string(tokens.size()));
        for (int c = 0; c < 3; ++c) {
            const auto d = parse_vector(header, "space directions", tokens[std::size_t(c)], 3);
            if (d.empty()) header.fail("space directions", "axis " + std::to_string(c) + " has no direction ('none')");
            v.directions[c] = glm::dvec3(d[0], d[1], d[2]) * to_lps;
        }
    } else if (const std::string* spacings = header.find("spacings")) {
        // no orientation: axis-aligned steps
        const auto tokens = split_whitespace(*spacings);
        if (tokens.size() != 3) header.fail("spacings", "expected 3 spacings, found " + std::to_string(tokens.size()));
        for (int c = 0; c < 3; ++c) {
            double s = 0;
            if (!parse_number(tokens[std::size_t(c)], s) || !std::isfinite(s) || s == 0)
                header.fail("spacings", quote_text(tokens[std::size_t(c)]) + " is not a finite non-zero number");
            v.directions[c][c] = s;
        }
    }
    if (is_singular(v.directions)) header.fail("space directions", "singular: the axes do not span 3D space");
    if (const std::string* origin = header.find("space origin")) {
        if (!space) header.fail("space origin", "given without a 'space' field");
        const auto o = parse_vector(header, "space origin", trim(*origin), 3);
        if (o.empty()) header.fail("space origin", "'none' is not an origin");
        v.origin = glm::dvec3(o[0], o[1], o[2]) * to_lps;
    }

    v.data = read_nrrd_data(in, header, memory_budget_bytes);
    for (int a = 0; a < 3; ++a) v.size[std::size_t(a)] = std::size_t(sizes[std::size_t(a)]);
    for (const auto& [key, value] : header.key_values) v.key_values.emplace(key, value);
    return v;
}

}  // namespace echosim::io

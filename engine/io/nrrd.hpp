// NRRD files (the format 3D Slicer, VTK and ITK read): volumes, label maps, and single echographic
// images placed in a volume's space (sizes W H 1, DESIGN.md §3).
//
// What we write: NRRD0004, one volume of uint8 / uint16 / int16 / float voxels, dimension 3, space
// left-posterior-superior, space directions and origin in millimetres, kinds domain domain domain,
// little endian, raw or gzip, then key/value pairs (label maps list their tissue codes there).
// What we read: that, and what Slicer writes: fields in any order, RAS or LAS spaces converted to
// LPS, the type names' synonyms, `gz` for gzip. Files are written to FILE.partial and renamed, so a
// half-written file never looks valid. Reading names the file and field it rejects.
//
// Memory: voxels stay as the file's raw little-endian bytes, x fastest, then y, then z; typed access
// reinterprets them in place (the library targets little-endian machines only).
#pragma once

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "core/printable_text.hpp"
#include "io/text_fields.hpp"

namespace echosim::io {

static_assert(std::endian::native == std::endian::little, "Volume keeps voxels as little-endian bytes");

class NrrdError : public InputFileError {  // its message escaped (core/printable_text.hpp)
public:
    using InputFileError::InputFileError;
};

// 8 GiB: read_nrrd refuses larger voxel data before allocating any of it.
inline constexpr std::uint64_t default_nrrd_memory_budget = std::uint64_t(8) << 30;

// int16: the signed short volumes ITK and Slicer write (MET_SHORT, NRRD "short").
enum class VoxelType : std::uint8_t { uint8, uint16, float32, int16 };

std::size_t voxel_size(VoxelType type);  // [bytes]
const char* to_string(VoxelType type);   // the NRRD type name we write: "unsigned char", ...

template <class T>
constexpr VoxelType voxel_type_of()
{
    using U = std::remove_const_t<T>;
    static_assert(std::is_same_v<U, std::uint8_t> || std::is_same_v<U, std::uint16_t> || std::is_same_v<U, std::int16_t> ||
                      std::is_same_v<U, float>,
                  "voxels are std::uint8_t, std::uint16_t, std::int16_t or float");
    if constexpr (std::is_same_v<U, std::uint8_t>) return VoxelType::uint8;
    else if constexpr (std::is_same_v<U, std::uint16_t>) return VoxelType::uint16;
    else if constexpr (std::is_same_v<U, std::int16_t>) return VoxelType::int16;
    else return VoxelType::float32;
}

// A volume (or, with size[2] == 1, one image) in patient space. Index (i, j, k) lies at
// origin + directions * (i, j, k) in world LPS [mm]: directions' columns are the steps of the i, j
// and k axes (for an image: lateral pixel step, depth pixel step, and the elevational normal scaled
// by the slice thickness, so that directions stays invertible).
struct Volume {
    std::array<std::size_t, 3> size{};
    glm::dmat3 directions{1.0};  // columns: i, j, k steps [mm, LPS]
    glm::dvec3 origin{0.0};      // centre of voxel (0, 0, 0) [mm, LPS]
    VoxelType type = VoxelType::uint8;
    std::vector<std::uint8_t> data;                     // raw little-endian voxels, x fastest
    std::map<std::string, std::string> key_values;      // e.g. label codes; keys: no ":=", ": ", leading '#'

    std::size_t voxel_count() const { return size[0] * size[1] * size[2]; }
    std::size_t index(std::size_t i, std::size_t j, std::size_t k) const { return (k * size[1] + j) * size[0] + i; }

    // The voxels as T; throws std::logic_error when T does not match `type` (a programming error).
    template <class T>
    T* as()
    {
        check_type(voxel_type_of<T>());
        return reinterpret_cast<T*>(data.data());
    }
    template <class T>
    const T* as() const
    {
        check_type(voxel_type_of<T>());
        return reinterpret_cast<const T*>(data.data());
    }

    // Continuous index <-> world [mm, LPS]. world_to_index inverts `directions` on every call: hoist
    // glm::inverse(directions) out of loops over many points.
    glm::dvec3 index_to_world(const glm::dvec3& ijk) const { return origin + directions * ijk; }
    glm::dvec3 world_to_index(const glm::dvec3& world) const;
    // The smallest voxel step along any of the three axes [mm].
    double finest_spacing_mm() const;

private:
    void check_type(VoxelType wanted) const;
};

// A zero-filled volume of the given size and type, identity geometry.
Volume make_volume(std::array<std::size_t, 3> size, VoxelType type);

// True when the axes do not span 3D space (relative to their lengths).
bool is_singular(const glm::dmat3& directions);

// Why a volume cannot be written in any format (a zero size, data not matching size and type,
// non-finite or singular geometry), or empty when it can. Keys are each format's business.
std::string volume_defect(const Volume& volume);

// Throws NrrdError naming the file (and the field) when the volume is inconsistent (data size,
// non-finite or singular geometry, bad key) or the file cannot be written; leaves no file behind.
void write_nrrd(const std::filesystem::path& path, const Volume& volume, bool gzip);

// Throws NrrdError naming the file and the field. Refuses voxel data above memory_budget_bytes.
Volume read_nrrd(const std::filesystem::path& path, std::uint64_t memory_budget_bytes = default_nrrd_memory_budget);

// ---- the layer below, for formats that wrap NRRD (the PLUS .seq.nrrd sequence) -------------------

// A header as read: fields (names lower-cased, synonyms such as "datafile" mapped to "data file")
// and key/value pairs (unescaped), with the file it came from for messages.
struct NrrdHeader {
    std::filesystem::path path;
    std::map<std::string, std::string, std::less<>> fields;
    std::map<std::string, std::string, std::less<>> key_values;

    const std::string* find(std::string_view field) const;
    const std::string& require(std::string_view field) const;  // throws "missing field"
    [[noreturn]] void fail(std::string_view field, const std::string& why) const;

    VoxelType type() const;                   // from "type", synonyms accepted
    std::vector<std::uint64_t> sizes() const;  // from "sizes", checked against "dimension", all > 0
};

// Reads the magic line and the header up to its blank line, leaving `in` at the first data byte.
// A header longer than `max_header_bytes` is refused as it is read (a sequence's reader, which
// bounds its header itself, passes text::unbounded_header_bytes).
NrrdHeader read_nrrd_header(std::istream& in, const std::filesystem::path& path, std::uint64_t max_header_bytes = text::max_volume_header_bytes);

// Reads the data that follows the header: product(sizes) voxels of type(), decoded from the
// header's encoding (raw, gzip). Checks endian, refuses detached data, sizes that overflow or exceed
// the budget, truncated and corrupt data.
std::vector<std::uint8_t> read_nrrd_data(std::istream& in, const NrrdHeader& header, std::uint64_t memory_budget_bytes);

}  // namespace echosim::io

// MetaImage files (ITK's MetaIO, as ITK, 3D Slicer and PLUS write them): a text header of
// `Name = Value` lines ending with ElementDataFile, then the element data, in the same file (.mha,
// ElementDataFile = LOCAL) or in a file beside the header (.mhd with a .raw or .zraw).
//
// Two layers:
// - the header and the element data, for any MetaImage (volumes here, PLUS sequences later:
//   io/plus_sequence.cpp's files are MetaImages with per-frame Seq_FrameNNNN_... fields): fields
//   kept in file order with their line numbers, element types, and the data read raw or inflated,
//   byte-swapped from big endian, every size checked for overflow and against a memory budget
//   before anything is allocated or inflated;
// - volumes: io::Volume from and to a 3D (or 2D: one slice) MetaImage.
//
// Geometry, as ITK reads it (itkMetaImageIO.cxx, ReadImageInformation: for axis i,
// `directionAxis[j] = transformMatrix[i * N + j]; SetDirection(i, directionAxis)`, and
// itkImageFileReader.hxx puts GetDirection(i) in column i of the image's direction matrix; Write does
// the reverse): the TransformMatrix's consecutive triples are the unit direction vectors of the i, j
// and k axes in patient space, LPS (ITK's world, whatever AnatomicalOrientation says: MetaIO's "RAI"
// names the side each axis comes *from*, so RAI is LPS). The world point of index (i, j, k) is
// Offset + sum over axes a of index[a] * ElementSpacing[a] * direction[a]: Offset is the centre of
// voxel (0, 0, 0), like NRRD's space origin. So io::Volume::directions' column a is
// ElementSpacing[a] * direction a, and writing splits each column into its length and unit vector.
//
// Errors are MetaImageError, the message opening with the file, then the field and its header line.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <iosfwd>
#include <map>
#include <stdexcept>
#include <span>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/printable_text.hpp"
#include "io/nrrd.hpp"

namespace echosim::io {

class MetaImageError : public InputFileError {  // its message escaped (core/printable_text.hpp)
public:
    using InputFileError::InputFileError;
};

// The same budget as NRRD volumes: element data above it is refused before any allocation.
inline constexpr std::uint64_t default_metaimage_memory_budget = default_nrrd_memory_budget;

// The element types we read, as MetaIO names them.
enum class MetElementType : std::uint8_t { met_uchar, met_char, met_ushort, met_short, met_float, met_double };

std::size_t element_size(MetElementType type);  // [bytes]
// The io::Volume voxel type that holds an element type exactly: none for MET_CHAR and MET_DOUBLE.
std::optional<VoxelType> exact_voxel_type(MetElementType type);
MetElementType element_type_of(VoxelType type);
const char* to_string(MetElementType type);    // "MET_UCHAR", ...

// ---- the header and the element data: any MetaImage ----------------------------------------------

struct MetaImageField {
    std::string name;   // as the file spells it (names are case-sensitive, as in MetaIO)
    std::string value;  // without the blanks around it
    std::size_t line = 0;  // in the header, from 1
};

// A header as read: every `Name = Value` line up to and including ElementDataFile, in file order.
class MetaImageHeader {
public:
    explicit MetaImageHeader(std::filesystem::path path) : path_(std::move(path)) {}

    const std::filesystem::path& path() const { return path_; }
    const std::vector<MetaImageField>& fields() const { return fields_; }

    // Adds a field; throws naming both lines when the name is already there.
    void add(MetaImageField field);

    const MetaImageField* find(std::string_view name) const;
    const MetaImageField& require(std::string_view name) const;  // throws "missing"
    // The one of `names` (synonyms, e.g. Offset, Position, Origin) the header gives, or null;
    // throws naming both when it gives two.
    const MetaImageField* find_one_of(std::initializer_list<std::string_view> names) const;

    // Throws MetaImageError "FILE: NAME (line N): why", without the line when the field is absent.
    [[noreturn]] void fail(std::string_view name, const std::string& why) const;

    MetElementType element_type() const;        // ElementType; the error lists the supported ones
    std::vector<std::uint64_t> dim_size() const;  // DimSize, all > 0, as many as NDims (when given)
    std::uint64_t channels() const;             // ElementNumberOfChannels, 1 when absent
    // True or False (any case, or 1 or 0); `absent` when the header does not give it.
    bool flag(std::string_view name, bool absent) const;
    // Exactly `count` finite numbers from the field.
    std::vector<double> numbers(const MetaImageField& field, std::size_t count) const;

private:
    std::filesystem::path path_;
    std::vector<MetaImageField> fields_;
    std::map<std::string, std::size_t, std::less<>> index_;  // name -> position in fields_
};

// Reads `Name = Value` lines (blank lines skipped, "\r\n" accepted) up to and including
// ElementDataFile, leaving `in` at the first byte after that line: the data, when LOCAL. Throws
// naming the file and line for a line that is not `Name = Value`, a field given twice, or a file
// that ends before ElementDataFile.
// A header longer than `max_header_bytes` is refused as it is read (a sequence's reader, which
// bounds its header itself, passes text::unbounded_header_bytes).
MetaImageHeader read_metaimage_header(std::istream& in, const std::filesystem::path& path,
                                      std::uint64_t max_header_bytes = text::max_volume_header_bytes);

// [bytes] of element data the header describes: product(DimSize) * ElementNumberOfChannels *
// element_size(ElementType). Throws naming DimSize when the product overflows 64 bits or exceeds
// `memory_budget_bytes`. Allocates nothing: call it before anything else costs memory.
std::uint64_t metaimage_data_bytes(const MetaImageHeader& header, std::uint64_t memory_budget_bytes);

// The element data after the header, as little-endian bytes: from `in` (positioned as
// read_metaimage_header left it) when ElementDataFile = LOCAL, else from the file it names (relative
// to the header's folder unless absolute). Raw, or with CompressedData = True a zlib (or gzip) stream
// of at most CompressedDataSize bytes (the rest of the file when absent), inflated as it streams.
// BinaryDataByteOrderMSB (or ElementByteOrderMSB) = True data is byte-swapped. Refused by name:
// BinaryData = False (text data), HeaderSize other than 0, ElementDataFile = LIST or a file pattern
// (with '%'), a missing data file, truncated or corrupt data, raw data longer than the header gives, sizes beyond the budget (checked first,
// by metaimage_data_bytes).
std::vector<std::uint8_t> read_metaimage_data(std::istream& in, const MetaImageHeader& header,
                                              std::uint64_t memory_budget_bytes = default_metaimage_memory_budget);

// Exactly `bytes` bytes inflated from a zlib (or gzip) stream of at most `packed` bytes in `in`,
// streamed: the compressed data is never held whole. Throws MetaImageError "FILE: CompressedData:
// ..." when the stream is corrupt, cut, or holds more or fewer bytes than `sizes_field` gives.
std::vector<std::uint8_t> inflate_metaimage_data(const std::filesystem::path& path, std::istream& in, std::uint64_t bytes,
                                                 std::uint64_t packed, std::string_view sizes_field = "DimSize");

// The element data deflated as MetaIO and PLUS write it (one zlib stream), for CompressedDataSize
// to be known before the header is written. Throws MetaImageError naming the file.
std::vector<std::uint8_t> deflate_metaimage_data(const std::filesystem::path& path, std::span<const std::uint8_t> data);

// ---- volumes ----------------------------------------------------------------------------------

// A volume from a MetaImage with NDims 3, or NDims 2 (one slice: k steps 1 mm along the normal
// (0, 0, 1), as ITK reads a 2D image into a 3D one). Element types: MET_UCHAR -> uint8, MET_USHORT ->
// uint16, MET_SHORT -> int16, MET_FLOAT -> float32; MET_CHAR and MET_DOUBLE are refused by name (no
// exact io::Volume type). Geometry: Offset (or Position, Origin, ImagePosition), ElementSpacing
// (else ElementSize, as MetaIO), TransformMatrix (or Rotation, Orientation); identity, unit spacing
// and zero offset when absent. DistanceUnits other than mm is refused; AnatomicalOrientation is a
// label only (see the top of this file). Fields MetaIO does not define become key_values; one
// channel only; a PLUS sequence (Kinds with a list axis) is refused, pointing to reconstruction.
Volume read_metaimage_volume(const std::filesystem::path& path,
                             std::uint64_t memory_budget_bytes = default_metaimage_memory_budget);

// Writes NDims 3, the geometry as above (AnatomicalOrientation: the acronym closest to the axes, as
// ITK writes it), key_values as extra fields before ElementType, then the voxels, raw or (compressed)
// zlib-deflated with CompressedDataSize. A `.mhd` path gets its voxels in a file beside it (STEM.raw,
// or STEM.zraw compressed); any other path holds them (ElementDataFile = LOCAL, the .mha way).
// Written to FILE.partial and renamed, so a failed write leaves nothing at `path`. Throws naming the
// file (and the key) for an inconsistent volume (data size, non-finite or singular geometry) or a
// key/value a header cannot hold: a key that is empty, holds blanks or '=', or is a MetaIO field;
// a value with a line break or blanks at either end.
void write_metaimage_volume(const std::filesystem::path& path, const Volume& volume, bool compressed);

}  // namespace echosim::io

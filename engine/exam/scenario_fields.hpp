// The fields of a case file, each object's in one table: its name, its JSON type, whether it is
// required, and its range (numbers), length (text) or count (arrays). The reader (scenario.cpp)
// checks every object against its table before it reads a value, so a field exists for the reader
// only if it is here; the schema (assets/cases/scenario.schema.json) is held to the same table by
// tests/exam/scenario_test.cpp, so the two cannot drift apart.
#pragma once

#include <array>
#include <span>
#include <string_view>

namespace echosim::exam::fields {

enum class Kind { string, number, integer, object, array };

struct Field {
    std::string_view name;
    Kind kind;
    bool required;
    // number, integer: the accepted range (lo refused too where lo_exclusive: a length must be
    // positive); string: its length in bytes; array: its count of items
    double lo = 0;
    double hi = 0;
    bool lo_exclusive = false;
    std::string_view unit = {};  // for messages: "mm", "N", "cm"
    bool multiline = false;      // string: may hold line breaks (a description), else one line
};

// One kind of object in the file: where it is (a JSON pointer, "*" for any array index) and, for
// the stations' three forms, which form.
struct ObjectFields {
    std::string_view where;
    std::string_view form;  // "" but for a station: "landmark", "distance" or "every"
    std::span<const Field> fields;
};

// Text limits [bytes]: an id names a file; a title is one line of a start screen.
inline constexpr double kIdBytes = 64, kTitleBytes = 120, kNameBytes = 40, kDescriptionBytes = 4000, kCommentBytes = 4000;
// The largest position along any vein a file may write [cm]: past the course (course_limits.hpp)
// the segment's own check refuses it, naming the segment's end.
inline constexpr double kMaxS_cm = 100;

inline constexpr Field kComment{"comment", Kind::string, false, 0, kCommentBytes, false, {}, true};

inline constexpr std::array kTop{
    Field{"$schema", Kind::string, false, 0, 1000},
    Field{"version", Kind::integer, true, 1, 1},
    Field{"id", Kind::string, true, 1, kIdBytes},
    Field{"title", Kind::string, true, 1, kTitleBytes},
    Field{"description", Kind::string, false, 0, kDescriptionBytes, false, {}, true},
    kComment,
    Field{"patient", Kind::object, true},
    Field{"anatomy", Kind::object, true},
    Field{"protocol", Kind::string, true, 1, 20},
    Field{"stations", Kind::array, true, 1, 200},
    Field{"bands", Kind::object, true},
    Field{"imaging", Kind::string, false, 1, 20},
};
inline constexpr std::array kPatient{
    // supine, the femoral vein's pressure is some 5..15 mmHg; 0..40 keeps a case of raised
    // pressure (heart failure) writable
    Field{"venous_pressure_mmHg", Kind::number, true, 0, 40, false, "mmHg"},
    Field{"heart_rate_bpm", Kind::number, true, 30, 200, false, "beats/min"},
    kComment,
};
inline constexpr std::array kAnatomy{
    // a very thin patient to a very large one; the phantom scales its fat by fat_mm / 12
    Field{"fat_mm", Kind::number, true, 3, 60, false, "mm"},
    Field{"thrombi", Kind::array, false, 0, 20},
    Field{"lymph_nodes", Kind::array, false, 0, 10},
    kComment,
};
inline constexpr std::array kThrombus{
    Field{"segment", Kind::string, true, 1, 20},
    Field{"kind", Kind::string, true, 1, 20},
    Field{"start_cm", Kind::number, true, 0, kMaxS_cm, false, "cm"},
    Field{"extent_cm", Kind::number, true, 0, kMaxS_cm, true, "cm"},
    Field{"occlusion", Kind::number, false, 0, 1, true},
    kComment,
};
inline constexpr std::array kLymphNode{
    Field{"s_cm", Kind::number, true, 0, kMaxS_cm, false, "cm"},
    Field{"size_mm", Kind::number, true, 5, 40, false, "mm"},  // a normal inguinal node to a large reactive one
    kComment,
};
inline constexpr std::array kLandmarkStation{
    Field{"landmark", Kind::string, true, 1, 30},
    Field{"name", Kind::string, false, 1, kNameBytes},
    kComment,
};
inline constexpr std::array kDistanceStation{
    Field{"segment", Kind::string, true, 1, 20},
    Field{"s_cm", Kind::number, true, 0, kMaxS_cm, false, "cm"},
    Field{"name", Kind::string, false, 1, kNameBytes},
    kComment,
};
inline constexpr std::array kEveryStation{
    Field{"every_cm", Kind::number, true, 0.5, 10, false, "cm"},
    Field{"segment", Kind::string, true, 1, 20},
    Field{"from_cm", Kind::number, true, 0, kMaxS_cm, false, "cm"},
    Field{"to_cm", Kind::number, true, 0, kMaxS_cm, false, "cm"},
    kComment,
};
inline constexpr std::array kBands{
    Field{"adequate_force_N", Kind::number, true, 0, 60, true, "N"},
    Field{"excessive_force_N", Kind::number, true, 0, 100, true, "N"},
    Field{"reach_mm", Kind::number, false, 0.5, 30, false, "mm"},
    Field{"transverse_deg", Kind::number, false, 1, 45, false, "deg"},
    Field{"collapsed_ratio", Kind::number, false, 0, 0.9},
    Field{"artery_deformed", Kind::number, false, 0.01, 1},
    Field{"pass_mark", Kind::number, false, 0, 1},
    kComment,
};

inline constexpr std::array<ObjectFields, 9> kObjects{{
    {"", "", kTop},
    {"/patient", "", kPatient},
    {"/anatomy", "", kAnatomy},
    {"/anatomy/thrombi/*", "", kThrombus},
    {"/anatomy/lymph_nodes/*", "", kLymphNode},
    {"/stations/*", "landmark", kLandmarkStation},
    {"/stations/*", "distance", kDistanceStation},
    {"/stations/*", "every", kEveryStation},
    {"/bands", "", kBands},
}};

// The names a text field takes from a fixed set, as the file writes them.
inline constexpr std::array<std::string_view, 3> kProtocolNames{"two-point", "three-point", "extended"};
inline constexpr std::array<std::string_view, 2> kImagingNames{"interpolative", "generative"};
inline constexpr std::array<std::string_view, 2> kThrombusKindNames{"acute", "chronic"};

}  // namespace echosim::exam::fields

// A case file's text into a JSON document, within limits, a key given twice refused naming it by
// its JSON pointer ("/anatomy/thrombi/1/extent_cm"), as every other error of a case file names its
// field. (io/json_text.hpp refuses a repeated key too, but names the object by its keys alone,
// without the array indices a case file's thrombi and stations need.)
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace echosim::exam {

// The most a case file may hold [bytes]: a case with every field and 200 stations written out is
// some 30 KB; a file of megabytes is not a case.
inline constexpr std::uintmax_t kMaxScenarioFileBytes = 1u << 20;

// A JSON pointer's reference token for `key` (RFC 6901: '~' as "~0", '/' as "~1").
std::string json_pointer_token(std::string_view key);

// `text` parsed; ScenarioError naming `file` and the field (or "" for the whole text) when it is not
// JSON, nested deeper than any case needs, or repeats a key in one object.
nlohmann::json parse_scenario_text(std::string_view text, const std::filesystem::path& file);

// The file's text, or ScenarioError naming it: missing, not a regular file (a FIFO or a device
// would block or never end), unreadable, or over kMaxScenarioFileBytes.
std::string read_scenario_text(const std::filesystem::path& file);

}  // namespace echosim::exam

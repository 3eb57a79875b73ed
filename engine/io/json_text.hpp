// JSON that a person wrote, or that a hostile file holds, parsed within limits its reader states.
//
// nlohmann::json accepts what a reader of ours must not: a key given twice in one object (it keeps
// the last, so a person's first edit is silently lost), any depth of nesting, and any size (its
// document costs up to twenty times the text: 200 MB of "[[],[],..." is 4 GB). Here the text is
// scanned once before it is parsed: its depth is capped, and the memory its document would take is
// estimated from its tokens (an upper bound for nlohmann's layout on 64-bit Linux, below) and held
// to the reader's budget; then it is parsed with duplicate keys refused. Linear in the text's size.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace echosim::io {

struct JsonLimits {
    int max_depth = 32;                           // arrays and objects nested in each other
    std::uint64_t max_document_bytes = 1ull << 30;  // what the parsed document may take in memory
};

// What is wrong with a JSON text, without the file's name (the reader adds it).
class JsonTextError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// The memory a parsed document of `text` would take at most [bytes], or JsonTextError when it is
// nested deeper than `max_depth` (naming the byte where). Does not check the syntax.
std::uint64_t json_document_bytes(std::string_view text, int max_depth);

// `text` parsed, or JsonTextError naming the defect: not JSON (nlohmann's message, with the byte),
// too deep, a document over the budget, or a key repeated in one object (naming the key and the
// object's path, e.g. "grid").
nlohmann::json parse_json_text(std::string_view text, const JsonLimits& limits);

}  // namespace echosim::io

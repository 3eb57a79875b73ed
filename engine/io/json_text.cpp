#include "io/json_text.hpp"

#include <set>
#include <vector>

namespace echosim::io {
namespace {

// nlohmann::json on 64-bit Linux: every value is 16 bytes (a tag and a union) wherever it lives;
// an array or object adds its container on the heap (a vector or map object, with malloc's
// overhead), an object member a red-black tree node (its links, a std::string key and the value),
// a string its std::string and characters. Rounded up.
constexpr std::uint64_t kValueBytes = 16;
constexpr std::uint64_t kContainerBytes = 64;
constexpr std::uint64_t kMemberBytes = 96;
constexpr std::uint64_t kStringBytes = 48;

}  // namespace

std::uint64_t json_document_bytes(std::string_view text, int max_depth)
{
    std::uint64_t containers = 0, commas = 0, members = 0, strings = 0, characters = 0;
    int depth = 0;
    bool in_string = false, escaped = false;
    for (std::size_t at = 0; at < text.size(); ++at) {
        const char c = text[at];
        if (in_string) {
            if (escaped) escaped = false;
            else if (c == '\\') escaped = true;
            else if (c == '"') in_string = false;
            else ++characters;
            continue;
        }
        switch (c) {
        case '"': in_string = true, ++strings; break;
        case '[':
        case '{':
            if (++depth > max_depth)
                throw JsonTextError("arrays and objects nested deeper than " + std::to_string(max_depth) + " (at byte " +
                                    std::to_string(at) + ")");
            ++containers;
            break;
        case ']':
        case '}': --depth; break;
        case ',': ++commas; break;
        case ':': ++members; break;
        default: break;
        }
    }
    // every value is followed by a comma or closes its container, or is the whole document
    const std::uint64_t values = commas + containers + 1;
    return values * kValueBytes + containers * kContainerBytes + members * kMemberBytes + strings * kStringBytes + characters;
}

nlohmann::json parse_json_text(std::string_view text, const JsonLimits& limits)
{
    const std::uint64_t bytes = json_document_bytes(text, limits.max_depth);
    if (bytes > limits.max_document_bytes)
        throw JsonTextError("its document would take about " + std::to_string(bytes >> 20) + " MiB of memory, over this reader's " +
                            std::to_string(limits.max_document_bytes >> 20) + " MiB");

    // each open object's keys so far, and the key each is under (for the message)
    struct Open {
        std::set<std::string> keys;
        std::string last;
    };
    std::vector<Open> open;
    using json = nlohmann::json;
    const json::parser_callback_t refuse_duplicates = [&](int, json::parse_event_t event, json& parsed) {
        switch (event) {
        case json::parse_event_t::object_start: open.emplace_back(); break;
        case json::parse_event_t::object_end: open.pop_back(); break;
        case json::parse_event_t::key: {
            std::string key = parsed.get<std::string>();
            if (!open.back().keys.insert(key).second) {
                std::string where;
                for (std::size_t i = 0; i + 1 < open.size(); ++i) where += (where.empty() ? "" : ".") + open[i].last;
                throw JsonTextError("key \"" + key + "\" given twice in " + (where.empty() ? "the top-level object" : "object '" + where + "'"));
            }
            open.back().last = std::move(key);
            break;
        }
        default: break;
        }
        return true;
    };
    try {
        return json::parse(text.begin(), text.end(), refuse_duplicates);
    } catch (const json::exception& e) {  // parse_error, and out_of_range for a number beyond double's range
        throw JsonTextError(std::string("not valid JSON: ") + e.what());
    }
}

}  // namespace echosim::io

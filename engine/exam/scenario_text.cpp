#include "exam/scenario_text.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>
#include <system_error>
#include <vector>

#include "exam/scenario.hpp"
#include "io/json_text.hpp"

namespace echosim::exam {
namespace {

// The deepest a case nests is 4 (the file, anatomy, thrombi, a thrombus); 8 leaves room and no more.
constexpr int kMaxDepth = 8;

}  // namespace

std::string json_pointer_token(std::string_view key)
{
    std::string out;
    for (const char c : key) {
        if (c == '~') out += "~0";
        else if (c == '/') out += "~1";
        else out += c;
    }
    return out;
}

nlohmann::json parse_scenario_text(std::string_view text, const std::filesystem::path& file)
{
    using json = nlohmann::json;
    try {
        io::json_document_bytes(text, kMaxDepth);  // refuses a deeper nesting before the parser recurses into it
    } catch (const io::JsonTextError& e) {
        throw ScenarioError(file, "", e.what());
    }
    // each open array or object: its JSON pointer token so far, and an object's keys
    struct Open {
        bool array = false;
        long index = -1;  // an array: the index of its latest item
        std::string key;  // an object: its latest key
        std::set<std::string> keys;
    };
    std::vector<Open> open;
    const auto pointer = [&] {
        std::string p;
        for (const Open& o : open) p += "/" + (o.array ? std::to_string(o.index) : json_pointer_token(o.key));
        return p;
    };
    // an item of an array: its index moves on as it starts
    const auto next_item = [&] {
        if (!open.empty() && open.back().array) ++open.back().index;
    };
    const json::parser_callback_t track = [&](int, json::parse_event_t event, json& parsed) {
        switch (event) {
        case json::parse_event_t::object_start:
            next_item();
            open.push_back(Open{});
            break;
        case json::parse_event_t::array_start:
            next_item();
            open.push_back(Open{true});
            break;
        case json::parse_event_t::object_end:
        case json::parse_event_t::array_end: open.pop_back(); break;
        case json::parse_event_t::key: {
            std::string key = parsed.get<std::string>();
            const bool repeated = !open.back().keys.insert(key).second;
            open.back().key = std::move(key);
            if (repeated) throw ScenarioError(file, pointer(), "given twice in one object (the reader would keep only the last)");
            break;
        }
        case json::parse_event_t::value: next_item(); break;
        }
        return true;
    };
    try {
        return json::parse(text.begin(), text.end(), track);
    } catch (const json::exception& e) {  // parse_error, and out_of_range for a number beyond double's range
        throw ScenarioError(file, "", std::string("not valid JSON: ") + e.what());
    }
}

std::string read_scenario_text(const std::filesystem::path& file)
{
    std::error_code ec;
    const auto status = std::filesystem::status(file, ec);
    if (ec || !std::filesystem::exists(status)) throw ScenarioError(file, "", "no such file");
    if (!std::filesystem::is_regular_file(status)) throw ScenarioError(file, "", "not a regular file (a folder, a device or a FIFO)");
    const std::uintmax_t size = std::filesystem::file_size(file, ec);
    if (ec) throw ScenarioError(file, "", "cannot tell its size: " + ec.message());
    if (size > kMaxScenarioFileBytes)
        throw ScenarioError(file, "", std::to_string(size) + " bytes, over the " + std::to_string(kMaxScenarioFileBytes) +
                                          " a case file may hold");
    std::ifstream in(file, std::ios::binary);
    if (!in) throw ScenarioError(file, "", std::string("cannot open: ") + std::strerror(errno));
    std::string text;
    text.reserve(std::size_t(size));
    // read at most one byte past the limit: a file that grew since its size was taken is still held to it
    char buffer[4096];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        text.append(buffer, std::size_t(in.gcount()));
        if (text.size() > kMaxScenarioFileBytes)
            throw ScenarioError(file, "", "over the " + std::to_string(kMaxScenarioFileBytes) + " bytes a case file may hold");
    }
    if (in.bad()) throw ScenarioError(file, "", "read error");
    return text;
}

}  // namespace echosim::exam

#include "exam/xapi.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "exam/report_text.hpp"
#include "exam/uuid.hpp"

namespace echosim::exam {
namespace {

using Json = nlohmann::ordered_json;

constexpr const char* kVerbs = "http://adlnet.gov/expapi/verbs/";

Json verb(const char* name) { return Json{{"id", std::string(kVerbs) + name}, {"display", {{"en-US", name}}}}; }

}  // namespace

std::string iso8601_duration(double seconds)
{
    if (!std::isfinite(seconds) || seconds < 0) return "";
    const long long centis = std::llround(seconds * 100);
    const long long h = centis / 360000, m = centis / 6000 % 60;
    const double s = double(centis % 6000) / 100;
    std::string out = "PT";
    if (h > 0) out += std::to_string(h) + "H";
    if (h > 0 || m > 0) out += std::to_string(m) + "M";
    std::string sec = fixed(s, 2);
    while (sec.back() == '0') sec.pop_back();  // "3.40" -> "3.4", "3.00" -> "3."
    if (sec.back() == '.') sec.pop_back();
    return out + sec + "S";
}

std::string percent_encode(const std::string& text)
{
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string out;
    for (const char ch : text) {
        const auto c = static_cast<unsigned char>(ch);
        if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '.' || c == '_' || c == '~') {
            out += ch;
        } else {
            out += '%';
            out += kHex[c >> 4];
            out += kHex[c & 15];
        }
    }
    return out;
}

std::string xapi_statements(const Records& records, const std::optional<std::string>& trainee, const XapiOptions& options)
{
    // every id is named within the database: its own UUID, the session's row, the station's place
    const Uuid space = uuid_v5(kUuidNamespaceUrl, options.activity_iri + "/statements/" + records.database_id());
    const std::string ext = options.activity_iri + "/extensions/";
    Json out = Json::array();
    for (const SessionRecord& s : records.sessions(trainee)) {
        const std::string session_name = "session/" + std::to_string(s.id);
        const Json actor{{"objectType", "Agent"}, {"name", s.trainee}, {"account", {{"homePage", options.homepage}, {"name", s.trainee}}}};
        const std::string case_iri = options.activity_iri + "/cases/" + percent_encode(s.case_id);
        const std::string registration = uuid_text(uuid_v5(space, session_name + "/registration"));
        const std::string timestamp = s.started_utc.empty() ? s.stored_utc : s.started_utc;
        const Json extensions{{ext + "case-id", s.case_id}, {ext + "protocol", s.protocol}, {ext + "session", s.id}};

        Json exam;
        exam["id"] = uuid_text(uuid_v5(space, session_name));
        exam["actor"] = actor;
        exam["verb"] = verb(s.passed ? "passed" : "failed");
        exam["object"] = Json{{"objectType", "Activity"},
                              {"id", case_iri},
                              {"definition",
                               {{"name", {{"en-US", s.case_title}}},
                                {"type", "http://adlnet.gov/expapi/activities/assessment"}}}};
        Json result{{"success", s.passed}, {"completion", true}};
        if (std::isfinite(s.score)) {
            // scaled must lie in [-1, 1] and raw within [min, max]: a score outside 0..1 is clamped
            const double scaled = rounded(std::clamp(s.score, 0.0, 1.0), 4);
            result["score"] = Json{{"scaled", scaled}, {"raw", rounded(100 * scaled, 2)}, {"min", 0}, {"max", 100}};
        }
        if (const std::string d = iso8601_duration(s.duration_s); !d.empty()) result["duration"] = d;
        if (!s.conclusion.empty()) result["extensions"] = Json{{ext + "conclusion", s.conclusion}};
        exam["result"] = std::move(result);
        exam["context"] = Json{{"registration", registration}, {"platform", "echosim"}, {"language", "en"}, {"extensions", extensions}};
        exam["timestamp"] = timestamp;
        out.push_back(std::move(exam));

        for (const StationRecord& st : records.stations(s.id)) {
            Json station;
            station["id"] = uuid_text(uuid_v5(space, session_name + "/station/" + std::to_string(st.position)));
            station["actor"] = actor;
            const bool answered = st.call != "none";
            station["verb"] = verb(answered ? "answered" : "attempted");
            station["object"] = Json{{"objectType", "Activity"},
                                     {"id", case_iri + "/stations/" + percent_encode(st.name)},
                                     {"definition",
                                      {{"name", {{"en-US", st.name}}},
                                       {"type", "http://adlnet.gov/expapi/activities/cmi.interaction"},
                                       {"interactionType", "choice"},
                                       {"choices",
                                        Json::array({Json{{"id", "compressible"}, {"description", {{"en-US", "compressible: no thrombus"}}}},
                                                     Json{{"id", "not-compressible"},
                                                          {"description", {{"en-US", "not compressible: thrombus"}}}}})},
                                       {"correctResponsesPattern", Json::array({st.thrombosed ? "not-compressible" : "compressible"})}}}};
            Json sresult{{"success", st.success()}};
            if (answered) sresult["response"] = st.call;
            Json sext{{ext + "reached", st.reached}, {ext + "adequate-pressure", st.adequate}};
            if (std::isfinite(st.collapse_ratio)) sext[ext + "collapse-ratio"] = rounded(st.collapse_ratio, 4);
            if (std::isfinite(st.peak_force_N)) sext[ext + "peak-force-N"] = rounded(st.peak_force_N, 3);
            sresult["extensions"] = std::move(sext);
            station["result"] = std::move(sresult);
            Json sctx_ext = extensions;
            sctx_ext[ext + "segment"] = st.segment;
            if (std::isfinite(st.s_cm)) sctx_ext[ext + "s-cm"] = rounded(st.s_cm, 2);
            station["context"] = Json{{"registration", registration},
                                      {"platform", "echosim"},
                                      {"language", "en"},
                                      {"contextActivities", {{"parent", Json::array({Json{{"objectType", "Activity"}, {"id", case_iri}}})}}},
                                      {"extensions", std::move(sctx_ext)}};
            station["timestamp"] = timestamp;
            out.push_back(std::move(station));
        }
    }
    return out.dump(2, ' ', false, Json::error_handler_t::replace) + "\n";
}

}  // namespace echosim::exam

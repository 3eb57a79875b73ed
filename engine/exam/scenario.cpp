// The case file's reader: every object checked against its table of fields (scenario_fields.hpp:
// unknown fields, missing ones, types, ranges, lengths), then each value read and checked against
// the anatomy (course_limits.hpp: a thrombus within its segment, a station on the course) and the
// protocol (protocol_check.hpp). Every error names the file and the field's JSON pointer.
#include "exam/scenario.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/printable_text.hpp"
#include "exam/course_limits.hpp"
#include "exam/protocol_check.hpp"
#include "exam/scenario_fields.hpp"
#include "exam/scenario_text.hpp"

namespace echosim::exam {
namespace {

using nlohmann::json;
using fields::Field;
using fields::Kind;

std::string message(const std::filesystem::path& file, const std::string& field, const std::string& why)
{
    // the file's own text reaches the message (a key, a value): printed escaped (core/printable_text.hpp)
    return printable(file.string() + ": " + (field.empty() ? std::string() : field + ": ") + why);
}

std::string number_text(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%g", v);
    return buf;
}

const char* kind_name(Kind k)
{
    switch (k) {
    case Kind::string: return "a string";
    case Kind::number: return "a number";
    case Kind::integer: return "a whole number";
    case Kind::object: return "an object";
    case Kind::array: return "an array";
    }
    return "?";
}

// What a JSON value is, for "expected a number, found a string".
const char* found_name(const json& v)
{
    if (v.is_string()) return "a string";
    if (v.is_boolean()) return "true or false";
    if (v.is_null()) return "null";
    if (v.is_number()) return "a number";
    if (v.is_object()) return "an object";
    if (v.is_array()) return "an array";
    return "something else";
}

template <std::size_t N>
std::string one_of(const std::array<std::string_view, N>& names)
{
    std::string out;
    for (const std::string_view n : names) out += (out.empty() ? "" : ", ") + std::string(n);
    return out;
}

// The case file's fields, read at their JSON pointers.
class Reader {
public:
    explicit Reader(const std::filesystem::path& file) : file_(file) {}

    [[noreturn]] void fail(const std::string& field, const std::string& why) const { throw ScenarioError(file_, field, why); }

    // `obj` against the table of its kind: an object, no field the table lacks (a misspelt field
    // would otherwise be dropped unsaid), every required one, each of its type and within its range.
    void check(const json& obj, const std::string& at, std::span<const Field> table) const
    {
        if (!obj.is_object()) fail(at, std::string("expected an object, found ") + found_name(obj));
        for (const auto& [key, value] : obj.items()) {
            const auto f = std::find_if(table.begin(), table.end(), [&](const Field& x) { return x.name == key; });
            if (f == table.end()) {
                std::string known;
                for (const Field& x : table) known += (known.empty() ? "" : ", ") + std::string(x.name);
                fail(at + "/" + json_pointer_token(key), "unknown field (known here: " + known + ")");
            }
            check_value(value, at + "/" + json_pointer_token(key), *f);
        }
        for (const Field& f : table)
            if (f.required && !obj.contains(f.name)) fail(at + "/" + std::string(f.name), "missing (required)");
    }

    static const Field& spec(std::span<const Field> table, std::string_view name)
    {
        for (const Field& f : table)
            if (f.name == name) return f;
        throw std::logic_error("scenario reader: no field '" + std::string(name) + "' in its table");
    }

private:
    void check_value(const json& v, const std::string& at, const Field& f) const
    {
        const std::string unit = f.unit.empty() ? std::string() : " " + std::string(f.unit);
        switch (f.kind) {
        case Kind::number:
        case Kind::integer: {
            if (!v.is_number()) fail(at, std::string("expected ") + kind_name(f.kind) + ", found " + found_name(v));
            const double d = v.get<double>();
            if (f.kind == Kind::integer && d != std::floor(d)) fail(at, number_text(d) + " is not a whole number");
            if (f.lo_exclusive && f.lo == 0 && d <= 0) fail(at, number_text(d) + " is not positive");
            if (!std::isfinite(d) || d < f.lo || (f.lo_exclusive && d <= f.lo) || d > f.hi) {
                const std::string range = f.lo == f.hi ? "must be " + number_text(f.lo) + unit
                                                       : "outside " + std::string(f.lo_exclusive ? "(" : "[") + number_text(f.lo) + ", " +
                                                             number_text(f.hi) + "]" + unit;
                fail(at, number_text(d) + " " + range);
            }
            break;
        }
        case Kind::string: {
            if (!v.is_string()) fail(at, std::string("expected a string, found ") + found_name(v));
            const std::string& s = v.get_ref<const std::string&>();
            if (double(s.size()) < f.lo) fail(at, "empty");
            if (double(s.size()) > f.hi) fail(at, std::to_string(s.size()) + " bytes, longer than the " + number_text(f.hi) + " allowed");
            for (const char c : s)
                if ((static_cast<unsigned char>(c) < 0x20 && !(f.multiline && (c == '\n' || c == '\t'))) || c == 0x7f)
                    fail(at, f.multiline ? "holds a control character (only line breaks and tabs may be written)"
                                         : "holds a control character or a line break (one line of text)");
            break;
        }
        case Kind::object:
            if (!v.is_object()) fail(at, std::string("expected an object, found ") + found_name(v));
            break;
        case Kind::array:
            if (!v.is_array()) fail(at, std::string("expected an array, found ") + found_name(v));
            if (double(v.size()) < f.lo) fail(at, "empty (at least " + number_text(f.lo) + ")");
            if (double(v.size()) > f.hi) fail(at, std::to_string(v.size()) + " items, more than the " + number_text(f.hi) + " allowed");
            break;
        }
    }

    const std::filesystem::path& file_;
};

double number(const json& obj, std::string_view key, double fallback = 0)
{
    const auto it = obj.find(key);
    return it == obj.end() ? fallback : it->get<double>();
}

std::string text(const json& obj, std::string_view key)
{
    const auto it = obj.find(key);
    return it == obj.end() ? std::string() : it->get<std::string>();
}

echo::VeinSegment segment(const Reader& r, const json& obj, const std::string& at)
{
    const std::string name = text(obj, "segment");
    echo::VeinSegment parsed;
    if (echo::parse_segment(name, parsed)) return parsed;
    std::string names;
    for (const course::SegmentSpan& s : course::kSegments) names += (names.empty() ? "" : ", ") + std::string(s.name);
    r.fail(at + "/segment", "'" + name + "' is not a vein segment (one of: " + names + ")");
}

// `s` within the segment's span, else refused at `field` naming the span's ends.
void within_segment(const Reader& r, const std::string& field, const std::string& what, double s, echo::VeinSegment seg)
{
    const course::SegmentSpan& span = course::span_of(seg);
    constexpr double slack = 1e-9;  // [cm] a sum of decimals (33 + 2) that lands a hair past the end
    if (s < span.begin_cm - slack || s > span.end_cm + slack)
        r.fail(field, what + " " + number_text(s) + " cm is off the " + std::string(span.name) + " (" + number_text(span.begin_cm) + " cm at " +
                          std::string(span.begins_at) + " to " + number_text(span.end_cm) + " cm at " + std::string(span.ends_at) + ")");
}

Patient read_patient(const Reader& r, const json& j)
{
    r.check(j, "/patient", fields::kPatient);
    Patient p;
    p.venous_pressure_mmHg = number(j, "venous_pressure_mmHg");
    p.heart_rate_bpm = number(j, "heart_rate_bpm");
    return p;
}

echo::Anatomy read_anatomy(const Reader& r, const json& j)
{
    r.check(j, "/anatomy", fields::kAnatomy);
    echo::Anatomy a;
    a.fat_mm = number(j, "fat_mm");
    if (j.contains("thrombi")) {
        const json& list = j.at("thrombi");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string at = "/anatomy/thrombi/" + std::to_string(i);
            r.check(list[i], at, fields::kThrombus);
            echo::Thrombus t;
            t.segment = segment(r, list[i], at);
            const std::string kind = text(list[i], "kind");
            if (!echo::parse_thrombus_kind(kind, t.kind)) r.fail(at + "/kind", "'" + kind + "' is not a kind of thrombus (one of: " + one_of(fields::kThrombusKindNames) + ")");
            t.start_cm = number(list[i], "start_cm");
            t.extent_cm = number(list[i], "extent_cm");
            t.occlusion = number(list[i], "occlusion", 1.0);
            // the clot lies within its segment: one that runs on into the next is written as two
            // thrombi, one per segment (the acute CFV-to-FV case)
            within_segment(r, at + "/start_cm", "start", t.start_cm, t.segment);
            within_segment(r, at + "/extent_cm", "start " + number_text(t.start_cm) + " + extent " + number_text(t.extent_cm) + " = end",
                           t.start_cm + t.extent_cm, t.segment);
            // two clots over the same stretch of one vein: which the phantom draws there is not said
            for (std::size_t k = 0; k < a.thrombi.size(); ++k) {
                const echo::Thrombus& o = a.thrombi[k];
                if (o.segment == t.segment && t.start_cm < o.start_cm + o.extent_cm && o.start_cm < t.start_cm + t.extent_cm)
                    r.fail(at, "overlaps /anatomy/thrombi/" + std::to_string(k) + " (" + number_text(o.start_cm) + " to " +
                                   number_text(o.start_cm + o.extent_cm) + " cm of the same segment)");
            }
            a.thrombi.push_back(t);
        }
    }
    if (j.contains("lymph_nodes")) {
        const json& list = j.at("lymph_nodes");
        for (std::size_t i = 0; i < list.size(); ++i) {
            const std::string at = "/anatomy/lymph_nodes/" + std::to_string(i);
            r.check(list[i], at, fields::kLymphNode);
            echo::LymphNode n{number(list[i], "s_cm"), number(list[i], "size_mm")};
            // beside the deep vein, anywhere the phantom models it
            if (n.s_cm > course::kTrifurcation_cm)
                r.fail(at + "/s_cm", number_text(n.s_cm) + " cm is past the modelled deep vein (0 cm at the inguinal ligament to " +
                                         number_text(course::kTrifurcation_cm) + " cm at the trifurcation)");
            a.lymph_nodes.push_back(n);
        }
    }
    return a;
}

std::string station_label(echo::VeinSegment seg, double s_cm)
{
    return std::string(course::span_of(seg).label) + " " + number_text(s_cm) + " cm";
}

// One entry of "stations", in any of its three forms, appended to `out` (the generator: each
// station it makes).
void read_station(const Reader& r, const json& j, const std::string& at, std::vector<Station>& out, std::vector<std::string>& from)
{
    if (!j.is_object()) r.fail(at, std::string("expected an object, found ") + found_name(j));
    if (j.contains("landmark")) {
        r.check(j, at, fields::kLandmarkStation);
        const std::string name = text(j, "landmark");
        const auto lm = std::find_if(course::kLandmarks.begin(), course::kLandmarks.end(), [&](const course::Landmark& l) { return l.name == name; });
        if (lm == course::kLandmarks.end()) {
            std::string names;
            for (const course::Landmark& l : course::kLandmarks) names += (names.empty() ? "" : ", ") + std::string(l.name);
            r.fail(at + "/landmark", "'" + name + "' is not a landmark (one of: " + names + ")");
        }
        out.push_back({j.contains("name") ? text(j, "name") : std::string(lm->station_name), lm->segment, lm->s_cm});
        from.push_back(at);
        return;
    }
    if (j.contains("every_cm")) {
        r.check(j, at, fields::kEveryStation);
        const echo::VeinSegment seg = segment(r, j, at);
        const double every = number(j, "every_cm"), first = number(j, "from_cm"), last = number(j, "to_cm");
        within_segment(r, at + "/from_cm", "from", first, seg);
        within_segment(r, at + "/to_cm", "to", last, seg);
        if (last < first) r.fail(at + "/to_cm", number_text(last) + " cm is before from_cm " + number_text(first) + " cm");
        // s computed from the start each time, not summed: 0.1 added 30 times is not 3
        for (int k = 0;; ++k) {
            const double s = std::round((first + k * every) * 1e6) / 1e6;
            if (s > last + 1e-9) break;
            out.push_back({station_label(seg, s), seg, s});
            from.push_back(at);
        }
        return;
    }
    if (!j.contains("segment") && !j.contains("s_cm"))
        r.fail(at, "a station names a \"landmark\", or a \"segment\" and \"s_cm\", or is a row of them (\"every_cm\", \"segment\", "
                   "\"from_cm\", \"to_cm\")");
    r.check(j, at, fields::kDistanceStation);
    const echo::VeinSegment seg = segment(r, j, at);
    const double s = number(j, "s_cm");
    within_segment(r, at + "/s_cm", "s", s, seg);
    out.push_back({j.contains("name") ? text(j, "name") : station_label(seg, s), seg, s});
    from.push_back(at);
}

std::vector<Station> read_stations(const Reader& r, const json& list, Protocol protocol)
{
    std::vector<Station> stations;
    std::vector<std::string> from;  // the JSON pointer each station was read from
    for (std::size_t i = 0; i < list.size(); ++i) read_station(r, list[i], "/stations/" + std::to_string(i), stations, from);
    constexpr std::size_t kMostStations = 200;  // a generator can make many from one entry
    if (stations.size() > kMostStations)
        r.fail("/stations", std::to_string(stations.size()) + " stations, more than the " + std::to_string(kMostStations) + " an exam may have");
    for (std::size_t i = 0; i < stations.size(); ++i) {
        if (stations[i].name.size() > std::size_t(fields::kNameBytes)) r.fail(from[i] + "/name", "longer than the station names allowed");
        for (std::size_t k = 0; k < i; ++k)
            if (stations[k].name == stations[i].name)
                r.fail(from[i], "a second station named '" + stations[i].name + "' (the report names stations: each its own name)");
    }
    if (const ProtocolDefect d = protocol_defect(protocol, stations)) r.fail(d.station < 0 ? "/stations" : from[std::size_t(d.station)], d.why);
    return stations;
}

ScoringBands read_bands(const Reader& r, const json& j)
{
    r.check(j, "/bands", fields::kBands);
    ScoringBands b;  // the optional bands keep their defaults (scenario.hpp)
    b.adequate_force_N = number(j, "adequate_force_N");
    b.excessive_force_N = number(j, "excessive_force_N");
    b.reach_mm = number(j, "reach_mm", b.reach_mm);
    b.transverse_deg = number(j, "transverse_deg", b.transverse_deg);
    b.collapsed_ratio = number(j, "collapsed_ratio", b.collapsed_ratio);
    b.artery_deformed = number(j, "artery_deformed", b.artery_deformed);
    b.pass_mark = number(j, "pass_mark", b.pass_mark);
    if (b.excessive_force_N <= b.adequate_force_N)
        r.fail("/bands/excessive_force_N", number_text(b.excessive_force_N) + " N is not above adequate_force_N " +
                                               number_text(b.adequate_force_N) + " N (adequate < excessive)");
    return b;
}

}  // namespace

ScenarioError::ScenarioError(const std::filesystem::path& f, const std::string& fld, const std::string& why)
    : std::runtime_error(message(f, fld, why)), file(f), field(fld)
{
}

const char* protocol_name(Protocol p)
{
    switch (p) {
    case Protocol::two_point: return "two-point";
    case Protocol::three_point: return "three-point";
    case Protocol::extended: return "extended";
    }
    return "?";
}

Scenario parse_scenario(const std::string& json_text, const std::filesystem::path& file)
{
    const json j = parse_scenario_text(json_text, file);
    const Reader r(file);
    // the schema beside the cases (a glob of *.json takes it too) is said to be one, not taken apart
    if (j.is_object() && j.contains("$schema") && j.at("$schema").is_string() &&
        j.at("$schema").get_ref<const std::string&>().rfind("https://json-schema.org/", 0) == 0)
        r.fail("", "a JSON Schema (the case format's own, scenario.schema.json), not a case");
    // the version first: a later version's file is refused as such, not for a field this reader lacks
    if (j.is_object() && j.contains("version") && !(j.at("version").is_number() && j.at("version").get<double>() == 1.0))
        r.fail("/version", j.at("version").dump() + ": this reader reads version 1 of the case format");
    r.check(j, "", fields::kTop);

    Scenario sc;
    sc.id = text(j, "id");
    // an id names the case's cached volume and its records: lower case, digits and '-' only
    if (sc.id.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-") != std::string::npos || sc.id.front() == '-')
        r.fail("/id", "'" + sc.id + "' is not an id: lower-case letters, digits and '-', not starting with '-'");
    sc.title = text(j, "title");
    sc.description = text(j, "description");
    sc.patient = read_patient(r, j.at("patient"));
    sc.anatomy = read_anatomy(r, j.at("anatomy"));

    const std::string protocol = text(j, "protocol");
    if (protocol == "two-point") sc.protocol = Protocol::two_point;
    else if (protocol == "three-point") sc.protocol = Protocol::three_point;
    else if (protocol == "extended") sc.protocol = Protocol::extended;
    else r.fail("/protocol", "'" + protocol + "' is not a protocol (one of: " + one_of(fields::kProtocolNames) + ")");
    sc.stations = read_stations(r, j.at("stations"), sc.protocol);
    sc.bands = read_bands(r, j.at("bands"));

    if (j.contains("imaging")) {
        const std::string imaging = text(j, "imaging");
        if (imaging == "interpolative") sc.imaging = Imaging::interpolative;
        else if (imaging == "generative") sc.imaging = Imaging::generative;
        else r.fail("/imaging", "'" + imaging + "' is not an imaging mode (one of: " + one_of(fields::kImagingNames) + ")");
    }
    return sc;
}

Scenario read_scenario(const std::filesystem::path& file)
{
    return parse_scenario(read_scenario_text(file), file);
}

}  // namespace echosim::exam

// The case file's reader (exam/scenario.cpp), its schema (assets/cases/scenario.schema.json) and
// the shipped cases: each shipped case reads as the test expects it; each field's bad value is
// refused naming its JSON pointer; the schema and the reader's table of fields are the same.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "exam/course_limits.hpp"
#include "exam/scenario.hpp"
#include "exam/scenario_fields.hpp"

namespace echosim::exam {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

fs::path cases_dir() { return fs::path(ECHOSIM_ASSET_DIR) / "cases"; }

json load(const fs::path& p)
{
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return json::parse(ss.str());
}

// A case with every field the format has, each valid: the test's reference, broken one field at a time.
json full_case()
{
    return json::parse(R"({
      "$schema": "./scenario.schema.json",
      "version": 1,
      "id": "test-case-2",
      "title": "A test case",
      "description": "Line one.\nLine two.",
      "comment": "for the test",
      "patient": {"venous_pressure_mmHg": 12, "heart_rate_bpm": 80, "comment": "c"},
      "anatomy": {
        "fat_mm": 20,
        "thrombi": [
          {"segment": "cfv", "kind": "acute", "start_cm": 1.5, "extent_cm": 2, "occlusion": 1, "comment": "c"},
          {"segment": "fv", "kind": "chronic", "start_cm": 10, "extent_cm": 6, "occlusion": 0.6}
        ],
        "lymph_nodes": [{"s_cm": 2, "size_mm": 15, "comment": "c"}],
        "comment": "c"
      },
      "protocol": "extended",
      "stations": [
        {"landmark": "groin", "name": "Groin", "comment": "c"},
        {"landmark": "sfj"},
        {"segment": "fv", "s_cm": 6, "name": "FV top", "comment": "c"},
        {"every_cm": 2, "segment": "fv", "from_cm": 8, "to_cm": 34, "comment": "c"},
        {"segment": "popliteal", "s_cm": 40},
        {"landmark": "popliteal-fossa"},
        {"segment": "gsv", "s_cm": 2}
      ],
      "bands": {"adequate_force_N": 9, "excessive_force_N": 25, "reach_mm": 4, "transverse_deg": 12, "collapsed_ratio": 0.15,
                "artery_deformed": 0.3, "pass_mark": 0.75, "comment": "c"},
      "imaging": "generative"
    })");
}

// The JSON pointer of the field the reader refused `text` for, and its message; "accepted" when read.
struct Refusal {
    bool refused = false;
    std::string field;
    std::string message;
};

Refusal refusal_of_text(const std::string& text)
{
    try {
        parse_scenario(text, "cases/x.json");
    } catch (const ScenarioError& e) {
        return {true, e.field, e.what()};
    }
    return {};
}

Refusal refusal_of(const json& doc) { return refusal_of_text(doc.dump()); }

void erase(json& doc, const std::string& pointer)
{
    const json::json_pointer p(pointer);
    json& parent = doc.at(p.parent_pointer());
    if (parent.is_array()) parent.erase(std::stoul(p.back()));
    else parent.erase(p.back());
}

void set(json& doc, const std::string& pointer, json value) { doc[json::json_pointer(pointer)] = std::move(value); }

// ---------------------------------------------------------------------------------------------
// A small validator of the JSON Schema keywords scenario.schema.json uses (no C++ validator is in
// Debian): enough to check a document against it, and it refuses a schema keyword it does not
// know, so the schema cannot say something this test silently skips.
class MiniValidator {
public:
    explicit MiniValidator(const json& schema) : root_(schema) {}

    // "" when `doc` is valid, else the first violation's pointer and why
    std::string errors(const json& doc) const
    {
        std::string out;
        validate(root_, doc, "", out);
        return out;
    }

private:
    const json& resolve(const json& s) const
    {
        if (!s.contains("$ref")) return s;
        const std::string ref = s.at("$ref");
        EXPECT_EQ(ref.rfind("#/$defs/", 0), 0u) << ref;
        return root_.at("$defs").at(ref.substr(8));
    }

    void validate(const json& schema_in, const json& v, const std::string& at, std::string& out) const
    {
        if (!out.empty()) return;
        static const std::set<std::string> known = {"$schema", "$id", "$defs", "$ref", "title", "description", "type", "enum",
                                                    "minimum", "maximum", "exclusiveMinimum", "minLength", "maxLength", "pattern",
                                                    "required", "properties", "additionalProperties", "items", "minItems",
                                                    "maxItems", "oneOf"};
        for (const auto& [k, _] : schema_in.items())
            if (!known.count(k)) ADD_FAILURE() << "schema keyword '" << k << "' at " << at << " unknown to the test's validator";
        if (schema_in.contains("$ref")) {
            validate(resolve(schema_in), v, at, out);
            if (!out.empty()) return;
        }
        const json& s = schema_in;
        const auto fail = [&](const std::string& why) {
            if (out.empty()) out = at + ": " + why;
        };
        if (s.contains("type")) {
            const std::string t = s.at("type");
            static const std::set<std::string> types = {"string", "number", "integer", "object", "array"};
            if (!types.count(t)) ADD_FAILURE() << "schema type '" << t << "' unknown to the test's validator";
            const bool ok = t == "string" ? v.is_string()
                            : t == "number" ? v.is_number()
                            : t == "integer" ? v.is_number() && v.get<double>() == std::floor(v.get<double>())
                            : t == "object" ? v.is_object()
                                            : v.is_array();
            if (!ok) return fail("not of type " + t);
        }
        if (s.contains("enum") && std::find(s.at("enum").begin(), s.at("enum").end(), v) == s.at("enum").end()) return fail("not in enum");
        if (v.is_number()) {
            const double d = v.get<double>();
            if (s.contains("minimum") && d < s.at("minimum").get<double>()) return fail("below minimum");
            if (s.contains("exclusiveMinimum") && d <= s.at("exclusiveMinimum").get<double>()) return fail("not above exclusiveMinimum");
            if (s.contains("maximum") && d > s.at("maximum").get<double>()) return fail("above maximum");
        }
        if (v.is_string()) {
            const std::string& t = v.get_ref<const std::string&>();
            if (s.contains("minLength") && t.size() < s.at("minLength").get<std::size_t>()) return fail("shorter than minLength");
            if (s.contains("maxLength") && t.size() > s.at("maxLength").get<std::size_t>()) return fail("longer than maxLength");
            if (s.contains("pattern") && !std::regex_search(t, std::regex(s.at("pattern").get<std::string>(), std::regex::ECMAScript)))
                return fail("does not match pattern");
        }
        if (v.is_object()) {
            if (s.contains("required"))
                for (const auto& r : s.at("required"))
                    if (!v.contains(r.get<std::string>())) return fail("missing required " + r.get<std::string>());
            for (const auto& [k, item] : v.items()) {
                if (s.contains("properties") && s.at("properties").contains(k)) validate(s.at("properties").at(k), item, at + "/" + k, out);
                else if (s.contains("additionalProperties") && s.at("additionalProperties") == false) return fail("property " + k + " not allowed");
            }
        }
        if (v.is_array()) {
            if (s.contains("minItems") && v.size() < s.at("minItems").get<std::size_t>()) return fail("fewer than minItems");
            if (s.contains("maxItems") && v.size() > s.at("maxItems").get<std::size_t>()) return fail("more than maxItems");
            if (s.contains("items"))
                for (std::size_t i = 0; i < v.size(); ++i) validate(s.at("items"), v[i], at + "/" + std::to_string(i), out);
        }
        if (s.contains("oneOf")) {
            int matched = 0;
            for (const auto& branch : s.at("oneOf")) {
                std::string e;
                validate(branch, v, at, e);
                matched += e.empty();
            }
            if (matched != 1) return fail("matches " + std::to_string(matched) + " of oneOf's schemas, not exactly one");
        }
    }

    const json& root_;
};

json schema() { return load(cases_dir() / "scenario.schema.json"); }

// ---------------------------------------------------------------------------------------------

TEST(Scenario, FullCaseReadsAsWritten)
{
    const json doc = full_case();
    const Scenario sc = parse_scenario(doc.dump(), "full.json");
    EXPECT_EQ(sc.id, "test-case-2");
    EXPECT_EQ(sc.title, "A test case");
    EXPECT_EQ(sc.description, "Line one.\nLine two.");
    EXPECT_EQ(sc.patient.venous_pressure_mmHg, 12);
    EXPECT_EQ(sc.patient.heart_rate_bpm, 80);
    EXPECT_EQ(sc.anatomy.fat_mm, 20);
    ASSERT_EQ(sc.anatomy.thrombi.size(), 2u);
    EXPECT_EQ(sc.anatomy.thrombi[0].segment, echo::VeinSegment::cfv);
    EXPECT_EQ(sc.anatomy.thrombi[0].kind, echo::ThrombusKind::acute);
    EXPECT_EQ(sc.anatomy.thrombi[0].start_cm, 1.5);
    EXPECT_EQ(sc.anatomy.thrombi[0].extent_cm, 2);
    EXPECT_EQ(sc.anatomy.thrombi[0].occlusion, 1);
    EXPECT_EQ(sc.anatomy.thrombi[1].segment, echo::VeinSegment::fv);
    EXPECT_EQ(sc.anatomy.thrombi[1].kind, echo::ThrombusKind::chronic);
    EXPECT_EQ(sc.anatomy.thrombi[1].start_cm, 10);
    EXPECT_EQ(sc.anatomy.thrombi[1].extent_cm, 6);
    EXPECT_EQ(sc.anatomy.thrombi[1].occlusion, 0.6);
    ASSERT_EQ(sc.anatomy.lymph_nodes.size(), 1u);
    EXPECT_EQ(sc.anatomy.lymph_nodes[0].s_cm, 2);
    EXPECT_EQ(sc.anatomy.lymph_nodes[0].size_mm, 15);
    EXPECT_EQ(sc.protocol, Protocol::extended);
    EXPECT_EQ(sc.imaging, Imaging::generative);

    // the stations: a named landmark (renamed), a landmark under its own name, a distance, the
    // generator's 14 (8, 10, ... 34 cm), a distance named by default, a landmark, a branch
    std::vector<std::tuple<std::string, echo::VeinSegment, double>> expected = {
        {"Groin", echo::VeinSegment::cfv, 1.0}, {"SFJ", echo::VeinSegment::cfv, 3.0}, {"FV top", echo::VeinSegment::fv, 6.0}};
    for (int s = 8; s <= 34; s += 2) expected.push_back({"FV " + std::to_string(s) + " cm", echo::VeinSegment::fv, double(s)});
    expected.push_back({"Popliteal 40 cm", echo::VeinSegment::popliteal, 40.0});
    expected.push_back({"Popliteal", echo::VeinSegment::popliteal, 42.0});
    expected.push_back({"GSV 2 cm", echo::VeinSegment::gsv, 2.0});
    ASSERT_EQ(sc.stations.size(), expected.size());
    for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(sc.stations[i].name, std::get<0>(expected[i])) << i;
        EXPECT_EQ(sc.stations[i].segment, std::get<1>(expected[i])) << i;
        EXPECT_DOUBLE_EQ(sc.stations[i].s_cm, std::get<2>(expected[i])) << i;
    }

    EXPECT_EQ(sc.bands.adequate_force_N, 9);
    EXPECT_EQ(sc.bands.excessive_force_N, 25);
    EXPECT_EQ(sc.bands.reach_mm, 4);
    EXPECT_EQ(sc.bands.transverse_deg, 12);
    EXPECT_EQ(sc.bands.collapsed_ratio, 0.15);
    EXPECT_EQ(sc.bands.artery_deformed, 0.3);
    EXPECT_EQ(sc.bands.pass_mark, 0.75);
}

TEST(Scenario, OptionalFieldsTakeTheirDefaults)
{
    json doc = full_case();
    for (const char* p : {"/$schema", "/description", "/comment", "/imaging", "/anatomy/thrombi", "/anatomy/lymph_nodes", "/bands/reach_mm",
                          "/bands/transverse_deg", "/bands/collapsed_ratio", "/bands/artery_deformed", "/bands/pass_mark", "/bands/comment"})
        erase(doc, p);
    const Scenario sc = parse_scenario(doc.dump(), "minimal.json");
    EXPECT_EQ(sc.description, "");
    EXPECT_FALSE(sc.imaging.has_value());  // as the machine suits (runner::RunnerConfig::imaging)
    EXPECT_TRUE(sc.anatomy.thrombi.empty());
    EXPECT_TRUE(sc.anatomy.lymph_nodes.empty());
    // the defaults scenario.hpp states
    EXPECT_EQ(sc.bands.reach_mm, 5.0);
    EXPECT_EQ(sc.bands.transverse_deg, 15.0);
    EXPECT_EQ(sc.bands.collapsed_ratio, 0.1);
    EXPECT_EQ(sc.bands.artery_deformed, 0.25);
    EXPECT_EQ(sc.bands.pass_mark, 0.8);

    json partly = full_case();
    erase(partly, "/anatomy/thrombi/1/occlusion");
    EXPECT_EQ(parse_scenario(partly.dump(), "x.json").anatomy.thrombi[1].occlusion, 1.0);
}

// One field broken at a time: the reader refuses it naming that field; `schema` says whether the
// schema alone can see the fault too (types, ranges, unknown and missing fields, names from a set),
// as against the anatomy's and the protocol's checks, which only the reader makes.
struct Broken {
    const char* what;
    std::function<void(json&)> edit;
    const char* field;
    const char* why;
    bool schema;
};

const std::vector<Broken>& broken_cases()
{
    static const std::vector<Broken> rows = {
        {"a later version", [](json& d) { set(d, "/version", 2); }, "/version", "version 1", true},
        {"a fractional version", [](json& d) { set(d, "/version", 1.5); }, "/version", "version 1", true},
        {"version missing", [](json& d) { erase(d, "/version"); }, "/version", "missing", true},
        {"an id with spaces", [](json& d) { set(d, "/id", "Bad Id"); }, "/id", "not an id", true},
        {"an id that is a number", [](json& d) { set(d, "/id", 5); }, "/id", "expected a string, found a number", true},
        {"an id too long", [](json& d) { set(d, "/id", std::string(65, 'a')); }, "/id", "longer than", true},
        {"an empty title", [](json& d) { set(d, "/title", ""); }, "/title", "empty", true},
        {"a title of two lines", [](json& d) { set(d, "/title", "one\ntwo"); }, "/title", "line break", false},
        {"a control character in the description", [](json& d) { set(d, "/description", "bell\x07"); }, "/description", "control character", false},
        {"title missing", [](json& d) { erase(d, "/title"); }, "/title", "missing", true},
        {"an unknown top-level field", [](json& d) { set(d, "/difficulty", 3); }, "/difficulty", "unknown field", true},
        {"a misspelt field", [](json& d) { set(d, "/station", json::array()); }, "/station", "unknown field", true},
        {"patient missing", [](json& d) { erase(d, "/patient"); }, "/patient", "missing", true},
        {"patient not an object", [](json& d) { set(d, "/patient", "old man"); }, "/patient", "expected an object", true},
        {"venous pressure too high", [](json& d) { set(d, "/patient/venous_pressure_mmHg", 80); }, "/patient/venous_pressure_mmHg", "80 outside [0, 40] mmHg", true},
        {"venous pressure negative", [](json& d) { set(d, "/patient/venous_pressure_mmHg", -1); }, "/patient/venous_pressure_mmHg", "outside", true},
        {"heart rate as text", [](json& d) { set(d, "/patient/heart_rate_bpm", "70"); }, "/patient/heart_rate_bpm", "expected a number, found a string", true},
        {"heart rate as a boolean", [](json& d) { set(d, "/patient/heart_rate_bpm", true); }, "/patient/heart_rate_bpm", "found true or false", true},
        {"heart rate too low", [](json& d) { set(d, "/patient/heart_rate_bpm", 10); }, "/patient/heart_rate_bpm", "10 outside [30, 200]", true},
        {"heart rate missing", [](json& d) { erase(d, "/patient/heart_rate_bpm"); }, "/patient/heart_rate_bpm", "missing", true},
        {"an unknown patient field", [](json& d) { set(d, "/patient/age", 70); }, "/patient/age", "unknown field", true},
        {"fat too thin", [](json& d) { set(d, "/anatomy/fat_mm", 2); }, "/anatomy/fat_mm", "2 outside [3, 60] mm", true},
        {"fat too thick", [](json& d) { set(d, "/anatomy/fat_mm", 70); }, "/anatomy/fat_mm", "outside", true},
        {"fat missing", [](json& d) { erase(d, "/anatomy/fat_mm"); }, "/anatomy/fat_mm", "missing", true},
        {"fat as null", [](json& d) { set(d, "/anatomy/fat_mm", nullptr); }, "/anatomy/fat_mm", "found null", true},
        {"thrombi not a list", [](json& d) { set(d, "/anatomy/thrombi", json::object()); }, "/anatomy/thrombi", "expected an array", true},
        {"a thrombus of no extent", [](json& d) { set(d, "/anatomy/thrombi/1/extent_cm", 0); }, "/anatomy/thrombi/1/extent_cm", "0 is not positive", true},
        {"a thrombus of negative extent", [](json& d) { set(d, "/anatomy/thrombi/1/extent_cm", -3); }, "/anatomy/thrombi/1/extent_cm", "not positive", true},
        {"a thrombus beyond its segment", [](json& d) { set(d, "/anatomy/thrombi/1/start_cm", 30); set(d, "/anatomy/thrombi/1/extent_cm", 8); },
         "/anatomy/thrombi/1/extent_cm", "off the fv", false},
        {"a CFV thrombus starting past the bifurcation", [](json& d) { set(d, "/anatomy/thrombi/0/start_cm", 6); }, "/anatomy/thrombi/0/start_cm",
         "off the cfv", false},
        {"an FV thrombus starting above the bifurcation", [](json& d) { set(d, "/anatomy/thrombi/1/start_cm", 2); }, "/anatomy/thrombi/1/start_cm",
         "off the fv", false},
        {"a thrombus on an unknown segment", [](json& d) { set(d, "/anatomy/thrombi/1/segment", "sfv"); }, "/anatomy/thrombi/1/segment",
         "'sfv' is not a vein segment", true},
        {"an unknown kind of thrombus", [](json& d) { set(d, "/anatomy/thrombi/1/kind", "subacute"); }, "/anatomy/thrombi/1/kind", "not a kind", true},
        {"a thrombus filling nothing", [](json& d) { set(d, "/anatomy/thrombi/1/occlusion", 0); }, "/anatomy/thrombi/1/occlusion", "not positive", true},
        {"a thrombus filling more than the vein", [](json& d) { set(d, "/anatomy/thrombi/1/occlusion", 1.5); }, "/anatomy/thrombi/1/occlusion", "outside", true},
        {"an unknown thrombus field", [](json& d) { set(d, "/anatomy/thrombi/0/side", "left"); }, "/anatomy/thrombi/0/side", "unknown field", true},
        {"a thrombus without a kind", [](json& d) { erase(d, "/anatomy/thrombi/1/kind"); }, "/anatomy/thrombi/1/kind", "missing", true},
        {"a thrombus that is a number", [](json& d) { set(d, "/anatomy/thrombi/1", 3); }, "/anatomy/thrombi/1", "expected an object", true},
        {"two thrombi over one stretch", [](json& d) { d["anatomy"]["thrombi"].push_back({{"segment", "fv"}, {"kind", "acute"}, {"start_cm", 12}, {"extent_cm", 2}}); },
         "/anatomy/thrombi/2", "overlaps /anatomy/thrombi/1", false},
        {"a lymph node past the course", [](json& d) { set(d, "/anatomy/lymph_nodes/0/s_cm", 55); }, "/anatomy/lymph_nodes/0/s_cm", "past the modelled", false},
        {"a lymph node too small", [](json& d) { set(d, "/anatomy/lymph_nodes/0/size_mm", 2); }, "/anatomy/lymph_nodes/0/size_mm", "outside [5, 40] mm", true},
        {"a lymph node without a size", [](json& d) { erase(d, "/anatomy/lymph_nodes/0/size_mm"); }, "/anatomy/lymph_nodes/0/size_mm", "missing", true},
        {"an unknown anatomy field", [](json& d) { set(d, "/anatomy/veins", 3); }, "/anatomy/veins", "unknown field", true},
        {"an unknown protocol", [](json& d) { set(d, "/protocol", "four-point"); }, "/protocol", "'four-point' is not a protocol", true},
        {"protocol missing", [](json& d) { erase(d, "/protocol"); }, "/protocol", "missing", true},
        {"no stations", [](json& d) { set(d, "/stations", json::array()); }, "/stations", "empty", true},
        {"stations not a list", [](json& d) { set(d, "/stations", "all"); }, "/stations", "expected an array", true},
        {"an unknown landmark", [](json& d) { set(d, "/stations/1/landmark", "knee"); }, "/stations/1/landmark", "'knee' is not a landmark", true},
        {"a landmark with a distance", [](json& d) { set(d, "/stations/1/s_cm", 3); }, "/stations/1/s_cm", "unknown field", true},
        {"a station past the popliteal vein", [](json& d) { set(d, "/stations/4/s_cm", 55); }, "/stations/4/s_cm", "off the popliteal", false},
        {"an FV station above the bifurcation", [](json& d) { set(d, "/stations/2/s_cm", 2); }, "/stations/2/s_cm", "off the fv", false},
        {"a station on an unknown segment", [](json& d) { set(d, "/stations/2/segment", "saphenous"); }, "/stations/2/segment", "not a vein segment", true},
        {"a station that is a number", [](json& d) { set(d, "/stations/2", 5); }, "/stations/2", "expected an object", true},
        {"a station of no form", [](json& d) { set(d, "/stations/2", json::object()); }, "/stations/2", "a station names", true},
        {"a distance station without s", [](json& d) { erase(d, "/stations/2/s_cm"); }, "/stations/2/s_cm", "missing", true},
        {"an empty station name", [](json& d) { set(d, "/stations/2/name", ""); }, "/stations/2/name", "empty", true},
        {"an unknown station field", [](json& d) { set(d, "/stations/2/depth_mm", 20); }, "/stations/2/depth_mm", "unknown field", true},
        {"stations closer than 5 mm", [](json& d) { set(d, "/stations/3/every_cm", 0.1); }, "/stations/3/every_cm", "outside [0.5, 10] cm", true},
        {"a row that ends before it starts", [](json& d) { set(d, "/stations/3/from_cm", 20); set(d, "/stations/3/to_cm", 10); }, "/stations/3/to_cm",
         "before from_cm", false},
        {"a row past its segment", [](json& d) { set(d, "/stations/3/to_cm", 40); }, "/stations/3/to_cm", "off the fv", false},
        {"a row without a segment", [](json& d) { erase(d, "/stations/3/segment"); }, "/stations/3/segment", "missing", true},
        {"two stations of one name", [](json& d) { set(d, "/stations/4/name", "Groin"); }, "/stations/4", "a second station named 'Groin'", false},
        {"a generated name taken", [](json& d) { set(d, "/stations/2/name", "FV 8 cm"); }, "/stations/3", "a second station named 'FV 8 cm'", false},
        {"stations out of order", [](json& d) { std::swap(d["stations"][0], d["stations"][1]); }, "/stations/1", "not past the station before it", false},
        {"extended: FV stations 4 cm apart", [](json& d) { set(d, "/stations/3/every_cm", 4); }, "/stations/3", "every 2 cm or closer", false},
        {"extended: no SFJ", [](json& d) { erase(d, "/stations/1"); }, "/stations", "compresses the SFJ", false},
        {"extended: no CFV at the groin", [](json& d) { erase(d, "/stations/0"); }, "/stations", "CFV at the groin", false},
        {"extended: stopping short of the canal", [](json& d) { set(d, "/stations/3/to_cm", 30); }, "/stations", "to the adductor canal", false},
        {"no popliteal station", [](json& d) { erase(d, "/stations/5"); erase(d, "/stations/4"); }, "/stations", "popliteal vein: no station", false},
        {"two-point with FV stations", [](json& d) { set(d, "/protocol", "two-point"); }, "/stations/2", "two-point protocol compresses the CFV and the popliteal",
         false},
        {"three-point with a row of FV stations", [](json& d) { set(d, "/protocol", "three-point"); }, "/stations/3", "a second FV station", false},
        {"adequate above excessive", [](json& d) { set(d, "/bands/adequate_force_N", 30); set(d, "/bands/excessive_force_N", 10); },
         "/bands/excessive_force_N", "not above adequate_force_N", false},
        {"adequate equal to excessive", [](json& d) { set(d, "/bands/excessive_force_N", 9); }, "/bands/excessive_force_N", "adequate < excessive", false},
        {"no adequate force", [](json& d) { set(d, "/bands/adequate_force_N", 0); }, "/bands/adequate_force_N", "0 is not positive", true},
        {"excessive missing", [](json& d) { erase(d, "/bands/excessive_force_N"); }, "/bands/excessive_force_N", "missing", true},
        {"a pass mark over 1", [](json& d) { set(d, "/bands/pass_mark", 1.5); }, "/bands/pass_mark", "outside [0, 1]", true},
        {"an angle band of 90 degrees", [](json& d) { set(d, "/bands/transverse_deg", 90); }, "/bands/transverse_deg", "outside [1, 45] deg", true},
        {"an unknown band", [](json& d) { set(d, "/bands/speed", 1); }, "/bands/speed", "unknown field", true},
        {"bands missing", [](json& d) { erase(d, "/bands"); }, "/bands", "missing", true},
        {"an unknown imaging mode", [](json& d) { set(d, "/imaging", "3d"); }, "/imaging", "not an imaging mode", true},
        {"the whole file an array", [](json& d) { d = json::array({1}); }, "", "expected an object", true},
    };
    return rows;
}

TEST(Scenario, EachBrokenFieldRefusedNamingIt)
{
    ASSERT_FALSE(refusal_of(full_case()).refused) << refusal_of(full_case()).message;
    for (const Broken& b : broken_cases()) {
        json doc = full_case();
        b.edit(doc);
        const Refusal r = refusal_of(doc);
        ASSERT_TRUE(r.refused) << b.what << ": accepted";
        EXPECT_EQ(r.field, b.field) << b.what << ": " << r.message;
        EXPECT_NE(r.message.find(b.why), std::string::npos) << b.what << ": " << r.message;
        // the message opens with the file, then the field: what a person needs to find it
        const std::string head = std::string("cases/x.json: ") + (std::string(b.field).empty() ? "" : std::string(b.field) + ": ");
        EXPECT_EQ(r.message.rfind(head, 0), 0u) << b.what << ": " << r.message;
    }
}

TEST(Scenario, SchemaRefusesWhatItCanSee)
{
    const json s = schema();
    const MiniValidator v(s);
    ASSERT_EQ(v.errors(full_case()), "");
    for (const Broken& b : broken_cases()) {
        if (!b.schema) continue;
        json doc = full_case();
        b.edit(doc);
        EXPECT_NE(v.errors(doc), "") << b.what << ": the schema accepts what the reader refuses";
    }
}

// Faults in the text itself, before any field is read.
TEST(Scenario, TextFaultsRefusedNamingWhere)
{
    const std::string good = full_case().dump();
    const auto replaced = [&](const std::string& from, const std::string& to) {
        std::string t = good;
        const auto at = t.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return t.replace(at, from.size(), to);
    };
    // a key given twice: nlohmann would keep the last and lose the first edit unsaid
    Refusal r = refusal_of_text(replaced("\"fat_mm\":20", "\"fat_mm\":20,\"fat_mm\":35"));
    EXPECT_EQ(r.field, "/anatomy/fat_mm") << r.message;
    EXPECT_NE(r.message.find("given twice"), std::string::npos) << r.message;
    r = refusal_of_text(replaced("\"kind\":\"chronic\"", "\"kind\":\"chronic\",\"kind\":\"acute\""));
    EXPECT_EQ(r.field, "/anatomy/thrombi/1/kind") << r.message;
    r = refusal_of_text(replaced("\"landmark\":\"sfj\"", "\"landmark\":\"sfj\",\"landmark\":\"cfv\""));
    EXPECT_EQ(r.field, "/stations/1/landmark") << r.message;

    r = refusal_of_text(good.substr(0, good.size() / 2));
    EXPECT_TRUE(r.refused);
    EXPECT_EQ(r.field, "");
    EXPECT_NE(r.message.find("not valid JSON"), std::string::npos) << r.message;

    r = refusal_of_text(replaced("\"comment\":\"for the test\"", "\"comment\":" + std::string(20, '[') + std::string(20, ']')));
    EXPECT_NE(r.message.find("nested deeper"), std::string::npos) << r.message;

    // the schema beside the cases, given as a case: said to be the schema
    r = refusal_of_text(schema().dump());
    EXPECT_EQ(r.field, "");
    EXPECT_NE(r.message.find("a JSON Schema"), std::string::npos) << r.message;

    // the file's own text in a message is escaped: no terminal escape sequence reaches the screen
    r = refusal_of_text(replaced("\"imaging\":\"generative\"", "\"imaging\":\"\\u001b]0;owned\\u0007\""));
    EXPECT_EQ(r.field, "/imaging");
    EXPECT_EQ(r.message.find('\x1b'), std::string::npos) << r.message;
}

TEST(Scenario, FileFaultsNameTheFile)
{
    const fs::path dir = fs::temp_directory_path() / ("echosim_scenario_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    try {
        read_scenario(dir / "missing.json");
        ADD_FAILURE() << "a missing file read";
    } catch (const ScenarioError& e) {
        EXPECT_EQ(e.file, dir / "missing.json");
        EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
    }
    EXPECT_THROW(read_scenario(dir), ScenarioError);  // a folder
    {
        std::ofstream big(dir / "big.json");
        big << std::string((1u << 20) + 10, ' ');
    }
    try {
        read_scenario(dir / "big.json");
        ADD_FAILURE() << "an oversized file read";
    } catch (const ScenarioError& e) {
        EXPECT_NE(std::string(e.what()).find("over the"), std::string::npos) << e.what();
    }
    fs::remove_all(dir);
}

// The protocols as protocol_check.hpp states them, accepted when met.
TEST(Scenario, EachProtocolAcceptsItsOwnStations)
{
    const auto with = [](const char* protocol, json stations) {
        json d = full_case();
        d["protocol"] = protocol;
        d["stations"] = std::move(stations);
        return refusal_of(d);
    };
    const json cfv = {{"landmark", "groin"}}, sfj = {{"landmark", "sfj"}}, pop = {{"landmark", "popliteal-fossa"}},
               mid = {{"landmark", "mid-thigh-fv"}};
    EXPECT_FALSE(with("two-point", {cfv, pop}).refused) << with("two-point", {cfv, pop}).message;
    EXPECT_FALSE(with("two-point", {cfv, sfj, pop}).refused);
    EXPECT_FALSE(with("three-point", {cfv, sfj, pop}).refused);
    EXPECT_FALSE(with("three-point", {cfv, mid, pop}).refused);
    EXPECT_FALSE(with("three-point", {cfv, sfj, mid, pop}).refused);
    EXPECT_EQ(with("two-point", {cfv}).field, "/stations");
    EXPECT_EQ(with("two-point", {pop}).field, "/stations");
    EXPECT_EQ(with("three-point", {cfv, pop}).field, "/stations");
    EXPECT_EQ(with("extended", {cfv, sfj, mid, pop}).field, "/stations/2");  // 15 cm past the bifurcation
    // the extended exam's FV stations exactly 2 cm apart, from 7 cm (2 cm past the bifurcation) to 33 cm (2 cm above the hiatus)
    json edge = {cfv, sfj, {{"every_cm", 2}, {"segment", "fv"}, {"from_cm", 7}, {"to_cm", 33}}, pop};
    EXPECT_FALSE(with("extended", edge).refused) << with("extended", edge).message;
    edge[2]["from_cm"] = 7.1;  // 2.1 cm past the bifurcation
    EXPECT_EQ(with("extended", edge).field, "/stations/2");
}

// Each shipped case: it reads, its file is named by its id, it holds only the schema's fields,
// and it is what the test expects of it: its protocol, its stations, and which of them lie over a
// thrombus (the stations where a correct exam finds the vein not compressible).
struct ShippedExpectation {
    double fat_mm;
    std::size_t stations;
    std::vector<std::string> thrombosed;
    std::size_t lymph_nodes = 0;
};

std::vector<std::string> fv_names(int from, int to)
{
    std::vector<std::string> out;
    for (int s = from; s <= to; s += 2) out.push_back("FV " + std::to_string(s) + " cm");
    return out;
}

TEST(Scenario, ShippedCasesReadAsExpected)
{
    const std::vector<std::string> none;
    std::vector<std::string> cfv_fv = {"CFV", "SFJ"};
    for (const auto& n : fv_names(6, 18)) cfv_fv.push_back(n);
    const std::map<std::string, ShippedExpectation> expected = {
        {"healthy", {12, 18, none}},
        {"cfv-fv-acute", {12, 18, cfv_fv}},
        {"fv-isolated-acute", {12, 18, fv_names(16, 24)}},
        {"fv-chronic", {12, 18, fv_names(10, 26)}},
        {"popliteal-acute", {12, 20, {"Popliteal above knee", "Popliteal", "Popliteal 46 cm"}}},
        {"large-patient", {38, 18, none}},
        {"lymph-node", {12, 18, none, 1}},
    };
    const std::vector<fs::path> files = shipped_cases();
    std::set<std::string> seen;
    const json s = schema();
    const MiniValidator v(s);
    for (const fs::path& f : files) {
        SCOPED_TRACE(f.string());
        const Scenario sc = read_scenario(f);
        EXPECT_EQ(sc.id, f.stem().string());
        EXPECT_TRUE(seen.insert(sc.id).second);
        EXPECT_EQ(v.errors(load(f)), "");
        EXPECT_FALSE(sc.title.empty());
        EXPECT_GE(sc.description.size(), 100u) << "an instructor's description";
        EXPECT_LT(sc.bands.adequate_force_N, sc.bands.excessive_force_N);
        const auto e = expected.find(sc.id);
        ASSERT_NE(e, expected.end()) << "a shipped case the test does not know: add its expectations";
        EXPECT_EQ(sc.protocol, Protocol::extended);
        EXPECT_EQ(sc.anatomy.fat_mm, e->second.fat_mm);
        EXPECT_EQ(sc.stations.size(), e->second.stations);
        EXPECT_EQ(sc.anatomy.lymph_nodes.size(), e->second.lymph_nodes);
        std::vector<std::string> thrombosed;
        for (const Station& st : sc.stations)
            for (const echo::Thrombus& t : sc.anatomy.thrombi)
                if (t.segment == st.segment && st.s_cm >= t.start_cm && st.s_cm <= t.start_cm + t.extent_cm) thrombosed.push_back(st.name);
        EXPECT_EQ(thrombosed, e->second.thrombosed);
        // the extended exam as shipped: the groin, the SFJ, the FV every 2 cm from 6 to 34 cm, the knee
        EXPECT_EQ(sc.stations.front().name, "CFV");
        EXPECT_EQ(sc.stations[1].name, "SFJ");
    }
    EXPECT_EQ(seen.size(), expected.size()) << "a case the test expects is not shipped";
    // the large patient needs more force than the average one
    EXPECT_GT(read_scenario(shipped_case("large-patient")).bands.adequate_force_N, read_scenario(shipped_case("healthy")).bands.adequate_force_N);
}

TEST(Scenario, ShippedCaseByIdAndRandomDraw)
{
    EXPECT_EQ(shipped_case("healthy").filename(), "healthy.json");
    try {
        shipped_case("no-such-case");
        ADD_FAILURE() << "an unknown id found";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("healthy"), std::string::npos) << "lists the ids: " << e.what();
    }
    const std::vector<fs::path> all = shipped_cases();
    EXPECT_EQ(std::count_if(all.begin(), all.end(), [](const fs::path& p) { return p.filename() == "scenario.schema.json"; }), 0);
    // the same seed, the same case; every case drawn by some seed, none far more often than its share
    EXPECT_EQ(random_case(42), random_case(42));
    std::map<fs::path, int> drawn;
    constexpr int kDraws = 7000;
    for (int seed = 0; seed < kDraws; ++seed) ++drawn[random_case(std::uint64_t(seed))];
    EXPECT_EQ(drawn.size(), all.size());
    for (const auto& [p, n] : drawn) {
        const double share = double(kDraws) / double(all.size());
        EXPECT_NEAR(n, share, 0.2 * share) << p;
    }
}

// ---------------------------------------------------------------------------------------------
// The schema and the reader's table of fields (scenario_fields.hpp) are one format.

// The schema node at a table entry's place: "" the root, "/patient", "/anatomy/thrombi/*", and a
// station's form by its definition's name (landmark_station, ...).
const json& schema_at(const json& root, std::string_view where, std::string_view form)
{
    const auto resolve = [&](const json& s) -> const json& {
        return s.contains("$ref") ? root.at("$defs").at(s.at("$ref").get<std::string>().substr(8)) : s;
    };
    const json* node = &root;
    std::string rest(where);
    while (!rest.empty()) {
        const auto next = rest.find('/', 1);
        const std::string token = rest.substr(1, next == std::string::npos ? std::string::npos : next - 1);
        rest = next == std::string::npos ? "" : rest.substr(next);
        node = token == "*" ? &resolve(node->at("items")) : &resolve(node->at("properties").at(token));
    }
    if (node->contains("oneOf")) {
        for (const json& branch : node->at("oneOf"))
            if (branch.at("$ref") == "#/$defs/" + std::string(form) + "_station") return resolve(branch);
        ADD_FAILURE() << "no station form '" << form << "' in the schema";
    }
    return *node;
}

// Every place in the schema that describes an object's properties, as the table names places.
void schema_objects(const json& root, const json& s, const std::string& where, std::multiset<std::string>& out)
{
    const json& node = s.contains("$ref") ? root.at("$defs").at(s.at("$ref").get<std::string>().substr(8)) : s;
    if (node.contains("properties")) {
        out.insert(where);
        for (const auto& [k, p] : node.at("properties").items()) schema_objects(root, p, where + "/" + k, out);
    }
    if (node.contains("items")) schema_objects(root, node.at("items"), where + "/*", out);
    if (node.contains("oneOf"))
        for (const json& b : node.at("oneOf")) schema_objects(root, b, where, out);
}

TEST(ScenarioSchema, ListsExactlyTheFieldsTheReaderReads)
{
    const json root = schema();
    EXPECT_EQ(root.at("$schema"), "https://json-schema.org/draft/2020-12/schema");
    std::multiset<std::string> in_schema, in_table;
    schema_objects(root, root, "", in_schema);
    for (const fields::ObjectFields& o : fields::kObjects) in_table.insert(std::string(o.where));
    EXPECT_EQ(in_schema, in_table) << "an object the schema describes and the reader does not read, or the other way";

    for (const fields::ObjectFields& o : fields::kObjects) {
        SCOPED_TRACE(std::string(o.where) + " " + std::string(o.form));
        const json& node = schema_at(root, o.where, o.form);
        EXPECT_EQ(node.at("type"), "object");
        EXPECT_EQ(node.at("additionalProperties"), false) << "unknown fields refused, as the reader refuses them";
        std::set<std::string> table_names, schema_names, table_required, schema_required;
        for (const fields::Field& f : o.fields) {
            table_names.insert(std::string(f.name));
            if (f.required) table_required.insert(std::string(f.name));
        }
        for (const auto& [k, _] : node.at("properties").items()) schema_names.insert(k);
        if (node.contains("required"))
            for (const auto& r : node.at("required")) schema_required.insert(r.get<std::string>());
        EXPECT_EQ(table_names, schema_names);
        EXPECT_EQ(table_required, schema_required);

        for (const fields::Field& f : o.fields) {
            if (!node.at("properties").contains(std::string(f.name))) continue;
            SCOPED_TRACE(std::string(f.name));
            const json& p0 = node.at("properties").at(std::string(f.name));
            const json& p = p0.contains("$ref") ? root.at("$defs").at(p0.at("$ref").get<std::string>().substr(8)) : p0;
            EXPECT_TRUE(p0.contains("description") || p.contains("description")) << "an instructor reads every field's description";
            switch (f.kind) {
            case fields::Kind::number:
            case fields::Kind::integer:
                EXPECT_EQ(p.at("type"), f.kind == fields::Kind::number ? "number" : "integer");
                EXPECT_EQ(p.at(f.lo_exclusive ? "exclusiveMinimum" : "minimum").get<double>(), f.lo);
                EXPECT_EQ(p.contains(f.lo_exclusive ? "minimum" : "exclusiveMinimum"), false);
                EXPECT_EQ(p.at("maximum").get<double>(), f.hi);
                break;
            case fields::Kind::string:
                if (p.contains("enum")) break;  // a name from a set: the enums are compared below
                EXPECT_EQ(p.at("type"), "string");
                EXPECT_EQ(p.value("minLength", 0.0), f.lo);
                EXPECT_EQ(p.at("maxLength").get<double>(), f.hi);
                break;
            case fields::Kind::object: EXPECT_EQ(p.at("type"), "object"); break;
            case fields::Kind::array:
                EXPECT_EQ(p.at("type"), "array");
                EXPECT_EQ(p.at("minItems").get<double>(), f.lo);
                EXPECT_EQ(p.at("maxItems").get<double>(), f.hi);
                break;
            }
        }
    }
}

TEST(ScenarioSchema, NamesFromASetAreTheReaders)
{
    const json root = schema();
    const auto names = [](const json& e) {
        std::vector<std::string> out;
        for (const auto& v : e) out.push_back(v.get<std::string>());
        return out;
    };
    std::vector<std::string> segments, landmarks;
    for (const course::SegmentSpan& s : course::kSegments) segments.emplace_back(s.name);
    for (const course::Landmark& l : course::kLandmarks) landmarks.emplace_back(l.name);
    EXPECT_EQ(names(root.at("$defs").at("segment").at("enum")), segments);
    EXPECT_EQ(names(root.at("$defs").at("landmark_station").at("properties").at("landmark").at("enum")), landmarks);
    EXPECT_EQ(names(root.at("$defs").at("thrombus").at("properties").at("kind").at("enum")),
              std::vector<std::string>(fields::kThrombusKindNames.begin(), fields::kThrombusKindNames.end()));
    EXPECT_EQ(names(root.at("properties").at("protocol").at("enum")),
              (std::vector<std::string>{protocol_name(Protocol::two_point), protocol_name(Protocol::three_point), protocol_name(Protocol::extended)}));
    EXPECT_EQ(names(root.at("properties").at("imaging").at("enum")),
              (std::vector<std::string>{imaging_name(Imaging::interpolative), imaging_name(Imaging::generative)}));
    // and the reader accepts each of them
    for (const course::SegmentSpan& span : course::kSegments) {
        json d = full_case();
        d["anatomy"]["thrombi"] = json::array({{{"segment", std::string(span.name)}, {"kind", "acute"}, {"start_cm", span.begin_cm}, {"extent_cm", 1}}});
        EXPECT_FALSE(refusal_of(d).refused) << span.name << ": " << refusal_of(d).message;
    }
    for (const std::string& lm : landmarks) {
        json d = full_case();
        d["protocol"] = "two-point";
        d["stations"] = json::array({{{"landmark", "groin"}, {"name", "Groin"}}, {{"landmark", "popliteal-fossa"}, {"name", "Knee"}}, {{"landmark", lm}}});
        const Refusal r = refusal_of(d);
        // each landmark is read (a station on the FV breaks two-point, and one out of order breaks the order: both past the reading)
        EXPECT_TRUE(!r.refused || r.field == "/stations/2") << lm << ": " << r.message;
        EXPECT_EQ(r.message.find("not a landmark"), std::string::npos) << lm << ": " << r.message;
    }
}

}  // namespace
}  // namespace echosim::exam

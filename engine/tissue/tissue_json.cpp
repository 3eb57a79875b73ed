#include "tissue/tissue_json.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <optional>
#include <string_view>

#include <nlohmann/json.hpp>

#include "io/json_text.hpp"
#include "io/partial_file.hpp"
#include "io/text_fields.hpp"
#include "tissue/physical_ranges.hpp"

namespace echosim::tissue {
namespace {

using nlohmann::json;
constexpr const char* kFormat = "echosim-tissue-model";
constexpr int kVersion = 1;

// The largest model the format allows (refine 64: 449 x 449 nodes, 4 springs each) is written in
// 91 MB, its document estimated at 167 MB (reading it peaks at 460 MB resident, 6 s): these bounds
// hold it with room, and nothing much larger. The deepest legitimate nesting is 4.
constexpr std::uint64_t kMaxModelFileBytes = 256ull << 20;
constexpr io::JsonLimits kModelJsonLimits{8, 1ull << 30};

json vec3s(const std::vector<glm::dvec3>& v)
{
    json out = json::array();
    for (const auto& p : v) out.push_back({p.x, p.y, p.z});
    return out;
}

// Field access that names the file and the field on any failure.
class Reader {
public:
    Reader(const std::filesystem::path& path, const json& root) : path_(path), root_(root) {}

    [[noreturn]] void fail(const std::string& field, const std::string& why) const
    {
        throw ModelFileError(path_.string() + ": field '" + field + "': " + why);
    }
    const json& at(const json& obj, const std::string& field, const std::string& name) const
    {
        if (!obj.is_object() || !obj.contains(field)) fail(name, "missing");
        return obj.at(field);
    }
    double number(const json& obj, const std::string& field, const std::string& name, double lo, double hi) const
    {
        const json& v = at(obj, field, name);
        if (!v.is_number()) fail(name, "not a number");
        const double d = v.get<double>();
        if (!std::isfinite(d) || d < lo || d > hi) {
            char why[96];
            std::snprintf(why, sizeof why, "%g outside [%g, %g]", d, lo, hi);
            fail(name, why);
        }
        return d;
    }
    std::vector<double> numbers(const json& obj, const std::string& field, std::size_t n, double lo, double hi) const
    {
        const json& v = at(obj, field, field);
        if (!v.is_array() || v.size() != n) fail(field, "expected an array of " + std::to_string(n) + " numbers");
        std::vector<double> out(n);
        for (std::size_t i = 0; i < n; ++i) out[i] = number(json{{"x", v[i]}}, "x", field + "[" + std::to_string(i) + "]", lo, hi);
        return out;
    }
    std::vector<glm::dvec3> points(const json& obj, const std::string& field, std::size_t n) const
    {
        const json& v = at(obj, field, field);
        if (!v.is_array() || v.size() != n) fail(field, "expected an array of " + std::to_string(n) + " [x, y, z]");
        std::vector<glm::dvec3> out(n);
        for (std::size_t i = 0; i < n; ++i) {
            const std::string name = field + "[" + std::to_string(i) + "]";
            if (!v[i].is_array() || v[i].size() != 3) fail(name, "expected [x, y, z]");
            for (int c = 0; c < 3; ++c) out[i][c] = number(json{{"x", v[i][std::size_t(c)]}}, "x", name, -1e6, 1e6);
        }
        return out;
    }
    // A whole number in [lo, hi]: a count or an index (2.5 rows is a typo, not 2).
    int count(const json& obj, const std::string& field, const std::string& name, int lo, int hi) const
    {
        const json& v = at(obj, field, name);
        if (!v.is_number_integer() && !(v.is_number_float() && v.get<double>() == std::floor(v.get<double>())))
            fail(name, v.is_number() ? v.dump() + " is not a whole number" : "not a number");
        return int(number(obj, field, name, lo, hi));
    }
    // Refuses a field of `obj` not in `known`: a misspelt or invented field would otherwise be
    // silently ignored, its value never reaching the simulator.
    void only_known(const json& obj, const std::string& prefix, std::initializer_list<std::string_view> known) const
    {
        if (!obj.is_object()) return;
        for (const auto& [key, value] : obj.items())
            if (std::find(known.begin(), known.end(), key) == known.end()) {
                std::string names;
                for (const std::string_view k : known) names += (names.empty() ? "" : ", ") + std::string(k);
                fail(prefix + key, "unknown field (known here: " + names + ")");
            }
    }
    // An optional field: `fallback` when absent, else as number() checks it.
    double optional_number(const json& obj, const std::string& field, const std::string& name, double lo, double hi,
                           double fallback) const
    {
        return obj.contains(field) ? number(obj, field, name, lo, hi) : fallback;
    }
    // An optional string field: empty when absent.
    std::string optional_text(const json& obj, const std::string& field, const std::string& name) const
    {
        if (!obj.contains(field)) return {};
        const json& v = obj.at(field);
        if (!v.is_string()) fail(name, "not a string");
        return v.get<std::string>();
    }
    const json& root() const { return root_; }

private:
    const std::filesystem::path& path_;
    const json& root_;
};

}  // namespace

void write_tissue_model(const std::filesystem::path& path, const TissueModel& m)
{
    json j;
    j["format"] = kFormat;
    j["version"] = kVersion;
    j["provenance"] = m.provenance;
    j["grid"] = {{"rows", m.rows}, {"cols", m.cols}, {"refine", m.refine}};
    j["lambda_N_per_mm"] = m.lambda;
    j["mu_Ns_per_mm"] = m.mu;
    j["samples"] = {{"a_per_N", m.samples.a}, {"b_mm_per_N", m.samples.b}};
    j["fit"] = {{"method", m.fit.method},         {"seconds", m.fit.seconds},
                {"samples", m.fit.samples},       {"mae_N", m.fit.mae_N},
                {"sd_N", m.fit.sd_N},             {"rel_error", m.fit.rel_error},
                {"mae_indenter_N", m.fit.mae_indenter_N}, {"mae_probe_N", m.fit.mae_probe_N}};
    json nodes;
    nodes["position_mm"] = vec3s(m.positions);
    nodes["normal"] = vec3s(m.normals);
    nodes["mass_kg"] = m.mass;
    nodes["a_per_N"] = m.a;
    nodes["b_mm_per_N"] = m.b;
    nodes["boundary"] = m.boundary;
    j["nodes"] = nodes;
    json springs = json::array();
    for (const auto& s : m.springs) springs.push_back({s.i, s.j, s.rest_length});
    j["springs_i_j_rest_mm"] = springs;

    io::write_file<ModelFileError>(path, j.dump(1) + "\n");
}

TissueModel read_tissue_model(const std::filesystem::path& path)
{
    std::ifstream in = io::text::open_binary<ModelFileError>(path);  // refuses devices and FIFOs
    std::uint64_t size = 0;
    std::optional<std::vector<std::uint8_t>> text;
    const std::uint64_t left = io::text::bytes_left(in);
    if (left > kMaxModelFileBytes)
        throw ModelFileError(path.string() + ": " + (left == std::numeric_limits<std::uint64_t>::max() ? std::string("of unknown size") : std::to_string(left >> 20) + " MiB") +
                             ", over the " + std::to_string(kMaxModelFileBytes >> 20) + " MiB a tissue model file may hold");
    text = io::text::read_exactly(in, left, size);
    if (!text) throw ModelFileError(path.string() + ": cannot read it whole");
    json j;
    try {
        j = io::parse_json_text(std::string_view(reinterpret_cast<const char*>(text->data()), text->size()), kModelJsonLimits);
    } catch (const io::JsonTextError& e) {
        throw ModelFileError(path.string() + ": " + e.what());
    }
    text.reset();
    Reader r(path, j);
    if (!j.is_object() || r.optional_text(j, "format", "format") != kFormat)
        r.fail("format", std::string("expected \"") + kFormat + "\"");
    if (r.count(j, "version", "version", 1, 1000000000) != kVersion) r.fail("version", "unsupported version");
    r.only_known(j, "", {"format", "version", "provenance", "grid", "lambda_N_per_mm", "mu_Ns_per_mm", "samples", "fit", "nodes",
                         "springs_i_j_rest_mm"});

    TissueModel m;
    const json& grid = r.at(j, "grid", "grid");
    r.only_known(grid, "grid.", {"rows", "cols", "refine"});
    m.rows = r.count(grid, "rows", "grid.rows", 2, 100000);
    m.cols = r.count(grid, "cols", "grid.cols", 2, 100000);
    m.refine = r.count(grid, "refine", "grid.refine", 1, 64);
    if (m.rows != (SampleGrid::rows - 1) * m.refine + 1 || m.cols != (SampleGrid::cols - 1) * m.refine + 1)
        r.fail("grid", "rows and cols do not match refine " + std::to_string(m.refine));
    // the ranges here only keep the numbers finite; physical_ranges.hpp's are checked below
    m.lambda = r.number(j, "lambda_N_per_mm", "lambda_N_per_mm", 0, 1e300);
    m.mu = r.number(j, "mu_Ns_per_mm", "mu_Ns_per_mm", 0, 1e300);
    if (j.contains("provenance") && j["provenance"].is_string()) m.provenance = j["provenance"].get<std::string>();

    const json& samples = r.at(j, "samples", "samples");
    r.only_known(samples, "samples.", {"a_per_N", "b_mm_per_N"});
    const auto sa = r.numbers(samples, "a_per_N", SampleGrid::count, 0, 1e300);
    const auto sb = r.numbers(samples, "b_mm_per_N", SampleGrid::count, 0, 1e300);
    std::copy(sa.begin(), sa.end(), m.samples.a.begin());
    std::copy(sb.begin(), sb.end(), m.samples.b.begin());
    // a refined model's mu is the sample points' over r^2 (tissue_model.hpp)
    const double scale = double(m.refine) * double(m.refine);
    m.samples.lambda = m.lambda;
    m.samples.mu = m.mu * scale;
    if (const ParameterDefect d = sample_parameters_defect(m.samples))
        r.fail(d.field, d.field == "mu_Ns_per_mm" && m.refine > 1 ? d.why + ", times refine^2 = " + std::to_string(int(scale)) : d.why);

    if (j.contains("fit") && j["fit"].is_object()) {
        // statistics, not physics: each optional, but of the right type and range (json's value() would
        // throw its own type_error for a string there, and cast 1e300 to int)
        const json& f = j["fit"];
        r.only_known(f, "fit.", {"method", "seconds", "samples", "mae_N", "sd_N", "rel_error", "mae_indenter_N", "mae_probe_N"});
        constexpr double most = 1e9;
        m.fit.method = r.optional_text(f, "method", "fit.method");
        m.fit.seconds = r.optional_number(f, "seconds", "fit.seconds", 0, most, 0);
        m.fit.samples = f.contains("samples") ? r.count(f, "samples", "fit.samples", 0, 1000000000) : 0;
        m.fit.mae_N = r.optional_number(f, "mae_N", "fit.mae_N", 0, most, 0);
        m.fit.sd_N = r.optional_number(f, "sd_N", "fit.sd_N", 0, most, 0);
        m.fit.rel_error = r.optional_number(f, "rel_error", "fit.rel_error", 0, most, 0);
        m.fit.mae_indenter_N = r.optional_number(f, "mae_indenter_N", "fit.mae_indenter_N", 0, most, 0);
        m.fit.mae_probe_N = r.optional_number(f, "mae_probe_N", "fit.mae_probe_N", 0, most, 0);
    }

    const std::size_t n = std::size_t(m.rows) * std::size_t(m.cols);
    const json& nodes = r.at(j, "nodes", "nodes");
    r.only_known(nodes, "nodes.", {"position_mm", "normal", "mass_kg", "a_per_N", "b_mm_per_N", "boundary"});
    m.positions = r.points(nodes, "position_mm", n);
    m.normals = r.points(nodes, "normal", n);
    for (std::size_t i = 0; i < n; ++i)
        if (std::abs(std::sqrt(m.normals[i].x * m.normals[i].x + m.normals[i].y * m.normals[i].y + m.normals[i].z * m.normals[i].z) - 1.0) > 1e-3)
            r.fail("normal[" + std::to_string(i) + "]", "not of unit length");
    m.mass = r.numbers(nodes, "mass_kg", n, 0, 1e300);
    m.a = r.numbers(nodes, "a_per_N", n, 0, 1e300);
    m.b = r.numbers(nodes, "b_mm_per_N", n, 0, 1e300);
    // every node against the sample points' ranges, scaled back by its 1/r^2 share of area
    for (std::size_t i = 0; i < n; ++i) {
        const std::string index = "[" + std::to_string(i) + "]";
        if (const ParameterDefect d = spring_defect(m.a[i] / scale, m.b[i] / scale, "nodes.a_per_N" + index, "nodes.b_mm_per_N" + index))
            r.fail(d.field, d.why);
        if (const std::string d = range_defect(kSampleMass, m.mass[i] * scale); !d.empty()) r.fail("nodes.mass_kg" + index, d);
    }
    const auto boundary = r.numbers(nodes, "boundary", n, 0, 1);
    for (std::size_t i = 0; i < n; ++i)
        if (boundary[i] != 0 && boundary[i] != 1) r.fail("nodes.boundary[" + std::to_string(i) + "]", "must be 0 or 1");
    m.boundary.assign(boundary.begin(), boundary.end());

    const json& springs = r.at(j, "springs_i_j_rest_mm", "springs_i_j_rest_mm");
    if (!springs.is_array() || springs.empty()) r.fail("springs_i_j_rest_mm", "expected a non-empty array of [i, j, rest_mm]");
    for (std::size_t s = 0; s < springs.size(); ++s) {
        const std::string name = "springs_i_j_rest_mm[" + std::to_string(s) + "]";
        if (!springs[s].is_array() || springs[s].size() != 3) r.fail(name, "expected [i, j, rest_mm]");
        const double i = r.number(json{{"x", springs[s][0]}}, "x", name + ".i", 0, double(n - 1));
        const double k = r.number(json{{"x", springs[s][1]}}, "x", name + ".j", 0, double(n - 1));
        const double rest = r.number(json{{"x", springs[s][2]}}, "x", name + ".rest_mm", 0, 1e300);
        if (const std::string d = range_defect(kSpringRestLength, rest); !d.empty()) r.fail(name + ".rest_mm", d);
        if (i == k || i != std::floor(i) || k != std::floor(k)) r.fail(name, "i and j must be two different node indices");
        m.springs.push_back({std::uint32_t(i), std::uint32_t(k), rest});
    }
    return m;
}

void check_derived_fields(const std::filesystem::path& path, const TissueModel& read, const TissueModel& rebuilt)
{
    const auto differ = [](double a, double b) { return std::abs(a - b) > 1e-6 * std::max({std::abs(a), std::abs(b), 1e-300}); };
    const auto fail = [&](const std::string& field, double value, double derived) {
        char why[256];
        std::snprintf(why, sizeof why, "%.9g differs from %.9g, what `samples` give on the simulator's leg", value, derived);
        throw ModelFileError(path.string() + ": field '" + field + "': " + why +
                             ": the simulator builds every node and spring from `samples` (edit those)");
    };
    const std::size_t n = rebuilt.positions.size();
    if (read.positions.size() != n || read.springs.size() != rebuilt.springs.size())
        throw ModelFileError(path.string() + ": field 'nodes': the mesh is not the one `grid` and the simulator's leg give");
    for (std::size_t i = 0; i < n; ++i) {
        const std::string index = "[" + std::to_string(i) + "]";
        for (int c = 0; c < 3; ++c) {
            if (std::abs(read.positions[i][c] - rebuilt.positions[i][c]) > 1e-6 * std::max(1.0, std::abs(rebuilt.positions[i][c])))
                fail("nodes.position_mm" + index, read.positions[i][c], rebuilt.positions[i][c]);
            if (std::abs(read.normals[i][c] - rebuilt.normals[i][c]) > 1e-6) fail("nodes.normal" + index, read.normals[i][c], rebuilt.normals[i][c]);
        }
        if (differ(read.mass[i], rebuilt.mass[i])) fail("nodes.mass_kg" + index, read.mass[i], rebuilt.mass[i]);
        if (differ(read.a[i], rebuilt.a[i])) fail("nodes.a_per_N" + index, read.a[i], rebuilt.a[i]);
        if (differ(read.b[i], rebuilt.b[i])) fail("nodes.b_mm_per_N" + index, read.b[i], rebuilt.b[i]);
        if (read.boundary[i] != rebuilt.boundary[i]) fail("nodes.boundary" + index, read.boundary[i], rebuilt.boundary[i]);
    }
    for (std::size_t s = 0; s < read.springs.size(); ++s) {
        const Spring &x = read.springs[s], &y = rebuilt.springs[s];
        const std::string name = "springs_i_j_rest_mm[" + std::to_string(s) + "]";
        if (x.i != y.i) fail(name + ".i", x.i, y.i);
        if (x.j != y.j) fail(name + ".j", x.j, y.j);
        if (differ(x.rest_length, y.rest_length)) fail(name + ".rest_mm", x.rest_length, y.rest_length);
    }
}

}  // namespace echosim::tissue

#include "tissue/tissue_model.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "scene/leg.hpp"
#include "tissue/nonlinear_spring.hpp"
#include "tissue/physical_ranges.hpp"
#include "io/json_text.hpp"
#include "tissue/tissue_json.hpp"
#include "test_files.hpp"

namespace echosim::tissue {
namespace {

SampleParameters varied_parameters()
{
    SampleParameters p;
    for (int i = 0; i < SampleGrid::count; ++i) {
        p.b[std::size_t(i)] = 0.5 + 0.01 * i;           // rest stiffness 2 .. 0.9 N/mm
        p.a[std::size_t(i)] = p.b[std::size_t(i)] / (30.0 + 0.2 * i);  // bottoms out at 30 .. 42.6 mm
    }
    p.lambda = 0.08;
    p.mu = 0.002;
    return p;
}

TEST(TissueModel, SamplePointsKeepTheirParametersAtEveryRefinement)
{
    const scene::LegModel leg;
    const SampleParameters params = varied_parameters();
    for (int refine : {1, 2, 3}) {
        const TissueModel m = build_tissue_model(leg, params, refine);
        EXPECT_EQ(m.rows, 7 * refine + 1);
        EXPECT_EQ(m.node_count(), std::size_t(m.rows * m.cols));
        for (int p : {0, 9, 36, 63}) {
            const auto k = m.sample_node(p);
            // scaled by the node's 1/r^2 share of area; the bottoming depth b/a is kept
            EXPECT_NEAR(m.b[k], params.b[std::size_t(p)] * refine * refine, 1e-9);
            EXPECT_NEAR(m.b[k] / m.a[k], params.b[std::size_t(p)] / params.a[std::size_t(p)], 1e-9);
        }
    }
}

TEST(TissueModel, RefinedNodesInterpolateStiffnessAndDepth)
{
    // a node halfway between sample points 9 and 10 (row 1, columns 1 and 2) at refine 2: its rest
    // stiffness per area (1/b) and its bottoming depth (b/a) are the two points' means
    const scene::LegModel leg;
    const SampleParameters params = varied_parameters();
    const TissueModel m = build_tissue_model(leg, params, 2);
    const auto k = m.node(2, 3);
    const double k9 = 1.0 / params.b[9], k10 = 1.0 / params.b[10];
    EXPECT_NEAR(4.0 / m.b[k], 0.5 * (k9 + k10), 1e-12);
    const double d9 = params.b[9] / params.a[9], d10 = params.b[10] / params.a[10];
    EXPECT_NEAR(m.b[k] / m.a[k], 0.5 * (d9 + d10), 1e-9);
    // a node in the middle of four sample points takes a quarter of each
    const auto c = m.node(3, 3);
    const double mean_k = 0.25 * (1 / params.b[9] + 1 / params.b[10] + 1 / params.b[17] + 1 / params.b[18]);
    EXPECT_NEAR(4.0 / m.b[c], mean_k, 1e-12);
}

TEST(TissueModel, GeometryFollowsTheLeg)
{
    const scene::LegModel leg;
    const TissueModel m = build_tissue_model(leg, varied_parameters(), 2);
    // the sample point 27 (row 3, col 3) lies where the leg's patch has it
    const glm::dvec3 expected(leg.patch_point(float(SampleGrid::u(3)), float(SampleGrid::v(3))));
    EXPECT_LT(glm::length(m.positions[m.sample_node(27)] - expected), 1e-4);
    // rest lengths are the node distances; every node has some mass; the rim is marked
    for (const Spring& s : m.springs) EXPECT_NEAR(s.rest_length, glm::length(m.positions[s.i] - m.positions[s.j]), 1e-9);
    for (double mass : m.mass) EXPECT_GT(mass, 0.0);
    EXPECT_TRUE(m.boundary[0]);
    EXPECT_FALSE(m.boundary[m.node(3, 3)]);
    // total mass: patch area times the surface density
    double total = 0;
    for (double mass : m.mass) total += mass;
    EXPECT_GT(total / kSurfaceMassPerArea, 3000.0);   // the sampled area is roughly 105 x 70 mm
    EXPECT_LT(total / kSurfaceMassPerArea, 12000.0);
}

std::filesystem::path temp(const char* name)
{
    return std::filesystem::temp_directory_path() / (std::string("echosim_tissue_") + std::to_string(::getpid()) + name);
}

TEST(TissueJson, RoundTrips)
{
    const scene::LegModel leg;
    TissueModel m = build_tissue_model(leg, varied_parameters(), 2);
    m.provenance = "test";
    m.fit.mae_N = 0.5;
    m.fit.method = "levenberg-marquardt";
    const auto path = temp("roundtrip.json");
    write_tissue_model(path, m);
    const TissueModel r = read_tissue_model(path);
    EXPECT_EQ(r.rows, m.rows);
    EXPECT_EQ(r.refine, 2);
    EXPECT_EQ(r.springs.size(), m.springs.size());
    EXPECT_DOUBLE_EQ(r.lambda, m.lambda);
    EXPECT_DOUBLE_EQ(r.a[17], m.a[17]);
    EXPECT_DOUBLE_EQ(r.samples.b[5], m.samples.b[5]);
    EXPECT_DOUBLE_EQ(r.fit.mae_N, 0.5);
    EXPECT_EQ(r.provenance, "test");
    EXPECT_LT(glm::length(r.positions[40] - m.positions[40]), 1e-9);
    std::filesystem::remove(path);
}

TEST(TissueJson, BadFilesNameTheField)
{
    const scene::LegModel leg;
    const auto good = temp("good.json");
    write_tissue_model(good, build_tissue_model(leg, varied_parameters(), 1));
    std::string text;
    {
        std::ifstream in(good);
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    auto message = [&](const std::string& broken) {
        const auto path = temp("bad.json");
        std::ofstream(path) << broken;
        try {
            read_tissue_model(path);
        } catch (const ModelFileError& e) {
            std::filesystem::remove(path);
            return std::string(e.what());
        }
        std::filesystem::remove(path);
        return std::string("no error");
    };
    auto replaced = [&](const std::string& from, const std::string& to) {
        std::string t = text;
        const auto at = t.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        return t.replace(at, from.size(), to);
    };
    // a misspelt field is named as unknown before the one it was meant to be is found missing
    EXPECT_NE(message(replaced("\"lambda_N_per_mm\"", "\"lambda_typo\"")).find("'lambda_typo': unknown field"), std::string::npos);
    nlohmann::json without = nlohmann::json::parse(text);
    without.erase("lambda_N_per_mm");
    EXPECT_NE(message(without.dump()).find("'lambda_N_per_mm': missing"), std::string::npos);
    EXPECT_NE(message(replaced("\"refine\": 1", "\"refine\": 2")).find("'grid'"), std::string::npos);
    EXPECT_NE(message(text.substr(0, text.size() / 2)).find("not valid JSON"), std::string::npos);
    EXPECT_NE(message(replaced("\"format\": \"echosim-tissue-model\"", "\"format\": \"other\"")).find("'format'"), std::string::npos);
    // issue 13 (fuzzing): json's own exceptions escaped for a number beyond double's range and for a
    // wrong type where value() was used, and 1e300 was cast to int
    EXPECT_NE(message(replaced("\"lambda_N_per_mm\": ", "\"lambda_N_per_mm\": 1e999, \"x\": ")).find("not valid JSON"), std::string::npos);
    EXPECT_NE(message(replaced("\"format\": \"echosim-tissue-model\"", "\"format\": 3")).find("'format'"), std::string::npos);
    EXPECT_NE(message(replaced("\"method\": \"\"", "\"method\": 7")).find("'fit.method': not a string"), std::string::npos);
    EXPECT_NE(message(replaced("\"samples\": 0", "\"samples\": 1e300")).find("'fit.samples'"), std::string::npos);

    // issue 34: what nlohmann::json accepts silently, refused by name. A key given twice (json keeps
    // the last, the first edit lost); a count that is not whole (2.5 rows was read as 2); a field
    // the reader does not know (a typo's value never reached the simulator)
    EXPECT_NE(message(replaced("\"refine\": 1", "\"refine\": 1, \"rows\": 8")).find("key \"rows\" given twice in object 'grid'"),
              std::string::npos);
    EXPECT_NE(message(replaced("\"lambda_N_per_mm\": ", "\"lambda_N_per_mm\": 1, \"lambda_N_per_mm\": ")).find("given twice in the top-level object"),
              std::string::npos);
    EXPECT_NE(message(replaced("\"refine\": 1", "\"refine\": 1.5")).find("'grid.refine': 1.5 is not a whole number"), std::string::npos);
    EXPECT_NE(message(replaced("\"samples\": 0", "\"samples\": 12.25")).find("'fit.samples': 12.25 is not a whole number"),
              std::string::npos);
    EXPECT_EQ(message(replaced("\"refine\": 1", "\"refine\": 1.0")), "no error");  // a whole number written as a float
    EXPECT_NE(message(replaced("\"a_per_N\"", "\"c_per_N\": [], \"a_per_N\"")).find("'nodes.c_per_N': unknown field"), std::string::npos);
    EXPECT_NE(message(replaced("\"boundary\": [\n   1", "\"boundary\": [\n   0.5")).find("'nodes.boundary[0]': must be 0 or 1"),
              std::string::npos);
    std::filesystem::remove(good);
}

// Issue 34: a model nested 200,000 arrays deep (nothing legitimate is nested deeper than 4), and one
// whose document would cost gigabytes ("[[],[],...": each 3 bytes a container on the heap), are
// refused before parsing; a document within the budget is not.
TEST(TissueJson, NestingAndDocumentSizeAreCappedBeforeParsing)
{
    const auto path = temp("deep.json");
    test::write_bytes(path, std::string(200000, '[') + std::string(200000, ']'));
    try {
        read_tissue_model(path);
        ADD_FAILURE() << "read a model nested 200,000 deep";
    } catch (const ModelFileError& e) {
        EXPECT_NE(std::string(e.what()).find("nested deeper than 8 (at byte 8)"), std::string::npos) << e.what();
    }
    // 20 MB of empty arrays: about 530 MB of document by the estimate, nlohmann's own layout
    std::string many = "[";
    for (int i = 0; i < 7'000'000; ++i) many += "[],";
    many += "[]]";
    EXPECT_GT(io::json_document_bytes(many, 8), 7'000'000ull * 64);
    EXPECT_THROW(io::parse_json_text(many, {8, 256ull << 20}), io::JsonTextError);
    EXPECT_EQ(io::parse_json_text(many, {8, 1ull << 30}).size(), 7'000'001u);
    // brackets inside strings are text, not nesting
    EXPECT_EQ(io::parse_json_text("{\"a\": \"[[[[[[[[[[\"}", {2, 1 << 20})["a"], "[[[[[[[[[[");
    std::filesystem::remove(path);
}

// Issue 34: the file's nodes and springs are what `samples` give; a file whose nodes say otherwise
// is refused naming the node, instead of being silently overruled by the samples.
TEST(TissueJson, NodesThatDisagreeWithTheSamplesAreRefused)
{
    const scene::LegModel leg;
    const TissueModel built = build_tissue_model(leg, varied_parameters(), 2);
    EXPECT_NO_THROW(check_derived_fields("m.json", built, build_tissue_model(leg, built.samples, 2)));
    TissueModel edited = built;
    edited.b[30] *= 1.5;
    try {
        check_derived_fields("m.json", edited, build_tissue_model(leg, edited.samples, 2));
        ADD_FAILURE() << "an edited node was accepted";
    } catch (const ModelFileError& e) {
        EXPECT_NE(std::string(e.what()).find("m.json: field 'nodes.b_mm_per_N[30]'"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("edit those"), std::string::npos) << e.what();
    }
    edited = built;
    edited.springs[7].rest_length += 1.0;
    EXPECT_THROW(check_derived_fields("m.json", edited, build_tissue_model(leg, edited.samples, 2)), ModelFileError);
    // the shipped thigh is what its samples give
    const TissueModel thigh = read_tissue_model(std::filesystem::path(ECHOSIM_ASSET_DIR) / "models" / "thigh.json");
    EXPECT_NO_THROW(check_derived_fields("thigh.json", thigh, build_tissue_model(leg, thigh.samples, thigh.refine)));
}

// Values inside the reader's number ranges but not a thigh's: refused with the field, the value
// and the physical range (the damping below settled 20x slower and reported a force that had not
// settled).
TEST(TissueJson, PhysicallyAbsurdParametersAreRefusedByName)
{
    const scene::LegModel leg;
    auto message = [&](TissueModel m) {
        const auto path = temp("absurd.json");
        write_tissue_model(path, m);
        std::string what = "no error";
        try {
            read_tissue_model(path);
        } catch (const ModelFileError& e) {
            what = e.what();
        }
        std::filesystem::remove(path);
        return what;
    };
    const TissueModel good = build_tissue_model(leg, varied_parameters(), 2);
    EXPECT_EQ(message(good), "no error");

    TissueModel m = good;
    m.mu = 65537.0;
    std::string why = message(m);
    EXPECT_NE(why.find("'mu_Ns_per_mm'"), std::string::npos) << why;
    EXPECT_NE(why.find("physical range [0, 0.1] N s/mm"), std::string::npos) << why;

    m = good;
    m.lambda = 1e-128;
    why = message(m);
    EXPECT_NE(why.find("'lambda_N_per_mm': 1e-128 N/mm outside the physical range"), std::string::npos) << why;

    m = good;
    m.samples.b[7] = 1e-4;  // 10,000 N/mm at rest: steel, not skin
    why = message(m);
    EXPECT_NE(why.find("'samples.b_mm_per_N[7]'"), std::string::npos) << why;
    EXPECT_NE(why.find("rest stiffness"), std::string::npos) << why;

    m = good;
    m.samples.a[3] = m.samples.b[3] / 0.01;  // bottoms out after 0.01 mm
    why = message(m);
    EXPECT_NE(why.find("'samples.a_per_N[3]'"), std::string::npos) << why;
    EXPECT_NE(why.find("bottoming depth"), std::string::npos) << why;

    // issue 34: inside the old ranges, but the force fell as the probe pressed deeper (the contact
    // cannot hold a spring bottoming within the 25 mm press, nor one this stiff: physical_ranges.hpp)
    m = good;
    m.samples.a[3] = m.samples.b[3] / 5.0;
    why = message(m);
    EXPECT_NE(why.find("'samples.a_per_N[3]': 5 mm outside the physical range [30, 1e+06] mm"), std::string::npos) << why;
    m = good;
    m.samples.b[9] = 0.1;  // 10 N/mm at rest
    why = message(m);
    EXPECT_NE(why.find("'samples.b_mm_per_N[9]': 10 N/mm outside the physical range [0.001, 2] N/mm"), std::string::npos) << why;
    // a denormal a made b/a infinite, and the nodes between sample points NaN
    m = good;
    m.samples.a[3] = 1e-310;
    why = message(m);
    EXPECT_NE(why.find("'samples.a_per_N[3]': inf mm outside the physical range"), std::string::npos) << why;

    // a node of a refined model is checked scaled back to a sample point's share (x r^2 = 4):
    // 0.3 g is a plausible sample point's mass, but at refine 2 the node carries a quarter of it
    m = good;
    m.mass[5] = 0.5;
    why = message(m);
    EXPECT_NE(why.find("'nodes.mass_kg[5]': 2 kg outside the physical range"), std::string::npos) << why;

    m = good;
    m.springs[4].rest_length = 1e-5;
    why = message(m);
    EXPECT_NE(why.find("'springs_i_j_rest_mm[4].rest_mm'"), std::string::npos) << why;
}

TEST(PhysicalRanges, TheShippedThighLiesWellInside)
{
    const TissueModel shipped = read_tissue_model(std::filesystem::path(ECHOSIM_ASSET_DIR) / "models" / "thigh.json");
    EXPECT_FALSE(sample_parameters_defect(shipped.samples)) << sample_parameters_defect(shipped.samples).why;
    // a decade inside every bound the shipped values approach
    SampleParameters tenfold = shipped.samples;
    tenfold.mu *= 10, tenfold.lambda /= 10;
    for (double& b : tenfold.b) b *= 10;
    EXPECT_FALSE(sample_parameters_defect(tenfold));
    EXPECT_EQ(range_defect(kSurfaceDamping, std::nan("")), "nan N s/mm outside the physical range [0, 0.1] N s/mm (surface spring damping mu)");
}

TEST(TissueJson, RefusesWhatIsNotARegularFile)
{
    test::expect_special_files_refused<ModelFileError>("tissue", [](const std::filesystem::path& p) { read_tissue_model(p); });
}

}  // namespace
}  // namespace echosim::tissue

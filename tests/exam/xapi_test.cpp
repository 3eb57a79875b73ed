// The xAPI export: the statements' required parts (id, actor, verb, object), ADL's verbs, scaled
// scores in [-1, 1], ISO 8601 durations, and ids that a second export repeats and another
// database does not; and the UUIDs under them against RFC 4122's and Python's uuid module's values.
#include <filesystem>
#include <regex>
#include <set>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "exam/uuid.hpp"
#include "exam/xapi.hpp"
#include "report_fixture.hpp"
#include "test_files.hpp"

namespace echosim::exam {
namespace {

std::string hex(const std::array<std::uint8_t, 20>& h)
{
    static constexpr char k[] = "0123456789abcdef";
    std::string s;
    for (auto b : h) s += k[b >> 4], s += k[b & 15];
    return s;
}

TEST(Uuid, Sha1AndVersion5MatchPublishedValues)
{
    // FIPS 180-2's examples
    EXPECT_EQ(hex(sha1("abc")), "a9993e364706816aba3e25717850c26c9cd0d89d");
    EXPECT_EQ(hex(sha1("")), "da39a3ee5e6b4b0d3255bfef95601890afd80709");
    EXPECT_EQ(hex(sha1("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq")), "84983e441c3bd26ebaae4aa1f95129e5e54670f1");
    EXPECT_EQ(hex(sha1(std::string(1000, 'a'))), "291e9a6c66994949b57ba5e650361e98fc36b1ba");  // hashlib
    // Python: uuid.uuid5(uuid.NAMESPACE_DNS, 'python.org'), uuid.uuid5(uuid.NAMESPACE_URL, 'https://echosim.org/xapi')
    const Uuid dns = *parse_uuid("6ba7b810-9dad-11d1-80b4-00c04fd430c8");
    EXPECT_EQ(uuid_text(uuid_v5(dns, "python.org")), "886313e1-3b8a-5372-9b90-0c9aee199e5d");
    EXPECT_EQ(uuid_text(uuid_v5(kUuidNamespaceUrl, "https://echosim.org/xapi")), "2d6bb236-b575-5ca0-b57a-105b603fbf15");
    const std::string random = uuid_text(uuid_v4_random());
    EXPECT_TRUE(std::regex_match(random, std::regex("[0-9a-f]{8}-[0-9a-f]{4}-4[0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}"))) << random;
    EXPECT_NE(random, uuid_text(uuid_v4_random()));
    EXPECT_FALSE(parse_uuid("6ba7b810-9dad-11d1-80b4-00c04fd430c"));
    EXPECT_FALSE(parse_uuid("6ba7b810x9dad-11d1-80b4-00c04fd430c8"));
}

TEST(Xapi, DurationsAndIris)
{
    EXPECT_EQ(iso8601_duration(0), "PT0S");
    EXPECT_EQ(iso8601_duration(16), "PT16S");
    EXPECT_EQ(iso8601_duration(3.4), "PT3.4S");
    EXPECT_EQ(iso8601_duration(3723.456), "PT1H2M3.46S");
    EXPECT_EQ(iso8601_duration(59.999), "PT1M0S");
    EXPECT_EQ(iso8601_duration(-1), "");
    EXPECT_EQ(percent_encode("FV 6 cm/é"), "FV%206%20cm%2F%C3%A9");
}

class XapiExport : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir_ = echosim::test::temp_path("xapi", "db");
        std::filesystem::remove_all(dir_);
    }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::filesystem::path dir_;
};

TEST_F(XapiExport, StatementsCarryTheRequiredPartsAndStableIds)
{
    Records records(dir_ / "a.sqlite");
    ExamReport passed = test::make_report();
    passed.passed = true;
    passed.score = 1.7;  // out of range: scaled is clamped into [-1, 1]
    passed.started_utc = "2026-11-27T09:00:00Z";
    records.store(test::make_report());
    records.store(passed);
    const std::string text = xapi_statements(records, std::nullopt);
    EXPECT_EQ(xapi_statements(records, std::nullopt), text);  // exported again: the same ids, the same text
    const nlohmann::json all = nlohmann::json::parse(text);
    ASSERT_TRUE(all.is_array());
    ASSERT_EQ(all.size(), 2u * (1 + 4));  // one per exam, one per station

    const std::regex uuid5("[0-9a-f]{8}-[0-9a-f]{4}-5[0-9a-f]{3}-[89ab][0-9a-f]{3}-[0-9a-f]{12}");
    const std::set<std::string> verbs{"passed", "failed", "answered", "attempted"};
    std::set<std::string> ids;
    for (const auto& st : all) {
        const std::string id = st.at("id");
        EXPECT_TRUE(std::regex_match(id, uuid5)) << id;
        ids.insert(id);
        EXPECT_EQ(st.at("actor").at("objectType"), "Agent");
        EXPECT_EQ(st.at("actor").at("account").at("homePage"), "https://echosim.org");
        EXPECT_EQ(st.at("actor").at("account").at("name"), "Ada Lovelace");
        EXPECT_FALSE(st.at("actor").contains("mbox"));
        const std::string verb = st.at("verb").at("id");
        ASSERT_EQ(verb.rfind("http://adlnet.gov/expapi/verbs/", 0), 0u) << verb;
        EXPECT_TRUE(verbs.count(verb.substr(31))) << verb;
        EXPECT_EQ(st.at("verb").at("display").at("en-US"), verb.substr(31));
        EXPECT_EQ(st.at("object").at("objectType"), "Activity");
        EXPECT_EQ(st.at("object").at("id").get<std::string>().rfind("https://echosim.org/xapi/cases/fv-isolated-acute", 0), 0u);
        EXPECT_EQ(st.at("context").at("extensions").at("https://echosim.org/xapi/extensions/protocol"), "extended");
        EXPECT_TRUE(std::regex_match(st.at("context").at("registration").get<std::string>(), uuid5));
        EXPECT_TRUE(st.at("result").at("success").is_boolean());
        if (st.at("result").contains("score")) {
            const double scaled = st.at("result").at("score").at("scaled");
            EXPECT_GE(scaled, -1.0);
            EXPECT_LE(scaled, 1.0);
        }
    }
    EXPECT_EQ(ids.size(), all.size());  // no id twice

    const auto& first = all.at(0);
    EXPECT_EQ(first.at("verb").at("id"), "http://adlnet.gov/expapi/verbs/failed");
    EXPECT_DOUBLE_EQ(first.at("result").at("score").at("scaled").get<double>(), 0.625);
    EXPECT_EQ(first.at("result").at("duration"), "PT16S");
    EXPECT_EQ(first.at("result").at("completion"), true);
    EXPECT_EQ(first.at("object").at("definition").at("name").at("en-US"), "Isolated acute clot of the femoral vein");
    const auto& cfv = all.at(1);
    EXPECT_EQ(cfv.at("verb").at("id"), "http://adlnet.gov/expapi/verbs/answered");
    EXPECT_EQ(cfv.at("object").at("id"), "https://echosim.org/xapi/cases/fv-isolated-acute/stations/CFV");
    EXPECT_EQ(cfv.at("result").at("response"), "compressible");
    EXPECT_EQ(cfv.at("result").at("success"), true);
    EXPECT_EQ(cfv.at("context").at("contextActivities").at("parent").at(0).at("id"), "https://echosim.org/xapi/cases/fv-isolated-acute");
    EXPECT_EQ(cfv.at("context").at("registration"), first.at("context").at("registration"));
    EXPECT_EQ(all.at(3).at("verb").at("id"), "http://adlnet.gov/expapi/verbs/attempted");  // FV 2 cm: skipped, no call
    EXPECT_EQ(all.at(3).at("object").at("id"), "https://echosim.org/xapi/cases/fv-isolated-acute/stations/FV%202%20cm");
    EXPECT_EQ(all.at(3).at("result").at("success"), false);
    EXPECT_EQ(all.at(4).at("object").at("definition").at("correctResponsesPattern").at(0), "not-compressible");
    const auto& second = all.at(5);
    EXPECT_EQ(second.at("verb").at("id"), "http://adlnet.gov/expapi/verbs/passed");
    EXPECT_DOUBLE_EQ(second.at("result").at("score").at("scaled").get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(second.at("result").at("score").at("raw").get<double>(), 100.0);
    EXPECT_EQ(second.at("timestamp"), "2026-11-27T09:00:00Z");

    // one trainee's only
    EXPECT_EQ(nlohmann::json::parse(xapi_statements(records, std::string("Nobody"))).size(), 0u);
    // another database with the same exam: its own ids, so a store holding both keeps both
    Records other(dir_ / "b.sqlite");
    other.store(test::make_report());
    const nlohmann::json theirs = nlohmann::json::parse(xapi_statements(other, std::nullopt));
    EXPECT_NE(theirs.at(0).at("id"), first.at("id"));
    // reopened, the same database: the same ids
    const Records again(dir_ / "a.sqlite", {.create = false});
    EXPECT_EQ(xapi_statements(again, std::nullopt), text);
}

}  // namespace
}  // namespace echosim::exam

// The exam's report files: report.json byte-stable and read back against the report given,
// report.html self-contained with every injected string escaped and the images embedded, and
// summary.png carrying the stations' images.
#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "exam/report_html.hpp"
#include "exam/report_json.hpp"
#include "exam/report_text.hpp"
#include "exam/report_writer.hpp"
#include "exam/report_svg.hpp"
#include "exam/station_sheet.hpp"
#include "exam/station_status.hpp"
#include "io/png.hpp"
#include "report_fixture.hpp"
#include "test_files.hpp"

namespace echosim::exam {
namespace {

using echosim::test::read_bytes;
using echosim::test::temp_path;
using test::make_report;
using test::write_station_images;

std::filesystem::path fresh_dir(const std::string& name)
{
    const auto dir = temp_path("report", name);
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

std::string lower(std::string s)
{
    for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

TEST(ReportText, Base64MatchesRfc4648Vectors)
{
    const auto b64 = [](const std::string& s) {
        return base64({reinterpret_cast<const std::uint8_t*>(s.data()), s.size()});
    };
    EXPECT_EQ(b64(""), "");
    EXPECT_EQ(b64("f"), "Zg==");
    EXPECT_EQ(b64("fo"), "Zm8=");
    EXPECT_EQ(b64("foo"), "Zm9v");
    EXPECT_EQ(b64("foob"), "Zm9vYg==");
    EXPECT_EQ(b64("fooba"), "Zm9vYmE=");
    EXPECT_EQ(b64("foobar"), "Zm9vYmFy");
}

TEST(ReportText, FixedAndEscapes)
{
    EXPECT_EQ(fixed(12.345, 1), "12.3");
    EXPECT_EQ(fixed(-0.0001, 2), "0.00");
    EXPECT_EQ(fixed(2.5, 0), "3");  // half away from zero, as std::round
    EXPECT_EQ(fixed(std::nan(""), 2), "-");
    EXPECT_EQ(html_escape("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
    // a Latin-1 byte, a cut 3-byte character, a surrogate: each one U+FFFD; good UTF-8 kept
    EXPECT_EQ(valid_utf8("caf\xE9"), "caf\xEF\xBF\xBD");
    EXPECT_EQ(valid_utf8("\xE2\x82"), "\xEF\xBF\xBD\xEF\xBF\xBD");
    EXPECT_EQ(valid_utf8("\xED\xA0\x80"), "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD");
    EXPECT_EQ(valid_utf8("\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80"), "\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80");
    EXPECT_EQ(html_escape(std::string("a\x01" "b", 3)), "a\xEF\xBF\xBD" "b");
}

TEST(ReportWriter, SameReportTwiceGivesIdenticalBytes)
{
    const ExamReport report = make_report();
    const auto a = fresh_dir("stable_a"), b = fresh_dir("stable_b");
    write_station_images(a);
    write_station_images(b);
    write_report(report, a);
    write_report(report, b);
    for (const char* name : {kReportJson, kReportHtml, kReportSummaryPng}) {
        const std::string first = read_bytes(a / name);
        EXPECT_GT(first.size(), 100u) << name;
        EXPECT_TRUE(first == read_bytes(b / name)) << name << " differs between two writes of one report";
    }
    // again into the same folder: the same bytes, and nothing left beside the files (no temporaries)
    const std::string json = read_bytes(a / kReportJson);
    write_report(report, a);
    EXPECT_EQ(read_bytes(a / kReportJson), json);
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(a)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"report.html", "report.json", "stations", "summary.png"}));
    std::filesystem::remove_all(a);
    std::filesystem::remove_all(b);
}

TEST(ReportWriter, JsonReadsBackAsTheReportGiven)
{
    const ExamReport r = make_report();
    const nlohmann::json j = nlohmann::json::parse(report_json(r));
    EXPECT_EQ(j.at("trainee"), r.trainee);
    EXPECT_EQ(j.at("case_id"), r.case_id);
    EXPECT_EQ(j.at("case_title"), r.case_title);
    EXPECT_EQ(j.at("protocol"), r.protocol);
    EXPECT_EQ(j.at("started_utc"), "");
    EXPECT_DOUBLE_EQ(j.at("score").get<double>(), 0.625);
    EXPECT_DOUBLE_EQ(j.at("pass_mark").get<double>(), 0.8);
    EXPECT_EQ(j.at("passed"), false);
    EXPECT_EQ(j.at("dvt_present"), true);
    EXPECT_EQ(j.at("conclusion"), r.conclusion);
    EXPECT_DOUBLE_EQ(j.at("adequate_force_N").get<double>(), 9.0);
    ASSERT_EQ(j.at("stations").size(), 4u);
    const auto& cfv = j.at("stations").at(0);
    EXPECT_EQ(cfv.at("name"), "CFV");
    EXPECT_EQ(cfv.at("segment"), "cfv");
    EXPECT_EQ(cfv.at("status"), "covered");
    EXPECT_DOUBLE_EQ(cfv.at("offset_mm").get<double>(), 1.23);        // 1.234 at 2 decimals
    EXPECT_DOUBLE_EQ(cfv.at("peak_force_N").get<double>(), 14.25);
    EXPECT_DOUBLE_EQ(cfv.at("lumen_pressed_mm2").get<double>(), 2.125);
    EXPECT_DOUBLE_EQ(cfv.at("collapse_ratio").get<double>(), 0.0223);  // 0.02225 at 4 decimals
    EXPECT_EQ(cfv.at("call"), "compressible");
    EXPECT_EQ(cfv.at("image_png"), "stations/cfv.png");
    EXPECT_EQ(j.at("stations").at(1).at("status"), "wrong");
    EXPECT_EQ(j.at("stations").at(1).at("call"), "not-compressible");
    EXPECT_EQ(j.at("stations").at(2).at("status"), "skipped");
    EXPECT_EQ(j.at("stations").at(2).at("reached"), false);
    EXPECT_EQ(j.at("stations").at(3).at("thrombosed"), true);
    EXPECT_EQ(j.at("stations").at(3).at("status"), "covered");
    ASSERT_EQ(j.at("errors").size(), 3u);
    EXPECT_EQ(j.at("errors").at(0).at("kind"), "too-little-pressure");
    EXPECT_EQ(j.at("errors").at(0).at("station"), "SFJ");
    EXPECT_EQ(j.at("errors").at(2).at("kind"), "skipped-station");
    EXPECT_DOUBLE_EQ(j.at("motion").at("path_mm").get<double>(), 312.5);
    EXPECT_DOUBLE_EQ(j.at("osaus").at("interpretation").get<double>(), 2.5);
    // keys in the written order, not sorted: the file opens with what it is
    const std::string text = report_json(r);
    EXPECT_LT(text.find("\"format\""), text.find("\"trainee\""));
    EXPECT_LT(text.find("\"trainee\""), text.find("\"stations\""));
}

TEST(ReportWriter, JsonParsesBackIntoTheSameReport)
{
    const ExamReport r = make_report();
    const std::string text = report_json(r);
    const ExamReport back = parse_report_json(text, "r.json");
    EXPECT_EQ(report_json(back), text);  // every field written came back (at the decimals written)
    EXPECT_EQ(back.stations.at(1).call, Call::not_compressible);
    EXPECT_EQ(back.errors.at(1).kind, ErrorKind::wrong_call);
    EXPECT_DOUBLE_EQ(back.stations.at(0).collapse_ratio, 0.0223);
    // a field missing, of the wrong type, or an unknown name: refused naming the file and the field
    const auto refused = [&](const std::string& broken, const char* field) {
        try {
            parse_report_json(broken, "r.json");
            ADD_FAILURE() << "accepted without " << field;
        } catch (const ReportError& e) {
            EXPECT_NE(std::string(e.what()).find(std::string("r.json: field '") + field + "'"), std::string::npos) << e.what();
        }
    };
    using echosim::test::with;
    refused(with(text, "\"case_title\": \"Isolated acute clot of the femoral vein\",", ""), "/case_title");
    refused(with(text, "\"call\": \"not-compressible\",\n      \"call_correct\": false", "\"call\": \"maybe\",\n      \"call_correct\": false"),
            "/stations/1/call");
    refused(with(text, "\"kind\": \"wrong-call\"", "\"kind\": 3"), "/errors/1/kind");
    refused(with(text, "\"format\": \"echosim-exam-report\"", "\"format\": \"other\""), "/format");
    EXPECT_THROW(parse_report_json("[1, 2", "r.json"), ReportError);
}

TEST(ReportWriter, InjectedStringsAreEscapedInHtmlAndKeptInJson)
{
    ExamReport r = make_report();
    r.trainee = "<script>alert('trainee')</script>";
    r.case_title = "\"><img src=x onerror=alert(1)>";
    r.case_id = "</style><script>x</script>";
    r.stations[0].name = "</svg><script>alert(2)</script>";
    r.errors[0].detail = "a & b <b>bold</b>";
    r.errors[0].station = r.stations[0].name;
    r.conclusion = "<iframe src=//evil>";
    const auto dir = fresh_dir("escape");
    write_station_images(dir);
    write_report(r, dir);
    const std::string html = read_bytes(dir / kReportHtml);
    const std::string l = lower(html);
    EXPECT_EQ(l.find("<script"), std::string::npos);
    EXPECT_EQ(l.find("<iframe"), std::string::npos);
    EXPECT_EQ(l.find("<img src=x"), std::string::npos);
    EXPECT_NE(html.find("&lt;script&gt;alert(&#39;trainee&#39;)&lt;/script&gt;"), std::string::npos);
    EXPECT_NE(html.find("&quot;&gt;&lt;img src=x onerror=alert(1)&gt;"), std::string::npos);
    EXPECT_NE(html.find("a &amp; b &lt;b&gt;bold&lt;/b&gt;"), std::string::npos);
    // every <svg> opened is closed by our own tags: the station's "</svg>" did not end one early
    std::size_t opened = 0, closed = 0;
    for (std::size_t at = 0; (at = html.find("<svg", at)) != std::string::npos; ++at) ++opened;
    for (std::size_t at = 0; (at = html.find("</svg>", at)) != std::string::npos; ++at) ++closed;
    EXPECT_EQ(opened, 2u);
    EXPECT_EQ(closed, 2u);
    // no script may run nor anything load even if a string slipped through
    EXPECT_NE(html.find("Content-Security-Policy\" content=\"default-src 'none'; img-src data:"), std::string::npos);

    // the JSON keeps the strings as they are
    const nlohmann::json j = nlohmann::json::parse(read_bytes(dir / kReportJson));
    EXPECT_EQ(j.at("trainee"), r.trainee);
    EXPECT_EQ(j.at("case_title"), r.case_title);
    EXPECT_EQ(j.at("stations").at(0).at("name"), r.stations[0].name);
    std::filesystem::remove_all(dir);
}

TEST(ReportWriter, BytesThatAreNotUtf8BecomeReplacementCharacters)
{
    ExamReport r = make_report();
    r.trainee = "Jos\xE9 \xFF";  // Latin-1 e-acute and a byte no UTF-8 has
    const nlohmann::json j = nlohmann::json::parse(report_json(r));  // throws on bad UTF-8
    EXPECT_EQ(j.at("trainee"), "Jos\xEF\xBF\xBD \xEF\xBF\xBD");
    const std::string html = report_html(r, ".");
    EXPECT_NE(html.find("Jos\xEF\xBF\xBD \xEF\xBF\xBD"), std::string::npos);
    EXPECT_EQ(valid_utf8(html), html);
}

TEST(ReportWriter, HtmlEmbedsTheStationImagesAndNamesThoseItCannot)
{
    ExamReport r = make_report();
    const auto dir = fresh_dir("images");
    write_station_images(dir);
    r.stations[2].image_png = "stations/missing.png";
    const auto outside = dir.parent_path() / (dir.filename().string() + "_outside.png");
    test::write_solid_png(outside, 1, 2, 3);
    r.stations[3].image_png = "../" + outside.filename().string();  // leaves the folder: refused
    write_report(r, dir);
    const std::string html = read_bytes(dir / kReportHtml);
    const std::string cfv = read_bytes(dir / "stations/cfv.png"), sfj = read_bytes(dir / "stations/sfj.png");
    const auto bytes = [](const std::string& s) { return std::span(reinterpret_cast<const std::uint8_t*>(s.data()), s.size()); };
    EXPECT_NE(html.find("src=\"data:image/png;base64," + base64(bytes(cfv)) + "\""), std::string::npos);
    EXPECT_NE(html.find("src=\"data:image/png;base64," + base64(bytes(sfj)) + "\""), std::string::npos);
    EXPECT_EQ(html.find(base64(bytes(read_bytes(outside)))), std::string::npos);
    EXPECT_NE(html.find("stations/missing.png: not found"), std::string::npos);
    EXPECT_NE(html.find("the name leaves the report&#39;s folder"), std::string::npos);
    // nothing fetched: every src is a data: URI, no http(s) reference but the SVG namespace
    for (std::size_t at = 0; (at = html.find("src=\"", at)) != std::string::npos; ++at)
        EXPECT_EQ(html.compare(at + 5, 5, "data:"), 0) << html.substr(at, 40);
    std::string rest = html;
    for (std::size_t at; (at = rest.find("http://www.w3.org/2000/svg")) != std::string::npos;) rest.erase(at, 26);
    EXPECT_EQ(rest.find("http:"), std::string::npos);
    EXPECT_EQ(rest.find("https:"), std::string::npos);
    std::filesystem::remove_all(dir);
    std::filesystem::remove(outside);
}

TEST(ReportWriter, SummaryPngShowsTheStationImages)
{
    const ExamReport r = make_report();
    const auto dir = fresh_dir("summary");
    write_station_images(dir);
    write_report(r, dir);
    const io::RgbaImage png = io::read_png(dir / kReportSummaryPng);
    EXPECT_EQ(png.width, 1600u);
    EXPECT_GT(png.height, 800u);
    // each station image is a solid colour no other part of the page uses: its thumbnail's pixels
    // are there, at least a 100 x 60 block of them
    const auto count = [&](std::uint8_t cr, std::uint8_t cg, std::uint8_t cb) {
        std::size_t n = 0;
        for (std::size_t i = 0; i < png.pixels.size(); i += 4)
            n += png.pixels[i] == cr && png.pixels[i + 1] == cg && png.pixels[i + 2] == cb;
        return n;
    };
    EXPECT_GT(count(255, 0, 255), 6000u);
    EXPECT_GT(count(0, 255, 255), 6000u);
    EXPECT_GT(count(255, 255, 0), 6000u);
    std::filesystem::remove_all(dir);
}

// The sheet of station images as the trainer's report screen asks for it: into a 600 x 200 area,
// the three images of make_report (160 x 120, solid magenta, cyan, yellow; the station without an
// image left out) in one row, each as wide as a third of the area allows, its aspect kept, framed in its station's status colour (CFV and FV 6 cm covered, green; the SFJ
// pressed too little, red).
TEST(StationSheet, FitsItsAreaAndFramesEachStationInItsStatus)
{
    const ExamReport r = make_report();
    const auto dir = fresh_dir("sheet");
    write_station_images(dir);
    SheetStyle style;
    style.width = 600;
    style.max_height = 200;
    style.thumb_width = 400;
    style.caption_scale = 1;
    style.status_frames = true;
    const io::RgbaImage sheet = station_sheet(r, dir, style);
    ASSERT_EQ(sheet.width, 600u);
    ASSERT_GT(sheet.height, 0u);
    EXPECT_LE(sheet.height, 200u);
    // each colour's block: its bounding box, its pixels all of it
    const auto block_in = [](const io::RgbaImage& img, std::uint8_t cr, std::uint8_t cg, std::uint8_t cb) {
        std::uint32_t x0 = img.width, y0 = img.height, x1 = 0, y1 = 0, n = 0;
        for (std::uint32_t y = 0; y < img.height; ++y)
            for (std::uint32_t x = 0; x < img.width; ++x)
                if (const std::uint8_t* p = img.at(x, y); p[0] == cr && p[1] == cg && p[2] == cb) {
                    x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x + 1), y1 = std::max(y1, y + 1), ++n;
                }
        return std::array<std::uint32_t, 5>{x0, y0, x1, y1, n};
    };
    const auto block = [&](std::uint8_t cr, std::uint8_t cg, std::uint8_t cb) { return block_in(sheet, cr, cg, cb); };
    const auto magenta = block(255, 0, 255), cyan = block(0, 255, 255), yellow = block(255, 255, 0);
    for (const auto& b : {magenta, cyan, yellow}) {
        const std::uint32_t w = b[2] - b[0], h = b[3] - b[1];
        EXPECT_EQ(b[4], w * h) << "a solid block";
        EXPECT_NEAR(double(w) / h, 160.0 / 120.0, 0.02);
        // as large as fits: three abreast in 600 px less two 16 px gaps and the 3 px frames
        // (187 px; 140 tall, within the 200 px less a caption)
        EXPECT_GE(w, 186u);
        EXPECT_LE(w, 188u);
        EXPECT_EQ(b[1], magenta[1]) << "one row";
    }
    EXPECT_LT(magenta[2], cyan[0]);
    EXPECT_LT(cyan[2], yellow[0]);
    // the frames: green round the CFV's and FV 6 cm's, red round the SFJ's
    const io::Rgba green = status_rgba(StationStatus::covered), red = status_rgba(StationStatus::wrong);
    const auto at = [&](std::uint32_t x, std::uint32_t y, io::Rgba c) {
        const std::uint8_t* p = sheet.at(x, y);
        return p[0] == c.r && p[1] == c.g && p[2] == c.b;
    };
    EXPECT_TRUE(at(magenta[0] - 1, magenta[1] + 10, green));
    EXPECT_TRUE(at(cyan[0] - 1, cyan[1] + 10, red));
    EXPECT_TRUE(at(yellow[2], yellow[1] + 10, green));
    // no area: as the PNG summary lays them, 296 px wide (five a row), as tall as their aspect makes them
    const io::RgbaImage page = station_sheet(r, dir, SheetStyle{});
    EXPECT_EQ(page.width, std::uint32_t(SheetStyle{}.width));
    const auto wide = block_in(page, 255, 0, 255);
    EXPECT_EQ(wide[2] - wide[0], 296u);
    EXPECT_EQ(wide[3] - wide[1], 222u);  // 296 x 120 / 160
    std::filesystem::remove_all(dir);
}

TEST(ReportWriter, AFolderThatCannotBeMadeIsNamed)
{
    const auto file = temp_path("report", "a_file");
    echosim::test::write_bytes(file, "x");
    try {
        write_report(make_report(), file / "report");
        ADD_FAILURE() << "wrote a report under a regular file";
    } catch (const ReportError& e) {
        EXPECT_NE(std::string(e.what()).find((file / "report").string()), std::string::npos) << e.what();
    }
    std::filesystem::remove(file);
}

TEST(StationStatus, TypesAndSuccess)
{
    EXPECT_EQ(station_type("CFV", "cfv"), "cfv");
    EXPECT_EQ(station_type("FV 6 cm", "fv"), "fv");
    EXPECT_EQ(station_type("  Popliteal (knee)", "popliteal"), "popliteal");
    EXPECT_EQ(station_type("SFJ", "gsv"), "sfj");
    EXPECT_EQ(station_type("", "dfv"), "dfv");
    const ExamReport r = make_report();
    EXPECT_TRUE(station_success(r, 0));
    EXPECT_FALSE(adequately_pressed(r, 1));  // too little pressure flagged at the SFJ
    EXPECT_FALSE(station_success(r, 1));
    EXPECT_FALSE(station_success(r, 2));  // skipped
    EXPECT_TRUE(station_success(r, 3));
}

}  // namespace
}  // namespace echosim::exam

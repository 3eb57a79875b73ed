#include "io/plus_config.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <utility>
#include <string_view>
#include <system_error>

#include <tinyxml2.h>

#include "core/parse_number.hpp"
#include "io/text_fields.hpp"
#include "io/transform_repository.hpp"

namespace echosim::io {
namespace {

using text::quote_text;
using text::split_whitespace;
using text::upper;

// [bytes] PLUS's own configurations are 5 to 60 KiB; a megabyte is room for a hundred devices. The
// parsed document costs tinyxml2 about 40 times the text at worst (a file of empty elements: one
// node, 100-odd bytes, for every 3 bytes); at 64 MiB that was 4.8 GB (issue 34).
constexpr std::uintmax_t max_config_bytes = std::uintmax_t(1) << 20;

// Where a message points: "FILE:LINE: Element: Attribute: why".
struct Place {
    const std::filesystem::path& path;
    const tinyxml2::XMLElement& element;

    std::string at(std::string_view attribute = {}) const
    {
        // an element's name is the file's text: tinyxml2 takes any byte of 0x80 and above in it
        std::string s = path.string() + ":" + std::to_string(element.GetLineNum()) + ": " + printable(element.Name());
        if (!attribute.empty()) s += ": " + std::string(attribute);
        return s;
    }
    [[noreturn]] void fail(std::string_view attribute, const std::string& why) const { throw PlusConfigError(at(attribute) + ": " + why); }
};

template <class T>
std::vector<T> numbers(const Place& place, std::string_view attribute, std::string_view text, std::size_t count)
{
    std::string flat(text);  // an attribute may span lines, as PLUS writes its matrices
    std::replace_if(flat.begin(), flat.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
    const auto tokens = split_whitespace(flat);
    if (tokens.size() != count)
        place.fail(attribute, quote_text(text) + ": expected " + std::to_string(count) + " numbers, found " + std::to_string(tokens.size()));
    std::vector<T> out(count);
    for (std::size_t i = 0; i < count; ++i) {
        if (!parse_number(tokens[i], out[i])) place.fail(attribute, quote_text(tokens[i]) + " is not a number");
        if constexpr (std::is_floating_point_v<T>)
            if (!std::isfinite(out[i])) place.fail(attribute, quote_text(tokens[i]) + " is not finite");
    }
    return out;
}

bool on_off(const Place& place, std::string_view attribute, std::string_view text)
{
    const std::string s = upper(text);
    if (s == "ON" || s == "TRUE") return true;
    if (s == "OFF" || s == "FALSE") return false;
    place.fail(attribute, quote_text(text) + " is neither ON nor OFF");
}

PlusConfigTransform read_transform(const Place& place)
{
    PlusConfigTransform t;
    t.line = place.element.GetLineNum();
    const char* from = place.element.Attribute("From");
    const char* to = place.element.Attribute("To");
    const char* matrix = place.element.Attribute("Matrix");
    if (!from || !*from) place.fail("From", "missing");
    if (!to || !*to) place.fail("To", "missing");
    if (!matrix) place.fail("Matrix", "missing");
    t.from = from;
    t.to = to;
    if (const char* valid = place.element.Attribute("Valid")) t.valid = upper(valid) != "FALSE";  // as PLUS reads it
    if (t.from == t.to) place.fail("To", "the same frame as From (" + t.from + ")");
    const auto m = numbers<double>(place, "Matrix", matrix, 16);
    for (int i = 0; i < 16; ++i) t.matrix[i % 4][i / 4] = m[std::size_t(i)];  // the file row by row, glm column-major
    if (!is_affine(t.matrix))
        place.fail("Matrix", "the last row is not 0 0 0 1: not an affine transform");
    return t;
}

PlusReconstructionSettings read_reconstruction(const Place& place, std::vector<std::string>& warnings)
{
    PlusReconstructionSettings s;
    s.line = place.element.GetLineNum();
    const auto warn = [&](std::string_view attribute, const std::string& why) { warnings.push_back(place.at(attribute) + ": " + why); };
    const auto ignored = [&](std::string_view attribute, std::string_view value, const char* why) {
        warn(attribute, quote_text(value) + " is not supported by echosim and is ignored: " + why);
    };

    std::optional<bool> compounding_on, calculation_maximum;
    using Handler = std::function<void(std::string_view name, std::string_view value)>;
    const std::vector<std::pair<std::string_view, Handler>> handlers = {
        {"OutputSpacing", [&](auto n, auto v) {
             const auto x = numbers<double>(place, n, v, 3);
             for (double d : x)
                 if (!(d > 0)) place.fail(n, quote_text(v) + ": the spacing must be positive [mm]");
             s.output_spacing = glm::dvec3(x[0], x[1], x[2]);
         }},
        {"OutputOrigin", [&](auto n, auto v) {
             const auto x = numbers<double>(place, n, v, 3);
             s.output_origin = glm::dvec3(x[0], x[1], x[2]);
         }},
        {"OutputExtent", [&](auto n, auto v) {
             const auto x = numbers<int>(place, n, v, 6);
             for (int a = 0; a < 3; ++a)
                 if (x[std::size_t(2 * a + 1)] < x[std::size_t(2 * a)])
                     place.fail(n, quote_text(v) + ": axis " + std::to_string(a) + " ends before it starts");
             s.output_extent = std::array<int, 6>{x[0], x[1], x[2], x[3], x[4], x[5]};
         }},
        {"ClipRectangleOrigin", [&](auto n, auto v) {
             const auto x = numbers<int>(place, n, v, 2);
             if (x[0] < 0 || x[1] < 0) place.fail(n, quote_text(v) + ": a negative pixel position");
             s.clip_origin = std::array<int, 2>{x[0], x[1]};
         }},
        {"ClipRectangleSize", [&](auto n, auto v) {
             const auto x = numbers<int>(place, n, v, 2);
             if (x[0] < 0 || x[1] < 0) place.fail(n, quote_text(v) + ": a negative size");
             s.clip_size = std::array<int, 2>{x[0], x[1]};
         }},
        {"Interpolation", [&](auto n, auto v) {
             const std::string u = upper(v);
             if (u == "NEAREST_NEIGHBOR") s.interpolation = PlusInterpolation::nearest_neighbor;
             else if (u == "LINEAR") s.interpolation = PlusInterpolation::linear;
             else place.fail(n, quote_text(v) + " is not NEAREST_NEIGHBOR or LINEAR");
         }},
        {"CompoundingMode", [&](auto n, auto v) {
             const std::string u = upper(v);
             if (u == "MEAN") s.compounding = PlusCompounding::mean;
             else if (u == "MAXIMUM") s.compounding = PlusCompounding::maximum;
             else if (u == "LATEST") s.compounding = PlusCompounding::latest;
             else if (u == "IMPORTANCE_MASK")
                 place.fail(n, "IMPORTANCE_MASK is not supported by echosim (it needs PLUS's importance mask image): use MEAN, MAXIMUM or LATEST");
             else place.fail(n, quote_text(v) + " is not MEAN, MAXIMUM or LATEST");
         }},
        // the attributes of PLUS versions before 2.2, still found in shipped configurations
        {"Compounding", [&](auto n, auto v) { compounding_on = on_off(place, n, v); }},
        {"Calculation", [&](auto n, auto v) {
             const std::string u = upper(v);
             if (u != "WEIGHTED_AVERAGE" && u != "MAXIMUM") place.fail(n, quote_text(v) + " is not WEIGHTED_AVERAGE or MAXIMUM");
             calculation_maximum = u == "MAXIMUM";
         }},
        {"FillHoles", [&](auto n, auto v) { s.fill_holes = on_off(place, n, v); }},
        {"PixelRejectionThreshold", [&](auto n, auto v) { s.pixel_rejection_threshold = numbers<double>(place, n, v, 1)[0]; }},
        {"ImageCoordinateFrame", [&](auto n, auto v) {
             if (v.empty()) place.fail(n, "empty");
             s.image_frame = std::string(v);
         }},
        {"ReferenceCoordinateFrame", [&](auto n, auto v) {
             if (v.empty()) place.fail(n, "empty");
             s.reference_frame = std::string(v);
         }},
        // speed only: PLUS's choice of code path and threads; echosim has its own
        {"Optimization", [](auto, auto) {}},
        {"NumberOfThreads", [](auto, auto) {}},
        // what echosim does not do: said, not dropped
        {"FanAnglesDeg", [&](auto n, auto v) { ignored(n, v, "fan clipping; every pixel of the clip rectangle is pasted"); }},
        {"FanOriginPixel", [&](auto n, auto v) { ignored(n, v, "fan clipping"); }},
        {"FanOrigin", [&](auto n, auto v) { ignored(n, v, "fan clipping"); }},
        {"FanRadiusStartPixel", [&](auto n, auto v) { ignored(n, v, "fan clipping"); }},
        {"FanRadiusStopPixel", [&](auto n, auto v) { ignored(n, v, "fan clipping"); }},
        {"FanDepth", [&](auto n, auto v) { ignored(n, v, "fan clipping"); }},
        {"EnableFanAnglesAutoDetect", [&](auto n, auto v) { ignored(n, v, "fan angle detection"); }},
        {"FanAnglesAutoDetectBrightnessThreshold", [&](auto n, auto v) { ignored(n, v, "fan angle detection"); }},
        {"FanAnglesAutoDetectFilterRadiusPixel", [&](auto n, auto v) { ignored(n, v, "fan angle detection"); }},
        {"ImportanceMaskFilename", [&](auto n, auto v) { ignored(n, v, "importance-mask compounding"); }},
        {"SkipInterval", [&](auto n, auto v) { ignored(n, v, "every valid frame is pasted"); }},
    };
    for (const tinyxml2::XMLAttribute* a = place.element.FirstAttribute(); a; a = a->Next()) {
        const std::string_view name = a->Name();
        const auto h = std::find_if(handlers.begin(), handlers.end(), [&](const auto& entry) { return entry.first == name; });
        if (h == handlers.end()) warn(name, quote_text(a->Value()) + " is not an attribute echosim knows; ignored");
        else h->second(name, text::trim(a->Value()));
    }
    // CompoundingMode wins; else the old pair, read as PLUS reads it
    if (!s.compounding && (compounding_on || calculation_maximum))
        s.compounding = calculation_maximum.value_or(false) ? PlusCompounding::maximum
                        : compounding_on.value_or(true)     ? PlusCompounding::mean
                                                            : PlusCompounding::latest;
    if (s.output_origin.has_value() != s.output_extent.has_value())
        place.fail(s.output_origin ? "OutputExtent" : "OutputOrigin", "missing: OutputOrigin and OutputExtent come together");
    if (s.clip_origin.has_value() != s.clip_size.has_value())
        place.fail(s.clip_origin ? "ClipRectangleSize" : "ClipRectangleOrigin",
                   "missing: ClipRectangleOrigin and ClipRectangleSize come together");
    for (const tinyxml2::XMLElement* child = place.element.FirstChildElement(); child; child = child->NextSiblingElement()) {
        if (std::string_view(child->Name()) == "HoleFilling")
            warnings.push_back(Place{place.path, *child}.at() +
                               ": PLUS's hole-filling kernels are not used: echosim fills holes its own way (the "
                               "distance-weighted mean of filled neighbours) when FillHoles is ON");
        else
            warnings.push_back(Place{place.path, *child}.at() + ": an element echosim does not know; ignored");
    }
    return s;
}

// [attributes] PLUS's elements have at most a few dozen; tinyxml2 checks each attribute against
// those before it on the element, so 50,000 on one element took 10 s (issue 34).
constexpr std::size_t max_attributes = 256;

// [warnings] listed at most; the rest are counted
constexpr std::size_t max_warnings = 100;

// The line of the first tag with more than max_attributes attributes (counted as '=' outside quoted
// values), or 0: looked for in the text before tinyxml2 parses it. Comments, CDATA sections and
// the document type are skipped; a tag's end found by '>' outside quotes.
int tag_with_too_many_attributes(std::string_view xml)
{
    int line = 1;
    for (std::size_t i = 0; i < xml.size(); ++i) {
        if (xml[i] == '\n') ++line;
        if (xml[i] != '<') continue;
        const auto skip_to = [&](std::string_view end) {
            const std::size_t at = xml.find(end, i);
            const std::size_t stop = at == std::string_view::npos ? xml.size() : at + end.size();
            line += int(std::count(xml.begin() + std::ptrdiff_t(i), xml.begin() + std::ptrdiff_t(stop), '\n'));
            i = stop - 1;
        };
        if (xml.substr(i, 4) == "<!--") { skip_to("-->"); continue; }
        if (xml.substr(i, 9) == "<![CDATA[") { skip_to("]]>"); continue; }
        if (xml.substr(i, 2) == "<!") { skip_to(">"); continue; }
        const int tag_line = line;
        std::size_t attributes = 0;
        char quote = 0;
        for (++i; i < xml.size() && (quote || xml[i] != '>'); ++i) {
            const char c = xml[i];
            if (c == '\n') ++line;
            if (quote) quote = c == quote ? 0 : quote;
            else if (c == '"' || c == '\'') quote = c;
            else if (c == '=' && ++attributes > max_attributes) return tag_line;
        }
    }
    return 0;
}

// Every element of that name in the document, depth first.
void find_all(const tinyxml2::XMLElement* e, std::string_view name, std::vector<const tinyxml2::XMLElement*>& out)
{
    for (; e; e = e->NextSiblingElement()) {
        if (name == e->Name()) out.push_back(e);
        find_all(e->FirstChildElement(), name, out);
    }
}

}  // namespace

PlusConfig read_plus_config(const std::filesystem::path& path)
{
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (ec || !std::filesystem::exists(status)) throw PlusConfigError(path.string() + ": cannot open: no such file");
    if (!std::filesystem::is_regular_file(status)) throw PlusConfigError(path.string() + ": not a regular file");
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec || size > max_config_bytes)
        throw PlusConfigError(path.string() + ": larger than " + std::to_string(max_config_bytes >> 20) +
                              " MiB: not a PLUS device-set configuration");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw PlusConfigError(path.string() + ": cannot open: " + std::generic_category().message(errno));
    const std::string xml{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};

    if (const int line = tag_with_too_many_attributes(xml))
        throw PlusConfigError(path.string() + ":" + std::to_string(line) + ": an element with more than " +
                              std::to_string(max_attributes) + " attributes: not a PLUS device-set configuration");
    tinyxml2::XMLDocument doc;
    if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS)
        throw PlusConfigError(path.string() + ":" + std::to_string(doc.ErrorLineNum()) + ": not well-formed XML: " + doc.ErrorStr());
    const tinyxml2::XMLElement* root = doc.RootElement();
    if (!root) throw PlusConfigError(path.string() + ": no XML element in the file");
    if (std::string_view(root->Name()) != "PlusConfiguration")
        throw PlusConfigError(path.string() + ":" + std::to_string(root->GetLineNum()) + ": the root element is " + root->Name() +
                              ", not PlusConfiguration: not a PLUS device-set configuration");

    PlusConfig config;
    // the transforms given so far, either way round -> their line: a repeat found in O(log n), not by
    // looking through all before it (80,000 transforms took over a minute, issue 34)
    std::map<std::pair<std::string, std::string>, int> defined;
    std::vector<const tinyxml2::XMLElement*> found;
    find_all(root, "CoordinateDefinitions", found);
    for (const tinyxml2::XMLElement* defs : found)
        for (const tinyxml2::XMLElement* t = defs->FirstChildElement(); t; t = t->NextSiblingElement()) {
            const Place place{path, *t};
            if (std::string_view(t->Name()) != "Transform") {
                config.warnings.push_back(place.at() + ": not a Transform; ignored");
                continue;
            }
            PlusConfigTransform transform = read_transform(place);
            const auto [at, added] = defined.try_emplace(std::minmax(transform.from, transform.to), transform.line);
            if (!added)
                place.fail("From", transform.from + "To" + transform.to + " is defined already, on line " + std::to_string(at->second));
            config.transforms.push_back(std::move(transform));
        }
    found.clear();
    find_all(root, "VolumeReconstruction", found);
    if (found.size() > 1)
        Place{path, *found[1]}.fail("", "a second VolumeReconstruction element (the first is on line " +
                                             std::to_string(found[0]->GetLineNum()) + ")");
    if (!found.empty()) config.reconstruction = read_reconstruction(Place{path, *found[0]}, config.warnings);
    // a file of a quarter of a million unknown elements is not a screenful of warnings each
    if (config.warnings.size() > max_warnings) {
        const std::size_t more = config.warnings.size() - max_warnings;
        config.warnings.resize(max_warnings);
        config.warnings.push_back(path.string() + ": " + std::to_string(more) + " more warnings like these, not listed");
    }
    return config;
}

}  // namespace echosim::io

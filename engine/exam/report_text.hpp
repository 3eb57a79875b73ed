// Text for the exam's reports: strings from a case file or typed by a trainee made safe for HTML
// (and for JSON: valid UTF-8 first), numbers written the same way on every run (fixed decimals,
// locale-free), and PNG files inlined as base64. Nothing here reads or writes files.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace echosim::exam {

// `text` with every byte sequence that is not UTF-8 (a stray Latin-1 byte, a cut character, an
// overlong form, a surrogate) replaced by U+FFFD, so writers that refuse bad UTF-8 (nlohmann's
// dump) or readers that guess an encoding (a browser) never see it.
std::string valid_utf8(std::string_view text);

// `text` as HTML character data or a quoted attribute value: valid UTF-8, & < > " ' as references,
// control characters other than tab and newline as U+FFFD (HTML forbids them). A trainee named
// "<script>" is shown as that name, never run.
std::string html_escape(std::string_view text);

// `v` with exactly `decimals` digits after the point ("12.30"), the same on every machine and
// locale (std::to_chars); "-" for a value that is not finite. -0 is written as 0.
std::string fixed(double v, int decimals);

// `v` rounded to `decimals` decimal places, so a JSON writer's shortest round-trip form of it is
// short and the same on every run ("12.3", not "12.299999999999999"); non-finite values as they are.
double rounded(double v, int decimals);

// RFC 4648 base64, with padding: the body of a data: URI.
std::string base64(std::span<const std::uint8_t> bytes);

}  // namespace echosim::exam

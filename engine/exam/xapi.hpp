// The records as xAPI 1.0.3 statements (the Experience API: what skills labs' learning record
// stores import): one per exam (verb passed or failed, ADL's vocabulary, with the score scaled to
// 0..1, the success and the duration) and one per station (answered, when the trainee made a call,
// else attempted; success = reached, adequately pressed and called right). The actor is an account
// on the lab's home page named by the trainee; the object is an activity under the project's IRI
// (https://echosim.org/xapi/cases/<case id>, its stations under .../stations/<name>).
//
// Statement ids are name-based UUIDs (version 5) of the database's own id and the session's row, so
// exporting again gives the same ids and a learning record store keeps one copy of each.
#pragma once

#include <optional>
#include <string>

#include "exam/records.hpp"

namespace echosim::exam {

struct XapiOptions {
    std::string homepage = "https://echosim.org";   // the actor's account's homePage: the lab's
    std::string activity_iri = "https://echosim.org/xapi";  // the root of the activity and extension IRIs
};

// The statements of the sessions stored (of one trainee, or of all), as a JSON array text.
std::string xapi_statements(const Records& records, const std::optional<std::string>& trainee, const XapiOptions& options = {});

// An ISO 8601 duration as xAPI writes it ("PT1H2M3.45S", at most hundredths of a second); "" for a
// value that is not finite or is negative.
std::string iso8601_duration(double seconds);

// `text` percent-encoded (RFC 3986: every byte but the unreserved A-Z a-z 0-9 - . _ ~), for one
// segment of an IRI's path.
std::string percent_encode(const std::string& text);

}  // namespace echosim::exam

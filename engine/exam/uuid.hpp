// UUIDs for the records: a random one (RFC 4122 version 4) naming a database when it is made, and
// name-based ones (version 5, SHA-1) for xAPI statement ids, so exporting the same session again
// gives the same id and a learning record store keeps one copy. SHA-1 here is a name hash, as RFC
// 4122 prescribes for version 5, not a security measure.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace echosim::exam {

using Uuid = std::array<std::uint8_t, 16>;

// FIPS 180-4 SHA-1 of `data`.
std::array<std::uint8_t, 20> sha1(std::string_view data);

// RFC 4122 §4.3: the version-5 UUID of `name` in `name_space`.
Uuid uuid_v5(const Uuid& name_space, std::string_view name);

// RFC 4122 §4.4: a random UUID (std::random_device).
Uuid uuid_v4_random();

// "xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx", lower case.
std::string uuid_text(const Uuid& u);
std::optional<Uuid> parse_uuid(std::string_view text);

// RFC 4122 Appendix C: the namespace for names that are URLs.
inline constexpr Uuid kUuidNamespaceUrl = {0x6b, 0xa7, 0xb8, 0x11, 0x9d, 0xad, 0x11, 0xd1,
                                          0x80, 0xb4, 0x00, 0xc0, 0x4f, 0xd4, 0x30, 0xc8};

}  // namespace echosim::exam

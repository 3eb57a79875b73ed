#include "exam/uuid.hpp"

#include <random>

namespace echosim::exam {
namespace {

std::uint32_t rotl(std::uint32_t x, int n) { return (x << n) | (x >> (32 - n)); }

int hex_value(char c)
{
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

}  // namespace

std::array<std::uint8_t, 20> sha1(std::string_view data)
{
    std::uint32_t h[5] = {0x67452301, 0xEFCDAB89, 0x98BADCFE, 0x10325476, 0xC3D2E1F0};
    // the message padded: a 1 bit, zeros, and its length in bits as 64-bit big-endian
    std::string m(data);
    const std::uint64_t bits = std::uint64_t(data.size()) * 8;
    m += char(0x80);
    while (m.size() % 64 != 56) m += char(0);
    for (int i = 7; i >= 0; --i) m += char((bits >> (8 * i)) & 0xFF);

    for (std::size_t chunk = 0; chunk < m.size(); chunk += 64) {
        std::uint32_t w[80];
        for (int i = 0; i < 16; ++i) {
            const auto b = [&](int k) { return std::uint32_t(static_cast<unsigned char>(m[chunk + std::size_t(4 * i + k)])); };
            w[i] = (b(0) << 24) | (b(1) << 16) | (b(2) << 8) | b(3);
        }
        for (int i = 16; i < 80; ++i) w[i] = rotl(w[i - 3] ^ w[i - 8] ^ w[i - 14] ^ w[i - 16], 1);
        std::uint32_t a = h[0], b = h[1], c = h[2], d = h[3], e = h[4];
        for (int i = 0; i < 80; ++i) {
            std::uint32_t f = 0, k = 0;
            if (i < 20) f = (b & c) | (~b & d), k = 0x5A827999;
            else if (i < 40) f = b ^ c ^ d, k = 0x6ED9EBA1;
            else if (i < 60) f = (b & c) | (b & d) | (c & d), k = 0x8F1BBCDC;
            else f = b ^ c ^ d, k = 0xCA62C1D6;
            const std::uint32_t t = rotl(a, 5) + f + e + k + w[i];
            e = d, d = c, c = rotl(b, 30), b = a, a = t;
        }
        h[0] += a, h[1] += b, h[2] += c, h[3] += d, h[4] += e;
    }
    std::array<std::uint8_t, 20> out{};
    for (int i = 0; i < 20; ++i) out[std::size_t(i)] = std::uint8_t(h[i / 4] >> (24 - 8 * (i % 4)));
    return out;
}

Uuid uuid_v5(const Uuid& name_space, std::string_view name)
{
    std::string input(name_space.begin(), name_space.end());
    input.append(name);
    const auto hash = sha1(input);
    Uuid u{};
    for (std::size_t i = 0; i < 16; ++i) u[i] = hash[i];
    u[6] = std::uint8_t((u[6] & 0x0F) | 0x50);  // version 5
    u[8] = std::uint8_t((u[8] & 0x3F) | 0x80);  // the RFC 4122 variant
    return u;
}

Uuid uuid_v4_random()
{
    std::random_device rd;
    Uuid u{};
    for (std::size_t i = 0; i < 16; i += 4) {
        const std::uint32_t r = rd();
        for (std::size_t k = 0; k < 4; ++k) u[i + k] = std::uint8_t(r >> (8 * k));
    }
    u[6] = std::uint8_t((u[6] & 0x0F) | 0x40);
    u[8] = std::uint8_t((u[8] & 0x3F) | 0x80);
    return u;
}

std::string uuid_text(const Uuid& u)
{
    static constexpr char kHex[] = "0123456789abcdef";
    std::string s;
    for (std::size_t i = 0; i < 16; ++i) {
        if (i == 4 || i == 6 || i == 8 || i == 10) s += '-';
        s += kHex[u[i] >> 4];
        s += kHex[u[i] & 15];
    }
    return s;
}

std::optional<Uuid> parse_uuid(std::string_view text)
{
    if (text.size() != 36) return std::nullopt;
    Uuid u{};
    std::size_t byte = 0;
    for (std::size_t i = 0; i < 36;) {
        if (i == 8 || i == 13 || i == 18 || i == 23) {
            if (text[i] != '-') return std::nullopt;
            ++i;
            continue;
        }
        const int hi = hex_value(text[i]), lo = hex_value(text[i + 1]);
        if (hi < 0 || lo < 0) return std::nullopt;
        u[byte++] = std::uint8_t(hi * 16 + lo);
        i += 2;
    }
    return u;
}

}  // namespace echosim::exam

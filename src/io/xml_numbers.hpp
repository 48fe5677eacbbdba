// Number parsing and position helpers shared by the XML-based readers (3MF, AMF).
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>

#include <fast_float/fast_float.h>

namespace polyvol::io::xmlnum {

inline bool is_xml_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

// Strips XML white space (space, tab, CR, LF) from both ends.
inline std::string_view trim(std::string_view s) {
    while (!s.empty() && is_xml_space(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_xml_space(s.back())) s.remove_suffix(1);
    return s;
}

// A decimal number ([+-]digits[.digits][(e|E)[+-]digits], surrounding white space
// allowed) as the correctly rounded double. Anything else -- empty text,
// trailing garbage, hexadecimal, "inf", "nan", or a value beyond the double
// range -- gives nullopt. Values below the smallest subnormal round to zero,
// which is the correctly rounded result.
inline std::optional<double> parse_double(std::string_view s) {
    s = trim(s);
    if (s.empty()) return std::nullopt;
    const char* first = s.data();
    const char* const last = s.data() + s.size();
    if (*first == '+') {  // fast_float rejects a leading '+' (XML Schema allows it)
        ++first;
        if (first == last || *first == '+' || *first == '-') return std::nullopt;
    }
    double v = 0;
    const auto r = fast_float::from_chars(first, last, v, fast_float::chars_format::general);
    if (r.ec != std::errc() || r.ptr != last || !std::isfinite(v)) return std::nullopt;
    return v;
}

// A non-negative decimal integer ([+]digits, surrounding white space allowed)
// that fits in uint64_t; nullopt otherwise.
inline std::optional<uint64_t> parse_index(std::string_view s) {
    s = trim(s);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    if (s.empty() || s.front() < '0' || s.front() > '9') return std::nullopt;
    uint64_t v = 0;
    const auto r = std::from_chars(s.data(), s.data() + s.size(), v, 10);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
    return v;
}

// The 1-based line of a byte offset in text.
inline uint64_t line_at(std::span<const std::byte> text, std::size_t offset) {
    offset = std::min(offset, text.size());
    return 1 + static_cast<uint64_t>(
                   std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset),
                              std::byte{'\n'}));
}

// A value quoted in a message: at most 40 characters, control characters shown as '?'.
inline std::string quote(std::string_view v) {
    std::string out = "'";
    const std::size_t n = std::min<std::size_t>(v.size(), 40);
    for (std::size_t i = 0; i < n; ++i) {
        const auto c = static_cast<unsigned char>(v[i]);
        out += (c < 0x20 || c == 0x7f) ? '?' : static_cast<char>(c);
    }
    if (v.size() > n) out += "...";
    out += "'";
    return out;
}

}  // namespace polyvol::io::xmlnum

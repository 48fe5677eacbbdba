// Shared pieces of the text readers (STL ASCII, OBJ, OFF, PLY ASCII):
// character classes, number parsing over string_views, and a tokenizing
// cursor that counts lines. Nothing here allocates per token.
//
// Line ends: "\n", "\r\n" and a lone "\r" each end one line (so classic Mac
// files and stray carriage returns count lines the way an editor shows them).
// Blanks: space, tab, vertical tab, form feed. Any other byte, NUL included,
// is part of a token.
#pragma once

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <system_error>

#include <fast_float/fast_float.h>

#include "io/readers.hpp"

namespace polyvol::io::text {

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
inline bool is_eol(char c) { return c == '\n' || c == '\r'; }
inline bool is_space(char c) { return is_blank(c) || is_eol(c); }

inline std::string_view as_text(Bytes data) {
    return {reinterpret_cast<const char*>(data.data()), data.size()};
}

inline std::string_view trim(std::string_view s) {
    while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
    return s;
}

// ASCII case-insensitive equality; `lower` must be lower case.
inline bool iequals(std::string_view s, std::string_view lower) {
    if (s.size() != lower.size()) return false;
    if (s == lower) return true;  // the usual spelling, one comparison
    for (std::size_t i = 0; i < s.size(); ++i) {
        char c = s[i];
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
        if (c != lower[i]) return false;
    }
    return true;
}

// A whole token as a double, with the syntax C's strtod accepts for decimal
// numbers: optional sign ('+' too), digits with an optional '.', optional
// exponent (".5", "5.", "-0", "1e-5"). The result is the correctly rounded
// double (fast_float). "inf"/"nan" parse here; callers that need finite
// values check with std::isfinite. Hexadecimal floats are not accepted.
inline bool parse_double(std::string_view tok, double& out) {
    const char* first = tok.data();
    const char* last = first + tok.size();
    if (first != last && *first == '+') {
        ++first;
        if (first != last && (*first == '-' || *first == '+')) return false;
    }
    if (first == last) return false;
    const auto r = fast_float::from_chars(first, last, out);
    return r.ec == std::errc() && r.ptr == last;
}

// A whole token as a signed 64-bit integer (optional '+' or '-').
inline bool parse_int(std::string_view tok, int64_t& out) {
    const char* first = tok.data();
    const char* last = first + tok.size();
    if (first != last && *first == '+') {
        ++first;
        if (first != last && *first == '-') return false;
    }
    if (first == last) return false;
    // Fast path, same result as std::from_chars: an optional '-' and at
    // most 18 digits (which cannot overflow). Face indices are almost
    // always this.
    const bool negative = *first == '-';
    const char* digits = first + (negative ? 1 : 0);
    const auto n = last - digits;
    if (n >= 1 && n <= 18) {
        uint64_t v = 0;
        for (const char* p = digits; p < last; ++p) {
            const auto d = static_cast<unsigned>(static_cast<unsigned char>(*p)) - unsigned{'0'};
            if (d > 9) return false;
            v = 10 * v + d;
        }
        out = negative ? -static_cast<int64_t>(v) : static_cast<int64_t>(v);
        return true;
    }
    const auto r = std::from_chars(first, last, out);
    return r.ec == std::errc() && r.ptr == last;
}

// A token quoted for an error message: at most 40 characters, non-printable
// bytes as \xNN.
inline std::string quote(std::string_view tok) {
    static constexpr char hex[] = "0123456789abcdef";
    std::string s = "'";
    const std::size_t n = tok.size() < 40 ? tok.size() : 40;
    for (std::size_t i = 0; i < n; ++i) {
        const auto c = static_cast<unsigned char>(tok[i]);
        if (c >= 0x20 && c < 0x7f) {
            s += static_cast<char>(c);
        } else {
            s += "\\x";
            s += hex[c >> 4];
            s += hex[c & 15];
        }
    }
    if (tok.size() > n) s += "...";
    s += "'";
    return s;
}

// Describes what was found where something else was expected.
inline std::string found(std::string_view tok) {
    return tok.empty() ? std::string("end of file") : quote(tok);
}

// Whitespace-separated tokens with line numbers. With a comment character,
// that character starts a comment up to the end of the line (also in the
// middle of a token: "0#red" is the token "0").
class Cursor {
public:
    explicit Cursor(std::string_view text, char comment = '\0')
        : begin_(text.data()), p_(text.data()), end_(text.data() + text.size()),
          comment_(comment), has_comment_(comment != '\0'),
          comment_in_numbers_(has_comment_ && std::string_view("0123456789.eE+-").find(comment) != std::string_view::npos) {}

    // The next token, across line ends and comments; empty at the end of input.
    std::string_view next() {
        skip_space();
        return p_ == end_ ? std::string_view() : take_token();
    }

    // The next token as a finite number, parsed where it stands: one scan of
    // its characters where next() and parse_double make two. Gives what
    // next() and parse_double would (fast_float reads the longest number at
    // the token's start; the token must end right after it). False, with
    // the token left unconsumed, for anything else: no number, a leading
    // '+', a comment or other characters right after the digits, or an
    // infinite or NaN value; the caller then reads it with next() and
    // parse_double, for the same value or its error message. (Always false
    // with a comment character that can occur in a number, where next()
    // would end the token early.)
    bool next_finite_number(double& out) {
        if (comment_in_numbers_) return false;
        skip_space();
        if (p_ == end_ || *p_ == '+') return false;
        double v;
        const auto r = fast_float::from_chars(p_, end_, v);
        if (r.ec != std::errc() || (r.ptr != end_ && !is_space(*r.ptr)) || !std::isfinite(v)) return false;
        p_ = r.ptr;
        out = v;
        return true;
    }

    // The next token on the current line; empty at the end of the line (the
    // line end is not consumed).
    std::string_view next_on_line() {
        while (p_ < end_ && is_blank(*p_)) ++p_;
        if (p_ == end_ || is_eol(*p_)) return {};
        if (has_comment_ && *p_ == comment_) {
            skip_to_eol();
            return {};
        }
        return take_token();
    }

    // The rest of the current line without its comment, trimmed; the line end
    // is not consumed.
    std::string_view rest_of_line() {
        const char* s = p_;
        while (p_ < end_ && !is_eol(*p_) && !(has_comment_ && *p_ == comment_)) ++p_;
        std::string_view r(s, static_cast<std::size_t>(p_ - s));
        skip_to_eol();
        return trim(r);
    }

    // Skips to the start of the next line.
    void skip_line() {
        skip_to_eol();
        if (p_ < end_) eat_eol();
    }

    uint64_t line() const { return line_; }
    std::size_t offset() const { return static_cast<std::size_t>(p_ - begin_); }
    std::size_t remaining() const { return static_cast<std::size_t>(end_ - p_); }
    bool at_end() const { return p_ == end_; }
    std::string_view rest() const { return {p_, remaining()}; }

private:
    std::string_view take_token() {
        const char* s = p_;
        if (has_comment_) {
            while (p_ < end_ && !is_space(*p_) && *p_ != comment_) ++p_;
        } else {
            while (p_ < end_ && !is_space(*p_)) ++p_;
        }
        return {s, static_cast<std::size_t>(p_ - s)};
    }
    void skip_to_eol() {
        while (p_ < end_ && !is_eol(*p_)) ++p_;
    }
    // Blanks, line ends and comments: what comes before a token.
    void skip_space() {
        for (;;) {
            while (p_ < end_ && is_blank(*p_)) ++p_;
            if (p_ == end_) return;
            if (is_eol(*p_)) {
                eat_eol();
            } else if (has_comment_ && *p_ == comment_) {
                skip_to_eol();
            } else {
                return;
            }
        }
    }
    void eat_eol() {  // at '\n' or '\r'
        if (*p_ == '\r' && p_ + 1 < end_ && p_[1] == '\n') ++p_;
        ++p_;
        ++line_;
    }

    const char* begin_;
    const char* p_;
    const char* end_;
    uint64_t line_ = 1;
    char comment_;
    bool has_comment_;
    bool comment_in_numbers_;  // comment_ is a digit, '.', 'e', 'E', '+' or '-'
};

// The OFF header keyword [ST][C][N][4][n]OFF (Geomview's prefixes, in that
// order). Shared by the OFF reader and format detection.
struct OffKeyword {
    bool valid = false;
    bool has4 = false;   // 4: one more coordinate per vertex
    bool has_n = false;  // n: a dimension line follows
};
inline OffKeyword parse_off_keyword(std::string_view tok) {
    OffKeyword h;
    if (tok.size() < 3 || tok.substr(tok.size() - 3) != "OFF") return h;
    std::string_view p = tok.substr(0, tok.size() - 3);
    if (p.starts_with("ST")) p.remove_prefix(2);
    if (p.starts_with("C")) p.remove_prefix(1);
    if (p.starts_with("N")) p.remove_prefix(1);
    if (p.starts_with("4")) {
        h.has4 = true;
        p.remove_prefix(1);
    }
    if (p.starts_with("n")) {
        h.has_n = true;
        p.remove_prefix(1);
    }
    h.valid = p.empty();
    return h;
}

// Adds a note once.
void add_note(LoadedMesh& out, std::string note);

}  // namespace polyvol::io::text

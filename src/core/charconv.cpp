#include "core/charconv.hpp"

#include <fast_float/fast_float.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

// __cpp_lib_to_chars: the floating-point overloads are there (libstdc++ 11+).
#if defined(__cpp_lib_to_chars)
#define POLYVOL_STD_TO_CHARS 1
#endif

namespace polyvol::core {
namespace {

// x's shortest round-trip digits from printf. For each length p, the
// correctly rounded p-digit decimal is the nearest of its length; where the
// interval of decimals that read back as x is lopsided (x a power of two: its
// lower half is half as wide), the nearest may miss it while the next one up
// reads back, so both neighbours are tried too. The first length with a
// decimal that reads back is the shortest; of those, the nearest is taken
// (std::to_chars's choice).
struct Digits {
    char digits[20];
    int count;     // significant digits
    int exponent;  // x = 0.d1d2... * 10^(exponent + 1), i.e. d1 is the 10^exponent digit
    bool negative;
};

// d (count digits, exponent) as text strtod reads: "d.ddde+E".
std::string scientific_text(const Digits& d) {
    std::string t = d.negative ? "-" : "";
    t += d.digits[0];
    t += '.';
    t.append(d.digits + 1, static_cast<std::size_t>(d.count - 1));
    return t + "e" + std::to_string(d.exponent);
}

// d moved by `step` (+1 or -1) in its last digit; false when that changes its length.
bool neighbour(Digits& d, int step) {
    int i = d.count - 1;
    if (step > 0) {
        while (i >= 0 && d.digits[i] == '9') d.digits[i--] = '0';
        if (i < 0) return false;
        ++d.digits[i];
    } else {
        while (i >= 0 && d.digits[i] == '0') d.digits[i--] = '9';
        if (i < 0 || (i == 0 && d.digits[0] == '1')) return false;
        --d.digits[i];
    }
    return true;
}

Digits shortest_digits(double x) {
    Digits d{};
    d.negative = std::signbit(x);
    char buf[40];
    for (int p = 1; p <= 17; ++p) {
        std::snprintf(buf, sizeof buf, "%.*e", p - 1, x);
        const char* s = buf + (buf[0] == '-');
        int n = 0;
        for (; *s != 'e'; ++s)
            if (*s != '.') d.digits[n++] = *s;
        d.count = n;
        d.exponent = std::atoi(s + 1);
        bool found = std::strtod(buf, nullptr) == x || p == 17;
        if (!found) {
            Digits best{};
            long double gap = 0;
            for (const int step : {-1, 1}) {
                Digits c = d;
                if (!neighbour(c, step) || std::strtod(scientific_text(c).c_str(), nullptr) != x) continue;
                const long double g = std::fabs(std::strtold(scientific_text(c).c_str(), nullptr) - x);
                if (!found || g < gap) best = c, gap = g, found = true;
            }
            if (found) d = best;
        }
        if (found) {
            while (d.count > 1 && d.digits[d.count - 1] == '0') --d.count;
            return d;
        }
    }
    return d;
}

// Positional text: the shortest digits around the point; an integer beyond
// them is written with its exact digits, as std::to_chars does (of two texts
// of one length it takes the closer), which printf's %.0f gives.
std::string positional(const Digits& d, double x) {
    std::string t = d.negative ? "-" : "";
    const std::string_view digits(d.digits, static_cast<std::size_t>(d.count));
    if (d.exponent + 1 > d.count) {
        char buf[320];
        std::snprintf(buf, sizeof buf, "%.0f", x);
        return buf;
    }
    if (d.exponent < 0) {
        t += "0.";
        t.append(static_cast<std::size_t>(-d.exponent - 1), '0');
        t += digits;
    } else if (d.exponent + 1 == d.count) {
        t += digits;
    } else {
        t += digits.substr(0, static_cast<std::size_t>(d.exponent + 1));
        t += '.';
        t += digits.substr(static_cast<std::size_t>(d.exponent + 1));
    }
    return t;
}

std::string scientific(const Digits& d) {
    std::string t = d.negative ? "-" : "";
    t += d.digits[0];
    if (d.count > 1) {
        t += '.';
        t.append(d.digits + 1, static_cast<std::size_t>(d.count - 1));
    }
    char e[16];
    std::snprintf(e, sizeof e, "e%c%02d", d.exponent < 0 ? '-' : '+', d.exponent < 0 ? -d.exponent : d.exponent);
    return t + e;
}

std::to_chars_result put(char* first, char* last, const std::string& t) {
    if (static_cast<std::size_t>(last - first) < t.size()) return {last, std::errc::value_too_large};
    std::memcpy(first, t.data(), t.size());
    return {first + t.size(), std::errc()};
}

}  // namespace

std::to_chars_result portable_shortest_chars(char* first, char* last, double x) {
    if (x == 0) return put(first, last, std::signbit(x) ? "-0" : "0");
    const Digits d = shortest_digits(x);
    const std::string f = positional(d, x), e = scientific(d);
    return put(first, last, f.size() <= e.size() ? f : e);
}

std::to_chars_result portable_shortest_chars(char* first, char* last, double x, Notation format) {
    if (x == 0) return put(first, last, std::signbit(x) ? "-0" : "0");
    const Digits d = shortest_digits(x);
    // general: %g's choice at its default precision, 6: scientific when the
    // exponent is below -4 or at least 6 (whatever the number of digits).
    const bool sci = format == Notation::general && (d.exponent < -4 || d.exponent >= 6);
    return put(first, last, sci ? scientific(d) : positional(d, x));
}

std::to_chars_result shortest_chars(char* first, char* last, double x) {
#ifdef POLYVOL_STD_TO_CHARS
    return std::to_chars(first, last, x);
#else
    return portable_shortest_chars(first, last, x);
#endif
}

std::to_chars_result shortest_chars(char* first, char* last, double x, Notation format) {
#ifdef POLYVOL_STD_TO_CHARS
    return std::to_chars(first, last, x, format == Notation::fixed ? std::chars_format::fixed : std::chars_format::general);
#else
    return portable_shortest_chars(first, last, x, format);
#endif
}

std::string shortest_text(double x) {
    char buf[400];
    return std::string(buf, shortest_chars(buf, buf + sizeof buf, x).ptr);
}

std::from_chars_result parse_double(const char* first, const char* last, double& value) {
    double v = 0;
    const auto r = fast_float::from_chars(first, last, v);
    if (r.ec != std::errc()) return {r.ptr, r.ec};
    // std::from_chars refuses what overflows to infinity or underflows to zero
    // (and leaves value as it was): fast_float rounds it there.
    const std::string_view text(first, static_cast<std::size_t>(r.ptr - first));
    const bool spelled_infinite = text.find_first_of("iI") != std::string_view::npos;
    const std::string_view mantissa = text.substr(0, text.find_first_of("eE"));
    const bool nonzero = mantissa.find_first_of("123456789") != std::string_view::npos;
    if ((std::isinf(v) && !spelled_infinite) || (v == 0 && nonzero)) return {r.ptr, std::errc::result_out_of_range};
    value = v;
    return {r.ptr, r.ec};
}

}  // namespace polyvol::core

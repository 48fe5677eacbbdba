// src/report/number_text.cpp — polyvol/number_text.hpp.
#include "polyvol/number_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "core/charconv.hpp"

namespace polyvol {
namespace {

// The double a decimal this file wrote reads back as (correctly rounded, as
// strtod, on every standard library).
double read_back(const char* text) {
    double v = 0;
    core::parse_double(text, text + std::strlen(text), v);
    return v;
}

}  // namespace

std::string shortest(double v) {
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[400];
    // The shortest digits that read back as v; positional in [1e-4, 1e15)
    // (1000000, not 1e+06), as significant_text writes rounded values.
    const double a = std::fabs(v);
    const auto format = a >= 1e-4 && a < 1e15 ? core::Notation::fixed : core::Notation::general;
    auto res = core::shortest_chars(buf, buf + sizeof buf, v, format);
    return std::string(buf, res.ptr);
}

std::string bound_text(double e) {
    const double step = std::pow(10.0, std::floor(std::log10(e)) - 1);
    if (!(e > 0) || !std::isfinite(e) || !(step > 0) || !std::isfinite(step)) return shortest(e);  // subnormal: as is
    char buf[32];
    for (double r = std::ceil(e / step) * step;; r += step) {
        std::snprintf(buf, sizeof buf, "%.2g", r);
        if (read_back(buf) >= e) return buf;
    }
}

std::string plus_minus(double v, double e, int digits) {
    const std::string shown = number_text(v, e, digits);
    return shown + " ±" + bound_text(e + std::fabs(read_back(shown.c_str()) - v));
}

namespace {

// v rounded to `significant` digits (as %.*g rounds it), written positionally
// when the rounded value lies in [1e-4, 1e15) — 400, not 4e+02 — and with
// an exponent otherwise; no trailing zeros.
std::string significant_text(double v, int significant) {
    char buf[400];
    std::snprintf(buf, sizeof buf, "%.*e", significant - 1, v);
    const double rounded = read_back(buf);  // the value %.*g shows
    if (!(std::fabs(rounded) >= 1e-4 && std::fabs(rounded) < 1e15)) {
        std::snprintf(buf, sizeof buf, "%.*g", significant, v);
        return buf;
    }
    // The rounded value's digits, positionally: they end `significant - 1`
    // places after its leading one.
    const int exponent = std::atoi(std::strchr(buf, 'e') + 1);
    std::snprintf(buf, sizeof buf, "%.*f", std::max(0, significant - 1 - exponent), rounded);
    std::string s = buf;
    if (s.find('.') != std::string::npos) {
        s.erase(s.find_last_not_of('0') + 1);
        if (s.back() == '.') s.pop_back();
    }
    return s;
}

}  // namespace

std::string shortest_within(double v, double abs_error) {
    v += 0.0;
    if (!std::isfinite(v) || v == 0 || !(abs_error > 0) || !std::isfinite(abs_error)) return shortest(v);
    if (std::fabs(v) <= abs_error) return "0";  // the shortest decimal within the bound: noise, not a figure
    for (int d = 1; d < 17; ++d) {
        const std::string s = significant_text(v, d);
        if (std::fabs(read_back(s.c_str()) - v) <= abs_error) return s;
    }
    return shortest(v);
}

std::string number_text(double v, double abs_error, int digits) {
    v += 0.0;  // no "-0"
    if (!std::isfinite(v) || v == 0) return shortest(v);
    // The shortest decimal within half the bound (at most the digits down to
    // the bound's leading one), or every digit when the value is correctly rounded.
    std::string s = abs_error > 0 && std::isfinite(abs_error) ? shortest_within(v, abs_error / 2) : shortest(v);
    if (digits > 0) {
        const std::string d = significant_text(v, digits);
        if (d.size() < s.size()) s = d;
    }
    return s;
}

// mass = density × volume: the density used is within density_error
// (relative; at least 2^-53, the decimal typed as a double; more when it was
// converted to the figures' units) of the density typed, and the product is
// rounded once more, so the mass of the decimal density is within
// (2^-53 + density_error) |mass| of the printed one, plus the volume's error.
// It is shown as the shortest decimal within that bound of the printed
// double (7.85 × 12 is 94.2, not 94.19999999999999).
std::string mass_text(double mass, double volume_error_times_density, double density_error, int digits) {
    const double error =
        volume_error_times_density + std::fabs(mass) * (0x1p-53 + std::max(0x1p-53, density_error)) * (1 + 0x1p-40);
    const std::string s = shortest_within(mass, error);
    return digits > 0 ? number_text(read_back(s.c_str()), error, digits) : s;
}

std::string point_text(std::span<const double> c) {
    std::string s = "(";
    for (std::size_t i = 0; i < c.size(); ++i) s += (i ? ", " : "") + shortest(c[i]);
    return s + ")";
}

}  // namespace polyvol

// polyvol/number_text.hpp — how polyvol writes numbers as text: for people,
// the digits a number's guarantee supports; for programs (JSON, CSV), every
// digit. The same bytes in every build (core/charconv.hpp's digits).
#pragma once

#include <span>
#include <string>

namespace polyvol {

// Shortest decimal that reads back as the same double, positional in [1e-4,
// 1e15) ("nan", "inf" spelled out).
std::string shortest(double v);
// v as the tables show it: the digits its guarantee supports, down to the
// leading digit of abs_error (abs_error 0: correctly rounded, every digit of
// the shortest round trip), at most `digits` significant ones when digits > 0;
// never "-0".
std::string number_text(double v, double abs_error, int digits);
// The shortest decimal within abs_error of v (v's own shortest when 0).
std::string shortest_within(double v, double abs_error);
// "V ±E": v as number_text shows it, and E >= e plus the display's rounding,
// rounded up to two digits, so that the printed interval holds the exact value.
std::string plus_minus(double v, double e, int digits);
// e rounded up to two significant digits.
std::string bound_text(double e);
// A mass, density × volume: the shortest decimal within its bound of `mass`
// (the bound: the volume's error times the density, plus (2^-53 +
// max(2^-53, density_error)) |mass| for the density typed as a double and
// the product), at most `digits` significant ones when digits > 0.
std::string mass_text(double mass, double volume_error_times_density, double density_error, int digits);
// "(x, y, z, ...)", each coordinate its shortest decimal.
std::string point_text(std::span<const double> c);

}  // namespace polyvol

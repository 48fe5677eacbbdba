// Length units and densities with units, for --units, --to, --scale and
// --density 7850kg/m3: what the CLI multiplies the figures by
// (scale_mass_properties) and how far that factor may be from the one meant.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace polyvol::cli {

// A length unit as an exact fraction of a metre: micron, mm, cm, m, in, ft.
struct LengthUnit {
    std::string name;        // the short name printed: "mm", ...
    long long metre_num = 1; // metres = metre_num / metre_den, exactly
    long long metre_den = 1;
};
// "micron" (also "um"), "mm", "cm", "m", "in", "ft"; nothing for anything else.
std::optional<LengthUnit> length_unit(std::string_view name);

// The factor from coordinates in `from` to lengths in `to`, times `scale`,
// as a double, with a bound on its relative error against the exact factor
// (0 when it is exact: same units, integer ratios, power-of-two scales).
struct LengthFactor {
    double factor = 1;
    double relative_error = 0;
};
// scale_typed_exactly: the scale's text is the double's own decimal (not
// "1.0000000000000001", which reads as 1).
LengthFactor length_factor(const LengthUnit& from, const LengthUnit& to, double scale, bool scale_typed_exactly = true);
LengthFactor scale_only(double scale, bool scale_typed_exactly = true);
// Whether the text of a number is the shortest decimal of its double (after
// a leading '+' and trailing zeros of a fraction): "2", "2.50", not "1.0000000000000001".
bool typed_exactly(const std::string& text, double value);

// --density: a number, optionally followed by kg/m3 or g/cm3 (also kg/m^3,
// kg/m³, g/cm^3, g/cm³): then `si` is set and `kg_per_m3` holds it.
struct Density {
    double value = 1;      // the number as typed
    bool si = false;       // a unit was given
    double kg_per_m3 = 0;  // when si
};
// Nothing when the text is not a positive number with one of those units.
std::optional<Density> parse_density(const std::string& text);

}  // namespace polyvol::cli

// polyvol/units.hpp — length units and densities with units: the factor
// from a mesh's coordinates to the lengths of its figures, how far that
// factor may be from the one meant, and a density in mass units per unit³.
// Conventions: a unit is an exact fraction of a metre; a factor carries a
// bound on its relative error (0 when exact); figures are never silently
// converted: a plan says what the coordinates are in and what it did.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "polyvol/mesh.hpp"

namespace polyvol {

// A length unit as an exact fraction of a metre: micron, mm, cm, m, in, ft.
struct LengthUnit {
    std::string name;        // the short name printed: "mm", ...
    long long metre_num = 1; // metres = metre_num / metre_den, exactly
    long long metre_den = 1;
};
// "micron" (also "um"), "mm", "cm", "m", "in", "ft"; nothing for anything else.
std::optional<LengthUnit> length_unit(std::string_view name);
// The names length_unit takes, for messages: "mm, cm, m, in, ft or micron".
inline constexpr const char* kLengthUnitNames = "mm, cm, m, in, ft or micron";

// The factor from coordinates in `from` to lengths in `to`, times `scale`,
// as a double, with a bound on its relative error against the exact factor
// (0 when it is exact: same units, integer ratios, power-of-two scales).
struct LengthFactor {
    double factor = 1;
    double relative_error = 0;
    // A power of two meant exactly: multiplying by it rounds nothing (in range).
    bool exact_power_of_two() const;
};
// x is a positive power of two (2^k for an integer k).
bool is_power_of_two(double x);
// scale_typed_exactly: the scale's text is the double's own decimal (not
// "1.0000000000000001", which reads as 1).
LengthFactor length_factor(const LengthUnit& from, const LengthUnit& to, double scale = 1,
                           bool scale_typed_exactly = true);
LengthFactor scale_only(double scale, bool scale_typed_exactly = true);
// Whether the text of a number is the shortest decimal of its double (after
// a leading '+' and trailing zeros of a fraction): "2", "2.50", not "1.0000000000000001".
bool typed_exactly(const std::string& text, double value);

// A density as typed: a number, optionally followed by kg/m3 or g/cm3 (also
// kg/m^3, kg/m³, g/cm^3, g/cm³): then `si` is set and `kg_per_m3` holds it.
struct Density {
    double value = 1;      // the number as typed
    bool si = false;       // a unit was given
    double kg_per_m3 = 0;  // when si
};
// Nothing when the text is not a positive number with one of those units.
std::optional<Density> parse_density(const std::string& text);

// The mass units a density with a unit gives: "kg", "g", "lb" (1 lb is
// 0.45359237 kg exactly); nothing for anything else.
std::optional<double> mass_units_per_kg(std::string_view mass_unit);

// A density with a unit in mass units per (length unit)³:
//   ρ_kg/m³ × (metres per unit)³ × (mass units per kg),
// each product rounded once: relative_error bounds the result's error
// against the exact value of the density as typed.
struct DensityIn {
    double value = 1;
    double relative_error = 0;
};
DensityIn density_in(const Density& density, const LengthUnit& length, std::string_view mass_unit);

// What the figures of one mesh are in: --units (or the file's own unit),
// --to, --scale and a density with a unit.
struct UnitsRequest {
    std::string units;       // the coordinates' unit; "" = the file's own, if it states one
    std::string to;          // the figures' unit; "" = the coordinates' (m with a density with a unit)
    double scale = 1;        // multiplies every coordinate first
    bool scale_typed_exactly = true;
    bool density_si = false; // the density has a unit: figures default to metres
    bool metres_when_known = false;  // figures in metres whenever the unit is known (URDF, SDF)
};
struct UnitsPlan {
    std::string error;       // why no figures can be given ("" when they can)
    std::string from;        // the coordinates' unit, "" when unknown
    std::string source;      // "--units", "declared by the file" or ""
    std::string length_unit; // the figures' unit, "" when unknown (then the factor is the scale's)
    LengthFactor length;     // coordinates × factor = figures' lengths
    std::string warning;     // the file declares a unit other than the one given
};
// declared: the unit the file states (LoadedMesh::unit), "" when none.
UnitsPlan plan_units(std::string_view declared, const UnitsRequest& request);

// Multiplies every coordinate of `mesh` by f.factor, each product rounded
// once, and returns the bound on |coordinate − exact value| that follows
// from `coordinate_error`, the bound before:
//   |fl(x f) − x f*| ≤ (|x f| (u + ε) + f δ)(1 + 2⁻⁴⁰)
// with f* the factor meant, ε its relative error and δ the old bound
// (0 when f = 1 and ε = 0: nothing moves).
double scale_coordinates(Mesh& mesh, const LengthFactor& f, double coordinate_error);

// Several meshes in one coordinate system (overlap's operands, the grid's
// bodies). Each mesh's unit is `units` when given, else the one it
// declares, else unknown. The common unit is `to` when given, else the first
// known one. A mesh whose unit is known and differs is converted into it
// (factors[i]; scale_coordinates); a mesh of unknown unit is taken to be in
// the common unit (notes say so when another mesh states one). With `to`
// given, a mesh of unknown unit is an error.
struct CommonUnit {
    std::string error;                 // "" when the meshes can be put together
    std::string unit;                  // "" when no mesh's unit is known
    std::vector<LengthFactor> factors; // per mesh: its coordinates × factor
    std::vector<std::string> notes;    // per mesh: what was assumed or converted ("" for nothing)
};
CommonUnit common_unit(std::span<const std::string> declared, std::string_view units, std::string_view to);

// Two operands whose figures are printed in one unit (overlap, a boolean):
// B is put into A's unit (common_unit without `to`: A's, or B's when A
// states none), the figures then scaled to `to` when given. With `to`
// given, an operand whose unit is not known is an error, naming it.
struct PairUnits {
    CommonUnit common;       // the operands' factors and notes (without `to`)
    std::string error;       // "" when they can be put together
    int error_operand = -1;  // 0: A, 1: B, -1: neither (a unit's name)
    std::string unit;        // the figures' unit: `to`, else common.unit ("" unknown)
    LengthFactor figures;    // from common.unit to `unit`
};
PairUnits pair_units(const std::string& declared_a, const std::string& declared_b, std::string_view units,
                     std::string_view to);

// A mesh put into another's unit `to` (a body in a mesh of cells): its unit
// is `units` when given, else the one it declares, as in common_unit. Where
// its unit is not known it is taken to be in `to`, and where `to` is not
// known (a mesh of cells that states none) its coordinates are taken as
// they are: a note says either. error: an unknown unit name.
struct UnitChange {
    std::string error;
    LengthFactor factor;  // its coordinates × factor (scale_coordinates)
    std::string note;     // what was assumed or converted ("" for nothing)
};
UnitChange into_unit(std::string_view declared, std::string_view units, std::string_view to);

}  // namespace polyvol

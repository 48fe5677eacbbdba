// src/core/units.cpp — polyvol/units.hpp.
#include "polyvol/units.hpp"
#include "core/charconv.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <utility>

namespace polyvol {
namespace {

constexpr double kU = 0x1p-53;

// x is exactly the double the decimal text meant when it is an integer below
// 2^53 or a power of two: --scale 2, 10, 0.5 are exact, 0.1 is not. (A text
// with more digits than the double keeps, "1.0000000000000001", is caught by
// the caller: scale_only's text.)
bool exact_decimal(double x) { return (x == std::floor(x) && std::fabs(x) < 0x1p53) || is_power_of_two(x); }

}  // namespace

bool is_power_of_two(double x) {
    int e = 0;
    return std::isfinite(x) && x > 0 && std::frexp(x, &e) == 0.5;  // 2^k = 0.5 · 2^(k+1)
}

bool LengthFactor::exact_power_of_two() const { return relative_error == 0 && is_power_of_two(factor); }

std::optional<LengthUnit> length_unit(std::string_view name) {
    static const std::pair<std::string_view, LengthUnit> kUnits[] = {
        {"micron", {"micron", 1, 1000000}}, {"um", {"micron", 1, 1000000}}, {"mm", {"mm", 1, 1000}},
        {"cm", {"cm", 1, 100}},             {"m", {"m", 1, 1}},               {"in", {"in", 254, 10000}},
        {"ft", {"ft", 3048, 10000}}};
    for (const auto& [n, u] : kUnits)
        if (n == name) return u;
    return std::nullopt;
}

LengthFactor scale_only(double scale, bool scale_typed_exactly) {
    return {scale, exact_decimal(scale) && scale_typed_exactly ? 0.0 : kU};
}

bool typed_exactly(const std::string& text, double value) {
    std::string t = !text.empty() && text[0] == '+' ? text.substr(1) : text;
    if (t.find('.') != std::string::npos && t.find_first_of("eE") == std::string::npos) {
        while (!t.empty() && t.back() == '0') t.pop_back();
        if (!t.empty() && t.back() == '.') t.pop_back();
    }
    return t == core::shortest_text(value);
}

LengthFactor length_factor(const LengthUnit& from, const LengthUnit& to, double scale, bool scale_typed_exactly) {
    // from / to = (from_num to_den) / (from_den to_num): integers far below 2^53.
    const long long p = from.metre_num * to.metre_den, q = from.metre_den * to.metre_num;
    const double ratio = static_cast<double>(p) / static_cast<double>(q);
    const bool ratio_exact = p % q == 0;
    LengthFactor f = scale_only(scale, scale_typed_exactly);
    f.relative_error += ratio_exact ? 0.0 : kU;
    const bool product_exact = ratio == 1 || scale == 1;
    f.factor = ratio * scale;
    f.relative_error += product_exact ? 0.0 : kU;
    return f;
}

std::optional<Density> parse_density(const std::string& text) {
    static const std::pair<std::string_view, double> kUnits[] = {
        {"kg/m3", 1},    {"kg/m^3", 1},    {"kg/m\u00b3", 1},
        {"g/cm3", 1000}, {"g/cm^3", 1000}, {"g/cm\u00b3", 1000}};
    double v = 0;
    const char* first = text.data() + (!text.empty() && text[0] == '+');
    const char* last = text.data() + text.size();
    const auto [end, ec] = core::parse_double(first, last, v);
    if (ec != std::errc() || !std::isfinite(v) || !(v > 0)) return std::nullopt;
    std::string_view rest(end, static_cast<std::size_t>(last - end));
    while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
    Density d;
    d.value = v;
    if (rest.empty()) return d;
    for (const auto& [unit, to_si] : kUnits)
        if (rest == unit) {
            d.si = true;
            d.kg_per_m3 = v * to_si;
            return d;
        }
    return std::nullopt;
}

std::optional<double> mass_units_per_kg(std::string_view mass_unit) {
    if (mass_unit == "kg") return 1.0;
    if (mass_unit == "g") return 1000.0;
    if (mass_unit == "lb") return 1 / 0.45359237;  // rounded once
    return std::nullopt;
}

DensityIn density_in(const Density& d, const LengthUnit& length, std::string_view mass_unit) {
    if (!d.si) return {d.value, 0};
    const double metres = static_cast<double>(length.metre_num) / static_cast<double>(length.metre_den);
    const double per_kg = mass_units_per_kg(mass_unit).value_or(1.0);
    // kg/m³ from g/cm³ (× 1000), metres per unit, its cube (two products),
    // the product with ρ, the mass unit (its own rounding and the product's).
    const double value = d.kg_per_m3 * (metres * metres * metres) * per_kg;
    return {value, (mass_unit == "kg" ? 4 : 6) * kU};
}

UnitsPlan plan_units(std::string_view declared, const UnitsRequest& q) {
    UnitsPlan p;
    std::optional<LengthUnit> from;
    if (!q.units.empty()) {
        from = length_unit(q.units);
        if (!from) {
            p.error = "unknown unit " + q.units + " (" + kLengthUnitNames + ")";
            return p;
        }
        p.source = "--units";
        if (!declared.empty() && declared != from->name)
            p.warning = "the file declares its unit as " + std::string(declared) + "; " + from->name +
                        " is used instead";
    } else if (!declared.empty()) {
        from = length_unit(declared);
        p.source = "declared by the file";
    }
    if (!q.to.empty() && !length_unit(q.to)) {
        p.error = "unknown unit " + q.to + " (" + kLengthUnitNames + ")";
        return p;
    }
    const std::string to = !q.to.empty()                                       ? q.to
                           : q.density_si || (q.metres_when_known && from)   ? "m"
                           : from                                              ? from->name
                                                                               : "";
    if (!to.empty() && !from) {
        p.error = "its length unit is not known (the file states none)";
        return p;
    }
    p.from = from ? from->name : "";
    p.length = from ? length_factor(*from, *length_unit(to), q.scale, q.scale_typed_exactly)
                    : scale_only(q.scale, q.scale_typed_exactly);
    p.length_unit = to;
    return p;
}

double scale_coordinates(Mesh& mesh, const LengthFactor& f, double coordinate_error) {
    if (f.factor == 1 && f.relative_error == 0) return coordinate_error;
    double largest = 0;
    for (double& x : mesh.positions) {
        x *= f.factor;
        largest = std::max(largest, std::fabs(x));
    }
    // A power-of-two factor meant exactly moves nothing but the old bound.
    const bool exact = f.exact_power_of_two();
    return ((exact ? 0.0 : largest * (kU + f.relative_error)) + std::fabs(f.factor) * coordinate_error) *
           (1 + 0x1p-40);
}

CommonUnit common_unit(std::span<const std::string> declared, std::string_view units, std::string_view to) {
    CommonUnit c;
    c.factors.assign(declared.size(), LengthFactor{});
    c.notes.assign(declared.size(), "");
    const auto unknown = [&](std::string_view name) {
        c.error = "unknown unit " + std::string(name) + " (" + kLengthUnitNames + ")";
        return c;
    };
    if (!units.empty() && !length_unit(units)) return unknown(units);
    if (!to.empty() && !length_unit(to)) return unknown(to);
    std::vector<std::string> unit(declared.size());
    for (std::size_t i = 0; i < declared.size(); ++i) {
        unit[i] = !units.empty() ? length_unit(units)->name : declared[i];
        if (!units.empty() && !declared[i].empty() && declared[i] != unit[i])
            c.notes[i] = "the file declares its unit as " + declared[i] + "; " + unit[i] + " is used instead";
        if (c.unit.empty() && !unit[i].empty()) c.unit = unit[i];
    }
    if (!to.empty()) c.unit = length_unit(to)->name;
    for (std::size_t i = 0; i < declared.size(); ++i) {
        if (unit[i].empty()) {
            if (!to.empty()) {
                c.error = "its length unit is not known (the file states none)";
                c.notes[i] = c.error;
                return c;
            }
            if (!c.unit.empty()) c.notes[i] = "it states no unit: taken to be in " + c.unit + ", as the others";
            continue;
        }
        if (unit[i] == c.unit) continue;
        c.factors[i] = length_factor(*length_unit(unit[i]), *length_unit(c.unit));
        const std::string factor = core::shortest_text(c.factors[i].factor);
        c.notes[i] += std::string(c.notes[i].empty() ? "" : "; ") + "its coordinates converted from " + unit[i] +
                      " to " + c.unit + " (× " + factor +
                      ", each rounded once)";
    }
    return c;
}

PairUnits pair_units(const std::string& declared_a, const std::string& declared_b, std::string_view units,
                     std::string_view to) {
    PairUnits p;
    const std::string declared[2] = {declared_a, declared_b};
    // The error of common_unit's plan c, naming the operand its note names; false when none.
    const auto refused = [&p](const CommonUnit& c) {
        if (c.error.empty()) return false;
        p.error = c.error;
        p.error_operand = c.notes[0] == c.error ? 0 : c.notes[1] == c.error ? 1 : -1;
        return true;
    };
    // With `to`, both units must be known (the figures go into it); the operands go into A's.
    if (!to.empty() && refused(common_unit(declared, units, to))) return p;
    p.common = common_unit(declared, units, "");
    if (refused(p.common)) return p;
    p.unit = to.empty() ? p.common.unit : length_unit(to)->name;
    if (!to.empty() && !p.common.unit.empty())
        p.figures = length_factor(*length_unit(p.common.unit), *length_unit(to));
    return p;
}

UnitChange into_unit(std::string_view declared, std::string_view units, std::string_view to) {
    UnitChange u;
    const std::string own = !units.empty() ? std::string(units) : std::string(declared);
    if (!own.empty() && !length_unit(own)) {
        u.error = "unknown unit " + own + " (" + kLengthUnitNames + ")";
    } else if (to.empty()) {
        if (!own.empty()) u.note = "the mesh states no unit: its coordinates are taken as they are";
    } else if (own.empty()) {
        u.note = "it states no unit: taken to be in " + std::string(to) + ", the mesh's";
    } else {
        const std::string declared_s(declared);
        const CommonUnit c = common_unit(std::span<const std::string>(&declared_s, 1), units, to);
        u.error = c.error;
        if (c.error.empty()) u.factor = c.factors[0], u.note = c.notes[0];
    }
    return u;
}

}  // namespace polyvol

// report/request_words.cpp — a request's words (polyvol/report.hpp's
// RequestWords) as FileOptions, read once for every door.
#include <cmath>

#include "core/charconv.hpp"
#include "polyvol/report.hpp"
#include "polyvol/units.hpp"

namespace polyvol {
namespace {

// A finite number > 0 and nothing else, or nullopt.
std::optional<double> positive(const std::string& s) {
    double v = 0;
    const char* first = s.data() + (!s.empty() && s[0] == '+');
    const auto [end, ec] = core::parse_double(first, s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || !std::isfinite(v) || !(v > 0)) return std::nullopt;
    return v;
}

}  // namespace

ReadRequest file_options(const RequestWords& w, ReportOf command, bool json) {
    ReadRequest r;
    FileOptions o;
    if (w.method == "cone") o.measure.method = Method::cone;
    else if (w.method == "prism") o.measure.method = Method::prism;
    else if (w.method == "pyramid") o.measure.method = Method::pyramid;
    else if (w.method == "vtnb") o.measure.method = Method::vtnb;
    else return {std::nullopt, "method must be cone, prism, pyramid or vtnb, not '" + w.method + "'"};
    if (w.accuracy == "exact" || w.accuracy == "correctly-rounded") o.measure.accuracy = Accuracy::correctly_rounded;
    else if (w.accuracy == "fast" || w.accuracy == "bounded") o.measure.accuracy = Accuracy::fast;
    else return {std::nullopt, "accuracy must be exact (correctly-rounded) or fast (bounded), not '" + w.accuracy + "'"};
    for (const std::string* u : {&w.units, &w.to})
        if (!u->empty() && !length_unit(*u))
            return {std::nullopt, "unknown length unit '" + *u + "' (" + std::string(kLengthUnitNames) + ")"};
    if (!mass_units_per_kg(w.mass_unit)) return {std::nullopt, "mass unit must be kg, g or lb, not '" + w.mass_unit + "'"};
    const std::optional<Density> d = parse_density(w.density);
    if (!d) return {std::nullopt, "density must be a number > 0, optionally with kg/m3 or g/cm3, not '" + w.density + "'"};
    if (w.mass_unit != "kg" && !d->si)
        return {std::nullopt, "a mass unit (" + w.mass_unit +
                                  ") needs a density with a unit (e.g. 1.24g/cm3): a plain number is already mass per volume"};
    const std::optional<double> scale = positive(w.scale);
    if (!scale) return {std::nullopt, "scale must be a number > 0, not '" + w.scale + "'"};
    if (!(w.weld_tolerance >= 0) || !std::isfinite(w.weld_tolerance))
        return {std::nullopt, "weld tolerance must be a number >= 0"};
    // A density with a unit is converted to mass_unit per output unit³ (metres by default).
    o.measure.density = d->value;
    if (d->si) {
        const DensityIn in = density_in(*d, *length_unit(w.to.empty() ? "m" : w.to), w.mass_unit);
        o.measure.density = in.value;
        o.density_kg_m3 = d->kg_per_m3;
        o.density_relative_error = in.relative_error;
        o.mass_unit = w.mass_unit;
    }
    o.units = w.units;
    o.units_where_unstated = w.units_where_unstated;
    o.to = w.to;
    o.scale = *scale;
    o.scale_typed_exactly = typed_exactly(w.scale, o.scale);
    o.allow_open = w.allow_open;
    o.need_mass = command != ReportOf::check;
    o.self_check_always = w.solid || command == ReportOf::check;
    o.orient = w.orient;
    o.keep_signed = w.keep_signed;
    o.weld_tolerance = w.weld_tolerance;
    // The route (measure_file streams a binary STL where these allow it).
    const bool volume = command == ReportOf::volume;
    o.volume_only = volume && w.volume_only;
    o.table_only = volume && (!json || o.volume_only || w.stream);  // the table's figures
    o.stream_any_size = volume && w.stream;
    o.mesh_counts = json && !o.stream_any_size;
    o.edge_counts = !(volume && !json);  // the table: closedness by fingerprint
    o.moments_bounded = volume && !json;
    if (o.table_only) {
        o.measure.second_moments = false;
        o.measure.edge_length = false;
    }
    r.options = std::move(o);
    return r;
}

}  // namespace polyvol

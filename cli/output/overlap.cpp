// cli/output/overlap.cpp — cli/output/overlap.hpp.
#include "output/overlap.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>
#include <utility>

#include "output/format.hpp"

namespace polyvol::cli {

std::string overlap_table(const std::string& a, const std::string& b, const BooleanVolumes& r, const std::string& unit,
                          double seconds) {
    const double bound = r.volume_error_bound;
    std::ostringstream out;
    out << "A = " << a << " (" << r.triangles_a << " triangles), B = " << b << " (" << r.triangles_b
        << " triangles)\n\n";
    const std::string volume_head = unit.empty() ? "volume" : "volume (" + unit + "³)";
    const std::string area_head = unit.empty() ? "area" : "area (" + unit + "²)";
    // setw counts bytes: ³ is two bytes, shown as one column.
    out << std::left << std::setw(8) << "" << std::setw(unit.empty() ? 26 : 27) << volume_head << area_head << "\n";
    const std::pair<const char*, std::pair<double, double>> rows[] = {
        {"A", {r.volume_a, r.area_a}},
        {"B", {r.volume_b, r.area_b}},
        {"A ∩ B", {r.intersection, r.area_intersection}},
        {"A ∪ B", {r.union_volume, r.area_union}},
        {"A − B", {r.a_minus_b, r.area_a_minus_b}},
        {"B − A", {r.b_minus_a, r.area_b_minus_a}},
    };
    for (const auto& [name, v] : rows) {
        // setw counts bytes: ∩ ∪ − are three bytes each, shown as one column.
        const std::string label = name;
        const int pad = label.size() > 1 ? 8 + 2 : 8;
        // Each figure to the digits its guarantee supports (as volume's table).
        const std::string volume = bound > 0 ? plus_minus(v.first, bound, 0) : number_text(v.first, 0, 0);
        out << std::setw(pad) << label << std::setw(26) << volume
            << (std::isnan(v.second) ? std::string("-") : number_text(v.second, r.area_error_bound, 0)) << "\n";
    }
    out << "\nvolumes: "
        << (bound > 0 ? "within the ± shown (a change of unit, or coordinates computed in floating point: 3MF "
                        "transforms)"
                      : std::string("correctly rounded (the exact volume of the coordinates as read, rounded once)"))
        << "\n"
        << "areas: within ±" << bound_text(r.area_error_bound) << " each"
        << (std::isnan(r.area_a_minus_b) ? "; A − B and B − A not computed where an operand's shells overlap or "
                                           "cross themselves (the parts of one solid's boundary inside the other)"
                                         : "")
        << "\n"
        << r.crossing_pairs << " crossing triangle pair" << (r.crossing_pairs == 1 ? "" : "s")
        // (solid_boolean_volumes counts the crossings of its three solids, not candidate pairs)
        << (r.candidate_pairs > 0 ? " (of " + std::to_string(r.candidate_pairs) + " whose boxes meet)" : std::string())
        << ", " << std::setprecision(3) << seconds << " s\n";
    return out.str();
}

}  // namespace polyvol::cli

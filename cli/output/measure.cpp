// cli/output/measure.cpp — cli/output/measure.hpp.
#include "output/measure.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <span>
#include <sstream>
#include <utility>

#include "output/format.hpp"
#include "polyvol/units.hpp"

namespace polyvol::cli {
namespace {

// The self-crossing line of the reports: none, or the pairs and what became of them.
std::string self_crossing_line(const FileResult& r) {
    if (!r.policy.self) return r.policy.self_not_checked;
    if (r.policy.self->pairs == 0) return "none within a shell";
    return self_crossing_sentence(*r.policy.self) +
           (r.policy.solid && r.policy.solid->shells_crossing_themselves > 0 ? "; resolved: the volume is the solid's"
            : r.policy.self_unresolved ? "; not resolved: it also touches or folds onto itself there"
                                : "");
}

// " mm³": the figures' length unit to a power ("" when it is not known).
std::string unit_power(const std::string& unit, int degree) {
    static const char* const kPowers[] = {"", "", "²", "³", "⁴", "⁵"};
    return unit.empty() ? "" : unit + kPowers[degree];
}

std::string unit_suffix(const FileResult& r, int degree) {
    return r.length_unit.empty() ? "" : " " + unit_power(r.length_unit, degree);
}

// The unit of a density-scaled quantity of length degree k: "kg·m²" (mass
// in kg: k - 3 left), or "mm⁵" times the density.
std::string mass_unit_suffix(const FileResult& r, int degree) {
    if (!r.mass_unit.empty()) return " " + r.mass_unit + (degree > 3 ? "·" + unit_power(r.length_unit, degree - 3) : "");
    return r.length_unit.empty() ? "" : " (density × " + unit_power(r.length_unit, degree) + ")";
}

// The density as typed: "7850 kg/m³", or the plain number.
std::string density_text(const Request& q) {
    return q.density_kg_m3 > 0 ? shortest(q.density_kg_m3) + " kg/m³" : shortest(q.measure.density);
}

// Where the units came from and what the figures are in.
std::string units_sentence(const FileResult& r) {
    std::string s = r.loaded && !r.loaded->unit.empty() ? "the file declares " + r.loaded->unit : "";
    if (r.units_source == "--units") s += (s.empty() ? "" : "; ") + std::string("coordinates in the unit --units gives");
    if (r.length_factor != 1) s += (s.empty() ? "" : "; ") + std::string("every coordinate × ") + shortest(r.length_factor);
    if (!r.length_unit.empty()) s += (s.empty() ? "" : "; ") + std::string("lengths in ") + r.length_unit;
    if (!r.mass_unit.empty()) s += ", mass in " + r.mass_unit;
    return s;
}

// What --weld-tolerance did, in words.
std::string weld_sentence(const ToleranceWeld& w, double tolerance) {
    return "welded at " + shortest(tolerance) + ": " + std::to_string(w.moved) + " point" + (w.moved == 1 ? "" : "s") +
           " moved, by at most " + shortest(w.largest_move) + "; the figures are the welded mesh's";
}

// What --orient did, in words.
std::string orient_sentence(const OrientResult& o) {
    std::string s = "oriented: " + std::to_string(o.flipped) + " face" + (o.flipped == 1 ? "" : "s") + " flipped";
    if (o.undecided > 0)
        s += "; " + std::to_string(o.undecided) + " shell" + (o.undecided == 1 ? "'s" : "s'") +
             " outward side not decided (left as wound)";
    return s;
}

// The sentence for a file whose shells overlap, or "".
std::string overlap_sentence(const FileResult& r) {
    if (!r.policy.solid || !r.policy.solid->differs_from_shells()) return "";
    const SolidVolume& s = *r.policy.solid;
    std::string what;
    if (s.overlapping_shells > 0)
        what = std::to_string(s.overlapping_shells) + " of " + std::to_string(s.shells) + " shells overlap (" +
               std::to_string(s.crossing_pairs) + " crossing triangle pairs)";
    if (s.shells_crossing_themselves > 0)
        what += (what.empty() ? "" : " and ") + std::to_string(s.shells_crossing_themselves) + " shell" +
                (s.shells_crossing_themselves == 1 ? " crosses itself" : "s cross themselves") + " (" +
                std::to_string(s.self_crossing_pairs) + " triangle pairs)";
    const std::string guarantee = r.mass && !r.mass->volume_correctly_rounded
                                      ? "within " + shortest(r.mass->volume_error_bound)
                                      : std::string("correctly rounded");
    return what + ": the volume is the solid's (winding number >= 1, " + guarantee + "); the shells' volumes add up to " +
           shortest(s.winding_volume);
}

}  // namespace

std::string volume_guarantee(const MassProperties& m) {
    if (m.volume_correctly_rounded) return "correctly rounded (the exact volume of the coordinates as read, rounded once)";
    return "error bound " + shortest(m.volume_error_bound) + " (absolute) for the value in full (JSON)";
}

std::string volume_table(const std::vector<FileResult>& results, const Request& request) {
    // Column widths from the content, so long paths keep the columns aligned.
    std::size_t name_w = 4;
    for (const auto& r : results) name_w = std::max(name_w, r.file.size());
    auto pad = [](std::string s, std::size_t w) {  // w characters (UTF-8: "±", "³" are one each)
        std::size_t n = 0;
        for (char c : s) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
        if (n < w) s.append(w - n, ' ');
        return s;
    };
    const bool all = !request.volume_only;  // area and centroid columns
    const bool mass = request.density_given;
    const int digits = request.digits;
    std::ostringstream out;
    // Units in the header when every measured file has the same.
    const std::pair<std::string, std::string> units = common_units(results);
    const std::string &unit = units.first, &mass_unit = units.second;
    const auto in = [](const std::string& u) { return u.empty() ? std::string() : " (" + u + ")"; };
    out << pad("file", name_w) << "  " << pad("triangles", 10) << "  ";
    if (mass) out << pad("mass" + in(mass_unit), 24) << "  ";
    if (all)
        out << pad("volume" + in(unit_power(unit, 3)), 24) << "  " << pad("area" + in(unit_power(unit, 2)), 24)
            << "  centroid" << in(unit) << "\n";
    else
        out << "volume" << in(unit_power(unit, 3)) << "\n";
    bool any_rounded = false, any_bound = false, any_fingerprint = false, any_checked = false;
    std::string figure_notes, overlap_notes, notes;
    const auto centroid_text = [&](const std::array<double, 3>& c, double error) {
        return "(" + number_text(c[0], error, digits) + ", " + number_text(c[1], error, digits) + ", " +
               number_text(c[2], error, digits) + ")";
    };
    for (const auto& r : results) {
        any_fingerprint = any_fingerprint || r.streamed || r.policy.closed_by_fingerprint;
        if (r.policy.welded) notes += "  " + r.file + ": " + weld_sentence(*r.policy.welded, r.weld_tolerance) + "\n";
        if (r.loaded && r.loaded->mesh.view().triangle_count() == 0)
            notes += "  " + r.file + ": no faces (a point cloud, or an empty file?): nothing to measure\n";
        if (r.policy.oriented && r.policy.oriented->orientable) notes += "  " + r.file + ": " + orient_sentence(*r.policy.oriented) + "\n";
        const std::string tris = r.loaded || r.streamed ? std::to_string(r.triangles) : "-";
        if (r.streamed)
            notes += "  " + r.file + ": streamed: its shells were not checked for overlap, so the figures are "
                     "the shells' sums (--solid checks)\n";
        out << pad(r.file, name_w) << "  " << pad(tris, 10) << "  ";
        if (!r.mass) {
            out << (r.exit_code == Exit::unreadable ? "unreadable"
                    : r.policy.topology && !r.policy.topology->closed_2_cycle ? "open surface: not measured"
                                                                  : "not measured") << "\n";
            continue;
        }
        const auto& m = *r.mass;
        const bool overlap = r.policy.solid && r.policy.solid->differs_from_shells();
        any_checked = any_checked || r.policy.overlap_checked;
        (m.volume_correctly_rounded ? any_rounded : any_bound) = true;
        const double volume_error = m.volume_correctly_rounded ? 0 : m.volume_error_bound;
        const std::string vol = m.volume_correctly_rounded ? number_text(m.volume, 0, digits)
                                                           : plus_minus(m.volume, m.volume_error_bound, digits);
        if (mass) out << pad(mass_text(m.mass, request.measure.density * volume_error, request.density_relative_error, digits), 24) << "  ";
        if (overlap)
            overlap_notes += "  " + r.file + ": " + overlap_sentence(r) + (all ? "; its centroid and area are the solid's" : "") + "\n";
        if (!all) {
            out << vol << "\n";
            continue;
        }
        const double centroid_error = moments_error_bound(m, m.centroid);
        out << pad(vol, 24) << "  " << pad(number_text(m.area, m.area * m.area_relative_error, digits), 24) << "  "
            << centroid_text(m.centroid, centroid_error) << "\n";
        figure_notes += "  " + r.file + ": area relative error <= " + shortest(m.area_relative_error) + "; centroid " +
                        (m.moments_correctly_rounded
                             ? std::string("correctly rounded")
                             : "within ±" + bound_text(centroid_error) + " per coordinate (" +
                                   shortest(m.moments_relative_error) + " of its largest coordinate's magnitude)") +
                        "\n";
    }
    std::vector<std::string> footer;
    if (any_rounded)
        footer.emplace_back(request.verbose ? "Volumes without ± are correctly rounded: the exact volume of the "
                                              "coordinates as read, rounded once"
                                            : "Volumes without ± are correctly rounded");
    if (any_bound) footer.emplace_back("± is a rigorous absolute error bound");
    if (mass) footer.push_back("mass = density " + density_text(request) + " × volume");

    if (all)
        footer.emplace_back(request.verbose ? "area and centroid: their guarantees below; inertia: `polyvol measure`"
                                            : "other figures are shown to within half their bounds (--verbose: "
                                              "the bounds)");
    if (!footer.empty()) footer[0][0] = static_cast<char>(std::toupper(static_cast<unsigned char>(footer[0][0])));
    out << "method: " << method_name(request.measure.method) << ".";
    for (std::size_t i = 0; i < footer.size(); ++i) out << (i == 0 ? " " : "; ") << footer[i];
    out << (footer.empty() ? "\n" : ".\n");
    if (unit.empty())  // not shared: each file's own (files without one have nothing to say)
        for (const auto& r : results)
            if (r.mass && !r.length_unit.empty())
                out << "  " << r.file << ": lengths in " << r.length_unit
                    << (r.mass_unit.empty() ? "" : ", mass in " + r.mass_unit) << "\n";
    out << notes;
    if (request.verbose) {
        out << figure_notes;
        if (any_fingerprint)
            out << "Closed 2-cycle checked by a randomized edge fingerprint (an open surface passes with probability "
                   "< 2^-113); a file it finds open, or cannot decide (e.g. a NaN or infinite coordinate), is analysed "
                   "in full and its unbalanced edges reported.\n";
        if (any_checked)
            out << "Shells checked for overlap with one another; a shell crossing itself looked for in files up to "
                << kSelfCheckTriangles << " triangles (--solid: in every file).\n";
    }
    out << overlap_notes;
    return out.str();
}

std::string measure_report(const FileResult& r, const Request& request) {
    std::ostringstream out;
    const auto& l = *r.loaded;
    const auto& m = *r.mass;
    out << r.file << "  (" << format_name(l.format) << ", " << l.encoding << (l.gzip ? ", gzip" : "")
        << "; " << l.vertices_in_file << " vertices, " << l.mesh.face_count() << " faces, "
        << l.mesh.view().triangle_count() << " triangles)\n";
    out << "  method          " << method_name(request.measure.method) << ", density " << density_text(request) << "\n";
    if (r.policy.welded) out << "  welded          " << weld_sentence(*r.policy.welded, r.weld_tolerance) << "\n";
    if (!r.units_source.empty() || r.length_factor != 1) out << "  units           " << units_sentence(r) << "\n";
    if (r.policy.oriented) out << "  orientation     " << orient_sentence(*r.policy.oriented) << "\n";
    if (r.policy.turned_outward)
        out << "  orientation     inside out: " << r.policy.turned_outward->components << " shell(s) turned outward, "
            << r.policy.turned_outward->flipped << " faces reversed (--signed keeps the signed sums)\n";
    const bool overlap = r.policy.solid && r.policy.solid->differs_from_shells();
    // Each figure shows the digits its guarantee supports (--digits caps them).
    const int digits = request.digits;
    const double volume_error = m.volume_correctly_rounded ? 0 : m.volume_error_bound;
    const std::string volume_text =
        m.volume_correctly_rounded ? number_text(m.volume, 0, digits) : plus_minus(m.volume, volume_error, digits);
    if (overlap) {
        out << "  volume          " << volume_text << unit_suffix(r, 3) << "   [" << volume_guarantee(m)
            << "; the solid where the winding number is >= 1]\n";
        out << "  shells          " << overlap_sentence(r) << "\n";
        out << "  note            mass, centroid, moments, inertia and surface area are the solid's; edge length "
               "is the shells' sum (an overlap counts once per shell covering it)\n";
    } else {
        out << "  volume          " << volume_text << unit_suffix(r, 3) << "   [" << volume_guarantee(m) << "]\n";
    }
    if (r.policy.overlap_checked) out << "  overlap         shells checked against one another\n";
    out << "  self-crossing   " << self_crossing_line(r) << "\n";
    out << "  mass            " << mass_text(m.mass, request.measure.density * volume_error, request.density_relative_error, digits)
        << mass_unit_suffix(r, 3) << "\n";
    out << "  surface area    " << number_text(m.area, m.area * m.area_relative_error, digits) << unit_suffix(r, 2)
        << "   [relative error <= " << bound_text(m.area_relative_error) << "]\n";
    out << "  edge length     " << number_text(m.edge_length, m.edge_length * m.edge_length_relative_error, digits)
        << unit_suffix(r, 1) << "   [relative error <= " << bound_text(m.edge_length_relative_error) << "]\n";
    const double centroid_error = moments_error_bound(m, m.centroid);
    out << "  centroid        (" << number_text(m.centroid[0], centroid_error, digits) << ", "
        << number_text(m.centroid[1], centroid_error, digits) << ", " << number_text(m.centroid[2], centroid_error, digits)
        << ")" << unit_suffix(r, 1) << "\n";
    if (r.loaded) {
        const std::array<double, 6> b = report_bounds(r);
        out << "  bounds          " << point_text(std::span(b).first<3>()) << " to " << point_text(std::span(b).last<3>()) << unit_suffix(r, 1)
            << "; size " << shortest(b[3] - b[0]) << " x " << shortest(b[4] - b[1]) << " x " << shortest(b[5] - b[2])
            << (r.length_factor == 1 ? " (differences rounded once)\n" : " (converted, then rounded)\n");
    }
    // Each part's and shell's own figures (their surfaces' sums), at most 20 of each.
    const auto pieces = [&](const char* what, const std::vector<FileResult::Piece>& list) {
        for (std::size_t i = 0; i < list.size() && i < 20; ++i) {
            const MassProperties& p = list[i].m;
            const double c = moments_error_bound(p, p.centroid);
            out << "  " << what << (*what ? " " : "") << list[i].name << ": volume "
                << number_text(p.volume, p.volume_correctly_rounded ? 0 : p.volume_error_bound, digits) << unit_suffix(r, 3)
                << ", area " << number_text(p.area, p.area * p.area_relative_error, digits) << unit_suffix(r, 2)
                << ", centroid (" << number_text(p.centroid[0], c, digits) << ", " << number_text(p.centroid[1], c, digits)
                << ", " << number_text(p.centroid[2], c, digits) << ")" << unit_suffix(r, 1) << ", " << list[i].faces
                << " faces\n";
        }
        if (list.size() > 20) out << "  ... " << list.size() - 20 << " more (--json lists them)\n";
    };
    if (r.part_figures.size() > 1) pieces("part", r.part_figures);
    if (r.shell_figures.size() > 1) pieces("", r.shell_figures);  // named "shell k"
    // A symmetric tensor {xx, yy, zz, xy, yz, zx} with labelled rows and columns.
    auto tensor = [&](const char* title, const std::array<double, 6>& s) {
        const double error = moments_error_bound(m, s);
        char line[256];
        out << "  " << title;
        if (!r.length_unit.empty()) out << " [" << mass_unit_suffix(r, 5).substr(1) << "]";
        out << "\n";
        std::snprintf(line, sizeof line, "      %24s %24s %24s\n", "x", "y", "z");
        out << line;
        const double rows[3][3] = {{s[0], s[3], s[5]}, {s[3], s[1], s[4]}, {s[5], s[4], s[2]}};
        for (int i = 0; i < 3; ++i) {
            std::snprintf(line, sizeof line, "    %c %24s %24s %24s\n", "xyz"[i],
                          number_text(rows[i][0], error, digits).c_str(), number_text(rows[i][1], error, digits).c_str(),
                          number_text(rows[i][2], error, digits).c_str());
            out << line;
        }
    };
    tensor("second moments about the origin (density × ∫ x_i x_j)", m.second_moments);
    tensor("inertia tensor about the origin", m.inertia_origin);
    tensor("inertia tensor about the centroid", m.inertia_centroid);
    if (std::isfinite(m.inertia_centroid[0])) {
        const PrincipalInertia p = principal_inertia(m);
        out << "  principal moments " << number_text(p.moments[0], p.moment_error, digits) << ", "
            << number_text(p.moments[1], p.moment_error, digits) << ", " << number_text(p.moments[2], p.moment_error, digits)
            << mass_unit_suffix(r, 5) << "   [each within " << bound_text(p.moment_error) << "]\n";
        for (std::size_t k = 0; k < 3; ++k) {
            const double e = std::isfinite(p.axis_angle[k]) ? p.axis_angle[k] : 0;
            out << "  principal axis " << k + 1 << "  (" << number_text(p.axes[k][0], e, digits) << ", "
                << number_text(p.axes[k][1], e, digits) << ", " << number_text(p.axes[k][2], e, digits) << ")";
            if (std::isfinite(p.axis_angle[k]))
                out << "   [within " << bound_text(p.axis_angle[k]) << " rad]\n";
            else
                out << "   [not determined: equal moments]\n";
        }
    }
    if (m.moments_correctly_rounded)
        out << "  centroid, moments and inertia: correctly rounded (exact values of the coordinates as read, rounded once)\n";
    else
        out << "  centroid, moments and inertia: relative error <= " << shortest(m.moments_relative_error)
            << " (of the largest magnitude in the same quantity)\n";
    if (!r.warning.empty()) out << "  warning: " << r.warning << "\n";
    return out.str();
}

std::string inertial_element(const FileResult& r, const Request& request, bool sdf) {
    const MassProperties& m = *r.mass;
    const auto& c = m.centroid;
    const auto& i = m.inertia_centroid;  // {xx, yy, zz, xy, yz, zx}
    std::ostringstream out;
    // Each value the shortest decimal within its bound (mass, centroid and
    // inertia each relative to the largest entry of its own array), so the
    // printed value is within twice the bound of the exact one.
    const double rel = m.moments_correctly_rounded ? 0.0 : m.moments_relative_error;
    const double c_err = moments_error_bound(m, c), i_err = moments_error_bound(m, i), m_err = rel * std::fabs(m.mass);
    const auto cs = [&](double x) { return shortest_within(x, c_err); };
    const auto is = [&](double x) { return shortest_within(x, i_err); };
    const std::string units = r.length_unit.empty() ? std::string("units as in the file")
                                                    : "lengths in " + r.length_unit +
                                                          (r.mass_unit.empty() ? "" : ", mass in " + r.mass_unit);
    out << "<!-- " << r.file << ": " << units << ", density " << density_text(request) << "; "
        << (m.moments_correctly_rounded
                ? std::string("correctly rounded")
                : "each value within " + bound_text(2 * rel) + " of the largest in its quantity")
        << " -->\n";
    const std::string mass = shortest_within(m.mass, m_err);
    if (sdf) {
        out << "<inertial>\n  <pose>" << cs(c[0]) << " " << cs(c[1]) << " " << cs(c[2]) << " 0 0 0</pose>\n  <mass>"
            << mass << "</mass>\n  <inertia>\n"
            << "    <ixx>" << is(i[0]) << "</ixx>\n    <ixy>" << is(i[3]) << "</ixy>\n"
            << "    <ixz>" << is(i[5]) << "</ixz>\n    <iyy>" << is(i[1]) << "</iyy>\n"
            << "    <iyz>" << is(i[4]) << "</iyz>\n    <izz>" << is(i[2]) << "</izz>\n"
            << "  </inertia>\n</inertial>\n";
    } else {
        out << "<inertial>\n  <origin xyz=\"" << cs(c[0]) << " " << cs(c[1]) << " " << cs(c[2])
            << "\" rpy=\"0 0 0\"/>\n  <mass value=\"" << mass << "\"/>\n"
            << "  <inertia ixx=\"" << is(i[0]) << "\" ixy=\"" << is(i[3]) << "\" ixz=\"" << is(i[5])
            << "\" iyy=\"" << is(i[1]) << "\" iyz=\"" << is(i[4]) << "\" izz=\"" << is(i[2]) << "\"/>\n</inertial>\n";
    }
    return out.str();
}

std::string check_report(const FileResult& r) {
    std::ostringstream out;
    const auto& t = *r.policy.topology;
    const auto& l = *r.loaded;
    out << r.file << "  (" << format_name(l.format) << ", " << l.encoding << (l.gzip ? ", gzip" : "") << ")\n";
    for (const auto& n : l.notes) out << "  note: " << note_words(n) << " (" << n << ")\n";
    if (r.policy.welded) out << "  welded          " << weld_sentence(*r.policy.welded, r.weld_tolerance) << "\n";
    if (l.format == Format::stl && l.facet_normals_against_winding)
        out << "  facet normals   " << l.facet_normals_against_winding << " of " << t.triangles
            << " point against their triangle's winding (the winding decides the orientation)\n";
    if (r.policy.oriented) out << "  orientation     " << orient_sentence(*r.policy.oriented) << "\n";
    out << "  vertices        " << l.vertices_in_file << " read, " << t.vertices_welded << " after welding, "
        << t.vertices_referenced << " used by faces\n";
    out << "  faces           " << t.faces << " (" << t.faces_with_lt3_vertices << " with fewer than 3 vertices, ignored), "
        << t.triangles << " fan triangles\n";
    out << "  edges           " << t.edges << "\n";
    out << "  boundary        " << t.boundary_edges << " edges";
    if (t.boundary_edges) out << " in " << t.holes << " hole" << (t.holes == 1 ? "" : "s") << " (boundary loops)";
    out << "\n";
    out << "  non-manifold    " << t.nonmanifold_edges << "\n";
    out << "  misoriented     " << t.misoriented_edges << "\n";
    out << "  unbalanced      " << t.unbalanced_edges << "\n";
    out << "  degenerate      " << t.zero_area_triangles << " triangles of zero area (" << t.triangles_with_repeated_vertex
        << " of them with a repeated vertex), " << t.degenerate_edge_uses << " zero-length sides\n";
    out << "  Euler char.     " << t.euler_characteristic << "\n";
    out << "  components      " << t.components_edge_connected << " edge-connected, " << t.components_vertex_connected
        << " vertex-connected\n";
    out << "  closed 2-cycle  " << (t.closed_2_cycle ? "yes: the volume does not depend on the origin"
                                                      : "no: " + unbalanced_message(t, r.policy.closes_at_tolerance))
        << "\n";
    std::size_t shown = 0;
    for (const Shell& s : t.shells) {
        if (shown++ == 20) {
            out << "  ... " << (t.shells.size() - 20) << " more shells\n";
            break;
        }
        const bool crossing = r.policy.solid && s.first_face < r.policy.solid->face_crosses.size() && r.policy.solid->face_crosses[s.first_face];
        out << "  shell " << shown << ": " << (crossing ? std::string_view("crossing another shell") : shell_role_name(s.role))
            << (s.role == ShellRole::open ? std::string() : ", volume " + shortest(s.signed_volume)) << ", "
            << s.faces << " faces, χ = " << s.euler_characteristic;
        if (s.genus) out << ", genus " << *s.genus;
        if (s.boundary_edges) out << ", " << s.boundary_edges << " boundary edges";
        out << "\n";
    }
    if (r.policy.solid && (r.policy.solid->crossing_pairs > 0 || r.policy.solid->overlapping_shells > 0)) {
        out << "  overlap         " << r.policy.solid->overlapping_shells << " overlapping shells, " << r.policy.solid->crossing_pairs
            << " crossing triangle pairs";
        if (r.policy.solid->crossing_example)
            out << " (e.g. faces " << (*r.policy.solid->crossing_example)[0] << " and " << (*r.policy.solid->crossing_example)[1] << ")";
        out << "; the solid (winding number >= 1) has volume " << shortest(r.policy.solid->properties.volume)
            << ", the shells add up to " << shortest(r.policy.solid->winding_volume) << "\n";
    }
    if (r.policy.self) out << "  self-crossing   " << self_crossing_line(r) << "\n";
    if (t.cavities || t.inside_out_shells || t.nested_shells)
        out << "  nesting         " << t.cavities << " cavities, " << t.inside_out_shells << " inside-out shells, "
            << t.nested_shells << " shells inside other solids\n";
    out << "  verdict         ";
    if (r.repairs.empty()) {
        out << "a solid as it is: ready to print or simulate\n";
    } else {
        out << "not ready — ";
        for (std::size_t i = 0; i < r.repairs.size(); ++i) out << (i ? "; " : "") << r.repairs[i];
        out << "\n";
    }
    return out.str();
}

}  // namespace polyvol::cli

// src/report/report_json.cpp — polyvol/report.hpp's report_json: the keys
// of a file's report, written once (the CLI prints them, Python's
// measure_file is them).
#include <cmath>
#include <limits>

#include "polyvol/report.hpp"

namespace polyvol {
namespace {

// Symmetric {xx,yy,zz,xy,yz,zx} -> 3x3 rows.
nlohmann::json matrix3(const std::array<double, 6>& s) {
    return nlohmann::json::array({{json_number(s[0]), json_number(s[3]), json_number(s[5])},
                                  {json_number(s[3]), json_number(s[1]), json_number(s[4])},
                                  {json_number(s[5]), json_number(s[4]), json_number(s[2])}});
}

// A piece's figures in the JSON: each with its bound.
nlohmann::json piece_json(const MassProperties& m) {
    return {{"volume", json_number(m.volume)},
            {"volume_error_bound", m.volume_correctly_rounded ? 0.0 : m.volume_error_bound},
            {"area", json_number(m.area)},
            {"area_relative_error", m.area_relative_error},
            {"centroid", {json_number(m.centroid[0]), json_number(m.centroid[1]), json_number(m.centroid[2])}},
            {"centroid_error_bound", json_number(moments_error_bound(m, m.centroid))}};
}

}  // namespace

nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v + 0.0) : nlohmann::json(nullptr); }  // no -0

std::array<double, 6> report_bounds(const FileReport& r) {
    std::array<double, 6> b = face_bounds(r.loaded->mesh.view());
    for (double& x : b) x *= r.length_factor;
    return b;
}

nlohmann::json report_json(const FileReport& r, const FileOptions& request) {
    nlohmann::json j;
    j["file"] = r.file;
    if (r.streamed) {  // no mesh loaded: what the stream knows of the file
        j["format"] = "stl";
        j["encoding"] = "binary_le";
        j["streamed"] = true;
        j["triangles"] = r.triangles;
        j["closed_2_cycle"] = true;  // by the fingerprint (else the file is loaded)
    }
    if (r.loaded) {
        const auto& l = *r.loaded;
        j["format"] = std::string(format_name(l.format));
        j["encoding"] = l.encoding;
        j["gzip"] = l.gzip;
        j["notes"] = l.notes;
        if (l.format == Format::stl) j["facet_normals_against_winding"] = l.facet_normals_against_winding;
        j["vertices"] = l.vertices_in_file;
        j["faces"] = l.mesh.face_count();
        j["triangles"] = l.mesh.view().triangle_count();
        if (r.policy.welded) {
            j["weld_tolerance"] = r.weld_tolerance;
            j["welded_points_moved"] = r.policy.welded->moved;
            j["weld_largest_move"] = r.policy.welded->largest_move;
        }
        if (r.policy.oriented) {
            j["oriented"] = r.policy.oriented->orientable;
            j["oriented_faces_flipped"] = r.policy.oriented->flipped;
            j["oriented_shells_undecided"] = r.policy.oriented->undecided;
        }
        if (request.need_mass && !request.keep_signed && !request.orient)
            j["turned_outward_faces"] = r.policy.turned_outward ? r.policy.turned_outward->flipped : 0;
    } else if (!r.streamed) {
        j["format"] = nullptr;
    }
    if (r.policy.topology) {
        const auto& t = *r.policy.topology;
        j["boundary_edges"] = t.boundary_edges;
        j["holes"] = t.holes;
        j["nonmanifold_edges"] = t.nonmanifold_edges;
        j["misoriented_edges"] = t.misoriented_edges;
        j["unbalanced_edges"] = t.unbalanced_edges;
        j["closed_2_cycle"] = t.closed_2_cycle;
        j["euler_characteristic"] = t.euler_characteristic;
        j["vertices_welded"] = t.vertices_welded;
        j["edges"] = t.edges;
        if (t.unbalanced_example) {
            const auto& e = *t.unbalanced_example;
            j["unbalanced_example"] = {{e[0], e[1], e[2]}, {e[3], e[4], e[5]}};
        }
    }
    if (r.policy.topology && !request.volume_only) {  // shells, nesting, degenerate faces: not computed for --volume-only
        const auto& t = *r.policy.topology;
        j["components"] = t.components_edge_connected;
        // zero_area_triangles counts those with a repeated vertex too (their cross product is zero)
        j["degenerate_triangles"] = t.zero_area_triangles;
        j["cavities"] = t.cavities;
        j["inside_out_shells"] = t.inside_out_shells;
        nlohmann::json shells = nlohmann::json::array();
        for (const Shell& s : t.shells) {
            // An open shell's volume depends on the origin: not a figure of the file.
            nlohmann::json sj{{"signed_volume", s.role == ShellRole::open ? nlohmann::json(nullptr) : nlohmann::json(s.signed_volume)},
                              {"faces", s.faces},
                              {"boundary_edges", s.boundary_edges},
                              {"unbalanced_edges", s.unbalanced_edges},
                              {"euler_characteristic", s.euler_characteristic},
                              {"winding_of_others", s.winding_of_others},
                              {"role", r.policy.solid && s.first_face < r.policy.solid->face_crosses.size() &&
                                               r.policy.solid->face_crosses[s.first_face]
                                           ? std::string("crossing")
                                           : std::string(shell_role_name(s.role))}};
            sj["genus"] = s.genus ? nlohmann::json(*s.genus) : nlohmann::json(nullptr);
            if (const std::size_t i = shells.size(); i < r.shell_figures.size()) sj.update(piece_json(r.shell_figures[i].m));
            shells.push_back(std::move(sj));
        }
        j["shells"] = std::move(shells);
    }
    if (r.loaded) {  // a surface crossing itself within a shell: looked for, and found
        j["self_crossing_checked"] = r.policy.self.has_value();
        if (r.policy.self) {
            j["self_crossing_pairs"] = r.policy.self->pairs;
            if (r.policy.self->example) j["self_crossing_example"] = {(*r.policy.self->example)[0], (*r.policy.self->example)[1]};
        }
    }
    if (!request.need_mass && r.loaded) {  // `check`: the solid, and whether the file is one as it is
        if (r.policy.solid) {
            j["solid_volume"] = json_number(r.policy.solid->properties.volume);
            j["winding_volume"] = json_number(r.policy.solid->winding_volume);
            j["overlapping_shells"] = r.policy.solid->overlapping_shells;
            j["crossing_pairs"] = r.policy.solid->crossing_pairs;
        }
        j["ready"] = r.repairs.empty() && r.exit_code == Exit::ok;
        j["repairs"] = r.repairs;
    }
    if (request.need_mass) {
        j["method"] = std::string(method_name(request.measure.method));
        j["accuracy"] = std::string(accuracy_name(request.measure.accuracy));
        if (!request.volume_only) j["density"] = request.measure.density;
    }
    if (r.mass) {
        const auto& m = *r.mass;
        j["unit"] = r.length_unit.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.length_unit);
        j["mass_unit"] = r.mass_unit.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.mass_unit);
        j["length_factor"] = r.length_factor;
        j["accuracy"] = m.volume_correctly_rounded ? "correctly-rounded" : "error-bound";
        j["volume"] = json_number(m.volume);
        j["volume_error_bound"] = m.volume_error_bound;
        j["overlap_checked"] = r.policy.overlap_checked;  // the volume above is already the solid's (use_solid_properties)
        if (r.policy.solid) {
            j["winding_volume"] = json_number(r.policy.solid->winding_volume);
            j["overlapping_shells"] = r.policy.solid->overlapping_shells;
            j["crossing_pairs"] = r.policy.solid->crossing_pairs;
            j["self_crossing_resolved"] = r.policy.solid->shells_crossing_themselves > 0;
        } else if (r.policy.overlap_checked) {
            j["winding_volume"] = json_number(m.volume);
            j["overlapping_shells"] = 0;
            j["crossing_pairs"] = 0;
            j["self_crossing_resolved"] = false;
        }
    }
    if (r.mass && !request.volume_only) {
        const auto& m = *r.mass;
        j["mass"] = json_number(m.mass);
        j["area"] = json_number(m.area);
        j["area_relative_error"] = m.area_relative_error;
        j["centroid"] = {json_number(m.centroid[0]), json_number(m.centroid[1]), json_number(m.centroid[2])};
        if (r.loaded) {
            const std::array<double, 6> b = report_bounds(r);
            j["bounds"] = {json_number(b[0]), json_number(b[1]), json_number(b[2]), json_number(b[3]), json_number(b[4]), json_number(b[5])};
            j["size"] = {json_number(b[3] - b[0]), json_number(b[4] - b[1]), json_number(b[5] - b[2])};
        }
        j["first_moments"] = {json_number(m.first_moments[0]), json_number(m.first_moments[1]), json_number(m.first_moments[2])};
        j["second_moments"] = matrix3(m.second_moments);
        j["inertia"] = matrix3(m.inertia_centroid);
        j["inertia_origin"] = matrix3(m.inertia_origin);
        j["moments_accuracy"] = m.moments_correctly_rounded ? "correctly-rounded" : "error-bound";
        j["moments_relative_error"] = m.moments_relative_error;
        // null where the inertia is not finite (no faces, say), so that the keys are always there
        {
            const double nan = std::numeric_limits<double>::quiet_NaN();
            PrincipalInertia p;
            if (std::isfinite(m.inertia_centroid[0]))
                p = principal_inertia(m);
            else
                p = {{nan, nan, nan}, {{{nan, nan, nan}, {nan, nan, nan}, {nan, nan, nan}}}, nan, {nan, nan, nan}};
            j["principal_moments"] = {json_number(p.moments[0]), json_number(p.moments[1]), json_number(p.moments[2])};
            j["principal_axes"] = nlohmann::json::array();
            for (const auto& a : p.axes) j["principal_axes"].push_back({json_number(a[0]), json_number(a[1]), json_number(a[2])});
            j["principal_moment_error"] = json_number(p.moment_error);
            j["principal_axis_angle_bound"] = {json_number(p.axis_angle[0]), json_number(p.axis_angle[1]), json_number(p.axis_angle[2])};
        }
        j["edge_length"] = json_number(m.edge_length);
        j["edge_length_relative_error"] = m.edge_length_relative_error;
        if (r.loaded && !r.loaded->parts.empty()) {
            nlohmann::json parts = nlohmann::json::array();
            for (const FileReport::Piece& p : r.part_figures) {
                nlohmann::json pj{{"name", p.name}, {"faces", p.faces}};
                pj.update(piece_json(p.m));
                parts.push_back(std::move(pj));
            }
            j["parts"] = std::move(parts);
        }
    }
    if (!r.warning.empty()) j["warning"] = r.warning;
    if (!r.error.empty()) j["error"] = r.error;
    j["exit_code"] = r.exit_code;
    return j;
}

}  // namespace polyvol

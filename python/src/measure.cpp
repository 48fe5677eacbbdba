// python/src/measure.cpp — mass properties (measure.hpp), topology
// (topology.hpp) and the volumes of booleans and overlapping shells
// (boolean.hpp) of meshes given as numpy arrays.
#include <cmath>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/solid.hpp"
#include "polyvol/topology.hpp"
#include "polyvol/units.hpp"

namespace polyvol::python {

Method parse_method(const std::string& s) {
    if (s == "cone") return Method::cone;
    if (s == "prism") return Method::prism;
    if (s == "pyramid") return Method::pyramid;
    if (s == "vtnb") return Method::vtnb;
    throw std::invalid_argument("method must be 'cone', 'prism', 'pyramid' or 'vtnb', not '" + s + "'");
}

Density parse_density_arg(const py::object& density, const std::string& mass_unit) {
    if (!mass_units_per_kg(mass_unit)) throw py::value_error("mass_unit must be 'kg', 'g' or 'lb'");
    Density d;
    if (py::isinstance<py::str>(density)) {
        const std::optional<Density> typed = parse_density(density.cast<std::string>());
        if (!typed)
            throw py::value_error("density must be a positive number, optionally with kg/m3 or g/cm3, not '" +
                                  density.cast<std::string>() + "'");
        d = *typed;
    } else {
        d.value = density.cast<double>();
    }
    if (mass_unit != "kg" && !d.si)
        throw py::value_error("mass_unit='" + mass_unit +
                              "' needs a density with a unit (e.g. '1.24g/cm3'): a plain number is already mass per "
                              "volume");
    return d;
}

Accuracy parse_accuracy(const std::string& s) {
    if (s == "correctly-rounded") return Accuracy::correctly_rounded;
    if (s == "fast") return Accuracy::fast;
    throw std::invalid_argument("accuracy must be 'correctly-rounded' or 'fast', not '" + s + "'");
}

namespace {

const char* status_name(BooleanStatus s) {
    switch (s) {
        case BooleanStatus::ok: return "ok";
        case BooleanStatus::a_not_closed: return "a_not_closed";
        case BooleanStatus::b_not_closed: return "b_not_closed";
        case BooleanStatus::a_inside_out: return "a_inside_out";
        case BooleanStatus::b_inside_out: return "b_inside_out";
        case BooleanStatus::a_overlaps_itself: return "a_overlaps_itself";
        case BooleanStatus::b_overlaps_itself: return "b_overlaps_itself";
        case BooleanStatus::invalid_coordinates: return "invalid_coordinates";
        case BooleanStatus::shell_crosses_itself: return "shell_crosses_itself";
        case BooleanStatus::shell_touches_itself: return "shell_touches_itself";
    }
    return "ok";
}

const char* solid_status_name(SolidStatus s) {
    switch (s) {
        case SolidStatus::ok: return "ok";
        case SolidStatus::open: return "open";
        case SolidStatus::misoriented: return "misoriented";
        case SolidStatus::not_orientable: return "not_orientable";
        case SolidStatus::bad_tolerance: return "bad_tolerance";
    }
    return "ok";
}

template <std::size_t N>
py::array_t<double> vec(const std::array<double, N>& a) {
    return copy_array<double>(std::span<const double>(a.data(), N), {static_cast<py::ssize_t>(N)});
}

}  // namespace

// The policy's options from Python's keywords (polyvol/solid.hpp).
SolidOptions solid_options(const py::dict& k) {
    SolidOptions o;
    if (k.contains("signed")) o.keep_signed = k["signed"].cast<bool>();
    if (k.contains("allow_open")) o.allow_open = k["allow_open"].cast<bool>();
    if (k.contains("orient")) o.orient = k["orient"].cast<bool>();
    if (k.contains("weld_tolerance")) o.weld_tolerance = k["weld_tolerance"].cast<double>();
    if (k.contains("solid")) o.resolve_overlaps = k["solid"].cast<bool>();
    return o;
}

// What the policy found, for Python: (status, message, notes).
py::tuple solid_verdict(const MeshSolid& s) {
    py::list notes;
    for (const SolidNote& n : s.notes) notes.append(n.text);
    return py::make_tuple(solid_status_name(s.status), s.message, notes);
}

namespace {

// Mass properties and the solid policy: measure_solid, solid_repairs, solid_parts, signed_volume, closedness.
void bind_mass(py::module_& m) {
    py::class_<MassProperties>(m, "_MassProperties")
        .def_readonly("volume", &MassProperties::volume)
        .def_readonly("mass", &MassProperties::mass)
        .def_readonly("area", &MassProperties::area)
        .def_readonly("edge_length", &MassProperties::edge_length)
        .def_property_readonly("first_moments", [](const MassProperties& p) { return vec(p.first_moments); })
        .def_property_readonly("centroid", [](const MassProperties& p) { return vec(p.centroid); })
        .def_property_readonly("second_moments", [](const MassProperties& p) { return symmetric3(p.second_moments); })
        .def_property_readonly("inertia", [](const MassProperties& p) { return symmetric3(p.inertia_centroid); })
        .def_property_readonly("inertia_origin", [](const MassProperties& p) { return symmetric3(p.inertia_origin); })
        .def_readonly("volume_correctly_rounded", &MassProperties::volume_correctly_rounded)
        .def_readonly("volume_error_bound", &MassProperties::volume_error_bound)
        .def_readonly("moments_correctly_rounded", &MassProperties::moments_correctly_rounded)
        .def_readonly("moments_relative_error", &MassProperties::moments_relative_error)
        .def_readonly("area_relative_error", &MassProperties::area_relative_error)
        .def_readonly("edge_length_relative_error", &MassProperties::edge_length_relative_error)
        .def_property_readonly("method", [](const MassProperties& p) { return std::string(method_name(p.method)); })
        .def_property_readonly("accuracy",
                               [](const MassProperties& p) { return std::string(accuracy_name(p.accuracy)); });

    // mass_properties of the solid the mesh means (polyvol/solid.hpp), in
    // the units asked for (polyvol/units.hpp): ((status, message, notes),
    // MassProperties or None, {unit, mass_unit, length_factor, density,
    // warning, principal moments and axes, bounds}).
    m.def(
        "measure_solid",
        [](const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets,
           const std::string& method, const std::string& accuracy, const py::object& density, bool second_moments,
           bool edge_length, const py::dict& policy, const py::dict& units) {
            Mesh mesh = to_mesh(mesh_view(positions, indices, offsets));  // make_solid changes it
            MeasureOptions o;
            o.method = parse_method(method);
            o.accuracy = parse_accuracy(accuracy);
            o.second_moments = second_moments;
            o.edge_length = edge_length;
            const std::string mass_unit = units["mass_unit"].cast<std::string>();
            const Density d = parse_density_arg(density, mass_unit);
            const UnitsPlan plan = plan_units(units["declared"].cast<std::string>(),
                                              UnitsRequest{.units = units["units"].cast<std::string>(),
                                                           .to = units["to"].cast<std::string>(),
                                                           .scale = 1,
                                                           .scale_typed_exactly = true,
                                                           .density_si = d.si,
                                                           .metres_when_known = false});
            if (!plan.error.empty())
                throw py::value_error(plan.error.find("not known") != std::string::npos
                                          ? plan.error + ": units= gives it (" + kLengthUnitNames + ")"
                                          : plan.error);
            const DensityIn in = density_in(d, *length_unit(plan.length_unit.empty() ? "m" : plan.length_unit), mass_unit);
            o.density = in.value;
            const SolidOptions p = solid_options(policy);
            SolidMass r;
            std::array<double, 6> box{};
            {
                py::gil_scoped_release release;
                r = measure_solid(mesh, p, o);
                if (r.mass && (plan.length.factor != 1 || plan.length.relative_error > 0 || in.relative_error > 0))
                    scale_mass_properties(*r.mass, plan.length.factor, plan.length.relative_error, in.relative_error);
                box = face_bounds(mesh.view());
                for (double& x : box) x *= plan.length.factor;
            }
            py::dict info;
            info["unit"] = plan.length_unit.empty() ? py::object(py::none()) : py::object(py::str(plan.length_unit));
            info["mass_unit"] = d.si ? py::object(py::str(mass_unit)) : py::object(py::none());
            info["length_factor"] = plan.length.factor;
            info["density"] = in.value;
            info["warning"] = plan.warning;
            info["bounds"] = vec(box);
            if (r.mass && std::isfinite(r.mass->inertia_centroid[0])) {
                const PrincipalInertia pi = principal_inertia(*r.mass);
                info["principal_moments"] = vec(pi.moments);
                py::array_t<double> axes({3, 3});
                for (int i = 0; i < 3; ++i)
                    for (int k = 0; k < 3; ++k) axes.mutable_at(i, k) = pi.axes[static_cast<std::size_t>(i)][static_cast<std::size_t>(k)];
                info["principal_axes"] = axes;
                info["principal_moment_error"] = pi.moment_error;
                info["principal_axis_angle_bound"] = vec(pi.axis_angle);
            }
            return py::make_tuple(solid_verdict(r.solid), r.mass ? py::cast(*r.mass) : py::none(), info);
        },
        py::arg("positions"), py::arg("indices"), py::arg("offsets"), py::arg("method"), py::arg("accuracy"),
        py::arg("density"), py::arg("second_moments"), py::arg("edge_length"), py::arg("policy"), py::arg("units"));

    // Whether the mesh is a solid as it is (`polyvol check`'s verdict):
    // ((status, message, notes), repairs, the solid's figures or {}).
    m.def(
        "solid_repairs",
        [](const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets) {
            Mesh mesh = to_mesh(mesh_view(positions, indices, offsets));
            MeshSolid s;
            {
                py::gil_scoped_release release;
                s = make_solid(mesh, SolidOptions{.keep_signed = true, .shells = true});
            }
            py::dict solid;  // as `polyvol check --json` gives it, when solid_volume ran
            if (s.solid) {
                solid["solid_volume"] = s.solid->properties.volume;
                solid["winding_volume"] = s.solid->winding_volume;
                solid["overlapping_shells"] = s.solid->overlapping_shells;
                solid["crossing_pairs"] = s.solid->crossing_pairs;
            }
            return py::make_tuple(solid_verdict(s), repairs_needed(s), solid);
        },
        py::arg("positions"), py::arg("indices"), py::arg("offsets"));

    // The solid of one body for the grid (polyvol/solid.hpp): ((status,
    // message, notes), [(positions, indices, offsets), ...] whose union it
    // is, its volume or None when it is the mesh's own).
    m.def(
        "solid_parts",
        [](const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets,
           const py::dict& policy) {
            Mesh mesh = to_mesh(mesh_view(positions, indices, offsets));
            SolidBody body;
            {
                py::gil_scoped_release release;
                body = solid_body(mesh, solid_options(policy));
            }
            if (!body.not_split.empty())
                return py::make_tuple(py::make_tuple("not_split", body.not_split, py::list()), py::list(), py::none());
            if (body.parts.empty() && body.solid.status == SolidStatus::ok) body.parts.push_back(std::move(mesh));
            py::list arrays;
            for (Mesh& part : body.parts) {
                const auto n = static_cast<py::ssize_t>(part.vertex_count());
                py::object part_offsets = part.face_offsets.empty()
                                         ? py::object(py::none())
                                         : py::object(adopt_array(std::move(part.face_offsets), {static_cast<py::ssize_t>(part.face_offsets.size())}));
                const auto ni = static_cast<py::ssize_t>(part.indices.size());
                arrays.append(py::make_tuple(adopt_array(std::move(part.positions), {n, 3}),
                                             adopt_array(std::move(part.indices), {ni}), part_offsets));
            }
            const py::object volume = body.solid.resolved() ? py::object(py::float_(body.volume)) : py::none();
            return py::make_tuple(solid_verdict(body.solid), arrays, volume);
        },
        py::arg("positions"), py::arg("indices"), py::arg("offsets"), py::arg("policy"));

    m.def(
        "signed_volume",
        [](const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets,
           const std::string& method, const std::string& accuracy) {
            const MeshView view = mesh_view(positions, indices, offsets);
            const Method me = parse_method(method);
            const Accuracy ac = parse_accuracy(accuracy);
            py::gil_scoped_release release;
            return signed_volume(view, me, ac);
        },
        py::arg("positions"), py::arg("indices"), py::arg("offsets"), py::arg("method"), py::arg("accuracy"));

    m.def(
        "closedness",
        [](const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets) {
            const MeshView view = mesh_view(positions, indices, offsets);
            py::gil_scoped_release release;
            const Closedness c = fingerprint_closedness(view);
            return std::string(c == Closedness::closed ? "closed" : c == Closedness::open ? "open" : "undecided");
        },
        py::arg("positions"), py::arg("indices"), py::arg("offsets"));

}

// Topology: shells, the topology report, self-crossings.
void bind_topology(py::module_& m) {
    py::class_<Shell>(m, "_Shell")
        .def_readonly("signed_volume", &Shell::signed_volume)
        .def_readonly("faces", &Shell::faces)
        .def_readonly("vertices", &Shell::vertices)
        .def_readonly("edges", &Shell::edges)
        .def_readonly("boundary_edges", &Shell::boundary_edges)
        .def_readonly("unbalanced_edges", &Shell::unbalanced_edges)
        .def_readonly("euler_characteristic", &Shell::euler_characteristic)
        .def_readonly("genus", &Shell::genus)
        .def_readonly("winding_of_others", &Shell::winding_of_others)
        .def_readonly("first_face", &Shell::first_face)
        .def_property_readonly("role", [](const Shell& s) { return std::string(shell_role_name(s.role)); });

    py::class_<TopologyReport>(m, "TopologyReport")
        .def_readonly("faces", &TopologyReport::faces)
        .def_readonly("faces_with_lt3_vertices", &TopologyReport::faces_with_lt3_vertices)
        .def_readonly("triangles", &TopologyReport::triangles)
        .def_readonly("vertices_welded", &TopologyReport::vertices_welded)
        .def_readonly("vertices_referenced", &TopologyReport::vertices_referenced)
        .def_readonly("edges", &TopologyReport::edges)
        .def_readonly("boundary_edges", &TopologyReport::boundary_edges)
        .def_readonly("holes", &TopologyReport::holes)
        .def_readonly("nonmanifold_edges", &TopologyReport::nonmanifold_edges)
        .def_readonly("misoriented_edges", &TopologyReport::misoriented_edges)
        .def_readonly("unbalanced_edges", &TopologyReport::unbalanced_edges)
        .def_readonly("degenerate_edge_uses", &TopologyReport::degenerate_edge_uses)
        .def_readonly("triangles_with_repeated_vertex", &TopologyReport::triangles_with_repeated_vertex)
        .def_readonly("zero_area_triangles", &TopologyReport::zero_area_triangles)
        .def_readonly("euler_characteristic", &TopologyReport::euler_characteristic)
        .def_readonly("components_vertex_connected", &TopologyReport::components_vertex_connected)
        .def_readonly("components_edge_connected", &TopologyReport::components_edge_connected)
        .def_readonly("closed", &TopologyReport::closed)
        .def_readonly("edge_manifold", &TopologyReport::edge_manifold)
        .def_readonly("consistently_oriented", &TopologyReport::consistently_oriented)
        .def_readonly("closed_2_cycle", &TopologyReport::closed_2_cycle)
        .def_readonly("unbalanced_example", &TopologyReport::unbalanced_example)
        .def_readonly("shells", &TopologyReport::shells)
        .def_readonly("cavities", &TopologyReport::cavities)
        .def_readonly("inside_out_shells", &TopologyReport::inside_out_shells)
        .def_readonly("nested_shells", &TopologyReport::nested_shells);

    m.def(
        "topology",
        [](const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets, bool shells) {
            const MeshView view = mesh_view(positions, indices, offsets);
            py::gil_scoped_release release;
            return analyze_topology(view, {shells});
        },
        py::arg("positions"), py::arg("indices"), py::arg("offsets"), py::arg("shells"));

    py::class_<SelfCrossings>(m, "_SelfCrossings")
        .def_property_readonly("status", [](const SelfCrossings& s) { return std::string(status_name(s.status)); })
        .def_readonly("pairs", &SelfCrossings::pairs)
        .def_readonly("candidate_pairs", &SelfCrossings::candidate_pairs)
        .def_readonly("example", &SelfCrossings::example);
    m.def(
        "self_crossings",
        [](const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets) {
            const MeshView view = mesh_view(positions, indices, offsets);
            py::gil_scoped_release release;
            return self_crossings(view);
        },
        py::arg("positions"), py::arg("indices"), py::arg("offsets"));

}

// Solids of overlapping shells and the booleans, with their units.
void bind_booleans(py::module_& m) {
    py::class_<SolidVolume>(m, "_SolidVolume")
        .def_property_readonly("status", [](const SolidVolume& s) { return std::string(status_name(s.status)); })
        .def_property_readonly("message",
                               [](const SolidVolume& s) { return std::string(boolean_status_message(s.status)); })
        .def_property_readonly("volume", [](const SolidVolume& s) { return s.properties.volume; })
        .def_readonly("winding_volume", &SolidVolume::winding_volume)
        .def_readonly("shells", &SolidVolume::shells)
        .def_readonly("overlapping_shells", &SolidVolume::overlapping_shells)
        .def_readonly("crossing_pairs", &SolidVolume::crossing_pairs)
        .def_readonly("crossing_example", &SolidVolume::crossing_example)
        .def_readonly("within_checked", &SolidVolume::within_checked)
        .def_readonly("self_crossing_pairs", &SolidVolume::self_crossing_pairs)
        .def_readonly("shells_crossing_themselves", &SolidVolume::shells_crossing_themselves)
        .def_readonly("self_crossing_example", &SolidVolume::self_crossing_example)
        .def_property_readonly("face_crosses",
                               [](const SolidVolume& s) {
                                   return copy_array<uint8_t>(s.face_crosses,
                                                              {static_cast<py::ssize_t>(s.face_crosses.size())});
                               })
        .def_readonly("moments", &SolidVolume::moments)
        .def_property_readonly("first_moments", [](const SolidVolume& s) { return vec(s.properties.first_moments); })
        .def_property_readonly("second_moments",
                               [](const SolidVolume& s) { return symmetric3(s.properties.second_moments); })
        .def_property_readonly("centroid", [](const SolidVolume& s) { return vec(s.properties.centroid); })
        .def_property_readonly("inertia", [](const SolidVolume& s) { return symmetric3(s.properties.inertia_centroid); })
        .def_property_readonly("inertia_relative_error",
                               [](const SolidVolume& s) { return s.properties.moments_relative_error; });
    m.def(
        "solid_volume",
        [](const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets, bool moments,
           bool within_shells) {
            const MeshView view = mesh_view(positions, indices, offsets);
            py::gil_scoped_release release;
            return solid_volume(view, {.moments = moments, .within_shells = within_shells});
        },
        py::arg("positions"), py::arg("indices"), py::arg("offsets"), py::arg("moments"),
        py::arg("within_shells") = false);

    py::class_<BooleanVolumes>(m, "_BooleanVolumes")
        .def_property_readonly("status", [](const BooleanVolumes& b) { return std::string(status_name(b.status)); })
        .def_property_readonly("message",
                               [](const BooleanVolumes& b) { return std::string(boolean_status_message(b.status)); })
        .def_readonly("volume_a", &BooleanVolumes::volume_a)
        .def_readonly("volume_b", &BooleanVolumes::volume_b)
        .def_readonly("intersection", &BooleanVolumes::intersection)
        .def_readonly("union", &BooleanVolumes::union_volume)
        .def_readonly("volume_error_bound", &BooleanVolumes::volume_error_bound)
        .def_readonly("a_minus_b", &BooleanVolumes::a_minus_b)
        .def_readonly("b_minus_a", &BooleanVolumes::b_minus_a)
        .def_readonly("area_a", &BooleanVolumes::area_a)
        .def_readonly("area_b", &BooleanVolumes::area_b)
        .def_readonly("area_intersection", &BooleanVolumes::area_intersection)
        .def_readonly("area_union", &BooleanVolumes::area_union)
        .def_readonly("area_a_minus_b", &BooleanVolumes::area_a_minus_b)
        .def_readonly("area_b_minus_a", &BooleanVolumes::area_b_minus_a)
        .def_readonly("area_error_bound", &BooleanVolumes::area_error_bound)
        .def_readonly("triangles_a", &BooleanVolumes::triangles_a)
        .def_readonly("triangles_b", &BooleanVolumes::triangles_b)
        .def_readonly("candidate_pairs", &BooleanVolumes::candidate_pairs)
        .def_readonly("crossing_pairs", &BooleanVolumes::crossing_pairs)
        .def_readonly("rational_terms", &BooleanVolumes::rational_terms);
    // The booleans of the solids two meshes mean (`polyvol overlap`):
    // ((status, message, notes) of A, of B, BooleanVolumes or None).
    m.def(
        "overlap_solids",
        [](const Doubles& pa, const Indices& ia, const std::optional<Indices>& oa, const Doubles& pb,
           const Indices& ib, const std::optional<Indices>& ob, const py::dict& policy, const py::dict& units) {
            Mesh a = to_mesh(mesh_view(pa, ia, oa)), b = to_mesh(mesh_view(pb, ib, ob));
            SolidOptions p = solid_options(policy);
            p.closedness_by_fingerprint = true;  // as `polyvol overlap`: no shells' report needed
            p.shells = false;
            // A and B in one unit (B converted where it states another), then
            // the figures in `to` (polyvol/units.hpp), as `polyvol overlap --units --to`.
            const PairUnits pu = pair_units(units["declared_a"].cast<std::string>(),
                                            units["declared_b"].cast<std::string>(), units["units"].cast<std::string>(),
                                            units["to"].cast<std::string>());
            if (!pu.error.empty())
                throw py::value_error(std::string(pu.error_operand == 0 ? "A: " : pu.error_operand == 1 ? "B: " : "") +
                                      pu.error + ": units= gives it (" + kLengthUnitNames + ")");
            const CommonUnit& c = pu.common;
            const double error_a = scale_coordinates(a, c.factors[0], units["error_a"].cast<double>());
            const double error_b = scale_coordinates(b, c.factors[1], units["error_b"].cast<double>());
            MeshSolid sa, sb;
            std::optional<BooleanVolumes> r;
            {
                py::gil_scoped_release release;
                sa = make_solid(a, p);
                if (sa.status == SolidStatus::ok) sb = make_solid(b, p);
                if (sa.status == SolidStatus::ok && sb.status == SolidStatus::ok) {
                    r = solid_booleans(a.view(), sa, b.view(), sb);
                    if (r->status == BooleanStatus::ok) {
                        widen_for_coordinate_error(*r, a.view(), error_a, b.view(), error_b);
                        scale_boolean_volumes(*r, pu.figures);
                    }
                }
            }
            py::list notes;
            for (std::size_t i = 0; i < 2; ++i)
                if (!c.notes[i].empty()) notes.append(std::string(i == 0 ? "A: " : "B: ") + c.notes[i]);
            const std::string& unit = pu.unit;
            return py::make_tuple(solid_verdict(sa), solid_verdict(sb), r ? py::cast(*r) : py::none(),
                                  unit.empty() ? py::object(py::none()) : py::object(py::str(unit)), notes);
        },
        py::arg("positions_a"), py::arg("indices_a"), py::arg("offsets_a"), py::arg("positions_b"),
        py::arg("indices_b"), py::arg("offsets_b"), py::arg("policy"), py::arg("units"));

    // Several meshes in one unit (polyvol/units.hpp): (error, unit or None,
    // [factor per mesh], [note per mesh]); each mesh's coordinates × its
    // factor, each product rounded once, is what scale_coordinates does.
    m.def(
        "common_unit",
        [](const std::vector<std::string>& declared, const std::string& units, const std::string& to) {
            const CommonUnit c = common_unit(declared, units, to);
            py::list factors;
            for (const LengthFactor& f : c.factors) factors.append(f.factor);
            return py::make_tuple(c.error, c.unit.empty() ? py::object(py::none()) : py::object(py::str(c.unit)),
                                  factors, c.notes);
        },
        py::arg("declared"), py::arg("units"), py::arg("to"));

    m.def(
        "boolean_volumes",
        [](const Doubles& pa, const Indices& ia, const std::optional<Indices>& oa, const Doubles& pb,
           const Indices& ib, const std::optional<Indices>& ob) {
            const MeshView a = mesh_view(pa, ia, oa), b = mesh_view(pb, ib, ob);
            py::gil_scoped_release release;
            return boolean_volumes(a, b);
        },
        py::arg("positions_a"), py::arg("indices_a"), py::arg("offsets_a"), py::arg("positions_b"),
        py::arg("indices_b"), py::arg("offsets_b"));
}

}  // namespace

void bind_measure(py::module_& m) {
    bind_mass(m);
    bind_topology(m);
    bind_booleans(m);
}

}  // namespace polyvol::python

// python/src/cells.cpp — meshes of cells (polyvol/cell_mesh_io.hpp) and the
// volume of bodies in every cell (polyvol/cells.hpp).
#include <memory>
#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "polyvol/cell_mesh_io.hpp"
#include "polyvol/cells.hpp"
#include "polyvol/units.hpp"

namespace polyvol::python {

namespace {

py::array_t<uint32_t> u32(py::object self, const std::vector<uint32_t>& v) {
    return view_array<uint32_t>(v.data(), {static_cast<py::ssize_t>(v.size())}, self);
}

// A body as body_in_cells took it (its solid's mesh, in the mesh's unit),
// kept for the bodies' union.
struct CellsBody {
    Mesh mesh;
    bool within = false;  // a shell crosses itself
    BodyInCells cells;    // its volumes and touched cells (for union_in_cells)
};

// BodyInCells as the dict polyvol.cells reads (the keys of `polyvol cells --json`).
py::dict result_dict(BodyInCells r) {
    py::dict d;
    const auto n = static_cast<py::ssize_t>(r.volumes.size());
    std::vector<uint8_t> cls(r.cell_class.size());
    for (std::size_t c = 0; c < cls.size(); ++c) cls[c] = static_cast<uint8_t>(r.cell_class[c]);
    d["volumes"] = adopt_array(std::move(r.volumes), {n});
    d["cell_class"] = adopt_array(std::move(cls), {n});
    d["inside_mesh"] = r.total;
    d["cells_sum"] = r.cells_sum;
    d["in_overlaps"] = r.in_overlaps;
    d["volume"] = r.body_volume;
    d["full_cells"] = r.full_cells;
    d["cut_cells"] = r.cut_cells;
    d["empty_cells"] = r.empty_cells;
    d["cells_intersected"] = r.touched_cells;
    if (!r.wetted_area.empty()) {
        d["wetted_area"] = adopt_array(std::move(r.wetted_area), {n});
        d["surface_normal"] = adopt_array(std::move(r.surface_normal), {n, 3});
        d["surface_bound"] = adopt_array(std::move(r.surface_bound), {n});
        d["wetted_area_total"] = r.wetted_area_total;
        d["wetted_area_total_bound"] = r.wetted_area_total_bound;
    }
    return d;
}

BodyInCells from_dict(const py::dict& d) {
    BodyInCells r;
    const auto v = d["volumes"].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
    r.volumes.assign(v.data(), v.data() + v.size());
    r.total = d["inside_mesh"].cast<double>();
    return r;
}

}  // namespace

void bind_cells(py::module_& m) {
    py::class_<CellsBody, std::shared_ptr<CellsBody>>(m, "_CellsBody");
    py::class_<LoadedCellMesh, std::shared_ptr<LoadedCellMesh>>(m, "CellMesh")
        .def_property_readonly("points",
                               [](py::object self) {
                                   const auto& l = self.cast<const LoadedCellMesh&>();
                                   return view_array<double>(l.mesh.points.data(),
                                                             {static_cast<py::ssize_t>(l.mesh.points.size() / 3), 3},
                                                             self);
                               })
        .def_property_readonly("face_offsets",
                               [](py::object self) { return u32(self, self.cast<const LoadedCellMesh&>().mesh.face_offsets); })
        .def_property_readonly("face_points",
                               [](py::object self) { return u32(self, self.cast<const LoadedCellMesh&>().mesh.face_points); })
        .def_property_readonly("owner",
                               [](py::object self) { return u32(self, self.cast<const LoadedCellMesh&>().mesh.owner); })
        .def_property_readonly("neighbour",
                               [](const LoadedCellMesh& l) {
                                   // -1 on the boundary, as numpy users expect.
                                   std::vector<int64_t> n(l.mesh.neighbour.begin(), l.mesh.neighbour.end());
                                   for (int64_t& x : n)
                                       if (x == kNoCell) x = -1;
                                   const auto size = static_cast<py::ssize_t>(n.size());
                                   return adopt_array(std::move(n), {size});
                               })
        .def_property_readonly("cell_count", [](const LoadedCellMesh& l) { return l.mesh.cells; })
        .def_property_readonly("face_count", [](const LoadedCellMesh& l) { return l.mesh.face_offsets.size() - 1; })
        .def_readonly("format", &LoadedCellMesh::format)
        .def_readonly("encoding", &LoadedCellMesh::encoding)
        .def_readonly("gzip", &LoadedCellMesh::gzip)
        .def_readonly("unit", &LoadedCellMesh::unit)
        .def_readonly("location", &LoadedCellMesh::location)
        .def_readonly("notes", &LoadedCellMesh::notes)
        .def_property_readonly("grid_dims",
                               [](const LoadedCellMesh& l) -> py::object {
                                   if (l.format != "grdecl") return py::none();
                                   return py::make_tuple(l.grid_dims[0], l.grid_dims[1], l.grid_dims[2]);
                               })
        .def_property_readonly("grid_index",
                               [](py::object self) -> py::object {
                                   const auto& l = self.cast<const LoadedCellMesh&>();
                                   if (l.format != "grdecl") return py::none();
                                   return view_array<uint64_t>(l.grid_index.data(),
                                                               {static_cast<py::ssize_t>(l.grid_index.size())}, self);
                               })
        .def_readonly("fault_faces", &LoadedCellMesh::fault_faces)
        .def_readonly("case_cells", &LoadedCellMesh::case_cells)
        .def_property_readonly("case_index",
                               [](py::object self) -> py::object {
                                   const auto& l = self.cast<const LoadedCellMesh&>();
                                   if (l.case_index.empty()) return py::none();
                                   return view_array<uint64_t>(l.case_index.data(),
                                                               {static_cast<py::ssize_t>(l.case_index.size())}, self);
                               })
        .def_property_readonly("cells_tile", [](const LoadedCellMesh& l) { return l.cells_tile; });

    m.def(
        "read_polymesh",
        [](const std::string& path, bool map_axes) {
            py::gil_scoped_release release;
            return std::make_shared<LoadedCellMesh>(read_cell_mesh(path, map_axes));
        },
        py::arg("path"), py::arg("map_axes") = true);

    m.def("foam_processor_dirs", &foam_processor_dirs, py::arg("case"));
    m.def(
        "cell_zone",
        [](const LoadedCellMesh& l, const std::string& zone) { return std::make_shared<LoadedCellMesh>(cell_zone(l, zone)); },
        py::arg("mesh"), py::arg("zone"));

    // The cells' own volumes and their total; check_cell_mesh's defect as a ValueError.
    m.def(
        "cell_volumes",
        [](const LoadedCellMesh& l) {
            CellVolumes v;
            {
                py::gil_scoped_release release;
                v = cell_volumes(l.mesh.view());
            }
            const auto n = static_cast<py::ssize_t>(v.volumes.size());
            return py::make_tuple(adopt_array(std::move(v.volumes), {n}), v.total);
        },
        py::arg("mesh"));

    // The region the cells cover, each point once (NaN: not decided).
    m.def(
        "covered_volume",
        [](const LoadedCellMesh& l) {
            py::gil_scoped_release release;
            return covered_volume(l.mesh.view());
        },
        py::arg("mesh"));

    // One body (positions, indices, offsets) in every cell, as `polyvol cells`
    // takes it: the solid policy, the body put in the mesh's unit (`unit`)
    // from `declared` or `units`. Returns (verdict, result dict or None, notes).
    m.def(
        "body_in_cells",
        [](const LoadedCellMesh& l, const Doubles& positions, const Indices& indices,
           const std::optional<Indices>& offsets, const py::dict& policy, const std::string& declared,
           const std::string& units, const std::string& unit, const Doubles& own, bool surface) {
            Mesh body = to_mesh(mesh_view(positions, indices, offsets));
            py::list notes;
            const UnitChange change = into_unit(declared, units, unit);
            if (!change.error.empty()) throw py::value_error(change.error);
            scale_coordinates(body, change.factor, 0);
            if (!change.note.empty()) notes.append(change.note);
            MeshSolid solid;
            std::optional<BodyInCells> r;
            const bool own_given = static_cast<std::size_t>(own.size()) == l.mesh.cells;
            {
                py::gil_scoped_release release;
                solid = make_solid(body, solid_options(policy));
                if (solid.status == SolidStatus::ok) {
                    const bool within = solid.solid && solid.solid->shells_crossing_themselves > 0;
                    r = body_in_cells(l.mesh.view(), body.view(),
                                      {.overlapping_shells = solid.resolved(), .within_shells = within,
                                       .reference = false, .own = own_given ? span_of(own) : std::span<const double>{},
                                       .cells_tile = l.cells_tile, .surface = surface});
                }
            }
            if (!r) return py::make_tuple(solid_verdict(solid), py::none(), notes);
            const bool within = solid.solid && solid.solid->shells_crossing_themselves > 0;
            BodyInCells kept;
            kept.volumes = r->volumes;
            kept.touched = r->touched;
            py::dict d = result_dict(std::move(*r));
            d["body"] = std::make_shared<CellsBody>(CellsBody{std::move(body), within, std::move(kept)});
            return py::make_tuple(solid_verdict(solid), d, notes);
        },
        py::arg("mesh"), py::arg("positions"), py::arg("indices"), py::arg("offsets"), py::arg("policy"),
        py::arg("declared"), py::arg("units"), py::arg("unit"), py::arg("own"), py::arg("surface"));

    // The bodies' union in every cell (union_in_cells), from the bodies
    // body_in_cells returned; and two bodies' intersection from the three results.
    m.def(
        "union_in_cells",
        [](const LoadedCellMesh& l, const std::vector<std::shared_ptr<CellsBody>>& bodies, const Doubles& own) {
            std::vector<MeshView> views;
            std::vector<BodyInCells> each;
            bool within = false;
            for (const auto& b : bodies) {
                views.push_back(b->mesh.view());
                each.push_back(b->cells);
                within = within || b->within;
            }
            BodyInCells r;
            {
                py::gil_scoped_release release;
                r = union_in_cells(l.mesh.view(), views, each,
                                   {.overlapping_shells = true, .within_shells = within, .reference = true,
                                    .own = span_of(own), .cells_tile = l.cells_tile, .surface = false});
            }
            return result_dict(std::move(r));
        },
        py::arg("mesh"), py::arg("bodies"), py::arg("own"));
    m.def(
        "intersection_in_cells",
        [](const py::dict& a, const py::dict& b, const py::dict& joined) {
            IntersectionInCells r = intersection_in_cells(from_dict(a), from_dict(b), from_dict(joined));
            const auto n = static_cast<py::ssize_t>(r.volumes.size());
            return py::make_tuple(adopt_array(std::move(r.volumes), {n}), r.total);
        },
        py::arg("a"), py::arg("b"), py::arg("union"));

    m.def(
        "write_foam_field",
        [](const LoadedCellMesh& l, const std::string& name, const Doubles& values, const std::string& time) {
            if (static_cast<std::size_t>(values.size()) != l.mesh.cells)
                throw py::value_error("write_foam_field: one value per cell (" + std::to_string(l.mesh.cells) +
                                      "), not " + std::to_string(values.size()));
            return write_foam_field(l.location, name, in_case_cells(l, span_of(values)), time);
        },
        py::arg("mesh"), py::arg("name"), py::arg("values"), py::arg("time"));

    m.def(
        "write_grdecl_keyword",
        [](const LoadedCellMesh& l, const std::string& path, const std::string& keyword, const Doubles& values) {
            write_grdecl_keyword(path, keyword, span_of(values), l);
        },
        py::arg("mesh"), py::arg("path"), py::arg("keyword"), py::arg("values"));
}

}  // namespace polyvol::python

// python/src/io.cpp — meshes read from files (polyvol/io.hpp) as zero-copy
// numpy views, and the grid writers (polyvol/grid_io.hpp).
#include <charconv>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "polyvol/grid_io.hpp"
#include "polyvol/io.hpp"
#include "polyvol/report.hpp"
#include "polyvol/simplicial.hpp"
#include "polyvol/units.hpp"

namespace polyvol::python {

namespace {

// A JSON value as the Python value json.loads gives (strings decoded with
// "replace": a file name that is not UTF-8 must not make the report throw).
py::object to_python(const nlohmann::json& j) {
    using T = nlohmann::json::value_t;
    switch (j.type()) {
        case T::boolean: return py::bool_(j.get<bool>());
        case T::number_integer: return py::int_(j.get<std::int64_t>());
        case T::number_unsigned: return py::int_(j.get<std::uint64_t>());
        case T::number_float: return py::float_(j.get<double>());
        case T::string: {
            const std::string& s = j.get_ref<const std::string&>();
            PyObject* o = PyUnicode_DecodeUTF8(s.data(), static_cast<Py_ssize_t>(s.size()), "replace");
            if (o == nullptr) throw py::error_already_set();
            return py::reinterpret_steal<py::object>(o);
        }
        case T::array: {
            py::list l;
            for (const nlohmann::json& e : j) l.append(to_python(e));
            return py::object(std::move(l));
        }
        case T::object: {
            py::dict d;
            for (const auto& [key, value] : j.items()) d[py::str(key)] = to_python(value);
            return py::object(std::move(d));
        }
        default: return py::none();
    }
}

LoadedMesh mesh_from_arrays(const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets) {
    const MeshView v = mesh_view(positions, indices, offsets);
    LoadedMesh l;
    l.mesh = to_mesh(v);
    l.vertices_in_file = l.mesh.vertex_count();
    return l;
}

}  // namespace

void bind_io(py::module_& m) {
    py::class_<LoadedMesh, std::shared_ptr<LoadedMesh>>(m, "Mesh")
        .def_property_readonly("vertices",
                               [](py::object self) {
                                   const auto& l = self.cast<const LoadedMesh&>();
                                   return view_array<double>(l.mesh.positions.data(),
                                                             {static_cast<py::ssize_t>(l.mesh.vertex_count()), 3}, self);
                               })
        .def_property_readonly("indices",
                               [](py::object self) {
                                   const auto& l = self.cast<const LoadedMesh&>();
                                   return view_array<uint32_t>(l.mesh.indices.data(),
                                                               {static_cast<py::ssize_t>(l.mesh.indices.size())}, self);
                               })
        .def_property_readonly("offsets",
                               [](py::object self) -> py::object {
                                   const auto& l = self.cast<const LoadedMesh&>();
                                   if (l.mesh.face_offsets.empty()) return py::none();
                                   return view_array<uint32_t>(
                                       l.mesh.face_offsets.data(),
                                       {static_cast<py::ssize_t>(l.mesh.face_offsets.size())}, self);
                               })
        .def_property_readonly("face_count", [](const LoadedMesh& l) { return l.mesh.face_count(); })
        .def_property_readonly("triangle_count", [](const LoadedMesh& l) { return l.mesh.view().triangle_count(); })
        .def_property_readonly("format", [](const LoadedMesh& l) { return std::string(format_name(l.format)); })
        .def_readonly("encoding", &LoadedMesh::encoding)
        .def_readonly("gzip", &LoadedMesh::gzip)
        .def_readonly("notes", &LoadedMesh::notes)
        .def_readonly("vertices_in_file", &LoadedMesh::vertices_in_file)
        .def_readonly("unit", &LoadedMesh::unit)
        .def_readonly("coordinate_error", &LoadedMesh::coordinate_error);

    m.def(
        "load",
        [](const std::string& path) {
            py::gil_scoped_release release;
            return std::make_shared<LoadedMesh>(read_mesh_file(path));
        },
        py::arg("path"));
    m.def(
        "load_bytes",
        [](const py::bytes& data, const std::string& name) {
            const std::string_view bytes = data;  // the bytes object outlives the call
            py::gil_scoped_release release;
            return std::make_shared<LoadedMesh>(read_mesh_memory(
                std::span<const std::byte>(reinterpret_cast<const std::byte*>(bytes.data()), bytes.size()), name));
        },
        py::arg("data"), py::arg("name"));
    m.def(
        "mesh_from_arrays",
        [](const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets) {
            return std::make_shared<LoadedMesh>(mesh_from_arrays(positions, indices, offsets));
        },
        py::arg("positions"), py::arg("indices"), py::arg("offsets"));

    m.def(
        "write_npy",
        [](const std::string& path, const Doubles& values) {
            std::vector<std::size_t> shape(values.shape(), values.shape() + values.ndim());
            py::gil_scoped_release release;
            write_npy(path, span_of(values), shape);
        },
        py::arg("path"), py::arg("values"));
    // arrays: a list of (name, values (cells[, components]) in polyvol's order, components)
    m.def(
        "write_vtk",
        [](const std::string& path, const Doubles& x, const Doubles& y, const Doubles& z,
           const std::vector<std::tuple<std::string, Doubles, int>>& arrays, bool image) {
            std::vector<CellArray> cells;
            for (const auto& [name, values, components] : arrays)
                cells.push_back({name, span_of(values), components, name == "cell_class"});  // UInt8 in the file
            py::gil_scoped_release release;
            if (image)
                write_vti(path, span_of(x), span_of(y), span_of(z), cells);
            else
                write_vtr(path, span_of(x), span_of(y), span_of(z), cells);
        },
        py::arg("path"), py::arg("x"), py::arg("y"), py::arg("z"), py::arg("arrays"), py::arg("image"));

    // What `polyvol measure --json FILE` (with --solid: self-crossings looked
    // for at any size) gives for the file: the library's report
    // (polyvol/report.hpp) under the keys report_json declares, as a dict;
    // never throwing for a bad file (errors are its fields).
    m.def(
        "measure_file_report",
        [](const std::string& path, const std::string& method, const std::string& accuracy, const py::object& density,
           const std::string& mass_unit, bool allow_open, bool solid, bool orient, bool keep_signed,
           double weld_tolerance, const std::string& units, const std::string& to, double scale) {
            // The arguments in the library's words, read by file_options as
            // the command line's flags are (a number as its shortest text,
            // which reads back as the same double).
            const auto text = [](double x) {
                char buf[64];
                return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
            };
            RequestWords w;
            w.method = method;
            w.accuracy = accuracy;
            w.density = py::isinstance<py::str>(density) ? density.cast<std::string>() : text(density.cast<double>());
            w.mass_unit = mass_unit;
            w.units = units;
            w.to = to;
            w.scale = text(scale);
            w.allow_open = allow_open;
            w.solid = solid;
            w.orient = orient;
            w.keep_signed = keep_signed;
            w.weld_tolerance = weld_tolerance;
            const ReadRequest read = file_options(w, ReportOf::measure, /*json=*/true);
            if (!read.options) throw py::value_error(read.error);
            const FileOptions& options = *read.options;
            nlohmann::json report;
            {
                py::gil_scoped_release release;
                report = report_json(measure_file(path, options), options);
            }
            return to_python(report);
        },
        py::arg("path"), py::arg("method"), py::arg("accuracy"), py::arg("density"), py::arg("mass_unit"),
        py::arg("allow_open"), py::arg("solid"), py::arg("orient"), py::arg("keep_signed") = false,
        py::arg("weld_tolerance") = 0.0, py::arg("units") = "", py::arg("to") = "", py::arg("scale") = 1.0);

    // A copy of the mesh wound consistently and outward (orient_mesh), and what that did.
    m.def(
        "orient",
        [](const Doubles& positions, const Indices& indices, const std::optional<Indices>& offsets) {
            auto l = std::make_shared<LoadedMesh>(mesh_from_arrays(positions, indices, offsets));
            OrientResult r;
            {
                py::gil_scoped_release release;
                r = orient_mesh(l->mesh);
            }
            py::dict d;
            d["orientable"] = r.orientable;
            d["faces_flipped"] = r.flipped;
            d["shells"] = r.components;
            d["undecided"] = r.undecided;
            return std::make_tuple(l, d);
        },
        py::arg("positions"), py::arg("indices"), py::arg("offsets"));
}

}  // namespace polyvol::python

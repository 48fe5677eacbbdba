// python/src/grid.cpp — the exact volume of one or many solids in every cell
// of a rectilinear grid (polyvol/grid.hpp), or of one block of its cells.
#include <limits>
#include <tuple>

#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "polyvol/device.hpp"
#include "polyvol/grid.hpp"

namespace polyvol::python {

namespace {

using BodyArrays = std::tuple<Doubles, Indices, std::optional<Indices>>;

std::vector<MeshView> views_of(const std::vector<BodyArrays>& bodies) {
    std::vector<MeshView> views;
    for (const auto& [p, i, o] : bodies) views.push_back(mesh_view(p, i, o));
    return views;
}

// Each body's parts (grid_union_volumes: the body is their union).
std::vector<std::vector<MeshView>> parts_of(const std::vector<std::vector<BodyArrays>>& bodies) {
    std::vector<std::vector<MeshView>> parts;
    for (const auto& b : bodies) parts.push_back(views_of(b));
    return parts;
}

std::vector<double> vector_of(const Doubles& a) { return {a.data(), a.data() + a.size()}; }

// A grid's planes as three new arrays.
std::tuple<py::array_t<double>, py::array_t<double>, py::array_t<double>> planes(const GridAxes& g) {
    auto one = [](const std::vector<double>& v) { return copy_array<double>(v, {static_cast<py::ssize_t>(v.size())}); };
    return {one(g.x), one(g.y), one(g.z)};
}

}  // namespace

void bind_grid(py::module_& m) {
    // The OpenCL devices (polyvol/device.hpp), each a dict as `polyvol devices --json` lists it.
    m.def("devices", [] {
        const DeviceList list = list_devices();
        py::dict r;
        r["opencl_runtime"] = list.runtime;
        r["note"] = list.note;
        py::list devices;
        for (const DeviceInfo& d : list.devices) {
            py::dict e;
            e["index"] = d.index;
            e["name"] = d.name;
            e["platform"] = d.platform;
            e["vendor"] = d.vendor;
            e["type"] = d.type;
            e["version"] = d.version;
            e["global_memory"] = d.global_memory;
            e["compute_units"] = d.compute_units;
            e["fp64"] = d.fp64;
            e["usable"] = d.usable;
            e["reason"] = d.reason;
            devices.append(e);
        }
        r["devices"] = devices;
        return r;
    });

    m.def(
        "grid_axes",
        [](const std::vector<BodyArrays>& bodies, uint32_t cells, double cell_size, std::array<uint32_t, 3> dims,
           std::optional<std::array<double, 6>> bounds) {
            const std::vector<MeshView> views = views_of(bodies);
            GridSpec spec;
            spec.cells = cells;
            spec.cell_size = cell_size;
            spec.dims = dims;
            spec.bounds = bounds;
            GridAxes g;
            {
                py::gil_scoped_release release;
                g = make_grid(views, spec);
            }
            return planes(g);
        },
        py::arg("bodies"), py::arg("cells"), py::arg("cell_size"), py::arg("dims"), py::arg("bounds"));

    m.def(
        "uniform_axes",
        [](std::array<double, 6> bounds, std::array<uint32_t, 3> dims) {
            return planes(uniform_axes(bounds, dims));
        },
        py::arg("bounds"), py::arg("dims"));

    // Returns a dict of the arrays asked for, shaped (bodies, bx, by, bz[, 3])
    // or (bx, by, bz[, 3]) for the union's, and the summary's figures.
    m.def(
        "grid_volumes",
        [](const std::vector<std::vector<BodyArrays>>& bodies, const Doubles& x, const Doubles& y, const Doubles& z,
           std::array<std::size_t, 6> block, bool moments, bool union_volume, bool intersection, bool surface,
           const std::string& device) {
            const std::vector<std::vector<MeshView>> views = parts_of(bodies);
            const GridAxes g{vector_of(x), vector_of(y), vector_of(z)};
            const GridBlock b{{block[0], block[2], block[4]}, {block[1], block[3], block[5]}};
            if (!(b.lo[0] < b.hi[0] && b.hi[0] <= g.nx() && b.lo[1] < b.hi[1] && b.hi[1] <= g.ny() &&
                  b.lo[2] < b.hi[2] && b.hi[2] <= g.nz()))
                throw std::invalid_argument("grid: the block must be a non-empty range of cells within the grid");
            const std::size_t nb = views.size(), cells = b.cell_count();
            const bool several = nb > 1;
            std::vector<double> volumes(nb * cells), first(moments ? 3 * nb * cells : 0);
            // One body: its union is its volumes, but its cells' classes can be asked for.
            std::vector<double> uni(several && union_volume ? cells : 0), inter(several && intersection ? cells : 0);
            std::vector<uint8_t> cls(union_volume ? cells : 0);
            std::vector<double> wet(surface ? nb * cells : 0), normal(surface ? 3 * nb * cells : 0);
            std::vector<double> uwet(surface && several && union_volume ? cells : 0),
                unormal(surface && several && union_volume ? 3 * cells : 0);
            GridOutput out;
            out.volumes = volumes;
            out.first_moments = first;
            out.union_volumes = uni;
            out.intersection_volumes = inter;
            out.cell_class = std::span<CellClass>(reinterpret_cast<CellClass*>(cls.data()), cls.size());
            out.wetted_area = wet;
            out.surface_normal = normal;
            out.union_wetted_area = uwet;
            out.union_surface_normal = unormal;
            GridSummary s;
            GridOptions options;
            options.device = parse_device(device);
            {
                py::gil_scoped_release release;
                s = grid_union_volumes(views, g, b, out, options);
            }
            const auto bx = static_cast<py::ssize_t>(b.hi[0] - b.lo[0]), by = static_cast<py::ssize_t>(b.hi[1] - b.lo[1]),
                       bz = static_cast<py::ssize_t>(b.hi[2] - b.lo[2]), n = static_cast<py::ssize_t>(nb);
            py::dict r;
            r["volumes"] = adopt_array(std::move(volumes), {n, bx, by, bz});
            if (moments) r["first_moments"] = adopt_array(std::move(first), {n, bx, by, bz, 3});
            if (!uni.empty()) r["union"] = adopt_array(std::move(uni), {bx, by, bz});
            if (!inter.empty()) r["intersection"] = adopt_array(std::move(inter), {bx, by, bz});
            if (!cls.empty()) r["cell_class"] = adopt_array(std::move(cls), {bx, by, bz});
            if (surface) {
                r["wetted_area"] = adopt_array(std::move(wet), {n, bx, by, bz});
                r["surface_normal"] = adopt_array(std::move(normal), {n, bx, by, bz, 3});
            }
            if (!uwet.empty()) {
                r["union_wetted_area"] = adopt_array(std::move(uwet), {bx, by, bz});
                r["union_surface_normal"] = adopt_array(std::move(unormal), {bx, by, bz, 3});
            }
            py::list per_body;
            for (const GridBodySummary& bs : s.bodies) {
                py::dict d;
                d["volume"] = bs.volume;
                d["triangles"] = bs.triangles;
                d["pieces"] = bs.pieces;
                d["full_cells"] = bs.full_cells;
                d["empty_cells"] = bs.empty_cells;
                d["cut_cells"] = bs.cut_cells;
                per_body.append(d);
            }
            r["bodies"] = per_body;
            r["union_volume"] = s.union_volume;
            r["intersection_volume"] = s.intersection_volume;
            r["crossing_pairs"] = s.crossing_pairs;
            r["full_cells"] = s.full_cells;
            r["empty_cells"] = s.empty_cells;
            r["cut_cells"] = s.cut_cells;
            r["contact_cells"] = s.contact_cells;
            r["device"] = s.device;
            return r;
        },
        py::arg("bodies"), py::arg("x"), py::arg("y"), py::arg("z"), py::arg("block"), py::arg("moments"),
        py::arg("union"), py::arg("intersection"), py::arg("surface"), py::arg("device") = "auto");
}

}  // namespace polyvol::python

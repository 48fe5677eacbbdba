// python/src/chain.cpp — boundary chains in R^n and plane polygons
// (chain.hpp, simplicial.hpp), and solids bounded by implicit surfaces
// (implicit.hpp), with F an expression or a Python function called on many
// points at once.
#include <pybind11/functional.h>
#include <pybind11/stl.h>

#include "arrays.hpp"
#include "bindings.hpp"
#include "polyvol/chain_io.hpp"
#include "polyvol/implicit.hpp"
#include "polyvol/simplicial.hpp"

namespace polyvol::python {

namespace {

ChainOptions chain_options(const std::string& formula, const std::string& accuracy) {
    ChainOptions o;
    if (formula == "cone")
        o.formula = SimplexFormula::cone;
    else if (formula == "prism")
        o.formula = SimplexFormula::prism;
    else
        throw std::invalid_argument("formula must be 'cone' or 'prism', not '" + formula + "'");
    if (accuracy == "auto")
        o.accuracy = ChainAccuracy::automatic;
    else if (accuracy == "bounded")
        o.accuracy = ChainAccuracy::bounded;
    else if (accuracy == "exact")
        o.accuracy = ChainAccuracy::exact;
    else
        throw std::invalid_argument("accuracy must be 'auto', 'bounded' or 'exact', not '" + accuracy + "'");
    return o;
}

py::dict chain_result(const ChainVolume& v) {
    py::dict d;
    d["dimension"] = v.dimension;
    d["volume"] = v.volume;
    d["volume_error_bound"] = v.volume_error_bound;
    d["volume_correctly_rounded"] = v.volume_correctly_rounded;
    d["centroid"] = copy_array<double>(v.centroid, {static_cast<py::ssize_t>(v.centroid.size())});
    d["centroid_error_bound"] = v.centroid_error_bound;
    d["centroid_correctly_rounded"] = v.centroid_correctly_rounded;
    d["formula"] = std::string(simplex_formula_name(v.formula));
    d["accuracy"] = std::string(chain_accuracy_name(v.accuracy));
    const ChainReport& t = v.topology;
    d["traversal"] = std::string(traversal_name(v.traversal));
    d["simplices"] = t.simplices;
    d["vertices"] = t.vertices;
    d["vertices_welded"] = t.vertices_welded;
    d["faces"] = t.faces;
    d["degenerate_simplices"] = t.degenerate_simplices;
    d["unmatched_faces"] = t.unmatched_faces;
    d["boundary_faces"] = t.boundary_faces;
    d["misoriented_faces"] = t.misoriented_faces;
    d["nonmanifold_faces"] = t.nonmanifold_faces;
    d["components"] = t.components;
    d["closed"] = t.closed();
    return d;
}

py::dict pass_dict(const ImplicitPass& p) {
    py::dict d;
    d["spacing"] = p.spacing;
    d["cells"] = p.cells;
    d["volume"] = p.volume;
    d["rounding_error_bound"] = p.rounding_error_bound;
    d["boundary_simplices"] = p.boundary_simplices;
    d["crossed_simplices"] = p.crossed_simplices;
    d["function_evaluations"] = p.function_evaluations;
    d["components"] = p.components;
    d["box_vertices_inside"] = p.box_vertices_inside;
    d["face_simplices"] = p.face_simplices;
    d["seconds"] = p.seconds;
    return d;
}

}  // namespace

void bind_chain(py::module_& m) {
    m.def(
        "chain_volume",
        [](const Doubles& points, const Indices& simplices, const std::string& formula, const std::string& accuracy) {
            if (points.ndim() != 2 || simplices.ndim() != 2 || points.shape(1) != simplices.shape(1))
                throw std::invalid_argument("points must have shape (m, n) and simplices shape (k, n)");
            const ChainView c{static_cast<int>(points.shape(1)), span_of(points), span_of(simplices)};
            const ChainOptions o = chain_options(formula, accuracy);
            ChainVolume v;
            {
                py::gil_scoped_release release;
                v = chain_volume(c, o);
            }
            return chain_result(v);
        },
        py::arg("points"), py::arg("simplices"), py::arg("formula"), py::arg("accuracy"));

    m.def(
        "polygon_area",
        [](const Doubles& points, const Indices& loop_offsets, const Indices& indices, const std::string& formula) {
            const PolygonsView p{span_of(points), span_of(loop_offsets), span_of(indices)};
            for (const uint32_t v : p.indices)
                if (v >= p.vertex_count()) throw std::invalid_argument("a loop vertex index is out of range");
            const ChainOptions o = chain_options(formula, "auto");
            ChainVolume v;
            std::size_t against = 0;
            {
                py::gil_scoped_release release;
                v = polygon_area(p, o);
                against = loops_wound_like_their_container(p).size();
            }
            py::dict d = chain_result(v);
            d["loops_wound_like_container"] = against;
            return d;
        },
        py::arg("points"), py::arg("loop_offsets"), py::arg("indices"), py::arg("formula"));

    m.def(
        "read_chain",
        [](const std::string& path) {
            LoadedChain c;
            {
                py::gil_scoped_release release;
                c = read_chain_file(path);
            }
            const auto n = static_cast<py::ssize_t>(c.chain.dimension);
            const auto vertices = static_cast<py::ssize_t>(c.chain.vertex_count()),
                       simplices = static_cast<py::ssize_t>(c.chain.simplex_count());
            return std::make_tuple(adopt_array(std::move(c.chain.coordinates), {vertices, n}),
                                   adopt_array(std::move(c.chain.simplices), {simplices, n}));
        },
        py::arg("path"));

    m.def(
        "read_polygons",
        [](const std::string& path) {
            Polygons p;
            {
                py::gil_scoped_release release;
                p = read_polygons_file(path);
            }
            py::list loops;
            for (std::size_t l = 0; l < p.loop_count(); ++l) {
                py::array_t<double> loop({static_cast<py::ssize_t>(p.loop_offsets[l + 1] - p.loop_offsets[l]),
                                          py::ssize_t{2}});
                double* out = loop.mutable_data();
                for (uint32_t i = p.loop_offsets[l]; i < p.loop_offsets[l + 1]; ++i) {
                    *out++ = p.coordinates[2 * std::size_t{p.indices[i]}];
                    *out++ = p.coordinates[2 * std::size_t{p.indices[i]} + 1];
                }
                loops.append(loop);
            }
            return loops;
        },
        py::arg("path"));

    // f: an expression string, or a callable taking a (k, n) float64 array
    // and returning k values (called with the GIL held, from one thread).
    m.def(
        "implicit_volume",
        [](const py::object& f, int dimension, std::vector<double> lo, std::vector<double> hi, double h,
           int coarse_cells, bool error_estimate, const std::string& box, std::vector<double> seeds) {
            ImplicitOptions o;
            o.dimension = dimension;
            o.lo = std::move(lo);
            o.hi = std::move(hi);
            o.h = h;
            o.coarse_cells = coarse_cells;
            o.error_estimate = error_estimate;
            o.seeds = std::move(seeds);
            if (box == "clip")
                o.box_rule = BoxRule::clip;
            else if (box == "error")
                o.box_rule = BoxRule::error;
            else
                throw std::invalid_argument("box must be 'clip' or 'error', not '" + box + "'");
            ImplicitVolume r;
            if (py::isinstance<py::str>(f)) {
                const ImplicitFunction fn = parse_implicit_expression(f.cast<std::string>(), dimension);
                py::gil_scoped_release release;
                r = implicit_volume(fn, o);
            } else {
                const auto n = static_cast<py::ssize_t>(dimension);
                const ImplicitBatchFunction fn = [&f, n](std::span<const double> points, std::span<double> values) {
                    py::gil_scoped_acquire acquire;
                    const auto k = static_cast<py::ssize_t>(values.size());
                    py::array_t<double> x({k, n});
                    std::copy(points.begin(), points.end(), x.mutable_data());
                    const auto y = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(f(x));
                    if (!y || y.size() != k)
                        throw std::invalid_argument("the function must return one number per point (" +
                                                    std::to_string(k) + " here)");
                    std::copy_n(y.data(), k, values.begin());
                };
                py::gil_scoped_release release;
                r = implicit_volume_batch(fn, o);
            }
            py::dict d;
            d["dimension"] = r.dimension;
            d["h"] = r.h;
            d["volume"] = r.volume;
            d["error_estimate"] = r.error_estimate;
            d["volume_extrapolated"] = r.volume_extrapolated;
            d["extrapolated_error_estimate"] = r.extrapolated_error_estimate;
            d["volume_pl_4h"] = r.coarser ? py::object(py::float_(r.coarser->volume)) : py::object(py::none());
            d["coarser_evaluations"] = r.coarser ? r.coarser->function_evaluations : 0;
            d["fine"] = pass_dict(r.fine);
            d["coarse"] = r.coarse ? py::object(pass_dict(*r.coarse)) : py::object(py::none());
            d["clipped"] = r.clipped;
            d["seconds"] = r.seconds;
            return d;
        },
        py::arg("f"), py::arg("dimension"), py::arg("lo"), py::arg("hi"), py::arg("h"), py::arg("coarse_cells"),
        py::arg("error_estimate"), py::arg("box"), py::arg("seeds"));
}

}  // namespace polyvol::python

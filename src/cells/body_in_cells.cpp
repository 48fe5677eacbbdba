// cells/body_in_cells.cpp — body_in_cells (polyvol/cells.hpp): the steps
// both paths share (the whole, the touched cells, the regions of untouched
// cells, the classes), the prepared path and the exact reference.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "boolean/prepared_body.hpp"
#include "cells/cell_faces.hpp"
#include "core/progress.hpp"
#include "core/union_find.hpp"
#include "exact/exact_sum.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/cells.hpp"

namespace polyvol {
namespace {

using Box = std::array<double, 6>;  // xmin ymin zmin xmax ymax zmax

// The cells' own volumes: the caller's, or computed (checking the mesh);
// every cell wound outward.
struct OwnVolumes {
    std::vector<double> computed;
    std::span<const double> volumes;
};
OwnVolumes own_volumes(const CellMeshView& m, const BodyInCellsOptions& options) {
    OwnVolumes own;
    if (options.own.size() == m.cell_count()) {
        if (const auto defect = check_cell_mesh(m)) throw std::invalid_argument(defect->message);
        own.volumes = options.own;
    } else {
        own.computed = cell_volumes(m).volumes;
        own.volumes = own.computed;
    }
    const auto c = std::find_if(own.volumes.begin(), own.volumes.end(), [](double v) { return v < 0; });
    if (c != own.volumes.end())
        throw std::invalid_argument("cell " + std::to_string(c - own.volumes.begin()) +
                                    " is wound inward (negative volume)");
    return own;
}

// |B ∩ c| exactly, or the defect that stops it.
BooleanVolumes booleans(const MeshView& a, const MeshView& body, const BodyInCellsOptions& o) {
    return o.overlapping_shells ? solid_boolean_volumes(a, body, o.within_shells) : boolean_volumes(a, body);
}

double intersect(const Mesh& cell, const MeshView& body, const BodyInCellsOptions& o, std::size_t c) {
    const BooleanVolumes r = booleans(cell.view(), body, o);
    switch (r.status) {
        case BooleanStatus::ok: return r.intersection;
        case BooleanStatus::a_not_closed:
        case BooleanStatus::a_inside_out:
            throw std::invalid_argument("cell " + std::to_string(c) + " is wound inward (negative volume)");
        case BooleanStatus::b_not_closed: throw std::invalid_argument("the body is not a closed surface");
        case BooleanStatus::b_inside_out: throw std::invalid_argument("the body is inside out (negative volume)");
        default: throw std::invalid_argument(std::string("cell ") + std::to_string(c) + ": " +
                                             boolean_status_message(r.status));
    }
}

// Cell c's face triangles over the mesh's points (outward from c).
void cell_triangles(const CellMeshView& m, const cells::CellFaces& cf, std::size_t c, std::vector<uint32_t>& out) {
    for (const uint32_t entry : cf.of(c)) {
        const bool reversed = (entry & 1u) != 0;
        face_triangles(m.face(entry >> 1), m.points, [&](uint32_t a, uint32_t b, uint32_t d) {
            if (reversed)
                out.insert(out.end(), {a, d, b});
            else
                out.insert(out.end(), {a, b, d});
        });
    }
}

// Cell c's triangles (outward) over its own points numbered from 0, with
// the body's winding at each when `winding` (at the mesh's points) is given.
struct LocalCell {
    std::vector<uint32_t> triangles;
    std::vector<double> points;
    std::vector<int32_t> winding;
};
LocalCell local_cell(const CellMeshView& m, const cells::CellFaces& cf, std::size_t c,
                     const std::vector<int32_t>* winding) {
    LocalCell l;
    cell_triangles(m, cf, c, l.triangles);
    std::vector<uint32_t> global;
    for (uint32_t& v : l.triangles) {
        const auto at = std::find(global.begin(), global.end(), v);
        if (at != global.end()) {
            v = static_cast<uint32_t>(at - global.begin());
            continue;
        }
        global.push_back(v);
        l.points.insert(l.points.end(), &m.points[3 * std::size_t{v}], &m.points[3 * std::size_t{v} + 3]);
        if (winding != nullptr) l.winding.push_back((*winding)[v]);
        v = static_cast<uint32_t>(global.size() - 1);
    }
    return l;
}

// Cell c as a closed triangle mesh of its own points, outward.
Mesh cell_surface(const CellMeshView& m, const cells::CellFaces& cf, std::size_t c) {
    LocalCell l = local_cell(m, cf, c, nullptr);
    Mesh out;
    out.positions = std::move(l.points);
    out.indices = std::move(l.triangles);
    return out;
}

// |B ∩ M| and |B| (B's checks too), by the booleans with M's boundary faces
// as A: M the region the cells cover, each point once. Where the cells may
// not tile (options.cells_tile false) the boundary faces' winding number is
// the number of cells covering a point (2 where two overlap), and M is its
// solid {winding >= 1}, the surface's crossings resolved; where that solid
// is not decided, total is left NaN for classify to make it the cells' sum.
void whole_volumes(const CellMeshView& m, const cells::CellFaces& cf, const MeshView& body,
                   const BodyInCellsOptions& options, BodyInCells& r) {
    const Mesh outside = cells::boundary_surface(m);
    BooleanVolumes whole = options.cells_tile ? booleans(outside.view(), body, options)
                                              : solid_boolean_volumes(outside.view(), body, true);
    if (!options.cells_tile && whole.status != BooleanStatus::ok && m.cell_count() > 0) {
        // The covered region is not decided (the boundary touches itself
        // where it crosses itself): B checked and measured against one cell.
        whole = booleans(cell_surface(m, cf, 0).view(), body, options);
        whole.intersection = NAN;
    }
    if (whole.status == BooleanStatus::b_not_closed) throw std::invalid_argument("the body is not a closed surface");
    if (whole.status == BooleanStatus::b_inside_out) throw std::invalid_argument("the body is inside out");
    if (whole.status != BooleanStatus::ok)
        throw std::invalid_argument(std::string("the mesh's boundary: ") + boolean_status_message(whole.status));
    r.total = whole.intersection;
    r.body_volume = whole.volume_b;
}

// 1 for each cell whose box meets a body triangle's box.
std::vector<uint8_t> touched_cells(const CellMeshView& m, const cells::CellFaces& cf,
                                   const boolean::PreparedBody& body) {
    std::vector<uint8_t> touched(m.cell_count(), 0);
    tbb::parallel_for(std::size_t{0}, m.cell_count(), [&](std::size_t c) {
        Box b{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
        for (const uint32_t entry : cf.of(c))
            for (const uint32_t p : m.face(entry >> 1))
                for (int k = 0; k < 3; ++k) {
                    b[k] = std::min(b[k], m.points[3 * std::size_t{p} + k]);
                    b[3 + k] = std::max(b[3 + k], m.points[3 * std::size_t{p} + k]);
                }
        touched[c] = boolean::meets_box(body, b) ? 1 : 0;
    });
    return touched;
}

std::vector<uint32_t> listed(const std::vector<uint8_t>& flags) {
    std::vector<uint32_t> out;
    for (std::size_t c = 0; c < flags.size(); ++c)
        if (flags[c] != 0) out.push_back(static_cast<uint32_t>(c));
    return out;
}

// Untouched cells are alike across a face between two of them (no part of
// the body's surface lies between): inside(c) decides each region once.
void fill_untouched(const CellMeshView& m, const std::vector<uint8_t>& touched, std::span<const double> own,
                    const std::function<bool(std::size_t)>& inside, BodyInCells& r) {
    const std::size_t n = m.cell_count();
    core::UnionFind regions(n);
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const uint32_t a = m.owner[f], b = m.neighbour[f];
        if (b != kNoCell && touched[a] == 0 && touched[b] == 0) regions.unite(a, b);
    }
    std::vector<int8_t> inside_of_root(n, -1);
    for (std::size_t c = 0; c < n; ++c) {
        if (touched[c] != 0) continue;
        const uint32_t root = regions.find(static_cast<uint32_t>(c));
        if (inside_of_root[root] < 0) inside_of_root[root] = inside(c) ? 1 : 0;
        r.volumes[c] = inside_of_root[root] != 0 ? own[c] : 0.0;
    }
}

// Each cell's class by its value: empty (0), full (its own volume), cut;
// the cells' values added exactly, rounded once; where the cells may not
// tile, what they count more than once: cells_sum − total (whole_volumes),
// or, where the covered region was not decided, the total is the cells' sum.
void classify(std::span<const double> own, bool cells_tile, BodyInCells& r) {
    exact::ExactSum sum;
    sum.add(r.volumes);
    r.cells_sum = sum.round();
    if (!cells_tile) {
        r.in_overlaps = r.cells_sum - r.total;  // NaN where total is not known
        if (std::isnan(r.total)) r.total = r.cells_sum;
    }
    r.cell_class.resize(r.volumes.size());
    for (std::size_t c = 0; c < r.volumes.size(); ++c) {
        const double v = r.volumes[c];
        r.cell_class[c] = v == 0 ? CellClass::empty : v == own[c] ? CellClass::full : CellClass::cut;
        (v == 0 ? r.empty_cells : v == own[c] ? r.full_cells : r.cut_cells) += 1;
    }
}

// The exact reference: a boolean against the whole body per touched cell and
// per region of untouched cells.
BodyInCells reference_volumes(const CellMeshView& m, const MeshView& body, const BodyInCellsOptions& options) {
    const OwnVolumes own = own_volumes(m, options);
    const cells::CellFaces cf = cells::cell_faces(m);
    BodyInCells r;
    r.volumes.assign(m.cell_count(), 0);
    whole_volumes(m, cf, body, options, r);
    const std::vector<uint8_t> touched = touched_cells(m, cf, *boolean::prepare_body(body));
    r.touched = touched;
    const std::vector<uint32_t> list = listed(touched);
    r.touched_cells = list.size();
    core::ProgressCounter progress(options.progress, list.size());  // cells intersected
    tbb::parallel_for(std::size_t{0}, list.size(), [&](std::size_t i) {
        r.volumes[list[i]] = intersect(cell_surface(m, cf, list[i]), body, options, list[i]);
        progress.add();
    });
    if (options.surface) {  // not given by the booleans of the whole body
        r.wetted_area.assign(m.cell_count(), NAN);
        r.surface_normal.assign(3 * m.cell_count(), NAN);
        r.surface_bound.assign(m.cell_count(), NAN);
    }
    fill_untouched(m, touched, own.volumes, [&](std::size_t c) {
        const double v = intersect(cell_surface(m, cf, c), body, options, c);
        if (v != 0 && v != own.volumes[c])
            throw std::logic_error("cell " + std::to_string(c) + " is neither inside nor outside the body");
        return v != 0;
    }, r);
    classify(own.volumes, options.cells_tile, r);
    return r;
}

// |B ∩ c| from B prepared once: the windings at the touched cells' points in
// one pass, then each touched cell with the body's triangles near it.
BodyInCells prepared_volumes(const CellMeshView& m, const MeshView& body, const BodyInCellsOptions& options) {
    const OwnVolumes own = own_volumes(m, options);
    const std::shared_ptr<const boolean::PreparedBody> prepared = boolean::prepare_body(body);
    const cells::CellFaces cf = cells::cell_faces(m);
    BodyInCells r;
    r.volumes.assign(m.cell_count(), 0);
    whole_volumes(m, cf, body, options, r);
    const std::vector<uint8_t> touched = touched_cells(m, cf, *prepared);
    r.touched = touched;
    const std::vector<uint32_t> list = listed(touched);
    r.touched_cells = list.size();
    // The body's winding at every point of the touched cells, in one pass over their faces.
    std::vector<uint32_t> faces_of_touched;
    for (std::size_t f = 0; f < m.face_count(); ++f)
        if (touched[m.owner[f]] != 0 || (m.neighbour[f] != kNoCell && touched[m.neighbour[f]] != 0))
            face_triangles(m.face(f), m.points, [&](uint32_t a, uint32_t b, uint32_t d) {
                faces_of_touched.insert(faces_of_touched.end(), {a, b, d});
            });
    const std::vector<int32_t> winding = boolean::windings_at(*prepared, m.points, faces_of_touched);
    if (options.surface) {
        r.wetted_area.assign(m.cell_count(), 0.0);
        r.surface_normal.assign(3 * m.cell_count(), 0.0);
        r.surface_bound.assign(m.cell_count(), 0.0);
    }
    core::ProgressCounter progress(options.progress, list.size());  // cells intersected
    tbb::parallel_for(std::size_t{0}, list.size(), [&](std::size_t i) {
        const LocalCell l = local_cell(m, cf, list[i], &winding);
        for (const int32_t x : l.winding)
            if (x != 0 && x != 1) throw std::invalid_argument("the body overlaps itself (a winding number above 1)");
        boolean::CellSurface surface;
        r.volumes[list[i]] = boolean::cell_intersection(*prepared, l.points, l.triangles, l.winding,
                                                        options.surface ? &surface : nullptr);
        if (options.surface) {
            r.wetted_area[list[i]] = surface.area;
            std::copy_n(surface.normal, 3, &r.surface_normal[3 * std::size_t{list[i]}]);
            r.surface_bound[list[i]] = surface.bound;
        }
        progress.add();
    });
    if (options.surface) {
        exact::ExactSum area;
        double bound = 0;
        for (std::size_t c = 0; c < m.cell_count(); ++c) {
            area.add(r.wetted_area[c]);
            bound += r.surface_bound[c];
        }
        r.wetted_area_total = area.round();
        // n doubles added in order: each addition's rounding within 2^-53 of the
        // running sum, so (1 + (n + 1) 2^-52) covers them all.
        r.wetted_area_total_bound = bound * (1 + static_cast<double>(m.cell_count() + 1) * 0x1p-52) +
                                    0x1p-53 * std::fabs(r.wetted_area_total);
    }
    fill_untouched(m, touched, own.volumes, [&](std::size_t c) {
        std::vector<uint32_t> tris;
        cell_triangles(m, cf, c, tris);
        if (tris.empty()) return false;  // a cell without faces holds nothing
        return boolean::windings_at(*prepared, m.points, tris)[tris[0]] != 0;  // one ray
    }, r);
    classify(own.volumes, options.cells_tile, r);
    return r;
}

}  // namespace

BodyInCells union_in_cells(const CellMeshView& m, std::span<const MeshView> bodies, std::span<const BodyInCells> each,
                           const BodyInCellsOptions& options) {
    Mesh all;
    for (const MeshView& b : bodies) all.append(to_mesh(b));
    BodyInCellsOptions o = options;
    o.overlapping_shells = true;
    o.surface = false;
    if (each.size() != bodies.size()) return reference_volumes(m, all.view(), o);
    for (const BodyInCells& b : each)
        if (b.volumes.size() != m.cell_count() || b.touched.size() != m.cell_count())
            throw std::invalid_argument("union_in_cells: a body's result is not of this mesh");
    const OwnVolumes own = own_volumes(m, o);
    const cells::CellFaces cf = cells::cell_faces(m);
    BodyInCells r;
    r.volumes.assign(m.cell_count(), 0);
    r.touched.assign(m.cell_count(), 0);
    whole_volumes(m, cf, all.view(), o, r);
    std::vector<uint32_t> list;  // the cells two bodies or more touch, none full
    for (std::size_t c = 0; c < m.cell_count(); ++c) {
        std::size_t touching = 0, last = 0;
        bool full = false;
        for (std::size_t i = 0; i < each.size(); ++i) {
            full = full || each[i].volumes[c] == own.volumes[c];
            if (each[i].touched[c] != 0) ++touching, last = i;
        }
        if (full) r.volumes[c] = own.volumes[c];
        else if (touching == 1) r.volumes[c] = each[last].volumes[c];
        else if (touching > 1) list.push_back(static_cast<uint32_t>(c));
    }
    r.touched_cells = list.size();
    core::ProgressCounter progress(o.progress, list.size());  // cells intersected
    tbb::parallel_for(std::size_t{0}, list.size(), [&](std::size_t i) {
        r.volumes[list[i]] = intersect(cell_surface(m, cf, list[i]), all.view(), o, list[i]);
        r.touched[list[i]] = 1;
        progress.add();
    });
    classify(own.volumes, o.cells_tile, r);
    return r;
}

IntersectionInCells intersection_in_cells(const BodyInCells& a, const BodyInCells& b, const BodyInCells& both) {
    if (a.volumes.size() != b.volumes.size() || a.volumes.size() != both.volumes.size())
        throw std::invalid_argument("intersection_in_cells: the three results are of different meshes");
    // a + b − (a ∪ b), added exactly and rounded once, within [0, min(a, b)].
    auto inclusion_exclusion = [](double x, double y, double u) {
        exact::ExactSum s;
        s.add(x);
        s.add(y);
        s.add(-u);
        return std::clamp(s.round(), 0.0, std::min(x, y));
    };
    IntersectionInCells r;
    r.volumes.resize(a.volumes.size());
    for (std::size_t c = 0; c < r.volumes.size(); ++c)
        r.volumes[c] = inclusion_exclusion(a.volumes[c], b.volumes[c], both.volumes[c]);
    r.total = inclusion_exclusion(a.total, b.total, both.total);
    return r;
}

BodyInCells body_in_cells(const CellMeshView& m, const MeshView& body, const BodyInCellsOptions& options) {
    if (options.reference || options.overlapping_shells) return reference_volumes(m, body, options);
    return prepared_volumes(m, body, options);
}

}  // namespace polyvol

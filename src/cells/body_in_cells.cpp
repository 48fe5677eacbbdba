// cells/body_in_cells.cpp — body_in_cells (polyvol/cells.hpp): the exact
// reference, a boolean per touched cell and one per region of untouched cells.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "boolean/prepared_body.hpp"
#include "cells/cell_faces.hpp"
#include "core/union_find.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/cells.hpp"

namespace polyvol {
namespace {

using Box = std::array<double, 6>;  // xmin ymin zmin xmax ymax zmax

Box empty_box() {
    return {INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
}

void grow(Box& b, const double* p) {
    for (int k = 0; k < 3; ++k) {
        b[k] = std::min(b[k], p[k]);
        b[3 + k] = std::max(b[3 + k], p[k]);
    }
}

bool meet(const Box& a, const Box& b) {
    for (int k = 0; k < 3; ++k)
        if (a[k] > b[3 + k] || b[k] > a[3 + k]) return false;
    return true;
}

// Cell c as a closed triangle mesh of its own points: the face rule's
// triangles, its neighbour faces reversed (outward from c).
Mesh cell_surface(const CellMeshView& m, const cells::CellFaces& cf, std::size_t c) {
    Mesh out;
    std::vector<uint32_t> global;  // local point -> mesh point
    auto local = [&](uint32_t p) {
        for (std::size_t i = 0; i < global.size(); ++i)
            if (global[i] == p) return static_cast<uint32_t>(i);
        global.push_back(p);
        out.positions.insert(out.positions.end(), &m.points[3 * std::size_t{p}], &m.points[3 * std::size_t{p} + 3]);
        return static_cast<uint32_t>(global.size() - 1);
    };
    for (const uint32_t entry : cf.of(c)) {
        const bool reversed = (entry & 1u) != 0;
        face_triangles(m.face(entry >> 1), [&](uint32_t a, uint32_t b, uint32_t d) {
            const uint32_t la = local(a), lb = local(b), ld = local(d);
            if (reversed)
                out.indices.insert(out.indices.end(), {la, ld, lb});
            else
                out.indices.insert(out.indices.end(), {la, lb, ld});
        });
    }
    return out;
}

// The boundary faces' triangles: the surface of the region the cells tile.
Mesh boundary_surface(const CellMeshView& m) {
    Mesh out;
    out.positions.assign(m.points.begin(), m.points.end());
    for (std::size_t f = 0; f < m.face_count(); ++f)
        if (m.neighbour[f] == kNoCell)
            face_triangles(m.face(f), [&](uint32_t a, uint32_t b, uint32_t d) {
                out.indices.insert(out.indices.end(), {a, b, d});
            });
    return out;
}

// The body's fan triangles' boxes in a uniform grid of buckets over the
// body's box, for the question "does any of them meet this box?".
class TriangleBoxes {
public:
    explicit TriangleBoxes(const MeshView& body) {
        bounds_ = empty_box();
        for (std::size_t f = 0; f < body.face_count(); ++f) {
            const std::span<const uint32_t> v = body.face(f);
            for (std::size_t i = 1; i + 1 < v.size(); ++i) {
                Box b = empty_box();
                for (const uint32_t p : {v[0], v[i], v[i + 1]}) grow(b, &body.positions[3 * std::size_t{p}]);
                boxes_.push_back(b);
                grow(bounds_, b.data());
                grow(bounds_, b.data() + 3);
            }
        }
        n_ = std::max<int>(1, static_cast<int>(std::cbrt(static_cast<double>(boxes_.size()))));
        std::vector<uint32_t> count(static_cast<std::size_t>(n_) * n_ * n_ + 1, 0);
        for_each_bucket_of_all([&](std::size_t bucket, uint32_t) { ++count[bucket + 1]; });
        for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
        offsets_ = count;
        items_.resize(count.back());
        for_each_bucket_of_all([&](std::size_t bucket, uint32_t t) { items_[count[bucket]++] = t; });
    }
    const Box& bounds() const { return bounds_; }
    bool any_meets(const Box& b) const {
        if (boxes_.empty() || !meet(b, bounds_)) return false;
        int lo[3], hi[3];
        range(b, lo, hi);
        for (int i = lo[0]; i <= hi[0]; ++i)
            for (int j = lo[1]; j <= hi[1]; ++j)
                for (int k = lo[2]; k <= hi[2]; ++k) {
                    const std::size_t bucket = (static_cast<std::size_t>(i) * n_ + j) * n_ + k;
                    for (uint32_t x = offsets_[bucket]; x < offsets_[bucket + 1]; ++x)
                        if (meet(boxes_[items_[x]], b)) return true;
                }
        return false;
    }

private:
    int cell_of(double x, int axis) const {
        const double lo = bounds_[axis], hi = bounds_[3 + axis];
        if (!(hi > lo)) return 0;
        const double t = (x - lo) / (hi - lo) * n_;
        return std::clamp(static_cast<int>(std::floor(t)), 0, n_ - 1);
    }
    void range(const Box& b, int* lo, int* hi) const {
        for (int k = 0; k < 3; ++k) {
            lo[k] = cell_of(b[k], k);
            hi[k] = cell_of(b[3 + k], k);
        }
    }
    template <class Fn>
    void for_each_bucket_of_all(Fn&& fn) const {
        for (uint32_t t = 0; t < boxes_.size(); ++t) {
            int lo[3], hi[3];
            range(boxes_[t], lo, hi);
            for (int i = lo[0]; i <= hi[0]; ++i)
                for (int j = lo[1]; j <= hi[1]; ++j)
                    for (int k = lo[2]; k <= hi[2]; ++k) fn((static_cast<std::size_t>(i) * n_ + j) * n_ + k, t);
        }
    }

    std::vector<Box> boxes_;
    Box bounds_{};
    int n_ = 1;
    std::vector<uint32_t> offsets_, items_;
};

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

}  // namespace

// The exact reference: a boolean against the whole body per touched cell.
static BodyInCells reference_volumes(const CellMeshView& m, const MeshView& body, const BodyInCellsOptions& options) {
    const OwnVolumes own = own_volumes(m, options);
    const cells::CellFaces cf = cells::cell_faces(m);
    const std::size_t n = m.cell_count();
    BodyInCells r;
    r.volumes.assign(n, 0);
    r.cell_class.assign(n, CellClass::empty);

    // The whole: |B ∩ M| and |B| (also checks the body).
    const Mesh outside = boundary_surface(m);
    const BooleanVolumes whole = booleans(outside.view(), body, options);
    if (whole.status == BooleanStatus::b_not_closed) throw std::invalid_argument("the body is not a closed surface");
    if (whole.status == BooleanStatus::b_inside_out) throw std::invalid_argument("the body is inside out");
    if (whole.status != BooleanStatus::ok)
        throw std::invalid_argument(std::string("the mesh's boundary: ") + boolean_status_message(whole.status));
    r.total = whole.intersection;
    r.body_volume = whole.volume_b;

    // Touched cells: their box meets a body triangle's box.
    const TriangleBoxes triangles(body);
    std::vector<uint8_t> touched(n, 0);
    std::vector<Box> box(n);
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t c) {
        Box b = empty_box();
        for (const uint32_t entry : cf.of(c))
            for (const uint32_t p : m.face(entry >> 1)) grow(b, &m.points[3 * std::size_t{p}]);
        box[c] = b;
        touched[c] = triangles.any_meets(b) ? 1 : 0;
    });
    std::vector<uint32_t> touched_cells;
    for (std::size_t c = 0; c < n; ++c)
        if (touched[c] != 0) touched_cells.push_back(static_cast<uint32_t>(c));
    r.touched_cells = touched_cells.size();
    tbb::parallel_for(std::size_t{0}, touched_cells.size(), [&](std::size_t i) {
        const uint32_t c = touched_cells[i];
        r.volumes[c] = intersect(cell_surface(m, cf, c), body, options, c);
    });

    // Untouched cells: alike across a face between two of them; one exact
    // decision per region (none where the region's cell is outside the body's box).
    core::UnionFind regions(n);
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const uint32_t a = m.owner[f], b = m.neighbour[f];
        if (b != kNoCell && touched[a] == 0 && touched[b] == 0) regions.unite(a, b);
    }
    std::vector<int8_t> inside_of_root(n, -1);
    for (std::size_t c = 0; c < n; ++c) {
        if (touched[c] != 0) continue;
        const uint32_t root = regions.find(static_cast<uint32_t>(c));
        if (inside_of_root[root] < 0) {
            double v = 0;
            if (meet(box[c], triangles.bounds())) v = intersect(cell_surface(m, cf, c), body, options, c);
            if (v != 0 && v != own.volumes[c])
                throw std::logic_error("cell " + std::to_string(c) + " is neither inside nor outside the body");
            inside_of_root[root] = v != 0 ? 1 : 0;
        }
        r.volumes[c] = inside_of_root[root] != 0 ? own.volumes[c] : 0.0;
    }
    for (std::size_t c = 0; c < n; ++c) {
        const double v = r.volumes[c];
        r.cell_class[c] = v == 0 ? CellClass::empty : v == own.volumes[c] ? CellClass::full : CellClass::cut;
        (v == 0 ? r.empty_cells : v == own.volumes[c] ? r.full_cells : r.cut_cells) += 1;
    }
    return r;
}

namespace {

// Cell c's face triangles over the mesh's points (outward from c).
void cell_triangles(const CellMeshView& m, const cells::CellFaces& cf, std::size_t c, std::vector<uint32_t>& out) {
    for (const uint32_t entry : cf.of(c)) {
        const bool reversed = (entry & 1u) != 0;
        face_triangles(m.face(entry >> 1), [&](uint32_t a, uint32_t b, uint32_t d) {
            if (reversed)
                out.insert(out.end(), {a, d, b});
            else
                out.insert(out.end(), {a, b, d});
        });
    }
}

// |B ∩ c| from B prepared once: the windings at the touched cells' points in
// one pass, then each touched cell with the body's triangles near it.
BodyInCells prepared_volumes(const CellMeshView& m, const MeshView& body, const BodyInCellsOptions& options) {
    const OwnVolumes own = own_volumes(m, options);
    const std::shared_ptr<const boolean::PreparedBody> held = boolean::prepare_body(body);
    const boolean::PreparedBody& prepared = *held;
    const cells::CellFaces cf = cells::cell_faces(m);
    const std::size_t n = m.cell_count();
    BodyInCells r;
    r.volumes.assign(n, 0);
    r.cell_class.assign(n, CellClass::empty);
    const Mesh outside = boundary_surface(m);
    const BooleanVolumes whole = boolean_volumes(outside.view(), body);
    if (whole.status != BooleanStatus::ok)
        throw std::invalid_argument(std::string("the mesh's boundary: ") + boolean_status_message(whole.status));
    r.total = whole.intersection;
    r.body_volume = whole.volume_b;

    // Touched cells: their box meets a body triangle's box.
    std::vector<uint8_t> touched(n, 0);
    tbb::parallel_for(std::size_t{0}, n, [&](std::size_t c) {
        Box b = empty_box();
        for (const uint32_t entry : cf.of(c))
            for (const uint32_t p : m.face(entry >> 1)) grow(b, &m.points[3 * std::size_t{p}]);
        touched[c] = boolean::meets_box(prepared, b) ? 1 : 0;
    });
    std::vector<uint32_t> touched_cells;
    for (std::size_t c = 0; c < n; ++c)
        if (touched[c] != 0) touched_cells.push_back(static_cast<uint32_t>(c));
    r.touched_cells = touched_cells.size();
    // The body's winding at every point of the touched cells, in one pass over their faces.
    std::vector<uint32_t> faces_of_touched;
    for (std::size_t f = 0; f < m.face_count(); ++f)
        if (touched[m.owner[f]] != 0 || (m.neighbour[f] != kNoCell && touched[m.neighbour[f]] != 0))
            face_triangles(m.face(f), [&](uint32_t a, uint32_t b, uint32_t d) {
                faces_of_touched.insert(faces_of_touched.end(), {a, b, d});
            });
    const std::vector<int32_t> winding = boolean::windings_at(prepared, m.points, faces_of_touched);
    tbb::parallel_for(std::size_t{0}, touched_cells.size(), [&](std::size_t i) {
        const uint32_t c = touched_cells[i];
        std::vector<uint32_t> tris;
        cell_triangles(m, cf, c, tris);
        // The cell's own points, numbered from 0, with their windings.
        std::vector<uint32_t> global;
        std::vector<double> points;
        std::vector<int32_t> w;
        for (uint32_t& v : tris) {
            const auto at = std::find(global.begin(), global.end(), v);
            if (at != global.end()) {
                v = static_cast<uint32_t>(at - global.begin());
                continue;
            }
            global.push_back(v);
            points.insert(points.end(), &m.points[3 * std::size_t{v}], &m.points[3 * std::size_t{v} + 3]);
            w.push_back(winding[v]);
            v = static_cast<uint32_t>(global.size() - 1);
        }
        for (const int32_t x : w)
            if (x != 0 && x != 1) throw std::invalid_argument("the body overlaps itself (a winding number above 1)");
        r.volumes[c] = boolean::cell_intersection(prepared, points, tris, w);
    });

    // Untouched cells: alike across a face between two of them; one ray per region.
    core::UnionFind regions(n);
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const uint32_t a = m.owner[f], b = m.neighbour[f];
        if (b != kNoCell && touched[a] == 0 && touched[b] == 0) regions.unite(a, b);
    }
    std::vector<int8_t> inside_of_root(n, -1);
    for (std::size_t c = 0; c < n; ++c) {
        if (touched[c] != 0) continue;
        const uint32_t root = regions.find(static_cast<uint32_t>(c));
        if (inside_of_root[root] < 0) {
            std::vector<uint32_t> tris;
            cell_triangles(m, cf, c, tris);
            const std::vector<int32_t> w = boolean::windings_at(prepared, m.points, tris);
            inside_of_root[root] = w[tris[0]] != 0 ? 1 : 0;
        }
        r.volumes[c] = inside_of_root[root] != 0 ? own.volumes[c] : 0.0;
    }
    for (std::size_t c = 0; c < n; ++c) {
        const double v = r.volumes[c];
        r.cell_class[c] = v == 0 ? CellClass::empty : v == own.volumes[c] ? CellClass::full : CellClass::cut;
        (v == 0 ? r.empty_cells : v == own.volumes[c] ? r.full_cells : r.cut_cells) += 1;
    }
    return r;
}

}  // namespace

BodyInCells body_in_cells(const CellMeshView& m, const MeshView& body, const BodyInCellsOptions& options) {
    if (options.reference || options.overlapping_shells) return reference_volumes(m, body, options);
    return prepared_volumes(m, body, options);
}

}  // namespace polyvol

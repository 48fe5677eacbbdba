// Shared helpers for the grid tests: closed-form cell volumes and a runner
// (the solids are common/shapes.hpp's).
#pragma once

#include <algorithm>
#include <array>
#include <vector>

#include "common/shapes.hpp"
#include "polyvol/grid.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::test {

// Volume of [lo, hi] ∩ [c0, c1].
inline double box_overlap(const std::array<double, 3>& lo, const std::array<double, 3>& hi, const double c0[3],
                          const double c1[3]) {
    double v = 1;
    for (int a = 0; a < 3; ++a) v *= std::max(0.0, std::min(hi[a], c1[a]) - std::max(lo[a], c0[a]));
    return v;
}

struct GridRun {
    std::vector<double> volumes, moments, union_volumes, intersection, union_area, union_normal;
    std::vector<CellClass> cls;
    GridSummary summary;
};

inline GridRun run_grid(const std::vector<const Mesh*>& meshes, const GridAxes& g, bool moments = false,
                        bool with_union = false) {
    std::vector<MeshView> views;
    for (const Mesh* m : meshes) views.push_back(m->view());
    GridRun r;
    const std::size_t cells = g.cell_count();
    r.volumes.assign(views.size() * cells, -1);
    GridOutput out{.volumes = r.volumes};
    if (moments) {
        r.moments.assign(3 * views.size() * cells, -1);
        out.first_moments = r.moments;
    }
    if (with_union) {  // also the intersection and the union's surface
        r.union_volumes.assign(cells, -1);
        r.intersection.assign(cells, -1);
        r.union_area.assign(cells, -1);
        r.union_normal.assign(3 * cells, -1);
        r.cls.assign(cells, CellClass::empty);
        out.union_volumes = r.union_volumes;
        out.intersection_volumes = r.intersection;
        out.union_wetted_area = r.union_area;
        out.union_surface_normal = r.union_normal;
        out.cell_class = r.cls;
    }
    r.summary = grid_volumes(views, g, out);
    return r;
}

inline GridRun run_grid(const Mesh& m, const GridAxes& g, bool moments = false) {
    return run_grid(std::vector<const Mesh*>{&m}, g, moments);
}

}  // namespace polyvol::test

// grid/union_bounds.cpp — the union's occupancy of a cell from the bodies'
// volumes in it (the source's "intersecting polyhedra": exact except where
// surfaces of different bodies meet).
//
// Where at most one body's surface enters the cell, every other body is
// empty or full there, so the union is known exactly. Where k >= 2 surfaces
// enter, the parts may overlap in any way, and the only bounds are
//     max_b V_b <= V(union) <= min(cell, Σ_b V_b).
// These cells lie along the curves where two bodies' surfaces cross: about
// L / h of them for a curve of length L, each of volume h^3, so the width
// of the bound summed over the grid is O(L h^2).
#include "grid/union_bounds.hpp"

#include <algorithm>

#include "grid/column_scan.hpp"

namespace polyvol::grid {

UnionCell union_cell(std::span<const double> volumes, std::span<const uint8_t> state, double cell_volume) {
    UnionCell u;
    int cut = 0;
    double vmax = 0, vsum = 0, empty_fraction = 1;
    std::size_t cut_body = 0;
    for (std::size_t b = 0; b < volumes.size(); ++b) {
        if (state[b] == kFull) {
            u.estimate = u.lower = u.upper = cell_volume;
            u.cls = CellClass::full;
            return u;
        }
        if (state[b] == kCut) {
            ++cut;
            cut_body = b;
            vmax = std::max(vmax, volumes[b]);
            vsum += volumes[b];
            empty_fraction *= 1 - volumes[b] / cell_volume;
        }
    }
    if (cut == 0) return u;  // empty
    if (cut == 1) {
        u.estimate = u.lower = u.upper = volumes[cut_body];
        u.cls = CellClass::cut;
        return u;
    }
    u.lower = vmax;
    u.upper = std::min(cell_volume, vsum);
    u.estimate = std::clamp(cell_volume * (1 - empty_fraction), u.lower, std::max(u.lower, u.upper));
    u.cls = CellClass::contact;
    return u;
}

}  // namespace polyvol::grid

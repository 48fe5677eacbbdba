// grid/union_bounds.hpp — private: the union of several bodies in one cell.
#pragma once

#include <cstdint>
#include <span>

#include "polyvol/grid.hpp"

namespace polyvol::grid {

struct UnionCell {
    double estimate = 0, lower = 0, upper = 0;
    CellClass cls = CellClass::empty;
};

// volumes[b] and state[b] (column_scan.hpp's BodyCell) of each body in one
// cell of volume cell_volume:
//   some body full              -> the cell (exact)
//   no body's surface enters    -> 0 (exact)
//   one body's surface enters   -> that body's volume (exact: the others are empty)
//   two or more (contact)       -> lower = max_b V_b, upper = min(cell, Σ_b V_b),
//                                  estimate = cell (1 - Π_b (1 - V_b / cell)) within them.
UnionCell union_cell(std::span<const double> volumes, std::span<const uint8_t> state, double cell_volume);

}  // namespace polyvol::grid

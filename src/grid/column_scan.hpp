// grid/column_scan.hpp — private: the reverse prefix sum down one column.
#pragma once

#include <cstdint>

#include "grid/tile_sums.hpp"

namespace polyvol::grid {

// What a cell is for one body.
enum BodyCell : uint8_t { kEmpty = 0, kFull = 1, kCut = 2 };

struct ColumnGeometry {
    double x0, x1, y0, y1;  // the column's sides
    const double* z;        // z planes, nz + 1
    int nz;
};

// Writes the body's volume of each cell of column (ci, cj) of `sums` to
// volume[k] (k = 0 .. nz-1), its first moments about the origin to
// moments[3k + a] when moments != nullptr, and its BodyCell to state[k]:
//     A_top(k) = Σ_{k' > k} P(k')   (layer nz included)
//     V(k)     = Q(k) + h_k A_top(k)                    when a piece enters the cell,
//              = round(A_top(k) / cell area) × cell volume  otherwise (exact).
// Only the cells that received pieces are visited one by one; the runs of
// cells between them take the same winding number.
// Returns how many cells are of each BodyCell kind.
struct ColumnCounts {
    std::size_t empty = 0, full = 0, cut = 0;
};
ColumnCounts scan_column(const TileSums& sums, int ci, int cj, const ColumnGeometry& g, double* volume,
                         double* moments, uint8_t* state);

}  // namespace polyvol::grid

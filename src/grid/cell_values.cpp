// src/grid/cell_values.cpp — polyvol/grid.hpp's per-cell values derived from
// the volumes: fractions and centroids.
#include <algorithm>
#include <limits>

#include "polyvol/grid.hpp"

namespace polyvol {

void to_fractions(std::span<double> values, const GridAxes& g, std::size_t arrays, bool keep_signed) {
    const std::size_t cells = g.cell_count();
    for (std::size_t i = 0; i < g.nx(); ++i)
        for (std::size_t j = 0; j < g.ny(); ++j)
            for (std::size_t k = 0; k < g.nz(); ++k) {
                const double cv = g.cell_volume(i, j, k);
                for (std::size_t b = 0; b < arrays; ++b) {
                    double& f = values[b * cells + g.cell(i, j, k)];
                    f = keep_signed ? f / cv : std::clamp(f / cv, 0.0, 1.0);
                }
            }
}

std::vector<double> cell_centroids(std::span<const double> volumes, std::span<const double> first_moments) {
    std::vector<double> c(first_moments.size());
    for (std::size_t n = 0; n < volumes.size(); ++n)
        for (std::size_t k = 0; k < 3; ++k)
            c[3 * n + k] = volumes[n] != 0 ? first_moments[3 * n + k] / volumes[n]
                                           : std::numeric_limits<double>::quiet_NaN();
    return c;
}

}  // namespace polyvol

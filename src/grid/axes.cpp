// grid/axes.cpp — choosing the grid: uniform axes, and the padded bounding
// box of the bodies (polyvol/grid.hpp, GridSpec).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "polyvol/grid.hpp"

namespace polyvol {
namespace {

constexpr uint32_t kMaxCellsPerAxis = 1u << 20;

bool axis_uniform(const std::vector<double>& c) {
    const std::size_t n = c.size() - 1;
    const double step = (c.back() - c.front()) / static_cast<double>(n);
    for (std::size_t i = 1; i <= n; ++i)
        if (std::abs((c[i] - c[i - 1]) - step) > 1e-9 * step) return false;
    return true;
}

// n equal cells from lo to hi; c[n] == hi exactly.
std::vector<double> uniform_planes(double lo, double hi, uint64_t n, const char* axis) {
    if (!(std::isfinite(lo) && std::isfinite(hi) && lo < hi))
        throw std::invalid_argument(std::string("grid: the ") + axis + " bounds must be finite with min < max");
    if (n < 1 || n > kMaxCellsPerAxis)
        throw std::invalid_argument(std::string("grid: ") + axis + " needs 1 to 2^20 cells, not " + std::to_string(n));
    std::vector<double> c(n + 1);
    const double h = (hi - lo) / static_cast<double>(n);
    for (uint64_t i = 0; i < n; ++i) c[i] = lo + static_cast<double>(i) * h;
    c[n] = hi;
    for (uint64_t i = 1; i <= n; ++i)
        if (!(c[i] > c[i - 1]))
            throw std::invalid_argument(std::string("grid: ") + axis + " cells too small for the coordinates' precision");
    return c;
}

// Bounding box of the vertices used by faces with >= 3 vertices; false if none.
bool bounding_box(std::span<const MeshView> bodies, std::array<double, 6>& box) {
    bool any = false;
    box = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
           -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
    for (const MeshView& m : bodies) {
        const std::size_t nv = m.vertex_count();
        for (std::size_t f = 0; f < m.face_count(); ++f) {
            if (m.face_size(f) < 3) continue;
            for (uint32_t v : m.face(f)) {
                if (v >= nv) throw std::invalid_argument("grid: a face index is out of range");
                for (int a = 0; a < 3; ++a) {
                    const double x = m.positions[3 * std::size_t{v} + a];
                    if (!std::isfinite(x)) throw std::invalid_argument("grid: a vertex has a non-finite coordinate");
                    box[a] = std::min(box[a], x);
                    box[a + 3] = std::max(box[a + 3], x);
                }
                any = true;
            }
        }
    }
    return any;
}

uint64_t cells_to_cover(double length, double h) {
    // ceil(length / h), not counting a last cell that rounding alone would add
    const double q = length / h;
    const double c = std::ceil(q * (1 - 1e-12));
    if (!(c < static_cast<double>(kMaxCellsPerAxis))) return uint64_t{kMaxCellsPerAxis} + 1;  // rejected later
    return std::max<uint64_t>(1, static_cast<uint64_t>(c));
}

}  // namespace

bool GridAxes::uniform() const { return axis_uniform(x) && axis_uniform(y) && axis_uniform(z); }

GridAxes uniform_axes(const std::array<double, 6>& b, const std::array<uint32_t, 3>& dims) {
    GridAxes g;
    g.x = uniform_planes(b[0], b[3], dims[0], "x");
    g.y = uniform_planes(b[1], b[4], dims[1], "y");
    g.z = uniform_planes(b[2], b[5], dims[2], "z");
    return g;
}

GridAxes make_grid(std::span<const MeshView> bodies, const GridSpec& spec) {
    const bool have_dims = spec.dims[0] > 0 && spec.dims[1] > 0 && spec.dims[2] > 0;
    if (spec.cell_size < 0 || !std::isfinite(spec.cell_size))
        throw std::invalid_argument("grid: the cell size must be positive");
    std::array<double, 6> box;
    if (spec.bounds) {
        box = *spec.bounds;
        const double len[3] = {box[3] - box[0], box[4] - box[1], box[5] - box[2]};
        std::array<uint64_t, 3> n{};
        const double lmax = std::max({len[0], len[1], len[2]});
        for (int a = 0; a < 3; ++a) {
            if (!(len[a] > 0) || !std::isfinite(len[a]))
                throw std::invalid_argument("grid: bounds must be finite with min < max on every axis");
            if (have_dims)
                n[a] = spec.dims[a];
            else if (spec.cell_size > 0)
                n[a] = cells_to_cover(len[a], spec.cell_size);
            else {
                if (spec.cells < 1) throw std::invalid_argument("grid: cells must be >= 1");
                const double h = lmax / spec.cells;
                n[a] = std::max<uint64_t>(1, static_cast<uint64_t>(std::llround(len[a] / h)));
            }
        }
        GridAxes g;
        g.x = uniform_planes(box[0], box[3], n[0], "x");
        g.y = uniform_planes(box[1], box[4], n[1], "y");
        g.z = uniform_planes(box[2], box[5], n[2], "z");
        return g;
    }
    if (!bounding_box(bodies, box))
        throw std::invalid_argument("grid: no faces to take a bounding box from (give bounds)");
    const double len[3] = {box[3] - box[0], box[4] - box[1], box[5] - box[2]};
    const int longest = static_cast<int>(std::max_element(len, len + 3) - len);
    const double lmax = len[longest];
    if (!(lmax > 0)) throw std::invalid_argument("grid: the bounding box is a single point (give bounds)");
    std::array<uint64_t, 3> n{};
    std::array<double, 3> h{};
    for (int a = 0; a < 3; ++a) {
        if (have_dims) {
            n[a] = spec.dims[a];
            // one cell of padding on each side when there are >= 3 cells
            const double span = len[a] > 0 ? len[a] : lmax;
            h[a] = n[a] >= 3 ? span / static_cast<double>(n[a] - 2) : span / static_cast<double>(n[a]);
            if (len[a] > 0 && n[a] < 3) h[a] *= 1 + 1e-9;  // keep the box strictly inside
        } else if (spec.cell_size > 0) {
            h[a] = spec.cell_size;
            n[a] = cells_to_cover(len[a], h[a]) + 2;
        } else {
            if (spec.cells < 3) throw std::invalid_argument("grid: cells must be >= 3 (one cell of padding each side)");
            h[a] = lmax / (spec.cells - 2);
            n[a] = a == longest ? spec.cells : cells_to_cover(len[a], h[a]) + 2;
        }
    }
    GridAxes g;
    std::vector<double>* axes[3] = {&g.x, &g.y, &g.z};
    const char* names[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        if (n[a] > kMaxCellsPerAxis)
            throw std::invalid_argument(std::string("grid: more than 2^20 cells along ") + names[a]);
        const double centre = 0.5 * (box[a] + box[a + 3]);
        const double lo = centre - 0.5 * static_cast<double>(n[a]) * h[a];
        const double hi = lo + static_cast<double>(n[a]) * h[a];
        *axes[a] = uniform_planes(lo, hi, n[a], names[a]);
    }
    return g;
}

}  // namespace polyvol

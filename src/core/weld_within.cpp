// weld_within: points closer than a tolerance merged, for CAD exports whose
// coordinates differ in their last digits where they should be equal.
//
// Points are filed in cubic cells of side `tolerance` (sorted by cell), so
// two points within the tolerance lie in the same or in adjacent cells; each
// cell is compared with itself and with the 13 of its 26 neighbours that
// come after it, so every pair is looked at once. Pairs within the tolerance
// are united (union–find): the merge is transitive, a chain of close points
// becomes one. Each class moves onto its smallest index, and the exact weld
// (weld_in_place) then joins the now equal positions.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <vector>

#include "core/union_find.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol {
namespace {

using Cell = std::array<int64_t, 3>;

struct CellHash {
    std::size_t operator()(const Cell& c) const {
        uint64_t h = 0x9E3779B97F4A7C15ull;
        for (int64_t v : c) h = (h ^ static_cast<uint64_t>(v)) * 0xBF58476D1CE4E5B9ull;
        return static_cast<std::size_t>(h ^ (h >> 31));
    }
};

// floor(x / tolerance). Where |x| / tolerance >= 2^53, the doubles next to
// x are more than the tolerance apart, so only equal coordinates can be
// within it: such a coordinate gets a cell of its own beyond ±2^62, from its
// bits (two values may share one; their distance still tells them apart).
int64_t cell_index(double x, double tolerance) {
    const double q = std::floor(x / tolerance);
    if (std::fabs(q) < 0x1p53) return static_cast<int64_t>(q);
    uint64_t bits = 0;
    std::memcpy(&bits, &x, sizeof bits);
    const auto own = static_cast<int64_t>((uint64_t{1} << 62) + (bits & ((uint64_t{1} << 61) - 1)));
    return x < 0 ? -own : own;
}

// The comparisons past which a tolerance is called too coarse: about a
// minute of work, where an honest tolerance costs a few per point.
constexpr uint64_t kMaxComparisons = uint64_t{1} << 33;

}  // namespace

ToleranceWeld weld_within(Mesh& mesh, double tolerance) {
    if (!(tolerance > 0) || !std::isfinite(tolerance))
        throw std::invalid_argument("weld tolerance must be a positive finite number");
    const std::size_t n = mesh.vertex_count();
    const double* p = mesh.positions.data();
    const auto finite = [&](std::size_t v) {
        return std::isfinite(p[3 * v]) && std::isfinite(p[3 * v + 1]) && std::isfinite(p[3 * v + 2]);
    };

    // Points by cell.
    std::vector<std::pair<Cell, uint32_t>> filed;
    filed.reserve(n);
    for (std::size_t v = 0; v < n; ++v)
        if (finite(v))
            filed.push_back({{cell_index(p[3 * v], tolerance), cell_index(p[3 * v + 1], tolerance),
                              cell_index(p[3 * v + 2], tolerance)},
                             static_cast<uint32_t>(v)});
    std::sort(filed.begin(), filed.end());
    std::unordered_map<Cell, std::pair<std::size_t, std::size_t>, CellHash> cells;  // cell -> [begin, end) in filed
    for (std::size_t i = 0; i < filed.size();) {
        std::size_t j = i;
        while (j < filed.size() && filed[j].first == filed[i].first) ++j;
        cells.emplace(filed[i].first, std::pair{i, j});
        i = j;
    }

    const double t2 = tolerance * tolerance;
    const auto close = [&](uint32_t a, uint32_t b) {
        const double dx = p[3 * a] - p[3 * b], dy = p[3 * a + 1] - p[3 * b + 1], dz = p[3 * a + 2] - p[3 * b + 2];
        return dx * dx + dy * dy + dz * dz <= t2;
    };
    core::UnionFind classes(n);
    uint64_t comparisons = 0;
    const auto compare = [&](uint32_t a, uint32_t b) {
        if (++comparisons > kMaxComparisons)
            throw std::invalid_argument("weld tolerance " + std::to_string(tolerance) +
                                        " is too coarse for this mesh: it puts more than 2^33 pairs of points within "
                                        "reach of one another");
        if (close(a, b)) classes.unite(a, b);
    };
    for (const auto& [cell, range] : cells) {
        const auto [b0, e0] = range;
        for (std::size_t i = b0; i < e0; ++i)
            for (std::size_t j = i + 1; j < e0; ++j) compare(filed[i].second, filed[j].second);
        // The 13 neighbours after this cell (dx, dy, dz) > (0, 0, 0) lexicographically.
        for (int dx = 0; dx <= 1; ++dx)
            for (int dy = dx == 0 ? 0 : -1; dy <= 1; ++dy)
                for (int dz = dx == 0 && dy == 0 ? 1 : -1; dz <= 1; ++dz) {
                    const auto it = cells.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
                    if (it == cells.end()) continue;
                    const auto [b1, e1] = it->second;
                    for (std::size_t i = b0; i < e0; ++i)
                        for (std::size_t j = b1; j < e1; ++j) compare(filed[i].second, filed[j].second);
                }
    }

    // Each class onto its smallest index.
    std::vector<uint32_t> first(n, UINT32_MAX);
    for (uint32_t v = 0; v < n; ++v) {
        uint32_t& f = first[classes.find(v)];
        f = std::min(f, v);
    }
    ToleranceWeld result;
    for (uint32_t v = 0; v < n; ++v) {
        const uint32_t to = first[classes.find(v)];
        if (to == v) continue;
        const double d2 = (p[3 * v] - p[3 * to]) * (p[3 * v] - p[3 * to]) +
                          (p[3 * v + 1] - p[3 * to + 1]) * (p[3 * v + 1] - p[3 * to + 1]) +
                          (p[3 * v + 2] - p[3 * to + 2]) * (p[3 * v + 2] - p[3 * to + 2]);
        result.largest_move = std::max(result.largest_move, std::sqrt(d2));
        if (p[3 * v] != p[3 * to] || p[3 * v + 1] != p[3 * to + 1] || p[3 * v + 2] != p[3 * to + 2]) ++result.moved;
        std::copy_n(mesh.positions.begin() + 3 * static_cast<std::ptrdiff_t>(to), 3, mesh.positions.begin() + 3 * static_cast<std::ptrdiff_t>(v));
    }
    weld_in_place(mesh);
    return result;
}

}  // namespace polyvol

// measure/area.cpp — the fan area Σ |(b-a)×(c-a)|/2 and the welded edge
// length Σ |b-a| over undirected polygon edges.
//
// Conventions (mesh.hpp, measure.hpp): the area is that of the fan triangles
// (a concave polygon's fan counts its overlapping triangles, as the corpus
// does); the edge length counts each undirected edge of the polygon faces
// (consecutive vertices of faces with >= 3 vertices, with the closing edge)
// once, after welding vertices with bit-identical coordinates (-0.0 == +0.0,
// weld_vertices in mesh.hpp); edges whose ends weld together are skipped.
//
// Error bounds (u = 2^-53, γ_k = k u/(1 - k u), exact quantities starred):
//   norm3() (certified_sum.hpp) returns |v| with relative error <= γ5
//   (squares of components, two additions, a square root; scaled by an exact
//   power of two when the largest component is outside [2^-500, 2^500], so
//   neither overflow nor underflow of the squares matters).
//   Area, per fan triangle: n = fl(d1 × d2) from rounded differences, each
//   component off by <= γ4 (|p*| + |q*|) (its two products), so
//   |n - n*|_2 <= |n - n*|_1 <= γ4 X*, X = Σ |products|; t = norm3(n):
//   |t - |n*|| <= γ5 |n| + γ4 X* <= γ5 t/(1-γ5) + γ4 X*   -> e = γ5 t + γ4 X.
//   Length, per edge: d = fl(b - a) = d*(1+δ) per component, so
//   t = norm3(d) = |d*|(1+θ6):  |t - |d*|| <= γ6 t/(1-γ6)   -> e = γ6 t.
// finish() (below) adds the summation error (terms summed with two_sum), the
// rounding of these per-term expressions and the final halving of the area;
// underflowing products add <= 6 · 2^-1075 per triangle, covered by the
// allowance of 2^-1060 per term.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>

#include "exact/eft.hpp"
#include "measure/certified_sum.hpp"
#include "measure/methods.hpp"

namespace polyvol::measure {
namespace {

using namespace certified;

}  // namespace

SumWithBound fan_area(const MeshView& mesh) {
    constexpr double g4 = gam(4), g5 = gam(5);
    const Acc acc = reduce_fan<Acc>(mesh, [&](const double* p0, const double* p1, const double* p2, Acc& a) {
        const double d1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        const double d2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        const BoundedCross c = bounded_cross(d1, d2);
        const double t = norm3(c.n[0], c.n[1], c.n[2]);  // |(b-a)×(c-a)|
        a.add(t, g5 * t + g4 * c.X);
        ++a.units;
    });
    return finish(acc, 2.0, 0);
}

SumWithBound welded_edge_length(const MeshView& mesh) {
    const std::vector<uint32_t> weld = weld_vertices(mesh.positions);
    // Each undirected edge as (smaller welded id) << 32 | (larger welded id).
    std::vector<uint64_t> edges;
    edges.reserve(mesh.indices.size());
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
        const std::size_t k = mesh.face_size(f);
        if (k < 3) continue;
        const std::span<const uint32_t> v = mesh.face(f);
        for (std::size_t j = 0; j < k; ++j) {
            const uint32_t a = weld[v[j]], b = weld[v[j + 1 == k ? 0 : j + 1]];
            if (a == b) continue;
            edges.push_back(uint64_t{std::min(a, b)} << 32 | std::max(a, b));
        }
    }
    tbb::parallel_sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

    const double* pos = mesh.positions.data();
    constexpr double g6 = gam(6);
    const Acc acc = reduce<Acc>(edges.size(), [&](std::size_t i, Acc& a) {
        const double* pa = pos + 3 * (edges[i] >> 32);
        const double* pb = pos + 3 * (edges[i] & 0xFFFFFFFFu);
        const double t = norm3(pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]);
        a.add(t, g6 * t);
        ++a.units;
    });
    return finish(acc, 1.0, 0);
}

}  // namespace polyvol::measure

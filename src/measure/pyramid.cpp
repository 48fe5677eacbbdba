// measure/pyramid.cpp — Franklin's pyramid per face.
//
// Source: W. R. Franklin's note on polyhedron volume: the volume is the sum
// over faces of pyramids joining the origin to each face, face area times the
// signed distance of its plane from the origin / 3. Per polygon face
// (v0 v1 ... v_{k-1}), with the fan's vector area
//   A_f = Σ_{i=1}^{k-2} (v_i - v0) × (v_{i+1} - v0) / 2,
//   V_f = A_f · v0 / 3,        V = Σ_f V_f.
// This is exactly the sum of the fan's cone volumes Σ_i det(v0, v_i, v_{i+1}) / 6
// (Allgower–Schmidt (2.1)) — also for concave or non-planar faces, where it is
// the volume of the fan the face means (mesh.hpp) — because
//   det(v0, v_i, v_{i+1}) = v0 · (v_i × v_{i+1}) = v0 · ((v_i - v0) × (v_{i+1} - v0))
// (expand: the two extra terms v0·(v_i × v0) and v0·(v0 × v_{i+1}) vanish).
// For a planar face, A_f · v0 = |A_f| · (signed distance of the plane from 0).
// Computed on the given doubles (no shift): the result depends on the origin
// unless the surface is closed.
//
// Error bound (u = 2^-53, γ_k = k u / (1 - k u), exact quantities starred).
// For a face of k >= 3 vertices, m = k - 2 fan triangles, d_i = fl(v_i - v0):
//   c_i = fl(d_i × d_{i+1}) per component, e.g. c_x = fl(fl(dy dz') - fl(dz dy')):
//       |c_i - c_i*| <= γ4 P*_i,  P*_i = |dy dz'|* + |dz dy'|*  (per component)
//   S = Σ_i c_i (recursive, m - 1 additions), Q* = Σ_i P*_i:
//       |S - S*| <= γ_{m-1} Σ|c_i| + γ4 Q* <= γ_{k+1} Q*,  |S| <= (1+γ_{k+1}) Q*
//   t = fl(v0 · S):  |t - v0·S*| <= γ3 Σ_j |v0_j| |S_j| + Σ_j |v0_j| |S_j - S*_j|
//                                <= γ_{k+4} W*,  W* = Σ_j |v0_j| Q*_j
//   (a term is 2 A_f · v0 = 6 V_f; the sum is divided by 6 at the end).
// The per-face bound e = γ_{k+4} · W is evaluated from the computed |products|;
// finish() covers its rounding, the summation and the division by 6.
// Underflow: each of the 2 products per component per fan triangle adds
// <= 2^-1075 to S, multiplied by |v0_j| in the dot product, plus <= 3 · 2^-1075
// from the dot product: <= (k - 1) · 2^-1072 · (1 + |v0|_1) per face, covered by
// the allowance 2^-1060 · (1 + max |v0|_1) per unit with k - 1 units per face.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "exact/eft.hpp"
#include "measure/certified_sum.hpp"
#include "measure/methods.hpp"

namespace polyvol::measure {
namespace {

using namespace certified;
}  // namespace

SumWithBound pyramid_volume(const MeshView& mesh) {
    const double* pos = mesh.positions.data();
    const uint32_t* idx = mesh.indices.data();
    const Acc acc = reduce<Acc>(mesh.face_count(), [&](std::size_t f, Acc& a) {
        const std::size_t k = mesh.face_size(f);
        if (k < 3) return;
        const uint32_t* v = idx + mesh.face_begin(f);
        const double* p0 = pos + 3 * std::size_t{v[0]};
        const double* p1 = pos + 3 * std::size_t{v[1]};
        double d1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
        double S[3] = {0, 0, 0};  // 2 A_f
        double Q[3] = {0, 0, 0};  // Σ of |products| per component
        for (std::size_t i = 1; i + 1 < k; ++i) {
            const double* p2 = pos + 3 * std::size_t{v[i + 1]};
            const double d2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
            const double px = d1[1] * d2[2], qx = d1[2] * d2[1];
            const double py = d1[2] * d2[0], qy = d1[0] * d2[2];
            const double pz = d1[0] * d2[1], qz = d1[1] * d2[0];
            S[0] += px - qx;
            S[1] += py - qy;
            S[2] += pz - qz;
            Q[0] += std::fabs(px) + std::fabs(qx);
            Q[1] += std::fabs(py) + std::fabs(qy);
            Q[2] += std::fabs(pz) + std::fabs(qz);
            std::copy(d2, d2 + 3, d1);
        }
        const double a0 = std::fabs(p0[0]), a1 = std::fabs(p0[1]), a2 = std::fabs(p0[2]);
        const double t = (p0[0] * S[0] + p0[1] * S[1]) + p0[2] * S[2];
        const double w = (a0 * Q[0] + a1 * Q[1]) + a2 * Q[2];
        a.add(t, gam(static_cast<double>(k + 4)) * w);
        a.aux = std::max(a.aux, (a0 + a1) + a2);
        a.units += k - 1;
    });
    return finish(acc, 6.0, 1);
}

}  // namespace polyvol::measure

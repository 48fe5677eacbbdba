// Private to implicit: the Freudenthal (Kuhn) triangulation of the integer
// lattice Z^n and the zero set of a linear interpolant in one of its simplices.
//
// Source: E. L. Allgower and K. Georg, "Numerical Continuation Methods"
// (Springer 1990), 12.1 (the Freudenthal triangulation and its pivoting
// rules); the staircase triangulation of a product of simplices: e.g.
// J. A. De Loera, J. Rambau, F. Santos, "Triangulations" (Springer 2010), 6.2.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "polyvol/implicit.hpp"

namespace polyvol::implicit {

inline constexpr int kMaxDim = kImplicitMaxDimension;
using Index = std::array<int32_t, kMaxDim>;  // a lattice point; entries >= n unused

// The simplex (corner, perm): vertices v_0 = corner, v_{j+1} = v_j + e_{perm[j]}
// (j = 0 .. n-1), so v_0 < v_1 < ... < v_n componentwise and every vertex lies
// in the unit cube at `corner`. The n! permutations tile the cube; the
// simplices of all cubes form a triangulation of R^n (face to face).
struct KuhnSimplex {
    Index corner{};
    std::array<uint8_t, kMaxDim> perm{};
};

// The (n+1) vertices, vertex j in out[j].
void kuhn_vertices(const KuhnSimplex& s, int n, std::array<Index, kMaxDim + 1>& out);

// The simplex sharing the facet opposite vertex j (Freudenthal pivoting):
//   j = 0:     corner + e_{perm[0]},     perm rotated left  (perm[1..n-1], perm[0]);
//   j = n:     corner - e_{perm[n-1]},   perm rotated right (perm[n-1], perm[0..n-2]);
//   0 < j < n: same corner, perm[j-1] and perm[j] exchanged.
KuhnSimplex kuhn_neighbour(const KuhnSimplex& s, int n, int j);

// A simplex of the cubes [0, cells]^n having the edge u -> u + e_axis
// (0 <= u_axis < cells_axis, 0 <= u_k <= cells_k): corner u, except c_k = u_k - 1
// on the axes where u_k = cells_k, which come first in perm, then `axis`,
// then the rest in increasing order.
KuhnSimplex kuhn_simplex_with_edge(const Index& u, int n, int axis, const std::array<int32_t, kMaxDim>& cells);

// Lehmer rank of perm in [0, n!), and its parity (true: odd).
uint32_t permutation_rank(const std::array<uint8_t, kMaxDim>& perm, int n);
bool permutation_odd(const std::array<uint8_t, kMaxDim>& perm, int n);
uint64_t factorial(int n);

// The zero set of the linear interpolant in one simplex, triangulated, for
// every sign pattern. Pattern m has bit j set when vertex j is positive; for
// 0 < m < 2^(n+1) - 1 (both signs present) the pieces are
//   pieces[offsets[m] .. offsets[m+1]-1], piece p's vertex i being the
//   crossing of the edge (vertex[p*n+i][0] positive, vertex[p*n+i][1] negative).
// Each piece is an (n-1)-simplex oriented outward from the negative side in
// the reference simplex (corner 0, perm = identity): a simplex with an odd
// perm is the image of the reference under a map of negative determinant, so
// its pieces take their first two vertices exchanged.
//
// Why this is a triangulation that matches across facets and keeps its
// orientation for every choice of values: with P (positive) and N (negative)
// vertices, the zero set is the image of Δ^(|P|-1) × Δ^(|N|-1) under the
// projective map (α, β) -> λ_i = s α_i / f_i (i in P), λ_j = -s β_j / f_j
// (j in N), s = 1 / Σ(α_i / f_i - β_j / f_j) > 0 in barycentric coordinates,
// with (e_i, e_j) going to the crossing of edge ij. The staircase triangulation
// (monotone lattice paths from (P_0, N_0) to (P_last, N_last), P and N in
// vertex order) of the product is carried to a triangulation of the zero set
// with nondegenerate simplices for all positive f_P and negative f_N, so each
// piece's orientation is constant in the values and can be decided at the
// midpoints (f = ±1) exactly. The staircase triangulation restricts on every
// face to the staircase triangulation of that face, and the vertex order is the
// lattice's componentwise order in every simplex, so the pieces of two
// simplices agree on their common facet.
struct PieceTable {
    int n = 0;
    std::vector<uint32_t> offsets;                  // 2^(n+1) + 1 entries
    std::vector<std::array<uint8_t, 2>> vertices;   // n per piece
};

// Built once per dimension (thread-safe).
const PieceTable& piece_table(int n);

// The negative part of a d-simplex (d = n-1: a simplex of the Kuhn
// triangulation of a box face), N(ρ) = {λ in ρ : Σ λ_i f_i <= 0}, as
// d-simplices: the pulling triangulation from the first negative vertex v,
//   T(ρ) = cone(v, T(ρ without v)) ∪ cone(v, staircase(Z(ρ))),
// Z(ρ) the zero set (when ρ has both signs), T(a negative vertex) = itself.
// A pulling triangulation for a fixed vertex order restricts on every face to
// the pulling triangulation of that face and cone(v, Z(ρ)) restricts to the
// staircase pieces on the box facet, so the closure pieces of neighbouring
// face simplices (across ridges of the box too) and the surface pieces match.
// Pattern m over the d+1 vertices (bit j: vertex j positive), m < 2^(d+1)-1;
// piece p's point i is vertices[p*(d+1)+i] = (a, b): the lattice vertex a when
// a == b, else the crossing of the edge (a positive, b negative). Pieces are
// oriented with det(w_1 - w_0, ..., w_d - w_0) > 0 in the reference d-simplex
// (corner 0, perm = identity, face coordinates).
const PieceTable& closure_table(int d);

}  // namespace polyvol::implicit

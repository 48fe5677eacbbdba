// boolean/predicates.hpp — exact signs on input doubles, with the symbolic
// perturbation that puts two operands in general position.
//
// Conventions (the rest of src/boolean relies on them):
//   * orient(a, b, c, d) = det(b - a, c - a, d - a) = N·(d - a), N = (b - a) × (c - a):
//     positive when d lies on the side N points to (in front of a
//     counter-clockwise triangle (a, b, c), outside a closed outward mesh).
//   * Operand B is translated by δ = (ε, ε², ε³), ε -> 0+, relative to A.
//     Every predicate between A and B is the sign of a polynomial in ε; its
//     first nonzero coefficient decides, so no sign is ever 0 for triangles
//     with N ≠ 0, and volume, being continuous in the coordinates, is the
//     limit ε -> 0 (docs/boolean.md).
// Exact for coordinates in exact::in_safe_range (0 or 2^-160 .. 2^190):
// a floating-point filter (Shewchuk's static bounds) decides almost every
// call, and Shewchuk's expansions decide the rest.
#pragma once

namespace polyvol::boolean {

// The exact sign (-1, 0, +1) of orient(a, b, c, d).
int orient3d_sign(const double* a, const double* b, const double* c, const double* d);

// The exact sign of (v - u)_i (q - p)_j - (v - u)_j (q - p)_i: component k of
// (v - u) × (q - p) for (i, j, k) a cyclic permutation of (0, 1, 2).
int cross_component_sign(const double* u, const double* v, const double* p, const double* q, int i, int j);

// The sign of the first nonzero of the components x, y, z of (v - u) × (q - p);
// 0 when the two directions are parallel (or one is zero).
int first_cross_sign(const double* u, const double* v, const double* p, const double* q);

// orient(t0, t1, t2, x + shift·δ) for shift = +1 (x in B, the triangle in A)
// or -1 (x in A, the triangle in B): sign(D) when D ≠ 0, else shift times the
// first nonzero component of N (δ·N = ε N_x + ε² N_y + ε³ N_z). 0 only for a
// triangle with N = 0.
int perturbed_side(const double* t0, const double* t1, const double* t2, const double* x, int shift);

// orient(p, q, u + shift·δ, v + shift·δ) (segment p q from one operand,
// u v from the other): D + shift·δ·((v - u) × (q - p)).
int perturbed_orient_edges(const double* p, const double* q, const double* u, const double* v, int shift);

}  // namespace polyvol::boolean

// Generalized winding numbers of shells at points of other shells.
//
// The winding number of an oriented triangle set at p is the sum of the
// triangles' signed solid angles over 4π (Jacobson et al. 2013); for one
// triangle Van Oosterom & Strackee (1983) give
//   tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|),  a, b, c relative to p.
// It is positive behind a counter-clockwise triangle, so a closed outward
// shell has winding 1 inside and 0 outside. For a balanced shell (a closed
// 2-cycle) it is an integer off the surface and exactly 0 outside its
// bounding box: such shells are skipped there, which makes the common case
// near-linear.
//
// When the exact sums would cost more than WindingOptions::exact_budget
// solid angles (many shells, or many open ones), far clusters of triangles
// (distance > far_ratio × their radius) are replaced by the first two terms
// of the multipole expansion of the solid-angle integral (Barill et al.,
// "Fast winding numbers for soups and clouds", 2018): Ω ≈ N·r/d³ + tr(J M),
// N = Σ area vectors, r = c - p with c the area-weighted centroid, J the
// Jacobian of r/|r|³ and M = Σ (c_t - c) ⊗ N_t. Balanced shells still
// contribute exact integers up to that approximation's error.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "topology/shells.hpp"
#include "topology/welded.hpp"

namespace polyvol::topology {

// Signed solid angle of triangle (a, b, c) seen from p, in (-2π, 2π].
double solid_angle(const double* p, const double* a, const double* b, const double* c);

struct WindingOptions {
    double exact_budget = 1 << 24;  // most solid angles evaluated before approximating
    double far_ratio = 3;           // approximate clusters farther than this × their radius
    // Most solid angles and tree nodes the approximate sums may visit; the
    // shells not reached by then get NaN (clusters that all overlap are
    // never far, and the sums would be quadratic).
    double work_limit = 1 << 25;
};

// w[s] = Σ over shells t != s of the winding number of t at shells[s].probe,
// or NaN for the shells left when the work limit was reached.
std::vector<double> winding_of_other_shells(const WeldedMesh& mesh, const ShellTriangles& triangles,
                                            std::span<const ShellGeometry> shells,
                                            const WindingOptions& options = {});

}  // namespace polyvol::topology

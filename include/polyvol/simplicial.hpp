// polyvol/simplicial.hpp — volume and centroid of a polyhedron in R^n from an
// oriented simplicial boundary chain (chain.hpp), its validation and orientation.
//
// Source: E. L. Allgower and P. H. Schmidt, "Computing volumes of polyhedra",
// Math. Comp. 46 (1986) 171-174.
//   (2.1) cone:  V = sum_s det(v_1, ..., v_n) / n!
//         (the signed simplex joining the origin to each boundary simplex);
//   (2.2) prism: V = (-1)^(n-1) sum_s mean_j(v_j[n]) det[1 ... 1; w_1 ... w_n] / (n-1)!
//         with w_j = v_j without its last coordinate (the signed prism between
//         the simplex and the hyperplane x_n = 0);
//   in the plane (3.1) and (3.2) are these two: A = 1/2 sum det(v_i, v_{i+1})
//   and A = sum (y_i + y_{i+1})/2 (x_i - x_{i+1}).
// Both equal the volume for a closed chain (every (n-2)-face matched by one of
// opposite orientation) and do not depend on the origin then; several
// components (holes, cavities, islands) add up.
//
// The centroid is the first moments over the volume. For n >= 4 (and in
// Accuracy::bounded) the moments come from the selected formula's sums:
//   cone:  int x_i = sum_s det_s * (sum_j v_j[i]) / (n+1)!
//   prism: int x_i = (-1)^(n-1) sum_s D_s (sum_j w_j[i] h_j + sum_j w_j[i] * sum_j h_j) / (n+1)!
//          int x_n = (-1)^(n-1) sum_s D_s (sum_j h_j^2 + (sum_j h_j)^2) / (2 (n+1)!)
//   (D_s the (n-1)-order determinant of (2.2), h_j = v_j[n]: the integral of
//   a product of two affine functions over a d-simplex is
//   vol * (sum f_j g_j + sum f_j sum g_j) / ((d+1)(d+2))).
// Correctly rounded centroids (n <= 3 by default, any n with Accuracy::exact)
// come from the cone rule's exact sums; for a closed chain every formula gives
// the same exact moments.
//
// Accuracy:
//   * n = 2, 3 (Accuracy::automatic): the exact volume and centroid of the
//     coordinates as given, each rounded once to the nearest double (exact
//     expansions summed in a superaccumulator; GMP when a coordinate is
//     outside {0} ∪ [2^-200, 2^200]).
//   * n >= 4: double-precision LU determinants with a rigorous absolute error
//     bound on the volume and on each centroid coordinate (see
//     src/simplicial/lu_update.hpp for the derivation). The bound assumes no
//     intermediate underflow (it holds when the nonzero coordinates and
//     determinants are far above 2^-900); non-finite results get an infinite
//     bound.
//   * Accuracy::exact: correctly rounded for any n (GMP, slow: O(n^3) big
//     rational operations per simplex) — a reference for tests and small inputs.
//
// Traversal (n >= 4 and Accuracy::bounded): the simplices are visited in a
// walk over the dual graph (successive simplices share an (n-2)-face, so their
// matrices differ in one column); an LU factorisation with row pivoting is kept
// and updated by a stable column replacement (Bartels–Golub/Fletcher–Matthews,
// O(n^2) per simplex) instead of refactoring (O(n^3)), refactoring when the
// walk jumps or the tracked backward error grows past `refactor_growth` times
// that of a fresh factorisation. Traversal::refactor factorises every simplex
// afresh (the reference; same error analysis). Determinants are taken in local
// coordinates through exact identities, so that Hadamard's inequality, which
// turns the backward error into the bound, sees short, well-spread columns;
// the bound is still a worst case, typically 10^3..10^9 times the actual error
// for n >= 10 (that error is usually a few units of 10^-15, relative).
//
// Faces are identified by a keyed 128-bit hash of their vertex sets (random
// keys per process): two different faces are confused with probability about
// 2^-128 per pair.
//
// Topology is decided after welding vertices with bit-identical coordinates
// (-0.0 equal to +0.0, NaN never welded). Non-finite coordinates on a used
// vertex give NaN results.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "polyvol/chain.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol {

enum class SimplexFormula { cone, prism };           // (2.1), (2.2)
enum class ChainAccuracy { automatic, bounded, exact };
enum class Traversal { rank_one, refactor };

std::string_view simplex_formula_name(SimplexFormula f);  // "cone", "prism"
std::string_view chain_accuracy_name(ChainAccuracy a);    // "automatic", "bounded", "exact"
std::string_view traversal_name(Traversal t);             // "rank-one", "refactor"

struct ChainOptions {
    SimplexFormula formula = SimplexFormula::cone;
    // automatic: exact (correctly rounded) for n <= 3, bounded for n >= 4.
    ChainAccuracy accuracy = ChainAccuracy::automatic;
    // How the determinants are formed on the bounded path.
    Traversal traversal = Traversal::rank_one;
    // Rank-one traversal: refactor when the tracked relative backward error of
    // the updated factors exceeds refactor_growth times that of the last fresh
    // factorisation (>= 1; larger means fewer refactorisations, looser bounds),
    // or when the walk has moved four simplex diameters away from the local
    // origin of the factors (see src/simplicial/volume.cpp).
    double refactor_growth = 8.0;
    bool centroid = true;  // compute the first moments and centroid
};

// An (n-2)-face that is not matched by one of opposite orientation.
struct UnmatchedFace {
    std::vector<uint32_t> vertices;  // input vertex indices: `simplex` as listed, without the vertex it omits
    std::size_t simplex = 0;         // the first simplex using it
    std::size_t same = 0;            // uses with that induced orientation
    std::size_t opposite = 0;        // uses with the opposite one
};

// Validation: a chain is a closed boundary (a cycle) when every (n-2)-face is
// used as often in one induced orientation as in the other; a closed
// pseudo-manifold boundary uses each exactly twice, once each way.
struct ChainReport {
    int dimension = 0;
    std::size_t simplices = 0;
    std::size_t vertices = 0;
    std::size_t vertices_welded = 0;        // distinct positions
    std::size_t degenerate_simplices = 0;   // repeated vertex (after welding): contribute nothing
    std::size_t faces = 0;                  // distinct (n-2)-faces of the non-degenerate simplices
    std::size_t unmatched_faces = 0;        // faces used a different number of times in the two orientations
    std::size_t boundary_faces = 0;         // used once
    std::size_t misoriented_faces = 0;      // used twice, both times with the same orientation
    std::size_t nonmanifold_faces = 0;      // used more than twice
    std::size_t components = 0;             // face-connected components of non-degenerate simplices
    std::optional<UnmatchedFace> unmatched_example;  // the first unmatched face, by first use
    bool closed() const { return unmatched_faces == 0; }
};

struct ChainStats {
    std::size_t factorizations = 0;  // fresh LU factorisations (walk starts, jumps, stability refactors)
    std::size_t updates = 0;         // column replacements
    std::size_t jumps = 0;           // walk steps to a simplex not adjacent to the previous one
    std::size_t stability_refactors = 0;  // refactorisations because the error grew
    std::size_t pass_throughs = 0;   // already-counted simplices walked through to reach a new one
    std::size_t elimination_steps = 0;  // sum over updates of the eliminations restoring triangularity (order - 1 - leaving position)
    double max_backward_error = 0;   // largest tracked sum_c ||e_c|| / ||a_c|| met
    double seconds_topology = 0;     // welding, face matching, the walk (wall clock)
    double seconds_sweep = 0;        // determinants and sums (wall clock)
    double cpu_seconds_topology = 0; // the same as processor time (std::clock)
    double cpu_seconds_sweep = 0;
};

struct ChainVolume {
    int dimension = 0;
    double volume = 0;              // signed: negative for an inward chain
    double volume_error_bound = 0;  // |volume - exact| <= bound (0 when correctly rounded)
    bool volume_correctly_rounded = false;
    std::vector<double> centroid;   // NaN when the volume may be 0 (or is 0 exactly)
    double centroid_error_bound = 0;  // max over coordinates, absolute (0 when correctly rounded; inf when undetermined)
    bool centroid_correctly_rounded = false;
    SimplexFormula formula = SimplexFormula::cone;
    ChainAccuracy accuracy = ChainAccuracy::bounded;  // as resolved: bounded or exact
    Traversal traversal = Traversal::rank_one;
    ChainReport topology;
    ChainStats stats;
};

// Validation only (welding, face matching).
ChainReport validate_chain(const ChainView& chain);

// Volume, centroid and validation. Throws std::invalid_argument when the
// arrays are inconsistent (dimension < 2, sizes not multiples of n, an index
// >= vertex_count()).
ChainVolume chain_volume(const ChainView& chain, const ChainOptions& options = {});

// Orients a chain in place: within each face-connected component the simplices
// are made consistent across every face used exactly twice (a breadth-first
// walk, flipping a simplex by exchanging its first two vertices), then every
// component is turned so that its volume has the sign (-1)^depth, depth being
// the number of other components around it (decided by ray parity): outer
// boundaries outward, cavities and holes inward, islands outward again.
struct OrientResult {
    bool orientable = true;         // false: some component cannot be made consistent (nothing changed)
    std::size_t flipped = 0;        // simplices whose orientation was reversed
    std::size_t components = 0;
    std::size_t undecided = 0;      // components whose volume sign or nesting could not be decided, or that are not
                                    // closed (cut off by faces used more than twice): left as made consistent
};
OrientResult orient_chain(Chain& chain);

// The same for a 3D mesh (mesh.hpp): its faces made consistent within each
// shell and turned so that outer shells face outward and cavities inward
// (orient_chain on the fan triangles; a face is reversed as
// (v0, vk, ..., v1)). `flipped` counts faces. Nothing changes when the
// mesh is not orientable (a shell with an edge used twice in one direction
// that no flip can fix: a Möbius strip, or three faces on an edge).
OrientResult orient_mesh(Mesh& mesh);

// The 2D chain of a polygon set: edge (v_i, v_{i+1}) for each loop, wrapping.
Chain polygon_chain(const PolygonsView& polygons);

// The loops wound against the rule (an outer loop counter-clockwise, a hole
// in it clockwise, an island in the hole counter-clockwise again): those
// wound the same way as the innermost loop that contains them. A hole wound
// like its outer loop adds its area instead of taking it away (orient_chain
// winds loops by nesting). Nesting from one vertex of each loop, tested
// against the others (loops are taken not to cross); areas and tests in
// double: a hint for a warning, not a predicate (a loop of zero area, or
// one whose vertex lies on another loop, is never counted).
std::vector<uint32_t> loops_wound_like_their_container(const PolygonsView& polygons);

// Area (in ChainVolume::volume) and centroid of polygons with holes and
// islands, by (3.1) (SimplexFormula::cone) or (3.2) (prism); correctly rounded
// unless options.accuracy says bounded.
ChainVolume polygon_area(const PolygonsView& polygons, const ChainOptions& options = {});

}  // namespace polyvol

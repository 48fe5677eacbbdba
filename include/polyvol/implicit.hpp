// polyvol/implicit.hpp — the volume of a solid {x in R^n : F(x) <= 0} bounded
// by an implicitly defined surface, from a piecewise-linear (PL) approximation
// of F = 0 on a Freudenthal (Kuhn) triangulation, measured by the boundary
// formulas of simplicial.hpp.
//
// Sources: E. L. Allgower and P. H. Schmidt, "An algorithm for piecewise-linear
// approximation of an implicitly defined manifold", SIAM J. Numer. Anal. 22
// (1985) 322-346, and "Computing volumes of polyhedra", Math. Comp. 46 (1986)
// 171-174; E. L. Allgower and K. Georg, "Numerical Continuation Methods"
// (Springer 1990), ch. 12 (Freudenthal triangulation, pivoting rules) and 15.
//
// The method (docs/implicit.md):
//   * Lattice. The box [lo_k, hi_k] gets N_k = 2 ceil((hi_k - lo_k) / (2h))
//     cells per axis (even, so that the lattice of spacing 2 h_k exists for the
//     error estimate); spacing h_k = (hi_k - lo_k) / N_k <= h; vertex i has
//     x_k = lo_k + i_k h_k (hi_k exactly for i_k = N_k).
//   * Kuhn triangulation. The cube with corner c (integers) and a permutation
//     pi of the axes give the n-simplex v_0 = c, v_{j+1} = v_j + e_{pi(j)}:
//     n! simplices per cube, meeting face to face across cubes.
//   * Sign rule (the symbolic perturbation). A vertex is positive when
//     F > 0 and negative when F <= 0: a value exactly 0 is treated as a tiny
//     negative one, so every simplex is either crossed (both signs) or not,
//     and the PL surface is a closed manifold with no special cases. The PL
//     solid is {PL interpolant of F <= 0}, zeros included.
//   * In each crossed simplex the zero set of the linear interpolant is a
//     convex polytope, combinatorially Δ^(p-1) × Δ^(q-1) (p positive and q
//     negative vertices), with vertices at the crossings of the p q
//     sign-changing edges, x = a + t (b - a), t = F(a) / (F(a) - F(b)),
//     a the negative end (computed once per edge, so neighbours share points
//     exactly). It is cut into C(n-1, p-1) (n-1)-simplices by the staircase
//     triangulation of the product for the vertex order v_0 < ... < v_n
//     (the componentwise order of the lattice, the same in every simplex, so
//     the pieces of two simplices match across their common facet), oriented
//     outward (the negative side inside; the orientation is decided once per
//     sign pattern with exact integer determinants and the parity of pi).
//   * Continuation. Only crossed cubes are visited: from a crossed cube the
//     walk steps across each cube facet with both signs to the neighbour (a
//     facet with both signs holds a crossed simplex facet, and the surface
//     passes between cubes only through crossed simplex facets), with a hash
//     set of visited cubes; in each cube the crossed Kuhn simplices are
//     enumerated depth first over the permutations' prefixes, a prefix being
//     dropped when no corner above its last vertex has the missing sign.
//     Cost follows the surface: O(area / h^(n-1)).
//   * Seeds. A coarse lattice (coarse_cells per axis, a sublattice of the
//     fine one, its cost independent of h) is sampled, every coarse axis
//     segment with a sign change is bisected down to one fine edge, and a walk
//     starts from a simplex containing that edge unless its component has
//     already been walked. Every component of the PL surface that separates
//     two coarse-lattice vertices is found; a component enclosing no coarse
//     vertex (smaller than the coarse spacing) may be missed — raise
//     coarse_cells or pass a seed point. With coarse_cells >= N_k on every axis
//     the scan is exhaustive.
//   * The box (clipping rule). F is taken as +infinity outside the box: the
//     PL solid is clipped by the box. The walk stays in the box's cubes, and
//     the chain is closed in the box's faces: every simplex of a face's own
//     Kuhn triangulation with a vertex where F <= 0 contributes its part with
//     F <= 0, cut by the pulling triangulation from its first such vertex
//     (which restricts to the same rule on shared faces and ridges, and to the
//     surface's staircase pieces on the face), oriented out of the box; these
//     face simplices are found by walks over each face's cubes (across cube
//     facets with a vertex where F <= 0) seeded from the box boundary
//     vertices with F <= 0 that were sampled; a face cube with both signs
//     also starts a surface walk from the cube owning it. With BoxRule::error, a
//     lattice vertex on the box boundary with F <= 0 is an error instead
//     (ImplicitError::Code::touches_box).
//   * Volume. The pieces form a closed oriented boundary chain (chain.hpp)
//     by construction, and its volume is the cone formula (2.1) of
//     simplicial.hpp, V = Σ det(p_1 - O, ..., p_n - O) / n!. By default
//     (keep_chain false, SimplexFormula::cone) the volume is streamed: no
//     chain is built, no point map, no validation; each crossed simplex (and
//     each box-face simplex) is recorded as the walk meets it, records are
//     buffered in blocks reduced on oneTBB workers (Gaussian elimination with
//     pivoting per piece, in the coordinates [p_1 - O, p_2 - p_1, ...], with
//     Higham's a-priori bound), and the blocks' sums are combined in walk
//     order, so the result has the same bits for every thread count. A
//     piece's points are recomputed from its edge (a function of the edge's
//     two lattice vertices and their two F values, a the negative end), the
//     same bits the chain path stores. The apex O is the box corner lo: the
//     pieces in the box faces x_k = lo_k contribute exactly 0 and are not
//     measured. With keep_chain (or SimplexFormula::prism) the chain is built
//     and measured by chain_volume: exact rounded once for n <= 3, with a
//     rigorous rounding bound for n >= 4.
//     Either way ImplicitPass::rounding_error_bound bounds |volume - exact
//     volume of that chain| (the PL surface with its points as computed): the
//     rounding of the determinants and of their sum, not the PL
//     approximation's error (that is the estimate below).
//   * Error estimate (Richardson). For a smooth surface the PL volume is
//     V(h) = V + C h^2 + o(h^2). The same computation on the lattice of
//     spacing 2h gives V(2h); then
//       volume_extrapolated = (4 V(h) - V(2h)) / 3,
//       error_estimate      = |V(h) - V(2h)| / 3 + rounding bounds,
//     the estimated error of V(h). The reported `volume` is the extrapolated
//     value; error_estimate bounds its error comfortably whenever the O(h^2)
//     regime holds (the extrapolated error is of higher order). The extra
//     pass costs 2^-(n-1) of the main one.
//   * The extrapolation's own estimate. Where every N_k is a multiple of 4,
//     the lattice of spacing 4h gives V(4h) too, and R(2h) = (4 V(2h) -
//     V(4h)) / 3. When the differences show the h^2 regime (their ratio
//     (V(2h) - V(4h)) / (V(h) - V(2h)) within [3, 5]; 4 in theory), the
//     extrapolation converges at a higher order q >= 1, so
//       |R(h) - V| = |R(h) - R(2h)| / (2^q - 1) <= |R(h) - R(2h)|,
//     and extrapolated_error_estimate is |R(h) - R(2h)| + rounding bounds:
//     the error of `volume` itself, far smaller than error_estimate. NaN
//     otherwise, or where it is not below error_estimate (4h too coarse for
//     R's regime; then error_estimate is the one to quote). It costs 4^-(n-1)
//     of the main pass more.
//
// F must be a pure function (the same value for the same point); it is called
// from the calling thread only. A NaN at any vertex where it is evaluated is
// an error (ImplicitError::Code::not_a_number); ±infinity are values like any
// other (a crossing next to an infinite value lies at the other end).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "polyvol/chain.hpp"
#include "polyvol/simplicial.hpp"

namespace polyvol {

// F(x) for x in R^n (x.size() == dimension). Inside is F <= 0.
using ImplicitFunction = std::function<double(std::span<const double>)>;
// F at k points at once (for callers whose F costs a call, as a Python
// function on a numpy array): points holds k × n coordinates, point i at
// points[n*i .. n*i + n-1]; values receives the k values. The walk asks for
// a cube's corners (the coarse scan, a lattice line) per call.
using ImplicitBatchFunction = std::function<void(std::span<const double> points, std::span<double> values)>;

inline constexpr int kImplicitMaxDimension = 8;

enum class BoxRule {
    clip,   // F is +infinity outside the box: the solid is clipped by the box
    error,  // a lattice vertex on the box boundary with F <= 0 throws ImplicitError
};

// Where a long computation is: called from the calling thread at the start
// of each pass and every 2^18 evaluations of F within it.
struct ImplicitProgress {
    int pass = 0;                      // 0: the 2h lattice (the estimate's), 1: the lattice at h
    std::size_t evaluations = 0;       // so far in this pass
    // Pass 1 after the 2h pass: its evaluations and time scaled to h (the
    // seeding scan's as they were, the surface's times 2^(n-1)); else 0 (unknown).
    double expected_evaluations = 0;
    double expected_seconds = 0;
};

struct ImplicitOptions {
    // n, 2 <= n <= kImplicitMaxDimension.
    int dimension = 3;
    // The box [lo_k, hi_k]: one entry applies to every axis, otherwise exactly
    // `dimension` entries; lo_k < hi_k, finite.
    std::vector<double> lo{-1.0};
    std::vector<double> hi{1.0};
    // Requested lattice spacing (> 0); the spacing used per axis is
    // h_k = (hi_k - lo_k) / N_k <= h with N_k even (see the top of this file).
    // 0: the widest side / default_cells(dimension).
    double h = 0;
    // Cells per axis of the coarse seeding scan (capped at N_k; the scan costs
    // about (coarse_cells + 1)^n evaluations, independent of h). 0: automatic,
    // default_coarse_cells(dimension). -1: no scan (seeds only).
    int coarse_cells = 0;
    // Extra seed points, flat: point s is seeds[n*s .. n*s + n-1]. From the
    // lattice vertex nearest to each, the lattice line in the +x_1 direction is
    // followed to the first sign change, and the component of the surface
    // found there is walked (if it is not already).
    std::vector<double> seeds;
    BoxRule box_rule = BoxRule::clip;
    // Compute the lattice of spacing 2h as well, for the Richardson estimate.
    bool error_estimate = true;
    // Keep the fine PL surface (ImplicitVolume::chain); its volume is then
    // chain_volume's. Without it (and with the cone formula) the volume is
    // streamed: no chain is built (see the top of this file).
    bool keep_chain = false;
    // cone: (2.1) — streamed, or chain_volume with keep_chain; prism: (2.2),
    // through a chain and chain_volume.
    SimplexFormula formula = SimplexFormula::cone;
    // Refuse (ImplicitError::Code::too_large) to build more boundary simplices
    // than this in one pass — a guard against an h far too small.
    std::size_t max_boundary_simplices = std::size_t{1} << 28;
    // Refuse (ImplicitError::Code::too_large) work that would take more
    // memory than this (bytes; 0: no limit). The memory follows the lattice
    // vertices F is evaluated at (their values, the cubes walked): about
    // kImplicitBytesPerEvaluation each, plus the chain when kept. With the
    // error estimate, the 2h lattice runs first and the fine one's need is
    // estimated from it (2^(n-1) times its evaluations) before it starts;
    // either pass stops when its evaluations pass the limit.
    std::size_t max_memory_bytes = 0;
    // Progress, for a caller that shows it (the library never prints); empty: none.
    std::function<void(const ImplicitProgress&)> progress;
};

// Measured peak memory per evaluated lattice vertex (values, visited cubes,
// hash tables at their load factor): 135 B in 3D, 176 B in 4D on a ball.
inline constexpr std::size_t kImplicitBytesPerEvaluation = 200;

// Default lattice cells along the widest side: 512, 96, 32, 16, 12, 8, 8 for
// n = 2 .. 8.
int default_cells(int dimension);
// Default coarse scan cells per axis: 256, 48, 16, 10, 6, 5, 4 for n = 2 .. 8.
int default_coarse_cells(int dimension);

// One lattice: the PL surface at one spacing and its volume.
struct ImplicitPass {
    std::vector<double> spacing;        // h_k
    std::vector<int64_t> cells;         // N_k
    double volume = 0;                  // volume of the PL solid (its chain's volume)
    // |volume - exact volume of the chain| <= this: the chain as computed (its
    // points rounded as they are), the rounding of the determinants and of
    // their sum only — not the PL approximation's error.
    double rounding_error_bound = 0;
    std::size_t boundary_simplices = 0; // (n-1)-simplices of the chain (some are flat ones in the box faces)
    std::size_t crossed_simplices = 0;  // Kuhn n-simplices with both signs in the cubes walked
    std::size_t function_evaluations = 0;
    // Walks through the box's cubes: pieces of the PL surface inside the box
    // (two sheets through one cube count once).
    std::size_t components = 0;
    // Simplices of the box faces' triangulations with a vertex where F <= 0,
    // in the face cubes walked.
    std::size_t face_simplices = 0;
    std::size_t face_walks = 0;         // walks over the box faces (the clipped solid's faces in the box boundary)
    std::size_t box_vertices_inside = 0;  // lattice vertices on the box boundary with F <= 0 among those sampled
    double seconds = 0;
};

struct ImplicitVolume {
    int dimension = 0;
    double h = 0;                    // requested spacing (options.h or its default)
    // The best estimate of the volume of {F <= 0} within the box: the
    // Richardson extrapolation when error_estimate, else fine.volume.
    double volume = 0;
    // |V(h) - V(2h)| / 3 + both rounding bounds: the estimated error of
    // fine.volume, and (conservatively) of volume. NaN without error_estimate.
    double error_estimate = 0;
    double volume_extrapolated = 0;  // (4 V(h) - V(2h)) / 3 (NaN without error_estimate)
    // |R(h) - R(2h)| + rounding bounds: the estimated error of volume_extrapolated
    // (see the top of this file); NaN where the 4h lattice does not show the h^2 regime.
    double extrapolated_error_estimate = 0;
    ImplicitPass fine;               // spacing h
    std::optional<ImplicitPass> coarse;  // spacing 2h (when error_estimate)
    std::optional<ImplicitPass> coarser; // spacing 4h (when error_estimate and every N_k is a multiple of 4)
    bool clipped = false;            // the fine PL solid reaches the box boundary
    double seconds = 0;              // wall time of everything
    std::optional<Chain> chain;      // the fine PL surface (when keep_chain)
};

class ImplicitError : public std::runtime_error {
public:
    enum class Code {
        not_a_number,  // F returned NaN at `point`
        touches_box,   // BoxRule::error and F <= 0 at `point` on the box boundary
        too_large,     // more than max_boundary_simplices, or the lattice does not fit 64-bit keys
    };
    ImplicitError(Code code, std::vector<double> point, const std::string& message)
        : std::runtime_error(message), code_(code), point_(std::move(point)) {}
    Code code() const { return code_; }
    const std::vector<double>& point() const { return point_; }

private:
    Code code_;
    std::vector<double> point_;
};

// The volume of {x in box : F(x) <= 0} (see the top of this file). Throws
// std::invalid_argument for invalid options and ImplicitError as documented.
ImplicitVolume implicit_volume(const ImplicitFunction& f, const ImplicitOptions& options);
// The same with F evaluated in batches: a cube's corners and those of its
// neighbours (up to 4^n points, n <= 4), a coarse lattice line. The result
// has the same bits as with the pointwise F of the same values; F is called
// at some points the pointwise walk never needs (ImplicitPass::
// function_evaluations counts them), in far fewer calls.
ImplicitVolume implicit_volume_batch(const ImplicitBatchFunction& f, const ImplicitOptions& options);

// The PL surface on the lattice of spacing options.h only (no estimate), as a
// closed oriented chain; `pass` receives the counts (its volume is left 0).
Chain implicit_surface(const ImplicitFunction& f, const ImplicitOptions& options, ImplicitPass* pass = nullptr);

// Richardson extrapolation for an error c h^order: from V(h) and V(h * ratio),
// (ratio^order V(h) - V(h ratio)) / (ratio^order - 1), and the estimated error
// of V(h), |V(h) - V(h ratio)| / (ratio^order - 1).
struct Richardson {
    double extrapolated = 0;
    double error_of_fine = 0;
};
Richardson richardson(double fine, double coarse, double ratio = 2.0, double order = 2.0);

// Expressions (muparser, Debian libmuparser-dev). Variables: x, y, z are the
// first three coordinates (as many as the dimension has), x1 .. xn all of them;
// also the constant pi, muparser's functions (sin, cos, tan, asin, acos, atan,
// sinh, cosh, tanh, exp, ln, log, log2, log10, sqrt, abs, sign, rint, min,
// max, sum, avg), the operators + - * / ^ and comparisons, and ?: .
class ExpressionError : public std::invalid_argument {
public:
    ExpressionError(const std::string& message, int position)
        : std::invalid_argument(message), position_(position) {}
    // 0-based character position in the expression, or -1.
    int position() const { return position_; }

private:
    int position_;
};

// F from an expression in `dimension` coordinates. The returned function is
// not thread-safe (one muparser instance). Throws ExpressionError for a
// syntax error, an unknown name, or a coordinate beyond `dimension`.
ImplicitFunction parse_implicit_expression(const std::string& expression, int dimension);

// The highest coordinate an expression names (1 for x only, 2 with y or x2,
// 3 with z or x3, k with xk), 0 when it names none. Throws ExpressionError
// like parse_implicit_expression with the largest dimension.
int expression_coordinates(const std::string& expression);

}  // namespace polyvol

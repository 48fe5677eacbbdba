// Volumes of solids bounded by implicit surfaces (implicit.hpp): n-balls,
// an ellipsoid and a torus against closed forms, second-order convergence,
// the Richardson estimate covering the true error, the symbolic perturbation
// (F = 0 at lattice vertices), the clipping rule, NaN, empty sets, closed
// chains, the streamed volume against chain_volume (and the exact chain
// volume), the same bits for every thread count and with or without AVX2,
// cost following the surface, and expressions.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>
#include <vector>

#include "core/simd.hpp"
#include "implicit/cone_sum.hpp"
#include "implicit/kuhn.hpp"
#include "polyvol/implicit.hpp"
#include "polyvol/simplicial.hpp"

namespace {

using namespace polyvol;

double ball_volume(int n) { return std::pow(std::numbers::pi, n / 2.0) / std::tgamma(n / 2.0 + 1); }

double sum_of_squares(std::span<const double> x) {
    double s = 0;
    for (double v : x) s += v * v;
    return s;
}

// |x|^2 - 1: the unit ball.
double unit_ball(std::span<const double> x) { return sum_of_squares(x) - 1.0; }

ImplicitOptions box_options(int n, double lo, double hi, double h) {
    ImplicitOptions o;
    o.dimension = n;
    o.lo = {lo};
    o.hi = {hi};
    o.h = h;
    return o;
}

uint64_t binomial(int n, int k) {
    uint64_t r = 1;
    for (int i = 1; i <= k; ++i) r = r * static_cast<uint64_t>(n - k + i) / static_cast<uint64_t>(i);
    return r;
}

// --- the building blocks ---------------------------------------------------

TEST(KuhnTriangulation, PieceCountsAreStaircaseCounts) {
    for (int n = 2; n <= 6; ++n) {
        const implicit::PieceTable& t = implicit::piece_table(n);
        for (uint32_t m = 1; m + 1 < (1u << (n + 1)); ++m) {
            const int positive = __builtin_popcount(m);
            EXPECT_EQ(t.offsets[m + 1] - t.offsets[m], binomial(n - 1, positive - 1)) << "n=" << n << " m=" << m;
        }
        EXPECT_EQ(t.offsets[1] - t.offsets[0], 0u);
    }
}

TEST(KuhnTriangulation, NeighbourIsAnInvolutionSharingTheFacet) {
    for (int n = 2; n <= 6; ++n) {
        implicit::KuhnSimplex s;
        for (int k = 0; k < n; ++k) {
            s.corner[k] = 3 + k;
            s.perm[k] = static_cast<uint8_t>((k * 5 + 1) % n);  // a permutation when gcd(5, n) = 1
        }
        if (n == 5)
            for (int k = 0; k < n; ++k) s.perm[k] = static_cast<uint8_t>(n - 1 - k);
        std::array<implicit::Index, implicit::kMaxDim + 1> v, w;
        implicit::kuhn_vertices(s, n, v);
        for (int j = 0; j <= n; ++j) {
            const implicit::KuhnSimplex t = implicit::kuhn_neighbour(s, n, j);
            implicit::kuhn_vertices(t, n, w);
            int shared = 0;
            for (int a = 0; a <= n; ++a)
                for (int b = 0; b <= n; ++b) shared += v[a] == w[b] ? 1 : 0;
            EXPECT_EQ(shared, n) << "n=" << n << " j=" << j;
            // Back across the same facet.
            bool back = false;
            for (int i = 0; i <= n; ++i) {
                const implicit::KuhnSimplex u = implicit::kuhn_neighbour(t, n, i);
                back = back || (u.corner == s.corner && u.perm == s.perm);
            }
            EXPECT_TRUE(back) << "n=" << n << " j=" << j;
        }
    }
}

TEST(Richardson, ExactForAQuadraticError) {
    // V(h) = 2 + 3 h^2
    const Richardson r = richardson(2 + 3 * 0.01, 2 + 3 * 0.04);
    EXPECT_NEAR(r.extrapolated, 2.0, 1e-15);
    EXPECT_NEAR(r.error_of_fine, 0.03, 1e-15);
}

// --- volumes against closed forms -----------------------------------------

TEST(ImplicitVolume, UnitDiskAreaIsPi) {
    const ImplicitVolume r = implicit_volume(unit_ball, box_options(2, -1.25, 1.25, 1.0 / 32));
    EXPECT_NEAR(r.volume, std::numbers::pi, 1e-3 * std::numbers::pi);
    EXPECT_LE(std::fabs(r.volume - std::numbers::pi), r.error_estimate);
    EXPECT_EQ(r.fine.components, 1u);
    EXPECT_FALSE(r.clipped);
}

// The orthant {x_k >= 0 for even k, <= 0 for odd k} (0-based k) within
// radius r: [0, r] x [-r, 0] x [0, r] x ...
ImplicitOptions alternating_orthant(int n, double r, double h) {
    ImplicitOptions o = box_options(n, 0, 0, h);
    o.lo.assign(static_cast<std::size_t>(n), 0.0);
    o.hi.assign(static_cast<std::size_t>(n), 0.0);
    for (int k = 0; k < n; ++k) (k % 2 == 0 ? o.hi : o.lo)[static_cast<std::size_t>(k)] = k % 2 == 0 ? r : -r;
    return o;
}

// Stated spacings: n = 3 the whole ball, h = 1/16; n = 4 .. 6 one orthant
// (the ball's part there, clipped by the box; 2^n times it; it costs 2^-n of
// the whole ball): n = 4 [0, 1.2]^4 with h = 0.1; n = 5 and 6 the
// alternating orthant [0, r] x [-r, 0] x ..., whose Kuhn simplices the sphere
// crosses about half as often as those of [0, r]^n (the main diagonal of
// the cubes is far from the sphere's normal there) for the same PL solid
// (F is separable: see PlSolidOfASeparableFDoesNotDependOnTheTriangulation):
// n = 5 with r = 1.2, h = 0.15 (8 cells: -0.26%, 0.8 million boundary
// simplices), n = 6 with r = 1, h = 0.17 (6 cells of 1/6: -0.91%, 18 million
// boundary simplices, the cheapest lattice found within 1e-2; 2 s of CPU in
// the Release build; docs/implicit.md).
TEST(ImplicitVolume, UnitBall3) {
    const ImplicitVolume r = implicit_volume(unit_ball, box_options(3, -1.25, 1.25, 1.0 / 16));
    EXPECT_NEAR(r.volume, ball_volume(3), 1e-3 * ball_volume(3));
    EXPECT_LE(std::fabs(r.volume - ball_volume(3)), r.error_estimate);
}

// Progress: each pass announced at its start, then its evaluations so far,
// increasing; the fine pass does about what it expects (the seeding scan's
// evaluations as at 2h, the surface's 2^(n-1) times as many).
TEST(ImplicitVolume, ProgressReportsEachPass) {
    ImplicitOptions o = box_options(3, -1.25, 1.25, 1.0 / 64);
    std::vector<ImplicitProgress> seen;
    o.progress = [&](const ImplicitProgress& p) { seen.push_back(p); };
    const ImplicitVolume r = implicit_volume(unit_ball, o);
    ASSERT_GE(seen.size(), 3u);
    EXPECT_EQ(seen.front().pass, 0);
    EXPECT_EQ(seen.front().evaluations, 0u);
    std::size_t starts = 0;
    for (std::size_t i = 0; i < seen.size(); ++i) {
        if (seen[i].evaluations == 0) {
            ++starts;
            continue;
        }
        EXPECT_EQ(seen[i].pass, seen[i - 1].pass);
        EXPECT_GT(seen[i].evaluations, seen[i - 1].evaluations);
    }
    EXPECT_EQ(starts, 2u);
    const ImplicitProgress& fine = *std::find_if(seen.begin(), seen.end(), [](const ImplicitProgress& p) { return p.pass == 1; });
    EXPECT_GT(fine.expected_evaluations, static_cast<double>(r.coarse->function_evaluations));
    EXPECT_NEAR(static_cast<double>(r.fine.function_evaluations), fine.expected_evaluations, 0.2 * fine.expected_evaluations);
}

TEST(ImplicitVolume, UnitBall4Orthant) {
    const ImplicitVolume r = implicit_volume(unit_ball, box_options(4, 0, 1.2, 0.1));
    EXPECT_NEAR(16 * r.volume, ball_volume(4), 1e-3 * ball_volume(4));
    EXPECT_LE(std::fabs(16 * r.volume - ball_volume(4)), 16 * r.error_estimate);
    EXPECT_TRUE(r.clipped);
}

TEST(ImplicitVolume, UnitBall5Orthant) {
    const ImplicitVolume r = implicit_volume(unit_ball, alternating_orthant(5, 1.2, 0.15));
    EXPECT_EQ(r.fine.cells[0], 8);
    EXPECT_NEAR(32 * r.volume, ball_volume(5), 1e-2 * ball_volume(5));
    EXPECT_LE(std::fabs(32 * r.volume - ball_volume(5)), 32 * r.error_estimate);
}

// The box touches the sphere at the lattice vertices ±e_k, where F is
// exactly 0 (inside by the sign rule).
TEST(ImplicitVolume, UnitBall6Orthant) {
    const ImplicitVolume r = implicit_volume(unit_ball, alternating_orthant(6, 1, 0.17));
    EXPECT_EQ(r.fine.cells[0], 6);
    EXPECT_NEAR(64 * r.volume, ball_volume(6), 1e-2 * ball_volume(6));
    EXPECT_LE(std::fabs(64 * r.volume - ball_volume(6)), 64 * r.error_estimate);
    EXPECT_LT(r.fine.rounding_error_bound, 1e-9 * r.fine.volume);
}

// For F = Σ_k f_k(x_k) the linear interpolant on a Kuhn simplex is
// Σ_k (f_k interpolated along axis k): every edge moves along one axis. So the
// PL solid does not depend on the triangulation, and mirroring the box in
// some axes (a different triangulation of the same solid: the Kuhn simplices
// follow the lattice's order) must give the same volume within the two
// rounding bounds (lattice coordinates exact here, F symmetric, so the mirror
// image's points are the exact negatives). The chains differ.
TEST(ImplicitVolume, PlSolidOfASeparableFDoesNotDependOnTheTriangulation) {
    ImplicitOptions plain = box_options(4, 0, 1.5, 0.25);
    plain.error_estimate = false;
    ImplicitOptions mirrored = alternating_orthant(4, 1.5, 0.25);
    mirrored.error_estimate = false;
    const ImplicitVolume a = implicit_volume(unit_ball, plain), b = implicit_volume(unit_ball, mirrored);
    EXPECT_NE(a.fine.boundary_simplices, b.fine.boundary_simplices);
    EXPECT_LE(std::fabs(a.fine.volume - b.fine.volume), a.fine.rounding_error_bound + b.fine.rounding_error_bound);
    EXPECT_GT(a.fine.volume, 0.25);
}

TEST(ImplicitVolume, OrthantTimesEightIsTheWholeBall) {
    const ImplicitVolume whole = implicit_volume(unit_ball, box_options(3, -1.25, 1.25, 0.125));
    const ImplicitVolume orthant = implicit_volume(unit_ball, box_options(3, 0, 1.25, 0.125));
    EXPECT_NEAR(8 * orthant.fine.volume, whole.fine.volume, 1e-12);
}

TEST(ImplicitVolume, Ellipsoid) {
    const double a = 1.5, b = 1.0, c = 0.5;
    auto f = [&](std::span<const double> x) {
        return x[0] * x[0] / (a * a) + x[1] * x[1] / (b * b) + x[2] * x[2] / (c * c) - 1;
    };
    ImplicitOptions o = box_options(3, 0, 0, 0.05);
    o.lo = {-1.6, -1.1, -0.6};
    o.hi = {1.6, 1.1, 0.6};
    const ImplicitVolume r = implicit_volume(f, o);
    const double exact = 4.0 / 3.0 * std::numbers::pi * a * b * c;
    EXPECT_NEAR(r.volume, exact, 1e-3 * exact);
    EXPECT_LE(std::fabs(r.volume - exact), r.error_estimate);
}

TEST(ImplicitVolume, Torus) {
    const double R = 1.0, rr = 0.4;
    auto f = [&](std::span<const double> x) {
        const double q = std::sqrt(x[0] * x[0] + x[1] * x[1]) - R;
        return q * q + x[2] * x[2] - rr * rr;
    };
    ImplicitOptions o = box_options(3, 0, 0, 0.05);
    o.lo = {-1.5, -1.5, -0.5};
    o.hi = {1.5, 1.5, 0.5};
    const ImplicitVolume r = implicit_volume(f, o);
    const double exact = 2 * std::numbers::pi * std::numbers::pi * R * rr * rr;
    EXPECT_NEAR(r.volume, exact, 1e-3 * exact);
    EXPECT_LE(std::fabs(r.volume - exact), r.error_estimate);
    EXPECT_EQ(r.fine.components, 1u);
}

// --- convergence and the estimate -------------------------------------------

double fitted_order(const std::vector<double>& h, const std::vector<double>& err) {
    // least-squares slope of log|err| against log h
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    const double m = static_cast<double>(h.size());
    for (std::size_t i = 0; i < h.size(); ++i) {
        const double x = std::log(h[i]), y = std::log(std::fabs(err[i]));
        sx += x;
        sy += y;
        sxx += x * x;
        sxy += x * y;
    }
    return (m * sxy - sx * sy) / (m * sxx - sx * sx);
}

TEST(ImplicitVolume, ConvergesAtSecondOrderAndTheEstimateCoversTheError) {
    for (int n : {2, 3}) {
        std::vector<double> hs, errors;
        for (double h : {0.2, 0.1, 0.05, 0.025}) {
            ImplicitOptions o = box_options(n, -1.2, 1.2, h);
            const ImplicitVolume r = implicit_volume(unit_ball, o);
            hs.push_back(h);
            errors.push_back(r.fine.volume - ball_volume(n));
            EXPECT_LT(r.fine.volume, ball_volume(n)) << "a convex F: the PL solid lies inside";
            EXPECT_LE(std::fabs(r.volume - ball_volume(n)), r.error_estimate) << "n=" << n << " h=" << h;
            // The estimate is the error of the PL volume at h to within 20%
            // (16% at the coarsest, 2D h = 0.2; within 2% from h = 0.05 on).
            EXPECT_NEAR(r.error_estimate, std::fabs(errors.back()), (h > 0.06 ? 0.2 : 0.05) * std::fabs(errors.back()))
                << "n=" << n << " h=" << h;
        }
        const double order = fitted_order(hs, errors);
        EXPECT_GT(order, 1.9) << "n=" << n;
        EXPECT_LT(order, 2.1) << "n=" << n;
    }
}

// The 4h lattice gives the extrapolated volume its own estimate: it covers
// the true error, far below V(h)'s estimate; none where the lattices do not
// show the h^2 regime (a square between lattice planes).
TEST(ImplicitVolume, ExtrapolationCarriesItsOwnEstimate) {
    for (int n : {2, 3}) {
        for (double h : {0.1, 0.05, 0.025}) {
            ImplicitOptions o = box_options(n, -1.2, 1.2, h);
            const ImplicitVolume r = implicit_volume(unit_ball, o);
            ASSERT_TRUE(r.coarser.has_value()) << "n=" << n << " h=" << h;  // 24, 48, 96 cells: multiples of 4
            if (h > 0.06) {  // 6 cells across at 4h: R(2h) barely in its regime; no better than V(h)'s
                if (std::isfinite(r.extrapolated_error_estimate)) {
                    EXPECT_LE(std::fabs(r.volume - ball_volume(n)), r.extrapolated_error_estimate) << "n=" << n;
                }
                continue;
            }
            ASSERT_TRUE(std::isfinite(r.extrapolated_error_estimate)) << "n=" << n << " h=" << h;
            EXPECT_LE(std::fabs(r.volume - ball_volume(n)), r.extrapolated_error_estimate) << "n=" << n << " h=" << h;
            EXPECT_LT(r.extrapolated_error_estimate, r.error_estimate / 10) << "n=" << n << " h=" << h;
        }
    }
    const ImplicitFunction square = [](std::span<const double> x) {
        return std::max(std::fabs(x[0]), std::fabs(x[1])) - 1;
    };
    const ImplicitVolume r = implicit_volume(square, box_options(2, -1.5, 1.5, 0.03));
    EXPECT_TRUE(std::isnan(r.extrapolated_error_estimate));
    EXPECT_FALSE(implicit_volume(unit_ball, box_options(2, -1.25, 1.25, 0.25)).coarser.has_value());  // 10 cells
}

TEST(ImplicitVolume, CostFollowsTheSurface) {
    // Halving h multiplies the work by about 2^(n-1) = 4 in 3D, not 8.
    ImplicitOptions coarse = box_options(3, -1.25, 1.25, 1.0 / 32);
    ImplicitOptions fine = coarse;
    fine.h = 1.0 / 64;
    coarse.error_estimate = fine.error_estimate = false;
    const ImplicitVolume a = implicit_volume(unit_ball, coarse), b = implicit_volume(unit_ball, fine);
    const double simplices = double(b.fine.crossed_simplices) / double(a.fine.crossed_simplices);
    const double evaluations = double(b.fine.function_evaluations) / double(a.fine.function_evaluations);
    EXPECT_NEAR(simplices, 4.0, 0.3);
    EXPECT_LT(evaluations, 4.5);
    // Far fewer evaluations than lattice vertices.
    EXPECT_LT(double(b.fine.function_evaluations), 0.1 * std::pow(161.0, 3));
}

// --- the sign rule, clipping, degenerate input -------------------------------

TEST(ImplicitVolume, ZerosAtLatticeVerticesCountAsInside) {
    // F = x vanishes on a whole lattice plane: the solid is exactly x <= 0.
    for (int n = 2; n <= 4; ++n) {
        ImplicitOptions o = box_options(n, -1, 1, 0.25);
        o.keep_chain = true;
        const ImplicitVolume r = implicit_volume([](std::span<const double> x) { return x[0]; }, o);
        EXPECT_EQ(r.fine.volume, std::pow(2.0, n - 1)) << n;
        EXPECT_TRUE(validate_chain(r.chain->view()).closed()) << n;
    }
    // F = 0 everywhere: everything is inside.
    const ImplicitVolume all = implicit_volume([](std::span<const double>) { return 0.0; }, box_options(3, -1, 1, 0.5));
    EXPECT_EQ(all.fine.volume, 8.0);
}

TEST(ImplicitVolume, ClipsByTheBoxOrRefuses) {
    // A half-space through the box: the PL solid is exact (F is linear).
    auto slab = [](std::span<const double> x) { return x[0] + 0.5 * x[1] - 0.3; };
    ImplicitOptions o = box_options(3, -1, 1, 0.2);
    o.keep_chain = true;
    const ImplicitVolume r = implicit_volume(slab, o);
    EXPECT_TRUE(r.clipped);
    EXPECT_NEAR(r.fine.volume, 4 * 1.3, 1e-12);  // the plane meets the box's x-faces only: 2*2*(1 + 0.3) mean width
    EXPECT_TRUE(validate_chain(r.chain->view()).closed());

    o.box_rule = BoxRule::error;
    try {
        implicit_volume(slab, o);
        FAIL() << "expected touches_box";
    } catch (const ImplicitError& e) {
        EXPECT_EQ(e.code(), ImplicitError::Code::touches_box);
        EXPECT_EQ(e.point().size(), 3u);
    }
    // Not touching: the error rule changes nothing.
    const ImplicitVolume inside = implicit_volume(unit_ball, [] {
        ImplicitOptions p = box_options(3, -1.25, 1.25, 0.125);
        p.box_rule = BoxRule::error;
        return p;
    }());
    EXPECT_FALSE(inside.clipped);
}

TEST(ImplicitVolume, WholeBoxInsideIsTheBox) {
    ImplicitOptions o = box_options(4, -1, 1, 0.5);
    o.lo = {-1, 0, 0, 0};
    o.hi = {1, 1, 0.5, 3};
    const ImplicitVolume r = implicit_volume([](std::span<const double>) { return -1.0; }, o);
    EXPECT_DOUBLE_EQ(r.fine.volume, 3.0);
    EXPECT_DOUBLE_EQ(r.volume, 3.0);
    EXPECT_EQ(r.fine.crossed_simplices, 0u);
}

TEST(ImplicitVolume, EmptySetHasVolumeZero) {
    const ImplicitVolume r = implicit_volume(
        [](std::span<const double> x) { return sum_of_squares(x) + 1; }, box_options(3, -1, 1, 0.1));
    EXPECT_EQ(r.volume, 0.0);
    EXPECT_EQ(r.error_estimate, 0.0);
    EXPECT_EQ(r.fine.boundary_simplices, 0u);
}

TEST(ImplicitVolume, NaNIsAClearError) {
    auto f = [](std::span<const double> x) { return std::sqrt(x[0]) - 0.5; };
    try {
        implicit_volume(f, box_options(2, -1, 1, 0.1));
        FAIL() << "expected not_a_number";
    } catch (const ImplicitError& e) {
        EXPECT_EQ(e.code(), ImplicitError::Code::not_a_number);
        ASSERT_EQ(e.point().size(), 2u);
        EXPECT_LT(e.point()[0], 0.0);
        EXPECT_NE(std::string(e.what()).find("NaN"), std::string::npos);
    }
}

TEST(ImplicitVolume, InvalidOptionsThrow) {
    EXPECT_THROW(implicit_volume(unit_ball, box_options(1, -1, 1, 0.1)), std::invalid_argument);
    EXPECT_THROW(implicit_volume(unit_ball, box_options(3, 1, -1, 0.1)), std::invalid_argument);
    EXPECT_THROW(implicit_volume(unit_ball, box_options(3, -1, 1, -0.1)), std::invalid_argument);
    ImplicitOptions o = box_options(3, -1, 1, 0.1);
    o.lo = {-1, -1};
    EXPECT_THROW(implicit_volume(unit_ball, o), std::invalid_argument);
    o = box_options(3, -1, 1, 1e-9);
    EXPECT_THROW(implicit_volume(unit_ball, o), ImplicitError);  // too many cells
    o = box_options(3, -1.25, 1.25, 0.01);
    o.max_boundary_simplices = 1000;
    EXPECT_THROW(implicit_volume(unit_ball, o), ImplicitError);
}

// --- the chain ---------------------------------------------------------------

TEST(ImplicitSurface, ChainsAreClosedAndMatchTheVolume) {
    for (int n = 2; n <= 6; ++n) {
        for (double lo : {-1.25, -0.6, 0.0}) {  // inside, cut by the box, the orthant
            if (n >= 5 && lo < 0) continue;     // (seconds each)
            ImplicitOptions o = box_options(n, lo, 1.25, n <= 3 ? 0.125 : n == 4 ? 0.25 : n == 5 ? 0.4 : 0.7);
            o.keep_chain = true;
            o.error_estimate = false;
            const ImplicitVolume r = implicit_volume(unit_ball, o);
            ASSERT_TRUE(r.chain);
            const ChainReport report = validate_chain(r.chain->view());
            EXPECT_TRUE(report.closed()) << "n=" << n << " lo=" << lo;
            EXPECT_EQ(report.misoriented_faces, 0u);
            EXPECT_EQ(r.chain->simplex_count(), r.fine.boundary_simplices);
            ChainOptions prism;
            prism.formula = SimplexFormula::prism;
            prism.centroid = false;
            const ChainVolume v = chain_volume(r.chain->view(), prism);
            EXPECT_NEAR(v.volume, r.fine.volume, 1e-9) << "n=" << n << " lo=" << lo;
            EXPECT_GT(v.volume, 0);
        }
    }
}

// An ellipsoid off the origin: no symmetry of the lattice or the apex.
double tilted_ellipsoid(std::span<const double> x) {
    double s = 0;
    for (std::size_t k = 0; k < x.size(); ++k) {
        const double d = (x[k] - 0.1 * static_cast<double>(k + 1)) / (1.0 - 0.07 * static_cast<double>(k));
        s += d * d;
    }
    return s - 1;
}

// The streamed volume (no chain) and chain_volume of the chain built from the
// same walk measure the same chain (the same points, bit for bit), so they
// agree within the sum of their rounding bounds; the chain is closed.
TEST(ImplicitSurface, StreamedVolumeIsTheChainVolume) {
    for (int n = 2; n <= 6; ++n) {
        for (double lo : {-1.3, -0.5, 0.0}) {  // inside, cut by the box, cut on every lo face
            const double h = n <= 3 ? 0.1 : n == 4 ? 0.25 : n == 5 ? 0.6 : 0.9;
            ImplicitOptions o = box_options(n, lo, 1.6, h);
            o.error_estimate = false;
            const ImplicitVolume streamed = implicit_volume(tilted_ellipsoid, o);
            o.keep_chain = true;
            const ImplicitVolume built = implicit_volume(tilted_ellipsoid, o);
            ASSERT_TRUE(built.chain);
            EXPECT_TRUE(validate_chain(built.chain->view()).closed()) << "n=" << n << " lo=" << lo;
            EXPECT_EQ(streamed.fine.boundary_simplices, built.fine.boundary_simplices);
            EXPECT_EQ(streamed.fine.crossed_simplices, built.fine.crossed_simplices);
            EXPECT_EQ(streamed.clipped, lo > -1);
            EXPECT_GT(streamed.fine.volume, 0);
            EXPECT_GT(streamed.fine.rounding_error_bound, 0);
            EXPECT_LT(streamed.fine.rounding_error_bound, 1e-9 * streamed.fine.volume);  // 2e-10 at most here
            EXPECT_LE(std::fabs(streamed.fine.volume - built.fine.volume),
                      streamed.fine.rounding_error_bound + built.fine.rounding_error_bound)
                << "n=" << n << " lo=" << lo << " streamed " << streamed.fine.volume << " chain "
                << built.fine.volume;
        }
    }
}

// The streamed bound against the exact volume of the chain (GMP, rounded
// once): a bound that is too small fails here.
TEST(ImplicitSurface, StreamedBoundCoversTheExactChainVolume) {
    for (int n = 4; n <= 5; ++n) {
        ImplicitOptions o = box_options(n, -0.5, 1.6, n == 4 ? 0.3 : 0.5);
        o.error_estimate = false;
        const ImplicitVolume streamed = implicit_volume(tilted_ellipsoid, o);
        const Chain chain = implicit_surface(tilted_ellipsoid, o);
        ChainOptions exact;
        exact.accuracy = ChainAccuracy::exact;
        exact.centroid = false;
        const ChainVolume v = chain_volume(chain.view(), exact);
        ASSERT_TRUE(v.volume_correctly_rounded);
        const double rounding = 0x1p-53 * std::fabs(v.volume);  // the exact value's own rounding
        EXPECT_LE(std::fabs(streamed.fine.volume - v.volume), streamed.fine.rounding_error_bound + rounding) << n;
        EXPECT_GT(v.volume, 0);
    }
}

// Blocks are reduced in parallel but combined in walk order: the same bits
// whatever the number of threads.
TEST(ImplicitSurface, StreamedVolumeHasTheSameBitsForEveryThreadCount) {
    ImplicitOptions o = box_options(4, -0.5, 1.6, 0.1);
    ImplicitVolume parallel = implicit_volume(tilted_ellipsoid, o);
    ImplicitVolume serial;
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        serial = implicit_volume(tilted_ellipsoid, o);
    }
    EXPECT_GT(parallel.fine.boundary_simplices, 100000u);  // dozens of blocks
    EXPECT_EQ(parallel.fine.volume, serial.fine.volume);
    EXPECT_EQ(parallel.fine.rounding_error_bound, serial.fine.rounding_error_bound);
    EXPECT_EQ(parallel.coarse->volume, serial.coarse->volume);
    EXPECT_EQ(parallel.volume, serial.volume);
}

// The determinants' kernel (implicit/eliminate.cpp) on every Highway target
// this CPU runs: the same operations on every lane, so the same bits as the
// scalar target's.
TEST(ImplicitSurface, StreamedVolumeHasTheSameBitsOnEveryTarget) {
    const std::vector<polyvol::simd::Level> levels = polyvol::simd::available_levels();
    for (int n = 2; n <= 8; ++n) {
        const double h[] = {0.005, 0.05, 0.2, 0.3, 0.6, 0.8, 0.8};
        ImplicitOptions o = box_options(n, n <= 6 ? -0.5 : 0.0, 1.6, h[n - 2]);
        o.error_estimate = false;
        polyvol::simd::limit_to(polyvol::simd::Level::scalar);
        const ImplicitVolume scalar = implicit_volume(tilted_ellipsoid, o);
        EXPECT_GT(scalar.fine.boundary_simplices, 1000u) << n;
        for (polyvol::simd::Level l : levels) {
            polyvol::simd::limit_to(l);
            const ImplicitVolume v = implicit_volume(tilted_ellipsoid, o);
            EXPECT_EQ(v.fine.volume, scalar.fine.volume) << n << " " << polyvol::simd::level_name(l);
            EXPECT_EQ(v.fine.rounding_error_bound, scalar.fine.rounding_error_bound) << n;
        }
        polyvol::simd::limit_to(polyvol::simd::Level::avx512);
    }
}

TEST(ImplicitSurface, SeedsFindWhatTheCoarseScanMisses) {
    // A ball of radius 0.2 between the vertices of a 2-cell coarse scan.
    auto small = [](std::span<const double> x) {
        double s = 0;
        for (double v : x) s += (v - 0.45) * (v - 0.45);
        return s - 0.04;
    };
    ImplicitOptions o = box_options(3, -1, 1, 0.05);
    o.coarse_cells = 2;
    o.error_estimate = false;
    EXPECT_EQ(implicit_volume(small, o).fine.volume, 0.0);  // missed, as documented
    o.seeds = {0.45, 0.45, 0.45};
    const ImplicitVolume r = implicit_volume(small, o);
    EXPECT_NEAR(r.fine.volume, 4.0 / 3.0 * std::numbers::pi * 0.008, 0.05 * 0.0335);
    EXPECT_EQ(r.fine.components, 1u);
}

TEST(ImplicitSurface, SeveralComponentsAddUp) {
    // Two balls of radius 0.5 and a spherical cavity of radius 0.25 in one.
    auto f = [](std::span<const double> x) {
        const double a = (x[0] + 0.8) * (x[0] + 0.8) + x[1] * x[1] + x[2] * x[2];
        const double b = (x[0] - 0.8) * (x[0] - 0.8) + x[1] * x[1] + x[2] * x[2];
        return std::min(std::max(a - 0.25, 0.0625 - a), b - 0.25);
    };
    ImplicitOptions o = box_options(3, -1.5, 1.5, 0.025);
    o.coarse_cells = 24;
    const ImplicitVolume r = implicit_volume(f, o);
    const double exact = 4.0 / 3.0 * std::numbers::pi * (2 * 0.125 - 0.015625);
    EXPECT_EQ(r.fine.components, 3u);
    EXPECT_NEAR(r.volume, exact, 2e-3 * exact);
}

// --- expressions --------------------------------------------------------------

TEST(Expression, CoordinatesByNameAndIndex) {
    const ImplicitFunction f = parse_implicit_expression("x^2 + y^2 + z^2 - 1", 3);
    const double p[3] = {1, 2, 3};
    EXPECT_EQ(f(p), 13.0);
    const ImplicitFunction g = parse_implicit_expression("x1 + 2*x2 + 4*x5 + pi*0", 5);
    const double q[5] = {1, 1, 0, 0, 1};
    EXPECT_EQ(g(q), 7.0);
    EXPECT_EQ(expression_coordinates("x^2 + y^2 - 1"), 2);
    EXPECT_EQ(expression_coordinates("x1*x6"), 6);
    EXPECT_EQ(expression_coordinates("z"), 3);
    EXPECT_EQ(expression_coordinates("1"), 0);
}

TEST(Expression, ErrorsNameTheProblem) {
    EXPECT_THROW(parse_implicit_expression("x^2 + ", 2), ExpressionError);
    EXPECT_THROW(parse_implicit_expression("x + foo", 2), ExpressionError);
    try {
        parse_implicit_expression("x + z", 2);
        FAIL();
    } catch (const ExpressionError& e) {
        EXPECT_NE(std::string(e.what()).find("\"z\""), std::string::npos) << e.what();
    }
    try {
        parse_implicit_expression("x + (y", 2);
        FAIL();
    } catch (const ExpressionError& e) {
        EXPECT_GE(e.position(), 0);
    }
}

TEST(Expression, DrivesTheVolume) {
    ImplicitOptions o = box_options(4, 0, 1.2, 0.1);
    const ImplicitVolume r = implicit_volume(parse_implicit_expression("x1^2+x2^2+x3^2+x4^2-1", 4), o);
    EXPECT_NEAR(16 * r.volume, ball_volume(4), 1e-3 * ball_volume(4));
}

// F in batches: the same points and bits as pointwise, in far fewer calls
// (a cube's corners, a coarse lattice line), clipped and not, in 3 and 4 dimensions.
TEST(ImplicitVolume, BatchedFHasThePointwiseBits) {
    for (const int n : {3, 4}) {
        ImplicitOptions o;
        o.dimension = n;
        o.lo = {-1.0};
        o.hi = {n == 3 ? 0.9 : 1.2};  // n = 3: the ball is clipped by the box
        o.h = n == 3 ? 0.05 : 0.2;
        const ImplicitFunction f = [](std::span<const double> x) {
            double s = -1;
            for (std::size_t k = 0; k < x.size(); ++k) s += (1 + 0.3 * static_cast<double>(k)) * x[k] * x[k];
            return s;
        };
        std::size_t calls = 0, points = 0;
        const ImplicitBatchFunction batch = [&](std::span<const double> p, std::span<double> v) {
            ++calls;
            points += v.size();
            ASSERT_EQ(p.size(), v.size() * static_cast<std::size_t>(n));
            for (std::size_t i = 0; i < v.size(); ++i) v[i] = f(p.subspan(i * n, static_cast<std::size_t>(n)));
        };
        const ImplicitVolume a = implicit_volume(f, o), b = implicit_volume_batch(batch, o);
        EXPECT_EQ(a.volume, b.volume);
        EXPECT_EQ(a.fine.volume, b.fine.volume);
        EXPECT_EQ(a.coarse->volume, b.coarse->volume);
        EXPECT_EQ(a.fine.boundary_simplices, b.fine.boundary_simplices);
        EXPECT_EQ(a.fine.box_vertices_inside, b.fine.box_vertices_inside);
        const auto evaluations = [](const ImplicitVolume& r) {
            return r.fine.function_evaluations + r.coarse->function_evaluations +
                   (r.coarser ? r.coarser->function_evaluations : 0);
        };
        EXPECT_EQ(std::isnan(a.extrapolated_error_estimate), std::isnan(b.extrapolated_error_estimate));
        if (!std::isnan(a.extrapolated_error_estimate)) {
            EXPECT_EQ(a.extrapolated_error_estimate, b.extrapolated_error_estimate);
        }
        EXPECT_EQ(points, evaluations(b));
        EXPECT_GE(points, evaluations(a));
        EXPECT_LT(16 * calls, points) << calls << " calls for " << points << " points";
    }
}

// A memory limit refuses a lattice before it is walked (estimated from the
// 2h lattice: 2^(n-1) times its evaluations) or while it is (without the
// estimate, when the evaluations pass the limit); within the limit, the
// result is the unlimited one.
TEST(ImplicitVolume, AMemoryLimitRefusesTooFineALattice) {
    const ImplicitFunction f = parse_implicit_expression("x^2+y^2+z^2-1", 3);
    ImplicitOptions o;
    o.dimension = 3;
    o.lo = {-1.5};
    o.hi = {1.5};
    o.h = 0.02;
    const ImplicitVolume free = implicit_volume(f, o);
    const std::size_t need = (free.fine.function_evaluations + free.coarse->function_evaluations) *
                             kImplicitBytesPerEvaluation;
    o.max_memory_bytes = 4 * need;
    EXPECT_EQ(implicit_volume(f, o).volume, free.volume);
    // the 2h lattice fits, the fine one's estimate (4 times its evaluations) does not
    o.max_memory_bytes = 2 * free.coarse->function_evaluations * kImplicitBytesPerEvaluation;
    try {
        implicit_volume(f, o);
        FAIL() << "no error";
    } catch (const ImplicitError& e) {
        EXPECT_EQ(e.code(), ImplicitError::Code::too_large);
        EXPECT_NE(std::string(e.what()).find("estimated from the 2h lattice"), std::string::npos) << e.what();
    }
    o.error_estimate = false;  // no 2h lattice to estimate from: the walk stops at the limit
    o.max_memory_bytes = free.fine.function_evaluations / 2 * kImplicitBytesPerEvaluation;
    try {
        implicit_volume(f, o);
        FAIL() << "no error";
    } catch (const ImplicitError& e) {
        EXPECT_EQ(e.code(), ImplicitError::Code::too_large);
        EXPECT_NE(std::string(e.what()).find("more memory than allowed"), std::string::npos) << e.what();
    }
}

}  // namespace

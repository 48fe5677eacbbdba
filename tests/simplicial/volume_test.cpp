// Volumes and centroids of chains in R^n: closed forms under affine maps,
// agreement of the rank-one traversal with refactoring and with exact
// arithmetic within the stated bounds, correct rounding for n = 2, 3, and the
// cross-check of n = 3 against the 3D mesh code.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "exact/rational.hpp"
#include "fixtures.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/simplicial.hpp"

using namespace polyvol;
namespace fx = polyvol::fixtures;

namespace {

ChainOptions opts(SimplexFormula f = SimplexFormula::cone, Traversal t = Traversal::rank_one,
                  ChainAccuracy a = ChainAccuracy::automatic) {
    ChainOptions o;
    o.formula = f;
    o.traversal = t;
    o.accuracy = a;
    return o;
}

// |got - want| <= bound, in exact arithmetic; bound 0 means correctly rounded.
::testing::AssertionResult within(double got, double bound, const mpq_class& want) {
    if (bound == 0) {
        const double r = exact::round_to_double(want.get_mpq_t());
        if (got == r) return ::testing::AssertionSuccess();
        return ::testing::AssertionFailure() << "got " << got << ", the correctly rounded value is " << r;
    }
    mpq_class diff = mpq_class(got) - want;
    if (diff < 0) diff = -diff;
    if (std::isfinite(bound) && diff <= mpq_class(bound)) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "got " << got << " want " << want.get_d() << " |diff| " << diff.get_d()
                                         << " > bound " << bound;
}

void expect_closed(const ChainVolume& v) {
    EXPECT_EQ(v.topology.unmatched_faces, 0u);
    EXPECT_EQ(v.topology.boundary_faces, 0u);
    EXPECT_EQ(v.topology.misoriented_faces, 0u);
    EXPECT_EQ(v.topology.nonmanifold_faces, 0u);
    EXPECT_TRUE(v.topology.closed());
}

// The closed form times the affine map's determinant; the transformed
// coordinates are rounded, so allow that (1e-12 relative) on top of the bound.
void expect_volume(const Chain& c, double want, const ChainOptions& o, const char* what) {
    const ChainVolume v = chain_volume(c.view(), o);
    SCOPED_TRACE(std::string(what) + " n=" + std::to_string(c.dimension) + " " +
                 std::string(simplex_formula_name(o.formula)));
    expect_closed(v);
    EXPECT_LE(std::abs(v.volume - want), v.volume_error_bound + 1e-12 * std::abs(want))
        << "volume " << v.volume << " want " << want << " bound " << v.volume_error_bound;
    // Hadamard-type bounds lose about two bits per dimension (the actual errors do not).
    EXPECT_LT(v.volume_error_bound, std::ldexp(std::abs(want), -40 + 2 * c.dimension));
    if (c.dimension <= 3) {
        EXPECT_TRUE(v.volume_correctly_rounded);
    }
}

}  // namespace

TEST(ChainVolume, StandardSimplexAndCrossPolytopeExactly) {
    for (int n = 2; n <= 16; ++n) {
        for (SimplexFormula f : {SimplexFormula::cone, SimplexFormula::prism}) {
            const Chain s = fx::standard_simplex(n);
            const ChainVolume vs = chain_volume(s.view(), opts(f));
            expect_closed(vs);
            EXPECT_TRUE(within(vs.volume, vs.volume_error_bound, mpq_class(1) / mpq_class(fx::factorial(n)))) << n;
            const Chain x = fx::cross_polytope(n);
            const ChainVolume vx = chain_volume(x.view(), opts(f));
            expect_closed(vx);
            EXPECT_TRUE(within(vx.volume, vx.volume_error_bound,
                               mpq_class(std::ldexp(1.0, n)) / mpq_class(fx::factorial(n))))
                << n;
            EXPECT_EQ(vx.topology.simplices, std::size_t{1} << n);
            // Centroids: (1/(n+1), ...) and 0.
            for (int i = 0; i < n; ++i) {
                EXPECT_NEAR(vs.centroid[i], 1.0 / (n + 1), vs.centroid_error_bound + 1e-300) << n;
                EXPECT_LE(std::abs(vs.centroid[i] - 1.0 / (n + 1)), vs.centroid_error_bound + 0x1p-53 / (n + 1));
                EXPECT_LE(std::abs(vx.centroid[i]), vx.centroid_error_bound);
            }
            EXPECT_LT(vs.centroid_error_bound, std::ldexp(1.0, -40 + 2 * n));
        }
    }
}

TEST(ChainVolume, HypercubeUnitVolume) {
    for (int n = 2; n <= 8; ++n) {
        const Chain c = fx::hypercube(n);
        for (SimplexFormula f : {SimplexFormula::cone, SimplexFormula::prism}) {
            const ChainVolume v = chain_volume(c.view(), opts(f));
            expect_closed(v);
            EXPECT_TRUE(within(v.volume, v.volume_error_bound, 1)) << n;
            for (int i = 0; i < n; ++i) EXPECT_LE(std::abs(v.centroid[i] - 0.5), v.centroid_error_bound + 1e-16);
        }
    }
}

TEST(ChainVolume, AffineImagesScaleByTheDeterminant) {
    std::mt19937_64 rng(42);
    for (int n = 2; n <= 16; ++n) {
        struct Case {
            const char* name;
            Chain chain;
            double volume;
        };
        std::vector<Case> cases;
        cases.push_back({"simplex", fx::standard_simplex(n), 1 / fx::factorial(n)});
        cases.push_back({"cross", fx::cross_polytope(n), std::ldexp(1.0, n) / fx::factorial(n)});
        if (n <= 8) cases.push_back({"cube", fx::hypercube(n), 1.0});
        for (auto& cs : cases) {
            const double det = fx::transform(cs.chain, rng, 1.7);
            for (SimplexFormula f : {SimplexFormula::cone, SimplexFormula::prism})
                expect_volume(cs.chain, cs.volume * det, opts(f), cs.name);
        }
    }
}

TEST(ChainVolume, RankOneAgreesWithRefactoringAndExact) {
    std::mt19937_64 rng(7);
    for (int n = 4; n <= 12; ++n) {
        Chain c = fx::cross_polytope(n);
        fx::subdivide(c, rng, n <= 6 ? 600 : (std::size_t{1} << n) + 400);
        fx::perturb(c, rng, 0.05);
        fx::transform(c, rng, 0.9);
        for (SimplexFormula f : {SimplexFormula::cone, SimplexFormula::prism}) {
            SCOPED_TRACE("n=" + std::to_string(n) + " " + std::string(simplex_formula_name(f)));
            const ChainVolume r1 = chain_volume(c.view(), opts(f, Traversal::rank_one));
            const ChainVolume rf = chain_volume(c.view(), opts(f, Traversal::refactor));
            expect_closed(r1);
            EXPECT_GT(r1.stats.updates, r1.stats.factorizations);  // the walk mostly updates
            EXPECT_EQ(rf.stats.updates, 0u);
            EXPECT_EQ(rf.stats.factorizations, c.simplex_count());
            EXPECT_LE(std::abs(r1.volume - rf.volume), r1.volume_error_bound + rf.volume_error_bound);
            // The updated factors' bound stays within the refactor growth of a fresh one's.
            EXPECT_LT(r1.volume_error_bound, 64 * rf.volume_error_bound);
            for (int i = 0; i < n; ++i)
                EXPECT_LE(std::abs(r1.centroid[i] - rf.centroid[i]), r1.centroid_error_bound + rf.centroid_error_bound);
            if (n <= 7) {
                const mpq_class ex = fx::exact_volume(c);
                EXPECT_TRUE(within(r1.volume, r1.volume_error_bound, ex));
                EXPECT_TRUE(within(rf.volume, rf.volume_error_bound, ex));
                const ChainVolume e = chain_volume(c.view(), opts(f, Traversal::rank_one, ChainAccuracy::exact));
                EXPECT_TRUE(e.volume_correctly_rounded);
                EXPECT_EQ(e.volume, exact::round_to_double(ex.get_mpq_t()));
                for (int i = 0; i < n; ++i)
                    EXPECT_LE(std::abs(r1.centroid[i] - e.centroid[i]),
                              r1.centroid_error_bound + 0x1p-52 * std::abs(e.centroid[i]));
            }
        }
    }
}

TEST(ChainVolume, TranslatedFarFromTheOriginKeepsARigorousBound) {
    // Terms of size |t|^n cancel to ~1: the bound says how much is left.
    for (int n : {4, 6}) {
        Chain c = fx::hypercube(n);
        for (std::size_t v = 0; v < c.vertex_count(); ++v)
            for (int i = 0; i < n; ++i) c.coordinates[v * n + i] += 1e3 * (i + 1);
        for (SimplexFormula f : {SimplexFormula::cone, SimplexFormula::prism}) {
            const ChainVolume v = chain_volume(c.view(), opts(f));
            EXPECT_TRUE(within(v.volume, v.volume_error_bound, fx::exact_volume(c))) << n;
            const ChainVolume e = chain_volume(c.view(), opts(f, Traversal::rank_one, ChainAccuracy::exact));
            EXPECT_EQ(e.volume, 1.0);
            for (int i = 0; i < n; ++i) EXPECT_EQ(e.centroid[i], 0.5 + 1e3 * (i + 1));
        }
    }
}

TEST(ChainVolume, TwoAndThreeDimensionsAreCorrectlyRounded) {
    std::mt19937_64 rng(5);
    for (int n : {2, 3}) {
        for (int trial = 0; trial < 4; ++trial) {
            Chain c = fx::cross_polytope(n);
            fx::subdivide(c, rng, 200);
            fx::perturb(c, rng, 0.2);
            const double det = fx::transform(c, rng, trial == 3 ? 1e-3 : 3.0);
            (void)det;
            if (trial == 2)  // far from the origin: naive sums lose everything
                for (std::size_t v = 0; v < c.vertex_count(); ++v) c.coordinates[v * n] += 1e8;
            const mpq_class ex = fx::exact_volume(c);
            for (SimplexFormula f : {SimplexFormula::cone, SimplexFormula::prism}) {
                const ChainVolume v = chain_volume(c.view(), opts(f));
                EXPECT_TRUE(v.volume_correctly_rounded);
                EXPECT_EQ(v.volume_error_bound, 0.0);
                EXPECT_EQ(v.volume, exact::round_to_double(ex.get_mpq_t())) << n << " " << trial;
                // The GMP path (the reference for any n) gives the same bits.
                const ChainVolume g = chain_volume(c.view(), opts(f, Traversal::rank_one, ChainAccuracy::exact));
                EXPECT_EQ(v.volume, g.volume);
                for (int i = 0; i < n; ++i) EXPECT_EQ(v.centroid[i], g.centroid[i]);
                // The bounded path is right within its bound.
                const ChainVolume b = chain_volume(c.view(), opts(f, Traversal::rank_one, ChainAccuracy::bounded));
                EXPECT_TRUE(within(b.volume, b.volume_error_bound, ex));
            }
        }
    }
}

TEST(ChainVolume, OutsideTheSmallExactRangeUsesGmp) {
    Chain c = fx::cross_polytope(3);
    for (double& x : c.coordinates) x *= 1e-70;  // products of 4 coordinates leave the expansion path's range
    const ChainVolume v = chain_volume(c.view());
    EXPECT_TRUE(v.volume_correctly_rounded);
    const mpq_class want = mpq_class(8, 6) * mpq_class(1e-70) * mpq_class(1e-70) * mpq_class(1e-70);
    EXPECT_EQ(v.volume, exact::round_to_double(want.get_mpq_t()));
}

TEST(ChainVolume, ThreeDimensionsMatchesTheMeshCode) {
    std::mt19937_64 rng(9);
    Chain c = fx::cross_polytope(3);
    fx::subdivide(c, rng, 500);
    fx::perturb(c, rng, 0.3);
    fx::transform(c, rng, 2.0);
    Mesh m;
    m.positions = c.coordinates;
    m.indices = c.simplices;
    const MassProperties mp = mass_properties(m.view());
    const ChainVolume v = chain_volume(c.view());
    EXPECT_EQ(v.volume, mp.volume);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(v.centroid[i], mp.centroid[i]);
    ChainOptions o;
    o.formula = SimplexFormula::prism;
    EXPECT_EQ(chain_volume(c.view(), o).volume, mp.volume);
}

TEST(ChainValidation, FlippedAndMissingSimplicesAreReported) {
    for (int n : {2, 3, 4, 6}) {
        Chain c = fx::cross_polytope(n);
        Chain flipped = c;
        std::swap(flipped.simplices[1 * n], flipped.simplices[1 * n + 1]);
        const ChainReport rf = validate_chain(flipped.view());
        EXPECT_EQ(rf.unmatched_faces, static_cast<std::size_t>(n)) << n;
        EXPECT_EQ(rf.misoriented_faces, static_cast<std::size_t>(n));
        EXPECT_EQ(rf.boundary_faces, 0u);
        ASSERT_TRUE(rf.unmatched_example.has_value());
        EXPECT_EQ(rf.unmatched_example->vertices.size(), static_cast<std::size_t>(n - 1));
        EXPECT_EQ(rf.unmatched_example->same + rf.unmatched_example->opposite, 2u);

        Chain missing = c;
        missing.simplices.erase(missing.simplices.begin() + 3 * n, missing.simplices.begin() + 4 * n);
        const ChainReport rm = validate_chain(missing.view());
        EXPECT_EQ(rm.unmatched_faces, static_cast<std::size_t>(n));
        EXPECT_EQ(rm.boundary_faces, static_cast<std::size_t>(n));
        ASSERT_TRUE(rm.unmatched_example.has_value());
        EXPECT_EQ(rm.unmatched_example->same, 1u);
        EXPECT_EQ(rm.unmatched_example->opposite, 0u);

        // orient_chain repairs the flipped one; the missing one stays open.
        OrientResult o = orient_chain(flipped);
        EXPECT_TRUE(o.orientable);
        EXPECT_EQ(o.flipped, 1u);
        EXPECT_EQ(validate_chain(flipped.view()).unmatched_faces, 0u);
        EXPECT_EQ(flipped.simplices, c.simplices);
    }
}

TEST(ChainValidation, WeldsBitIdenticalVerticesAndCountsDegenerateSimplices) {
    Chain c = fx::standard_simplex(3);
    // A copy of vertex 0 used by one facet: still closed after welding.
    c.coordinates.insert(c.coordinates.end(), {-0.0, 0.0, 0.0});
    for (std::size_t i = 0; i < c.simplices.size(); ++i)
        if (c.simplices[i] == 0) {
            c.simplices[i] = 4;
            break;
        }
    c.simplices.insert(c.simplices.end(), {1, 1, 2});  // degenerate
    const ChainReport r = validate_chain(c.view());
    EXPECT_EQ(r.vertices_welded, 4u);
    EXPECT_EQ(r.degenerate_simplices, 1u);
    EXPECT_EQ(r.unmatched_faces, 0u);
    EXPECT_EQ(r.components, 1u);
    EXPECT_EQ(chain_volume(c.view()).volume, 1.0 / 6);
}

TEST(ChainOrientation, InsideOutComponentsAndCavities) {
    // A cube with a cubic cavity, everything listed outward: orient_chain turns
    // the cavity inward; then a fully inverted copy is turned back.
    for (int n : {3, 4}) {
        Chain outer = fx::hypercube(n);
        for (double& x : outer.coordinates) x = 4 * x;
        Chain inner = fx::hypercube(n);
        for (double& x : inner.coordinates) x = 1 + x;
        Chain both = outer;
        const auto off = static_cast<uint32_t>(outer.vertex_count());
        both.coordinates.insert(both.coordinates.end(), inner.coordinates.begin(), inner.coordinates.end());
        for (uint32_t v : inner.simplices) both.simplices.push_back(v + off);
        OrientResult o = orient_chain(both);
        EXPECT_TRUE(o.orientable);
        EXPECT_EQ(o.components, 2u);
        EXPECT_EQ(o.undecided, 0u);
        EXPECT_EQ(o.flipped, inner.simplex_count());
        EXPECT_NEAR(chain_volume(both.view()).volume, std::pow(4.0, n) - 1, 1e-9);
        for (std::size_t s = 0; s < both.simplex_count(); ++s)
            std::swap(both.simplices[s * n], both.simplices[s * n + 1]);
        o = orient_chain(both);
        EXPECT_EQ(o.flipped, both.simplex_count());
        EXPECT_NEAR(chain_volume(both.view()).volume, std::pow(4.0, n) - 1, 1e-9);
    }
}

TEST(ChainVolume, RejectsInconsistentArrays) {
    Chain c = fx::standard_simplex(3);
    c.simplices.push_back(99);
    c.simplices.push_back(0);
    c.simplices.push_back(1);
    EXPECT_THROW(chain_volume(c.view()), std::invalid_argument);
    Chain d;
    d.dimension = 1;
    EXPECT_THROW(chain_volume(d.view()), std::invalid_argument);
}

TEST(ChainVolume, NonFiniteCoordinatesGiveNaN) {
    Chain c = fx::standard_simplex(4);
    c.coordinates[5] = std::numeric_limits<double>::infinity();
    const ChainVolume v = chain_volume(c.view());
    EXPECT_TRUE(std::isnan(v.volume));
    EXPECT_TRUE(std::isinf(v.volume_error_bound));
}

TEST(ChainVolume, UpToThirtyTwoDimensions) {
    std::mt19937_64 rng(32);
    for (int n : {20, 24, 32}) {
        Chain s = fx::standard_simplex(n);
        const double det = fx::transform(s, rng, 1.25);
        for (SimplexFormula f : {SimplexFormula::cone, SimplexFormula::prism}) {
            const ChainVolume v = chain_volume(s.view(), opts(f));
            expect_closed(v);
            const double want = det / fx::factorial(n);
            EXPECT_LE(std::abs(v.volume - want), v.volume_error_bound + 1e-12 * std::abs(want)) << n;
            EXPECT_TRUE(std::isfinite(v.volume_error_bound));
        }
        // A subdivided simplex: the walk, its updates and the exact reference.
        Chain c = fx::standard_simplex(n);
        fx::subdivide(c, rng, 3 * static_cast<std::size_t>(n), 0.1);
        fx::perturb(c, rng, 0.05);
        const ChainVolume r1 = chain_volume(c.view(), opts());
        const ChainVolume rf = chain_volume(c.view(), opts(SimplexFormula::cone, Traversal::refactor));
        const ChainVolume ex = chain_volume(c.view(), opts(SimplexFormula::cone, Traversal::rank_one, ChainAccuracy::exact));
        expect_closed(r1);
        EXPECT_GT(r1.stats.updates, 0u);
        EXPECT_TRUE(ex.volume_correctly_rounded);
        // ex is the exact value rounded once: allow half an ulp of it on top.
        EXPECT_LE(std::abs(r1.volume - ex.volume), r1.volume_error_bound + 0x1p-53 * std::abs(ex.volume)) << n;
        EXPECT_LE(std::abs(rf.volume - ex.volume), rf.volume_error_bound + 0x1p-53 * std::abs(ex.volume)) << n;
    }
}

// Tests of the cone rule's sums (src/measure/cone.hpp) against an
// independent GMP computation: filtered bounds hold, exact sums are exact.
#include "common/kernel_levels.hpp"
#include "measure/cone.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>

#include "cone_fixtures.hpp"
#include "exact/rational.hpp"

using namespace polyvol;
using namespace polyvol::measure::cone;
using polyvol::fixtures::q;
using polyvol::fixtures::as_mpq;
namespace fx = polyvol::fixtures;

namespace {


std::vector<Mesh> test_meshes() {
    std::mt19937_64 rng(11);
    std::vector<Mesh> ms;
    ms.push_back(fx::unit_tetrahedron());
    ms.push_back(fx::box(-1, -2, -3, 0.5, 4, 7));
    ms.push_back(fx::box(1e6, 1e6, 1e6, 1e6 + 1, 1e6 + 2, 1e6 + 3, true));
    ms.push_back(fx::octahedron(3));
    ms.push_back(fx::random_sphere(rng, 3, 1.0, {0, 0, 0}));
    ms.push_back(fx::random_sphere(rng, 3, 1.0, {1e6, -2e6, 3e6}));
    ms.push_back(fx::random_sphere(rng, 2, 1e-3, {1e8, 1e8, -1e8}));
    ms.push_back(fx::random_sphere(rng, 2, 1e5, {0.5, 0, 0}, 0.5));
    ms.push_back(fx::random_sphere(rng, 4, 2.0, {-7, 1e3, 0}));
    // Wild exponents inside the safe range: triangles whose coordinates of
    // one axis span more than 60 bits take the expansion path.
    Mesh wild = fx::random_sphere(rng, 2, 1e50, {0, 3e49, 0});
    for (std::size_t i = 0; i < wild.positions.size(); i += 7) wild.positions[i] = 1e-45 * static_cast<double>(i % 5);
    ms.push_back(std::move(wild));
    Mesh noisy = fx::random_sphere(rng, 3, 1.0, {0, 0, 0});
    for (std::size_t i = 0; i < noisy.positions.size(); i += 5) noisy.positions[i] *= 1e-17;
    ms.push_back(std::move(noisy));
    return ms;
}

}  // namespace

TEST(Cone, CoordinateRange) {
    EXPECT_EQ(coordinate_range(fx::unit_tetrahedron().view()), Range::safe);
    EXPECT_EQ(coordinate_range(fx::box(0, 0, 0, 1e-100, 1, 1).view()), Range::unsafe);
    EXPECT_EQ(coordinate_range(fx::box(0, 0, 0, 1e60, 1, 1).view()), Range::unsafe);
    EXPECT_EQ(coordinate_range(fx::box(0, 0, 0, HUGE_VAL, 1, 1).view()), Range::nonfinite);
    EXPECT_EQ(coordinate_range(fx::box(0, 0, 0, NAN, 1, 1).view()), Range::nonfinite);
}

TEST(Cone, FilteredBoundsHoldAndAreTight) {
    for (const Mesh& m : test_meshes()) {
        const auto ref = fx::reference_sums(m.view());
        for (Precision p : {Precision::double_double, Precision::fast}) {
            const ConeSums s = filtered_sums(m.view(), kSumCount, p);
            EXPECT_EQ(s.triangles, m.view().triangle_count());
            for (int k = 0; k < kSumCount; ++k) {
                const mpq_class err = abs(as_mpq(s.sum[k]) - ref[static_cast<std::size_t>(k)]);
                EXPECT_LE(err, q(s.bound[k])) << "sum " << k;
                // The double-double bound decides a double's rounding unless the
                // cancellation is enormous: for these meshes it is < 2^-56 relative
                // (the worst: radius 1e-3 at 1e8, 2^-59.5).
                if (p == Precision::double_double && ref[static_cast<std::size_t>(k)] != 0) {
                    EXPECT_LE(q(s.bound[k]), abs(ref[static_cast<std::size_t>(k)]) * q(0x1p-56)) << "sum " << k;
                }
            }
            // Volume only: same sums.
            const ConeSums v = filtered_sums(m.view(), 1, p);
            EXPECT_LE(abs(as_mpq(v.sum[kV]) - ref[0]), q(v.bound[kV]));
        }
    }
}

TEST(Cone, ExactSumsAreExact) {
    for (const Mesh& m : test_meshes()) {
        ASSERT_EQ(coordinate_range(m.view()), Range::safe);
        const auto ref = fx::reference_sums(m.view());
        ConeSums s = filtered_sums(m.view(), kSumCount, Precision::fast);
        exact_sums(m.view(), (1u << kSumCount) - 1, s);
        for (int k = 0; k < kSumCount; ++k) {
            EXPECT_EQ(as_mpq(s.sum[k]), ref[static_cast<std::size_t>(k)]) << "sum " << k;
            EXPECT_EQ(s.bound[k], 0.0);
        }
        const RationalSums g = gmp_sums(m.view(), kSumCount);
        ASSERT_TRUE(g.ok);
        for (int k = 0; k < kSumCount; ++k)
            EXPECT_EQ(mpq_class(g.sum[static_cast<std::size_t>(k)].get()), ref[static_cast<std::size_t>(k)]);
    }
}

TEST(Cone, GmpSumsOutsideTheSafeRange) {
    std::mt19937_64 rng(12);
    const Mesh tiny = fx::random_sphere(rng, 2, 1e-200, {3e-200, 0, 0});
    const Mesh huge = fx::random_sphere(rng, 2, 1e250, {0, 1e250, 0});
    Mesh mixed = fx::random_sphere(rng, 1, 1.0, {0, 0, 0});
    mixed.positions[0] = 1e-300;  // one wild coordinate
    mixed.positions[4] = 1e200;
    for (const Mesh* m : std::initializer_list<const Mesh*>{&tiny, &huge, &mixed}) {
        EXPECT_EQ(coordinate_range(m->view()), Range::unsafe);
        const auto ref = fx::reference_sums(m->view());
        const RationalSums g = gmp_sums(m->view(), kSumCount);
        ASSERT_TRUE(g.ok);
        for (int k = 0; k < kSumCount; ++k)
            EXPECT_EQ(mpq_class(g.sum[static_cast<std::size_t>(k)].get()), ref[static_cast<std::size_t>(k)]);
    }
    Mesh bad = fx::unit_tetrahedron();
    bad.positions[3] = NAN;
    EXPECT_FALSE(gmp_sums(bad.view(), 1).ok);
    bad.positions[3] = 1;
    bad.add_vertex(NAN, 0, 0);  // unused: harmless
    EXPECT_TRUE(gmp_sums(bad.view(), 1).ok);
}

TEST(Cone, SplitOfTheWorkDoesNotMatter) {
    // A large mesh: several parallel tasks; the result is bit-identical to a
    // single-block computation of the same faces in another order.
    std::mt19937_64 rng(13);
    const Mesh m = fx::random_sphere(rng, 6, 1.0, {1e6, 0, 0});  // 32768 triangles
    const ConeSums a = filtered_sums(m.view(), kSumCount, Precision::double_double);
    const ConeSums b = filtered_sums(m.view(), kSumCount, Precision::double_double);
    for (int k = 0; k < kSumCount; ++k) {
        EXPECT_EQ(as_mpq(a.sum[k]), as_mpq(b.sum[k]));
        EXPECT_EQ(a.bound[k], b.bound[k]);
    }
    const auto ref = fx::reference_sums(m.view());
    EXPECT_LE(abs(as_mpq(a.sum[kV]) - ref[0]), q(a.bound[kV]));
}

TEST(Cone, BaselineKernelsWithoutFma) {
    polyvol::test::cap_kernel_level(0);
    for (const Mesh& m : test_meshes()) {
        const auto ref = fx::reference_sums(m.view());
        const ConeSums s = filtered_sums(m.view(), kSumCount, Precision::double_double);
        for (int k = 0; k < kSumCount; ++k)
            EXPECT_LE(abs(as_mpq(s.sum[k]) - ref[static_cast<std::size_t>(k)]), q(s.bound[k])) << "sum " << k;
        ConeSums e = s;
        exact_sums(m.view(), (1u << kSumCount) - 1, e);
        for (int k = 0; k < kSumCount; ++k) EXPECT_EQ(as_mpq(e.sum[k]), ref[static_cast<std::size_t>(k)]);
    }
    polyvol::test::cap_kernel_level(-1);
}

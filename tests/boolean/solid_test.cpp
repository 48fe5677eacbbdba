// solid_volume: one mesh whose shells overlap. The solid is {winding >= 1};
// boxes on an integer (or half-integer) lattice give it by counting cells:
// the winding number at every cell centre is the sum of ±1 over the boxes
// (−1 for a box turned inside out) that contain it.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <array>
#include <random>
#include <vector>

#include "common/generate.hpp"
#include "common/shapes.hpp"
#include "exact/rational.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/measure.hpp"

namespace polyvol {
namespace {

struct LatticeBox {
    std::array<int, 6> c;  // lo x y z, hi x y z, in units of `unit`
    bool inward = false;
};

Mesh mesh_of(const std::vector<LatticeBox>& boxes, double unit) {
    Mesh m;
    for (const LatticeBox& b : boxes) {
        test::BoxOptions o;
        o.inverted = b.inward;
        test::add_box(m, {b.c[0] * unit, b.c[1] * unit, b.c[2] * unit}, {b.c[3] * unit, b.c[4] * unit, b.c[5] * unit}, o);
    }
    return m;
}

// The winding number at the centre of lattice cell (x, y, z): ±1 per box
// (−1 inward) containing it.
int winding_at(const std::vector<LatticeBox>& boxes, int x, int y, int z) {
    int w = 0;
    for (const LatticeBox& b : boxes)
        if (b.c[0] <= x && x < b.c[3] && b.c[1] <= y && y < b.c[4] && b.c[2] <= z && z < b.c[5]) w += b.inward ? -1 : 1;
    return w;
}

// Counts the lattice cells whose winding number is >= 1 (and the winding integral).
void count_cells(const std::vector<LatticeBox>& boxes, int n, double unit, double& solid, double& winding) {
    long cells = 0, total = 0;
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y)
            for (int z = 0; z < n; ++z) {
                const int w = winding_at(boxes, x, y, z);
                cells += w >= 1;
                total += w;
            }
    solid = static_cast<double>(cells) * unit * unit * unit;
    winding = static_cast<double>(total) * unit * unit * unit;
}

void expect_counted(const std::vector<LatticeBox>& boxes, int n, double unit) {
    double solid, winding;
    count_cells(boxes, n, unit, solid, winding);
    const Mesh m = mesh_of(boxes, unit);
    const SolidVolume r = solid_volume(m.view());
    ASSERT_EQ(r.status, BooleanStatus::ok);
    EXPECT_EQ(r.properties.volume, solid);
    EXPECT_EQ(r.winding_volume, winding);
    EXPECT_EQ(r.shells, boxes.size());
}

// A set of `count(rng)` random boxes with corners in [0, 4]^3 on the
// lattice, one in six inward.
template <class Count>
std::vector<LatticeBox> random_boxes(std::mt19937& rng, Count& count) {
    std::uniform_int_distribution<int> coord(0, 4), inward(0, 5);
    std::vector<LatticeBox> boxes(count(rng));
    for (LatticeBox& b : boxes) {
        for (int k = 0; k < 3; ++k) {
            int lo = coord(rng), hi = coord(rng);
            if (lo == hi) ++hi;
            b.c[k] = std::min(lo, hi);
            b.c[3 + k] = std::max(lo, hi);
        }
        b.inward = inward(rng) == 0;
    }
    return boxes;
}

TEST(SolidVolume, TwoOverlappingCubesAreFifteenNotSixteen) {
    const std::vector<LatticeBox> boxes = {{{0, 0, 0, 2, 2, 2}}, {{1, 1, 1, 3, 3, 3}}};
    const SolidVolume r = solid_volume(mesh_of(boxes, 1).view());
    ASSERT_EQ(r.status, BooleanStatus::ok);
    EXPECT_EQ(r.properties.volume, 15.0);
    EXPECT_EQ(r.winding_volume, 16.0);
    EXPECT_EQ(r.overlapping_shells, 2u);
    EXPECT_GT(r.crossing_pairs, 0u);
}

TEST(SolidVolume, DisjointAndNestedShells) {
    // Apart: nothing to check; nested outward: counted once; a cavity subtracts.
    expect_counted({{{0, 0, 0, 1, 1, 1}}, {{2, 2, 2, 4, 4, 4}}}, 4, 1);
    const SolidVolume apart = solid_volume(mesh_of({{{0, 0, 0, 1, 1, 1}}, {{2, 2, 2, 4, 4, 4}}}, 1).view());
    EXPECT_EQ(apart.shells_checked, 0u);
    EXPECT_EQ(apart.overlapping_shells, 0u);
    expect_counted({{{0, 0, 0, 4, 4, 4}}, {{1, 1, 1, 3, 3, 3}}}, 4, 1);
    const SolidVolume nested = solid_volume(mesh_of({{{0, 0, 0, 4, 4, 4}}, {{1, 1, 1, 3, 3, 3}}}, 1).view());
    EXPECT_EQ(nested.overlapping_shells, 1u);
    expect_counted({{{0, 0, 0, 4, 4, 4}}, {{1, 1, 1, 3, 3, 3}, true}}, 4, 1);
    // A bar through the cavity's wall, and one through the whole part.
    expect_counted({{{0, 0, 0, 8, 8, 8}}, {{2, 2, 2, 6, 6, 6}, true}, {{4, 3, 3, 10, 5, 5}}}, 10, 0.5);
    expect_counted({{{0, 0, 0, 8, 8, 8}}, {{2, 2, 2, 6, 6, 6}, true}, {{1, 3, 3, 10, 5, 5}}}, 10, 0.5);
}

TEST(SolidVolume, RandomLatticeBoxes) {
    std::mt19937 rng(1126);
    std::uniform_int_distribution<int> count(2, 5);
    for (int trial = 0; trial < 150; ++trial) {
        const std::vector<LatticeBox> boxes = random_boxes(rng, count);
        SCOPED_TRACE(::testing::Message() << "trial " << trial);
        expect_counted(boxes, 5, 1);
    }
}

// The first and second moments of the cells with winding >= 1, exactly:
// per unit cell [x0, x0 + 1] (in lattice units), ∫x = x0 + 1/2,
// ∫x² = x0² + x0 + 1/3, ∫xy = (x0 + 1/2)(y0 + 1/2); then scaled by the unit.
void expect_counted_moments(const std::vector<LatticeBox>& boxes, int n, double unit) {
    std::array<mpq_class, 3> f;
    std::array<mpq_class, 6> s;
    for (int x = 0; x < n; ++x)
        for (int y = 0; y < n; ++y)
            for (int z = 0; z < n; ++z) {
                if (winding_at(boxes, x, y, z) < 1) continue;
                const mpq_class half(1, 2), third(1, 3);
                const mpq_class m[3] = {x + half, y + half, z + half};
                const mpq_class sq[3] = {x * x + x + third, y * y + y + third, z * z + z + third};
                for (int i = 0; i < 3; ++i) f[i] += m[i];
                s[0] += sq[0], s[1] += sq[1], s[2] += sq[2];
                s[3] += m[0] * m[1], s[4] += m[1] * m[2], s[5] += m[2] * m[0];
            }
    const mpq_class u4 = mpq_class(unit) * unit * unit * unit, u5 = u4 * unit;
    const SolidVolume r = solid_volume(mesh_of(boxes, unit).view(), {.moments = true});
    ASSERT_EQ(r.status, BooleanStatus::ok);
    ASSERT_TRUE(r.moments);
    for (int i = 0; i < 3; ++i) {
        const mpq_class v = f[i] * u4;
        EXPECT_EQ(r.properties.first_moments[i], exact::round_to_double(v.get_mpq_t())) << i;
    }
    for (int k = 0; k < 6; ++k) {
        const mpq_class v = s[k] * u5;
        EXPECT_EQ(r.properties.second_moments[k], exact::round_to_double(v.get_mpq_t())) << k;
    }
}

TEST(SolidVolume, MomentsOfLatticeBoxes) {
    expect_counted_moments({{{0, 0, 0, 2, 2, 2}}, {{1, 1, 1, 3, 3, 3}}}, 3, 1);
    expect_counted_moments({{{0, 0, 0, 8, 8, 8}}, {{2, 2, 2, 6, 6, 6}, true}, {{1, 3, 3, 10, 5, 5}}}, 10, 0.5);
    std::mt19937 rng(2611);
    std::uniform_int_distribution<int> count(2, 4);
    for (int trial = 0; trial < 40; ++trial) {
        const std::vector<LatticeBox> boxes = random_boxes(rng, count);
        SCOPED_TRACE(::testing::Message() << "trial " << trial);
        expect_counted_moments(boxes, 5, 1);
    }
}

TEST(SolidVolume, MomentsOfApartShellsAreTheMeshMoments) {
    Mesh m = generate::uv_sphere(12, 24, 1.0);
    m.append(generate::uv_sphere(10, 20, 0.5, 3, 0.25, -1));
    const SolidVolume r = solid_volume(m.view(), {.moments = true});
    const MassProperties p = mass_properties(m.view());
    ASSERT_EQ(r.status, BooleanStatus::ok);
    EXPECT_EQ(r.properties.volume, p.volume);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(r.properties.first_moments[i], p.first_moments[i]);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(r.properties.second_moments[k], p.second_moments[k]);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(r.properties.centroid[i], p.centroid[i], 0x1p-50 * std::fabs(p.centroid[i]));
}

TEST(SolidVolume, TwoSpheresInOneFileAreTheirUnion) {
    Mesh a = generate::uv_sphere(16, 32, 1.0), b = generate::uv_sphere(14, 28, 0.8, 0.5, 0.375, 0.25);
    const BooleanVolumes pair = boolean_volumes(a.view(), b.view());
    ASSERT_EQ(pair.status, BooleanStatus::ok);
    a.append(b);
    const SolidVolume r = solid_volume(a.view());
    ASSERT_EQ(r.status, BooleanStatus::ok);
    EXPECT_EQ(r.properties.volume, pair.union_volume);
    EXPECT_EQ(r.overlapping_shells, 2u);
    EXPECT_EQ(r.crossing_pairs, pair.crossing_pairs);
}

TEST(SolidVolume, OpenMeshIsReported) {
    Mesh m = test::box({0, 0, 0}, {1, 1, 1});
    m.indices.resize(m.indices.size() - 3);
    EXPECT_EQ(solid_volume(m.view()).status, BooleanStatus::a_not_closed);
}

}  // namespace
}  // namespace polyvol

// Booleans where an operand's shells overlap (solid_boolean_volumes): A is
// the union of two boxes in one mesh, B a box; every volume against its
// closed form by inclusion–exclusion over boxes, the solid's area against
// |a1| + |a2| - |a1 ∩ a2| of the boxes' surfaces in general position.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>

#include "common/shapes.hpp"
#include "polyvol/boolean.hpp"

namespace polyvol {
namespace {

using Box = std::array<double, 6>;  // lo x y z, hi x y z

double volume_of(const Box& b) { return (b[3] - b[0]) * (b[4] - b[1]) * (b[5] - b[2]); }
double area_of(const Box& b) {
    const double dx = b[3] - b[0], dy = b[4] - b[1], dz = b[5] - b[2];
    return 2 * (dx * dy + dy * dz + dz * dx);
}
Box common(const Box& a, const Box& b) {
    Box c;
    for (int k = 0; k < 3; ++k) {
        c[k] = std::max(a[k], b[k]);
        c[3 + k] = std::max(c[k], std::min(a[3 + k], b[3 + k]));
    }
    return c;
}
void add(Mesh& m, const Box& b) { test::add_box(m, {b[0], b[1], b[2]}, {b[3], b[4], b[5]}); }

void expect_closed_forms(const Box& a1, const Box& a2, const Box& b) {
    SCOPED_TRACE(::testing::Message() << "a1 [" << a1[0] << "," << a1[1] << "," << a1[2] << " .. " << a1[3] << ","
                                      << a1[4] << "," << a1[5] << "] a2 [" << a2[0] << "," << a2[1] << "," << a2[2]
                                      << " .. " << a2[3] << "," << a2[4] << "," << a2[5] << "]");
    Mesh a, mb;
    add(a, a1);
    add(a, a2);
    add(mb, b);
    const double va = volume_of(a1) + volume_of(a2) - volume_of(common(a1, a2));
    const double i = volume_of(common(a1, b)) + volume_of(common(a2, b)) - volume_of(common(common(a1, a2), b));
    for (const bool a_first : {true, false}) {
        const BooleanVolumes r = a_first ? solid_boolean_volumes(a.view(), mb.view())
                                         : solid_boolean_volumes(mb.view(), a.view());
        ASSERT_EQ(r.status, BooleanStatus::ok);
        EXPECT_EQ(a_first ? r.volume_a : r.volume_b, va);
        EXPECT_EQ(a_first ? r.volume_b : r.volume_a, volume_of(b));
        EXPECT_EQ(r.intersection, i);
        EXPECT_EQ(r.union_volume, va + volume_of(b) - i);
        EXPECT_EQ(a_first ? r.a_minus_b : r.b_minus_a, va - i);
        EXPECT_EQ(a_first ? r.b_minus_a : r.a_minus_b, volume_of(b) - i);
        EXPECT_NEAR(a_first ? r.area_b : r.area_a, area_of(b), r.area_error_bound);
        // The identity the areas are formed by.
        EXPECT_NEAR(r.area_intersection + r.area_union, r.area_a + r.area_b, 4 * r.area_error_bound);
    }
}

TEST(SolidBooleans, OverlappingShellsOfAnOperandAgainstABox) {
    expect_closed_forms({0, 0, 0, 2, 2, 2}, {1, 1, 1, 3, 3, 3}, {-1, -1, -1, 4, 4, 4});  // B holds A: |A ∩ B| = 15
    expect_closed_forms({0, 0, 0, 20, 20, 20}, {10, 10, 10, 30, 30, 30}, {0, 0, 0, 20, 20, 20});  // B a part of A
    expect_closed_forms({0, 0, 0, 2, 2, 2}, {1, 1, 1, 3, 3, 3}, {1.5, -1, -1, 2.5, 4, 4});  // B cuts both parts
    expect_closed_forms({0, 0, 0, 2, 2, 2}, {0, 0, 0, 2, 2, 2}, {1, 1, 1, 3, 3, 3});  // two coincident shells
}

TEST(SolidBooleans, RandomBoxes) {
    std::mt19937 rng(33);
    std::uniform_int_distribution<int> c(0, 6);
    auto random_box = [&] {
        Box b;
        for (int k = 0; k < 3; ++k) {
            int lo = c(rng), hi = c(rng);
            if (lo == hi) ++hi;
            b[k] = std::min(lo, hi);
            b[3 + k] = std::max(lo, hi);
        }
        return b;
    };
    for (int n = 0; n < 40; ++n) expect_closed_forms(random_box(), random_box(), random_box());
}

// The solid's boundary area (solid_volume with moments): for two boxes in
// general position the parts of each surface inside the other make up the
// common box's surface, so |∂(a1 ∪ a2)| = |∂a1| + |∂a2| - |∂(a1 ∩ a2)|.
TEST(SolidBooleans, TheSolidsAreaOfTwoBoxesInGeneralPosition) {
    std::mt19937 rng(34);
    std::uniform_int_distribution<int> c(0, 8);
    for (int n = 0; n < 30; ++n) {
        Box a1, a2;
        for (int k = 0; k < 3; ++k) {
            const int lo = c(rng), hi = lo + 1 + c(rng);
            a1[k] = lo, a1[3 + k] = hi;
            const int lo2 = c(rng), hi2 = lo2 + 1 + c(rng);  // half-integers: no plane of a1
            a2[k] = lo2 + 0.5, a2[3 + k] = hi2 + 0.5;
        }
        Mesh m;
        add(m, a1);
        add(m, a2);
        const SolidVolume s = solid_volume(m.view(), {.moments = true});
        ASSERT_EQ(s.status, BooleanStatus::ok);
        const Box k = common(a1, a2);
        const bool meet = volume_of(k) > 0;
        const double area_bound = s.properties.area_relative_error * s.properties.area;
        EXPECT_NEAR(s.properties.area, area_of(a1) + area_of(a2) - (meet ? area_of(k) : 0.0), area_bound)
            << n << ": bound " << area_bound;
        EXPECT_LT(s.properties.area_relative_error, 1e-12);
        EXPECT_EQ(s.properties.volume, volume_of(a1) + volume_of(a2) - volume_of(k));
    }
}

}  // namespace
}  // namespace polyvol

// Boolean volumes of axis-aligned boxes against their closed forms: every
// placement of faces, edges and vertices (disjoint, touching, shared faces,
// nested, identical, overlapping), and random integer boxes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <stdexcept>

#include "common/shapes.hpp"
#include "polyvol/boolean.hpp"

namespace polyvol {
namespace {

using Box = std::array<double, 6>;  // lo x y z, hi x y z

Mesh mesh_of(const Box& b, bool quads = false) {
    test::BoxOptions o;
    o.quads = quads;
    return test::box({b[0], b[1], b[2]}, {b[3], b[4], b[5]}, o);
}
double volume_of(const Box& b) { return (b[3] - b[0]) * (b[4] - b[1]) * (b[5] - b[2]); }
double area_of(const Box& b) {
    const double dx = b[3] - b[0], dy = b[4] - b[1], dz = b[5] - b[2];
    return 2 * (dx * dy + dy * dz + dz * dx);
}
// The common box, with negative extents clamped to an empty box.
Box common(const Box& a, const Box& b) {
    Box c;
    for (int k = 0; k < 3; ++k) {
        c[k] = std::max(a[k], b[k]);
        c[3 + k] = std::max(c[k], std::min(a[3 + k], b[3 + k]));
    }
    return c;
}

void expect_closed_forms(const Box& a, const Box& b, bool quads = false) {
    SCOPED_TRACE(::testing::Message() << "A = [" << a[0] << "," << a[1] << "," << a[2] << " .. " << a[3] << ","
                                      << a[4] << "," << a[5] << "], B = [" << b[0] << "," << b[1] << "," << b[2]
                                      << " .. " << b[3] << "," << b[4] << "," << b[5] << "]");
    const Mesh ma = mesh_of(a, quads), mb = mesh_of(b, quads);
    const BooleanVolumes r = boolean_volumes(ma.view(), mb.view());
    ASSERT_EQ(r.status, BooleanStatus::ok);
    const double i = volume_of(common(a, b));
    EXPECT_EQ(r.volume_a, volume_of(a));
    EXPECT_EQ(r.volume_b, volume_of(b));
    EXPECT_EQ(r.intersection, i);
    EXPECT_EQ(r.union_volume, volume_of(a) + volume_of(b) - i);
    EXPECT_EQ(r.a_minus_b, volume_of(a) - i);
    EXPECT_EQ(r.b_minus_a, volume_of(b) - i);
    EXPECT_NEAR(r.area_a, area_of(a), r.area_error_bound);
    EXPECT_NEAR(r.area_b, area_of(b), r.area_error_bound);
}

TEST(BooleanBoxes, EveryPlacement) {
    const Box a = {0, 0, 0, 2, 2, 2};
    const Box cases[] = {
        {5, 5, 5, 6, 6, 6},        // disjoint
        {2, 0, 0, 3, 2, 2},        // touching at a whole face
        {2, 0.5, 0.5, 3, 1, 1},    // touching inside a face
        {2, 2, 0, 3, 3, 2},        // touching along an edge
        {2, 2, 2, 3, 3, 3},        // touching at a vertex
        {1, 0, 0, 3, 2, 2},        // overlapping, two faces shared in part
        {1, 1, 1, 3, 3, 3},        // overlapping in a unit cube (three faces cut)
        {0.5, 0.5, 0.5, 1.5, 1.5, 1.5},  // nested
        {0, 0, 0, 1, 1, 1},        // nested, sharing a corner and three faces
        {0, 0, 0, 2, 2, 2},        // identical
        {-1, -1, -1, 3, 3, 3},     // A inside B
        {0.5, -1, 0.5, 1.5, 3, 1.5},  // a bar through A
        {-1, 0.5, -1, 3, 1.5, 3},  // a slab through A
    };
    for (const Box& b : cases) {
        expect_closed_forms(a, b);
        expect_closed_forms(b, a);
        expect_closed_forms(a, b, true);
    }
}

TEST(BooleanBoxes, AreasInGeneralPosition) {
    const Box a = {0, 0, 0, 2, 2, 2}, b = {1, 0.5, 0.25, 3, 3, 1.5};
    const Mesh ma = mesh_of(a), mb = mesh_of(b);
    const BooleanVolumes r = boolean_volumes(ma.view(), mb.view());
    ASSERT_EQ(r.status, BooleanStatus::ok);
    const Box c = common(a, b);
    EXPECT_NEAR(r.area_intersection, area_of(c), r.area_error_bound);
    EXPECT_NEAR(r.area_union, area_of(a) + area_of(b) - area_of(c), r.area_error_bound);
    EXPECT_GT(r.crossing_pairs, 0u);
    EXPECT_LT(r.area_error_bound, 1e-11);  // about 6e-14 relative here
}

TEST(BooleanBoxes, RandomIntegerBoxes) {
    std::mt19937 rng(20261126);
    std::uniform_int_distribution<int> coord(0, 4);
    for (int trial = 0; trial < 300; ++trial) {
        Box a, b;
        for (Box* x : {&a, &b}) {
            for (int k = 0; k < 3; ++k) {
                int lo = coord(rng), hi = coord(rng);
                if (lo == hi) ++hi;
                (*x)[k] = std::min(lo, hi);
                (*x)[3 + k] = std::max(lo, hi);
            }
        }
        expect_closed_forms(a, b);
    }
}

TEST(BooleanStatus, InvalidOperandsAreReported) {
    const Mesh good = mesh_of({0, 0, 0, 1, 1, 1});
    Mesh open = good;
    open.indices.resize(open.indices.size() - 3);
    EXPECT_EQ(boolean_volumes(open.view(), good.view()).status, BooleanStatus::a_not_closed);
    EXPECT_EQ(boolean_volumes(good.view(), open.view()).status, BooleanStatus::b_not_closed);
    test::BoxOptions inverted;
    inverted.inverted = true;
    const Mesh inside_out = test::box({0, 0, 0}, {1, 1, 1}, inverted);
    EXPECT_EQ(boolean_volumes(inside_out.view(), good.view()).status, BooleanStatus::a_inside_out);
    // Two boxes overlapping in one operand: winding number 2 at B's corner (0.5, 0.5, 0.5).
    Mesh twice = mesh_of({0, 0, 0, 1, 1, 1});
    test::add_box(twice, {0.25, 0.25, 0.25}, {2, 2, 2});
    const Mesh probe = mesh_of({0.5, 0.5, 0.5, 0.75, 0.75, 0.75});
    const BooleanVolumes r = boolean_volumes(probe.view(), twice.view());
    EXPECT_EQ(r.status, BooleanStatus::b_overlaps_itself);
    EXPECT_TRUE(std::isnan(r.intersection));
    // Inconsistent arrays are a programming error: an exception, not a crash.
    Mesh broken = good;
    broken.indices[5] = 99;
    EXPECT_THROW(boolean_volumes(broken.view(), good.view()), std::invalid_argument);
}

}  // namespace
}  // namespace polyvol

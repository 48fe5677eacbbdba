// Boolean volumes where the exact answer is known in closed form or by an
// exact identity:
//   * a cube against the same cube turned about z by the rational rotation
//     (3/5, 4/5): the intersection is a convex polygon (clipped exactly in
//     rationals here) times the common z range; shared top and bottom planes
//     exercise the perturbation;
//   * spheres in general position: the same bits when A and B swap (the
//     perturbation then runs the other way), when both move by an exact
//     offset; the grid's union and intersection cells add up to them.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <cmath>
#include <vector>

#include "common/generate.hpp"
#include "common/shapes.hpp"
#include "exact/rational.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/grid.hpp"

namespace polyvol {
namespace {

using Polygon = std::vector<std::array<mpq_class, 2>>;

// The part of convex polygon p (counter-clockwise) left of the directed line a -> b.
Polygon clip(const Polygon& p, const std::array<mpq_class, 2>& a, const std::array<mpq_class, 2>& b) {
    auto side = [&](const std::array<mpq_class, 2>& x) {
        return mpq_class((b[0] - a[0]) * (x[1] - a[1]) - (b[1] - a[1]) * (x[0] - a[0]));
    };
    Polygon out;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const auto& x = p[i];
        const auto& y = p[(i + 1) % p.size()];
        const mpq_class sx = side(x), sy = side(y);
        if (sx >= 0) out.push_back(x);
        if ((sx > 0 && sy < 0) || (sx < 0 && sy > 0)) {
            const mpq_class t = sx / (sx - sy);
            out.push_back({mpq_class(x[0] + t * (y[0] - x[0])), mpq_class(x[1] + t * (y[1] - x[1]))});
        }
    }
    return out;
}

mpq_class area(const Polygon& p) {
    mpq_class s = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
        const auto& x = p[i];
        const auto& y = p[(i + 1) % p.size()];
        s += x[0] * y[1] - x[1] * y[0];
    }
    return s / 2;
}

double rounded(const mpq_class& q) { return exact::round_to_double(q.get_mpq_t()); }

// The square [-5, 5]^2 turned by (c, s) = (3/5, 4/5): integer corners.
std::array<double, 2> turn(double x, double y) { return {(3 * x - 4 * y) / 5, (4 * x + 3 * y) / 5}; }

Mesh turned_box(double z0, double z1, double dx) {
    Mesh m = test::box({-5, -5, z0}, {5, 5, z1});
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        const auto p = turn(m.positions[3 * v], m.positions[3 * v + 1]);
        m.positions[3 * v] = p[0] + dx;
        m.positions[3 * v + 1] = p[1];
    }
    return m;
}

TEST(BooleanRotated, CubeAgainstTurnedCube) {
    struct Case {
        double z0, z1, dx;
    };
    for (const Case c : {Case{-5, 5, 0}, Case{-3, 7, 0}, Case{-4.5, 5.5, 1.5}, Case{5, 9, 0.25}}) {
        SCOPED_TRACE(::testing::Message() << "z " << c.z0 << ".." << c.z1 << ", dx " << c.dx);
        const Mesh a = test::box({-5, -5, -5}, {5, 5, 5});
        const Mesh b = turned_box(c.z0, c.z1, c.dx);
        Polygon square = {{mpq_class(-5), mpq_class(-5)}, {mpq_class(5), mpq_class(-5)},
                          {mpq_class(5), mpq_class(5)}, {mpq_class(-5), mpq_class(5)}};
        Polygon turned;
        for (const auto& p : square) {
            const auto t = turn(p[0].get_d(), p[1].get_d());
            turned.push_back({mpq_class(t[0] + c.dx), mpq_class(t[1])});
        }
        Polygon common = square;
        for (std::size_t i = 0; i < turned.size(); ++i) common = clip(common, turned[i], turned[(i + 1) % turned.size()]);
        const mpq_class height = std::max(0.0, std::min(5.0, c.z1) - std::max(-5.0, c.z0));
        const mpq_class inter = area(common) * height;
        const mpq_class va = 1000, vb = mpq_class(100) * mpq_class(c.z1 - c.z0);

        const BooleanVolumes r = boolean_volumes(a.view(), b.view());
        ASSERT_EQ(r.status, BooleanStatus::ok);
        EXPECT_EQ(r.intersection, rounded(inter));
        EXPECT_EQ(r.union_volume, rounded(va + vb - inter));
        EXPECT_EQ(r.a_minus_b, rounded(va - inter));
        EXPECT_EQ(r.b_minus_a, rounded(vb - inter));
    }
}

// bench's UV sphere of radius r about c (rings bands, segments longitudes),
// its coordinates rounded to multiples of 2^-30, so that moving it by an
// offset up to 2^20 keeps them exact.
Mesh sphere(std::array<double, 3> c, double r, uint32_t rings, uint32_t segments) {
    Mesh m = generate::uv_sphere(rings, segments, r, c[0], c[1], c[2]);
    for (double& x : m.positions) x = std::ldexp(std::nearbyint(std::ldexp(x, 30)), -30);
    return m;
}

Mesh moved(Mesh m, std::array<double, 3> d) {
    for (std::size_t v = 0; v < m.vertex_count(); ++v)
        for (int k = 0; k < 3; ++k) m.positions[3 * v + k] += d[k];
    return m;
}

TEST(BooleanSpheres, SwapAndExactOffsetGiveTheSameBits) {
    const Mesh a = sphere({0, 0, 0}, 1, 24, 48), b = sphere({0.5, 0.375, 0.25}, 0.8, 20, 40);
    const BooleanVolumes r = boolean_volumes(a.view(), b.view());
    ASSERT_EQ(r.status, BooleanStatus::ok);
    EXPECT_GT(r.crossing_pairs, 50u);
    EXPECT_GT(r.intersection, 0.5);
    const BooleanVolumes s = boolean_volumes(b.view(), a.view());
    ASSERT_EQ(s.status, BooleanStatus::ok);
    EXPECT_EQ(s.intersection, r.intersection);
    EXPECT_EQ(s.union_volume, r.union_volume);
    EXPECT_EQ(s.a_minus_b, r.b_minus_a);
    EXPECT_EQ(s.b_minus_a, r.a_minus_b);
    const std::array<double, 3> far = {1024, -2048, 65536};
    const BooleanVolumes t = boolean_volumes(moved(a, far).view(), moved(b, far).view());
    ASSERT_EQ(t.status, BooleanStatus::ok);
    EXPECT_EQ(t.intersection, r.intersection);
    EXPECT_EQ(t.union_volume, r.union_volume);
    EXPECT_EQ(t.a_minus_b, r.a_minus_b);
    EXPECT_EQ(t.b_minus_a, r.b_minus_a);
}

TEST(BooleanSpheres, TheGridCellsAddUpToUnionAndIntersection) {
    const Mesh a = sphere({0, 0, 0}, 1, 16, 32), b = sphere({0.5, 0.3, 0.2}, 0.8, 14, 28);
    const BooleanVolumes r = boolean_volumes(a.view(), b.view());
    ASSERT_EQ(r.status, BooleanStatus::ok);
    const MeshView bodies[] = {a.view(), b.view()};
    GridSpec spec;
    spec.cells = 48;
    const GridAxes axes = make_grid(bodies, spec);
    std::vector<double> volumes(2 * axes.cell_count()), inter(axes.cell_count());
    GridOutput out;
    out.volumes = volumes;
    out.intersection_volumes = inter;
    const GridSummary g = grid_volumes(bodies, axes, out);
    // The cells add up to the exact union and intersection (each cell exact
    // to a few units of rounding of its terms).
    EXPECT_GT(g.contact_cells, 0u);
    EXPECT_NEAR(g.union_volume, r.union_volume, 1e-14 * r.union_volume);
    EXPECT_NEAR(g.intersection_volume, r.intersection, 1e-14 * r.union_volume);
}

TEST(BooleanSpheres, AgainstItselfIsItself) {
    const Mesh a = sphere({0.25, 0, 0}, 1, 12, 24);
    const BooleanVolumes r = boolean_volumes(a.view(), a.view());
    ASSERT_EQ(r.status, BooleanStatus::ok);
    EXPECT_EQ(r.intersection, r.volume_a);
    EXPECT_EQ(r.union_volume, r.volume_a);
    EXPECT_EQ(r.a_minus_b, 0.0);
    EXPECT_EQ(r.b_minus_a, 0.0);
    EXPECT_NEAR(r.area_intersection, r.area_a, r.area_error_bound);
    EXPECT_NEAR(r.area_union, r.area_a, r.area_error_bound);
}

}  // namespace
}  // namespace polyvol

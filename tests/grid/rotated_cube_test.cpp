// A cube turned by an exact rational rotation, against an independent exact
// computation: the convex cube clipped by each cell's six half-spaces in
// rational arithmetic (GMP), its volume summed over the clipped faces' fan
// tetrahedra — no grid code involved.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <array>
#include <cmath>
#include <vector>

#include "grid_fixtures.hpp"

namespace {

using namespace polyvol;
using Point = std::array<mpq_class, 3>;
using Face = std::vector<Point>;  // counter-clockwise seen from outside
using Solid = std::vector<Face>;

bool same(const Point& a, const Point& b) { return a[0] == b[0] && a[1] == b[1] && a[2] == b[2]; }

// Keeps the part of a convex solid with sign * (p[axis] - c) <= 0 (Sutherland–
// Hodgman per face), and closes it with the cap on the plane, chained from
// the clipped faces' edges that lie on the plane (each reversed).
Solid clip(const Solid& solid, int axis, const mpq_class& c, int sign) {
    auto side = [&](const Point& p) { return sign * sgn(p[axis] - c); };
    Solid out;
    std::vector<std::pair<Point, Point>> cap_edges;
    for (const Face& f : solid) {
        Face g;
        for (std::size_t i = 0; i < f.size(); ++i) {
            const Point& a = f[i];
            const Point& b = f[(i + 1) % f.size()];
            const int sa = side(a), sb = side(b);
            if (sa <= 0) g.push_back(a);
            if (sa * sb < 0) {
                const mpq_class t = (c - a[axis]) / (b[axis] - a[axis]);
                Point x;
                for (int k = 0; k < 3; ++k) x[k] = a[k] + t * (b[k] - a[k]);
                g.push_back(x);
            }
        }
        if (g.size() < 3) continue;
        for (std::size_t i = 0; i < g.size(); ++i) {
            const Point& a = g[i];
            const Point& b = g[(i + 1) % g.size()];
            if (side(a) == 0 && side(b) == 0) cap_edges.emplace_back(b, a);
        }
        out.push_back(std::move(g));
    }
    if (cap_edges.size() >= 3) {
        Face cap{cap_edges[0].first};
        Point at = cap_edges[0].second;
        while (!same(at, cap.front())) {
            cap.push_back(at);
            bool found = false;
            for (const auto& e : cap_edges)
                if (same(e.first, at)) {
                    at = e.second;
                    found = true;
                    break;
                }
            if (!found || cap.size() > cap_edges.size()) {
                ADD_FAILURE() << "cap does not close";
                break;
            }
        }
        out.push_back(std::move(cap));
    }
    return out;
}

mpq_class volume(const Solid& s) {
    mpq_class v = 0;
    for (const Face& f : s)
        for (std::size_t i = 1; i + 1 < f.size(); ++i) {
            const Point &a = f[0], &b = f[i], &c = f[i + 1];
            v += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0]);
        }
    return v / 6;
}

// R = (1/3) [[2,-1,2],[2,2,-1],[-1,2,2]] (orthogonal, det 1) applied to the
// cube [0,3]^3: integer vertices, and no edge or face parallel to a grid plane.
struct RotatedCube {
    std::array<double, 3> offset;
    std::array<std::array<double, 3>, 8> vertex;
    Mesh mesh;
    Solid solid;

    explicit RotatedCube(std::array<double, 3> off) : offset(off) {
        const int r[3][3] = {{2, -1, 2}, {2, 2, -1}, {-1, 2, 2}};
        for (int v = 0; v < 8; ++v) {
            const int u[3] = {v & 1, (v >> 1) & 1, (v >> 2) & 1};  // (R * 3u) / 3 = R u
            for (int a = 0; a < 3; ++a)
                vertex[v][a] = r[a][0] * u[0] + r[a][1] * u[1] + r[a][2] * u[2] + offset[a];
            mesh.add_vertex(vertex[v][0], vertex[v][1], vertex[v][2]);
        }
        const uint32_t faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& f : faces) {
            mesh.add_triangle(f[0], f[1], f[2]);
            mesh.add_triangle(f[0], f[2], f[3]);
            Face face;
            for (uint32_t v : f) face.push_back({mpq_class(vertex[v][0]), mpq_class(vertex[v][1]), mpq_class(vertex[v][2])});
            solid.push_back(face);
        }
    }
};

// max over cells of |grid - exact| / cell volume
double compare(const RotatedCube& cube, const GridAxes& g) {
    const auto r = test::run_grid(cube.mesh, g);
    double worst = 0;
    mpq_class total = 0;
    for (std::size_t i = 0; i < g.nx(); ++i)
        for (std::size_t j = 0; j < g.ny(); ++j)
            for (std::size_t k = 0; k < g.nz(); ++k) {
                Solid s = cube.solid;
                s = clip(s, 0, mpq_class(g.x[i]), -1);
                s = clip(s, 0, mpq_class(g.x[i + 1]), 1);
                s = clip(s, 1, mpq_class(g.y[j]), -1);
                s = clip(s, 1, mpq_class(g.y[j + 1]), 1);
                s = clip(s, 2, mpq_class(g.z[k]), -1);
                s = clip(s, 2, mpq_class(g.z[k + 1]), 1);
                const mpq_class exact = volume(s);
                total += exact;
                const double err = std::abs(r.volumes[g.cell(i, j, k)] - exact.get_d()) / g.cell_volume(i, j, k);
                worst = std::max(worst, err);
            }
    EXPECT_EQ(total, 27) << "the reference itself must add up to the cube";
    EXPECT_NEAR(r.summary.bodies[0].volume, 27.0, 27 * 4e-16);
    return worst;
}

TEST(GridRotatedCube, PlanesThroughTheVertices) {
    // integer planes: every vertex of the cube lies on three grid planes
    const RotatedCube cube({0, 0, 0});
    const GridAxes g = uniform_axes({-1, -1, -1, 4, 4, 4}, {5, 5, 5});
    EXPECT_LT(compare(cube, g), 2e-15);  // measured: <= 3.5e-16
    // and on a grid of half-integer planes, finer
    const GridAxes h = uniform_axes({-1, -1, -1, 4, 4, 4}, {10, 10, 10});
    EXPECT_LT(compare(cube, h), 2e-15);  // measured: <= 3.5e-16
}

TEST(GridRotatedCube, GenericPlanes) {
    const RotatedCube cube({0.375, -0.25, 0.0625});
    const GridAxes g = uniform_axes({-1.1, -1.3, -0.95, 4.7, 4.1, 4.3}, {9, 8, 7});
    EXPECT_LT(compare(cube, g), 2e-15);  // measured: <= 3.5e-16
    GridAxes nonuniform;
    nonuniform.x = {-2, -0.1, 0.7, 1.3, 1.31, 2.5, 5};
    nonuniform.y = {-1.5, 0.2, 1.75, 3.4, 4.5};
    nonuniform.z = {-1, 0.0625, 0.9, 1.1, 2.2, 3.7, 4.2, 5};
    EXPECT_LT(compare(cube, nonuniform), 2e-15);  // measured: <= 3.5e-16
}

}  // namespace

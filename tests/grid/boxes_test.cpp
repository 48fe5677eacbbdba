// Axis-aligned boxes and a tetrahedron, whose cell volumes are known in
// closed form: faces inside cells, faces exactly on grid planes, grids that
// cover only part of the solid, non-uniform planes, polygon faces, moments.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include <tbb/task_arena.h>

#include "grid_fixtures.hpp"
#include "polyvol/measure.hpp"

namespace {

using namespace polyvol;
using polyvol::test::box;
using polyvol::test::box_overlap;
using polyvol::test::run_grid;

// Every cell of `r` against the closed form for the box [lo, hi].
void expect_box_cells(const test::GridRun& r, const GridAxes& g, const std::array<double, 3>& lo,
                      const std::array<double, 3>& hi, double rel_tol) {
    for (std::size_t i = 0; i < g.nx(); ++i)
        for (std::size_t j = 0; j < g.ny(); ++j)
            for (std::size_t k = 0; k < g.nz(); ++k) {
                const double c0[3] = {g.x[i], g.y[j], g.z[k]}, c1[3] = {g.x[i + 1], g.y[j + 1], g.z[k + 1]};
                const double want = box_overlap(lo, hi, c0, c1);
                const double cell = g.cell_volume(i, j, k);
                ASSERT_NEAR(r.volumes[g.cell(i, j, k)], want, rel_tol * cell) << i << " " << j << " " << k;
            }
}

TEST(GridBoxes, BoxInsideCellsMatchesClosedForm) {
    const std::array<double, 3> lo{0.13, 0.271, 0.0905}, hi{0.77, 0.5, 0.9311};
    const Mesh m = box(lo, hi);
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {7, 9, 11});
    const auto r = run_grid(m, g);
    expect_box_cells(r, g, lo, hi, 1e-15);
    const double v = (hi[0] - lo[0]) * (hi[1] - lo[1]) * (hi[2] - lo[2]);
    EXPECT_NEAR(r.summary.bodies[0].volume, v, 1e-15 * v);
    // cells with no surface are exactly full or empty
    EXPECT_GT(r.summary.bodies[0].full_cells, 0u);
    EXPECT_EQ(r.summary.bodies[0].full_cells + r.summary.bodies[0].empty_cells + r.summary.bodies[0].cut_cells,
              g.cell_count());
}

TEST(GridBoxes, FacesOnGridPlanesGiveExactFullAndEmptyCellsAndNoCut) {
    // faces at planes 1/8 ... of a grid with spacing 1/8: every cell exactly 0 or 1/512
    const std::array<double, 3> lo{0.125, 0.25, 0.375}, hi{0.75, 0.625, 1.0};
    const Mesh m = box(lo, hi);
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {8, 8, 8});
    const auto r = run_grid(m, g);
    expect_box_cells(r, g, lo, hi, 0);
    EXPECT_EQ(r.summary.bodies[0].cut_cells, 0u);
    EXPECT_EQ(r.summary.bodies[0].volume, 0.625 * 0.375 * 0.625);
    // the top face on the grid's top plane, the bottom face below the grid
    const GridAxes g2 = uniform_axes({0, 0, 0.5, 1, 1, 1}, {8, 8, 4});
    const auto r2 = run_grid(m, g2);
    expect_box_cells(r2, g2, lo, hi, 0);
    EXPECT_EQ(r2.summary.bodies[0].cut_cells, 0u);
}

TEST(GridBoxes, GridCoveringPartOfTheSolid) {
    // the box reaches above, below and beside the grid: only its part inside counts
    const std::array<double, 3> lo{-0.3, 0.2, -1.7}, hi{0.61, 2.5, 3.3};
    const Mesh m = box(lo, hi);
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {5, 6, 7});
    const auto r = run_grid(m, g);
    expect_box_cells(r, g, lo, hi, 1e-15);
    // and a grid wholly inside the solid: every cell full
    const GridAxes inside = uniform_axes({0, 0.5, 0, 0.5, 1, 1}, {3, 3, 3});
    const auto ri = run_grid(m, inside);
    EXPECT_EQ(ri.summary.bodies[0].full_cells, inside.cell_count());
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j)
            for (std::size_t k = 0; k < 3; ++k)
                EXPECT_EQ(ri.volumes[inside.cell(i, j, k)], inside.cell_volume(i, j, k));
    // and a grid wholly outside it: every cell empty
    const GridAxes outside = uniform_axes({2, 3, 4, 3, 4, 5}, {2, 2, 2});
    const auto ro = run_grid(m, outside);
    EXPECT_EQ(ro.summary.bodies[0].empty_cells, outside.cell_count());
    EXPECT_EQ(ro.summary.bodies[0].volume, 0);
}

TEST(GridBoxes, NonUniformPlanes) {
    const std::array<double, 3> lo{0.05, 0.3, 0.2}, hi{0.95, 0.35, 0.8};
    const Mesh m = box(lo, hi);
    GridAxes g;
    g.x = {0, 0.1, 0.35, 0.5, 0.9, 1.0};
    g.y = {0, 0.3, 0.31, 0.33, 1};
    g.z = {0, 0.2, 0.21, 0.7, 0.8, 0.81, 2};
    EXPECT_FALSE(g.uniform());
    const auto r = run_grid(m, g);
    expect_box_cells(r, g, lo, hi, 1e-15);
}

TEST(GridBoxes, QuadFacesGiveTheSameAsTriangles) {
    const std::array<double, 3> lo{0.13, 0.271, 0.0905}, hi{0.77, 0.5, 0.9311};
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {6, 5, 4});
    const auto tri = run_grid(box(lo, hi), g);
    const auto quad = run_grid(box(lo, hi, {.quads = true}), g);
    EXPECT_EQ(tri.volumes, quad.volumes);
}

TEST(GridBoxes, FirstMomentsOfBoxCellsAndTheirSum) {
    const std::array<double, 3> lo{0.13, 0.271, 0.0905}, hi{0.77, 0.5, 0.9311};
    const Mesh m = box(lo, hi);
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {5, 4, 6});
    const auto r = run_grid(m, g, /*moments=*/true);
    std::array<double, 3> sum{0, 0, 0};
    for (std::size_t i = 0; i < g.nx(); ++i)
        for (std::size_t j = 0; j < g.ny(); ++j)
            for (std::size_t k = 0; k < g.nz(); ++k) {
                const double c0[3] = {g.x[i], g.y[j], g.z[k]}, c1[3] = {g.x[i + 1], g.y[j + 1], g.z[k + 1]};
                const double v = box_overlap(lo, hi, c0, c1);
                const std::size_t c = g.cell(i, j, k);
                for (int a = 0; a < 3; ++a) {
                    // centre of the overlap box
                    const double mid = 0.5 * (std::max(lo[a], c0[a]) + std::min(hi[a], c1[a]));
                    EXPECT_NEAR(r.moments[3 * c + a], v * mid, 1e-15) << c << " " << a;
                    sum[a] += r.moments[3 * c + a];
                }
            }
    const MassProperties mp = mass_properties(m.view());
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(sum[a], mp.first_moments[a], 1e-14 * std::abs(mp.first_moments[a]));
}

TEST(GridTetrahedron, PlanesThroughVerticesEdgesAndFaces) {
    // unit corner tetrahedron on 2 x 2 x 2 cells of [0,1]^3: the planes x=0, y=0,
    // z=0 hold faces, the planes at 1/2 pass through edge midpoints, and the
    // vertices lie on the grid's corners.
    const Mesh m = test::unit_tetrahedron();
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {2, 2, 2});
    const auto r = run_grid(m, g, true);
    const double corner = 1.0 / 48;  // a tetrahedron with legs 1/2
    for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
            for (int k = 0; k < 2; ++k) {
                const int ups = i + j + k;
                const double want = ups == 0 ? 0.125 - corner : (ups == 1 ? corner : 0);
                EXPECT_NEAR(r.volumes[g.cell(i, j, k)], want, 1e-16) << i << j << k;
            }
    EXPECT_NEAR(r.summary.bodies[0].volume, 1.0 / 6, 1e-16);
    // finer grids, planes through the vertices and many edges: total stays 1/6
    for (uint32_t n : {3u, 4u, 5u, 8u}) {
        const GridAxes gn = uniform_axes({0, 0, 0, 1, 1, 1}, {n, n, n});
        const auto rn = run_grid(m, gn);
        EXPECT_NEAR(rn.summary.bodies[0].volume, 1.0 / 6, 4e-16) << n;
    }
}

TEST(GridBoxes, InsideOutBoxGivesNegativeCells) {
    const std::array<double, 3> lo{0.13, 0.271, 0.0905}, hi{0.77, 0.5, 0.9311};
    Mesh m = box(lo, hi);
    for (std::size_t t = 0; t < m.indices.size(); t += 3) std::swap(m.indices[t + 1], m.indices[t + 2]);
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {4, 4, 4});
    const auto r = run_grid(m, g);
    const auto r_out = run_grid(box(lo, hi), g);
    // the same up to the rounding of the pieces (reversed triangles fan differently)
    for (std::size_t c = 0; c < g.cell_count(); ++c) EXPECT_NEAR(r.volumes[c], -r_out.volumes[c], 1e-16);
    EXPECT_EQ(r.summary.bodies[0].full_cells, 0u);
}

TEST(GridBoxes, ResultsDoNotDependOnTheThreadCount) {
    const Mesh m = box({0.13, 0.271, 0.0905}, {0.77, 0.5, 0.9311});
    Mesh two = m;
    two.append(box({0.5, 0.1, 0.3}, {0.9, 0.45, 0.6}));
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {70, 65, 9});
    const auto many = run_grid(two, g, true);
    test::GridRun one;
    tbb::task_arena arena(1);
    arena.execute([&] { one = run_grid(two, g, true); });
    EXPECT_EQ(many.volumes, one.volumes);
    EXPECT_EQ(many.moments, one.moments);
    EXPECT_EQ(many.summary.bodies[0].volume, one.summary.bodies[0].volume);
}

TEST(GridBoxes, ProgressIsReportedUpToOne) {
    const Mesh m = box({0.13, 0.271, 0.0905}, {0.77, 0.5, 0.9311});
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {64, 64, 8});
    std::vector<double> vol(g.cell_count()), seen;
    const MeshView views[1] = {m.view()};
    grid_volumes(views, g, {.volumes = vol}, {.progress = [&](double f) { seen.push_back(f); }});
    ASSERT_FALSE(seen.empty());
    EXPECT_EQ(seen.back(), 1.0);
    for (std::size_t i = 1; i < seen.size(); ++i) EXPECT_GT(seen[i], seen[i - 1]);
}

TEST(GridErrors, BadInputIsRejected) {
    const Mesh m = box({0.1, 0.1, 0.1}, {0.9, 0.9, 0.9});
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {2, 2, 2});
    const MeshView views[1] = {m.view()};
    std::vector<double> small(7);
    EXPECT_THROW(grid_volumes(views, g, {.volumes = small}), std::invalid_argument);
    std::vector<double> vol(8);
    GridAxes bad = g;
    bad.x = {0, 0.5, 0.5, 1};
    EXPECT_THROW(grid_volumes(views, bad, {.volumes = std::span<double>(vol.data(), 9)}), std::invalid_argument);
    Mesh nan = m;
    nan.positions[4] = std::numeric_limits<double>::quiet_NaN();
    const MeshView nan_view[1] = {nan.view()};
    EXPECT_THROW(grid_volumes(nan_view, g, {.volumes = vol}), std::invalid_argument);
    Mesh bad_index = m;
    bad_index.indices[5] = 99;
    const MeshView bad_view[1] = {bad_index.view()};
    EXPECT_THROW(grid_volumes(bad_view, g, {.volumes = vol}), std::invalid_argument);
    EXPECT_THROW(uniform_axes({0, 0, 0, 1, 0, 1}, {2, 2, 2}), std::invalid_argument);
}

TEST(GridSpecs, DefaultPaddedCubicCells) {
    const Mesh m = box({1, 2, 3}, {3, 3, 3.5});
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {});
    EXPECT_EQ(g.nx(), 128u);
    const double h = g.x[1] - g.x[0];
    EXPECT_NEAR(h, 2.0 / 126, 1e-15);
    EXPECT_NEAR(g.x.front(), 1 - h, 1e-12);
    EXPECT_NEAR(g.y[1] - g.y[0], h, 1e-12);
    EXPECT_NEAR(g.z[1] - g.z[0], h, 1e-12);
    EXPECT_EQ(g.ny(), 63u + 2);  // ceil(1 / h) + 2
    EXPECT_LE(g.y.front(), 2 - h);
    EXPECT_GE(g.z.back(), 3.5 + h);
    EXPECT_TRUE(g.uniform());
    const GridAxes c = make_grid(views, {.cell_size = 0.25});
    EXPECT_EQ(c.nx(), 10u);
    EXPECT_EQ(c.ny(), 6u);
    EXPECT_EQ(c.nz(), 4u);
    const GridAxes d = make_grid(views, {.dims = {10, 6, 3}});
    EXPECT_EQ(d.nx(), 10u);
    EXPECT_EQ(d.nz(), 3u);
    EXPECT_LT(d.z.front(), 3);
    const GridAxes b = make_grid(views, {.cells = 10, .bounds = std::array<double, 6>{0, 0, 0, 4, 2, 1}});
    EXPECT_EQ(b.nx(), 10u);
    EXPECT_EQ(b.ny(), 5u);
    EXPECT_EQ(b.x.back(), 4);
    Mesh empty;
    const MeshView none[1] = {empty.view()};
    EXPECT_THROW(make_grid(none, {}), std::invalid_argument);
}

}  // namespace

// Each cell's wetted area and area-weighted normal (GridOutput::wetted_area,
// surface_normal): closed forms for a box whose faces cross the cells, a box
// whose faces lie on grid planes (each face counted once), and a sphere
// whose cells add up to its area and to a zero net normal.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "common/generate.hpp"
#include "common/shapes.hpp"
#include "grid_fixtures.hpp"
#include "polyvol/grid.hpp"
#include "polyvol/measure.hpp"

namespace polyvol {
namespace {

struct Surface {
    std::vector<double> area, normal;
};

Surface surface_of(const Mesh& m, const GridAxes& g) {
    const std::size_t cells = g.cell_count();
    std::vector<double> volumes(cells);
    Surface s{std::vector<double>(cells, -1), std::vector<double>(3 * cells, -1)};
    GridOutput out{.volumes = volumes};
    out.wetted_area = s.area;
    out.surface_normal = s.normal;
    const MeshView bodies[] = {m.view()};
    test::expect_test_device(grid_volumes(bodies, g, out, test::test_options()));
    return s;
}

TEST(GridSurface, BoxFacesCrossingTheCells) {
    // [0.25, 1.75]^3 in 2 x 2 x 2 unit cells: each cell holds a quarter of
    // three faces (0.75 x 0.75 each), their normals pointing away from the centre.
    const Mesh box = test::box({0.25, 0.25, 0.25}, {1.75, 1.75, 1.75});
    const GridAxes g = uniform_axes({0, 0, 0, 2, 2, 2}, {2, 2, 2});
    const Surface s = surface_of(box, g);
    for (std::size_t i = 0; i < 2; ++i)
        for (std::size_t j = 0; j < 2; ++j)
            for (std::size_t k = 0; k < 2; ++k) {
                const std::size_t c = g.cell(i, j, k);
                EXPECT_DOUBLE_EQ(s.area[c], 3 * 0.5625);
                const double sign[3] = {i ? 1.0 : -1.0, j ? 1.0 : -1.0, k ? 1.0 : -1.0};
                for (int a = 0; a < 3; ++a) EXPECT_DOUBLE_EQ(s.normal[3 * c + a], 0.5625 * sign[a]);
            }
}

TEST(GridSurface, FacesOnGridPlanesCountOnce) {
    const Mesh box = test::box({0, 0, 0}, {1, 1, 1});
    const GridAxes g = uniform_axes({0, 0, 0, 2, 2, 2}, {2, 2, 2});
    const Surface s = surface_of(box, g);
    double total = 0, net[3] = {0, 0, 0};
    for (std::size_t c = 0; c < g.cell_count(); ++c) {
        total += s.area[c];
        for (int a = 0; a < 3; ++a) net[a] += s.normal[3 * c + a];
    }
    EXPECT_DOUBLE_EQ(total, 6.0);
    for (double x : net) EXPECT_EQ(x, 0.0);
}

TEST(GridSurface, SphereCellsAddUpToItsArea) {
    const Mesh sphere = generate::uv_sphere(24, 48, 1.0, 0.1, -0.2, 0.05);
    const GridAxes g = uniform_axes({-1.5, -1.5, -1.5, 1.5, 1.5, 1.5}, {13, 11, 12});
    const Surface s = surface_of(sphere, g);
    double total = 0, net[3] = {0, 0, 0}, outside = 0;
    for (std::size_t c = 0; c < g.cell_count(); ++c) {
        total += s.area[c];
        for (int a = 0; a < 3; ++a) net[a] += s.normal[3 * c + a];
        // A cell's area-weighted normal is never longer than its area.
        const double len = std::hypot(s.normal[3 * c], s.normal[3 * c + 1], s.normal[3 * c + 2]);
        outside = std::max(outside, len - s.area[c]);
    }
    const double area = surface_area(sphere.view());
    EXPECT_NEAR(total, area, 1e-13 * area);
    for (double x : net) EXPECT_NEAR(x, 0.0, 1e-13 * area);
    EXPECT_LE(outside, 1e-15);
}

}  // namespace
}  // namespace polyvol

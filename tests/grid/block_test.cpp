// grid_block_volumes: every block of a grid, computed alone from the bodies,
// has the bits of the same cells in the whole grid — volumes, moments,
// wetted areas and normals, and with several bodies the union, the
// intersection and the cell classes; the blocks' summaries add up to the
// grid's counts.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "common/generate.hpp"
#include "grid_fixtures.hpp"

namespace {

using namespace polyvol;

struct Outputs {
    std::vector<double> volumes, moments, wetted, normal, uni, inter, uwet, unormal;
    std::vector<CellClass> cls;
    GridOutput out;
    Outputs(std::size_t bodies, std::size_t cells) {
        volumes.assign(bodies * cells, -1);
        moments.assign(3 * bodies * cells, -1);
        wetted.assign(bodies * cells, -1);
        normal.assign(3 * bodies * cells, -1);
        out = GridOutput{.volumes = volumes, .first_moments = moments, .wetted_area = wetted, .surface_normal = normal};
        if (bodies > 1) {
            uni.assign(cells, -1);
            inter.assign(cells, -1);
            uwet.assign(cells, -1);
            unormal.assign(3 * cells, -1);
            cls.assign(cells, CellClass::empty);
            out.union_volumes = uni;
            out.intersection_volumes = inter;
            out.union_wetted_area = uwet;
            out.union_surface_normal = unormal;
            out.cell_class = cls;
        }
    }
};

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Cuts the grid into blocks of the given sizes and compares each with the whole grid.
void check_blocks(const std::vector<const Mesh*>& meshes, const GridAxes& g, std::array<std::size_t, 3> size) {
    std::vector<MeshView> views;
    for (const Mesh* m : meshes) views.push_back(m->view());
    const std::size_t nb = views.size(), cells = g.cell_count();
    Outputs whole(nb, cells);
    const GridSummary all = grid_volumes(views, g, whole.out, test::test_options());
    test::expect_test_device(all);
    std::size_t cut = 0, full = 0, contact = 0;
    for (std::size_t i0 = 0; i0 < g.nx(); i0 += size[0])
        for (std::size_t j0 = 0; j0 < g.ny(); j0 += size[1])
            for (std::size_t k0 = 0; k0 < g.nz(); k0 += size[2]) {
                const GridBlock b{{i0, j0, k0},
                                  {std::min(g.nx(), i0 + size[0]), std::min(g.ny(), j0 + size[1]),
                                   std::min(g.nz(), k0 + size[2])}};
                const std::size_t bx = b.hi[0] - b.lo[0], by = b.hi[1] - b.lo[1], bz = b.hi[2] - b.lo[2];
                Outputs part(nb, b.cell_count());
                const GridSummary s = grid_block_volumes(views, g, b, part.out, test::test_options());
                test::expect_test_device(s);
                for (std::size_t body = 0; body < nb; ++body) {
                    cut += s.bodies[body].cut_cells;
                    full += s.bodies[body].full_cells;
                }
                contact += s.contact_cells;
                for (std::size_t i = 0; i < bx; ++i)
                    for (std::size_t j = 0; j < by; ++j)
                        for (std::size_t k = 0; k < bz; ++k) {
                            const std::size_t c = g.cell(i0 + i, j0 + j, k0 + k), d = (i * by + j) * bz + k;
                            for (std::size_t body = 0; body < nb; ++body) {
                                const std::size_t wc = body * cells + c, bc = body * b.cell_count() + d;
                                ASSERT_TRUE(same_bits(whole.volumes[wc], part.volumes[bc]))
                                    << "body " << body << " cell " << i0 + i << " " << j0 + j << " " << k0 + k << ": "
                                    << whole.volumes[wc] << " vs " << part.volumes[bc];
                                ASSERT_TRUE(same_bits(whole.wetted[wc], part.wetted[bc]));
                                for (int a = 0; a < 3; ++a) {
                                    ASSERT_TRUE(same_bits(whole.moments[3 * wc + a], part.moments[3 * bc + a]));
                                    ASSERT_TRUE(same_bits(whole.normal[3 * wc + a], part.normal[3 * bc + a]));
                                }
                            }
                            if (nb == 1) continue;
                            ASSERT_TRUE(same_bits(whole.uni[c], part.uni[d])) << whole.uni[c] << " vs " << part.uni[d];
                            ASSERT_TRUE(same_bits(whole.inter[c], part.inter[d]));
                            ASSERT_TRUE(same_bits(whole.uwet[c], part.uwet[d]));
                            ASSERT_EQ(whole.cls[c], part.cls[d]);
                            for (int a = 0; a < 3; ++a)
                                ASSERT_TRUE(same_bits(whole.unormal[3 * c + a], part.unormal[3 * d + a]));
                        }
            }
    std::size_t all_cut = 0, all_full = 0;
    for (const GridBodySummary& s : all.bodies) {
        all_cut += s.cut_cells;
        all_full += s.full_cells;
    }
    EXPECT_EQ(cut, all_cut);
    EXPECT_EQ(full, all_full);
    EXPECT_EQ(contact, all.contact_cells);
    EXPECT_GT(all_cut, 0u);
}

TEST(GridBlock, SphereBlocksHaveTheWholeGridsBits) {
    const Mesh s = generate::uv_sphere(24, 48, 1.0, 0.013, -0.021, 0.007);
    const GridAxes g = uniform_axes({-1.3, -1.2, -1.1, 1.2, 1.3, 1.25}, {19, 17, 23});
    check_blocks({&s}, g, {7, 5, 6});
    check_blocks({&s}, g, {19, 17, 4});  // full columns, thin layers
    check_blocks({&s}, g, {1, 1, 23});   // one column at a time
}

TEST(GridBlock, NonUniformPlanesAndATorus) {
    const Mesh t = generate::torus(40, 24, 1.0, 0.42);
    GridAxes g = uniform_axes({-1.5, -1.5, -0.5, 1.5, 1.5, 0.5}, {14, 13, 9});
    std::mt19937_64 rng(7);
    for (auto* axis : {&g.x, &g.y, &g.z})
        for (std::size_t p = 1; p + 1 < axis->size(); ++p)
            (*axis)[p] += std::uniform_real_distribution<double>(-0.2, 0.2)(rng) * ((*axis)[p + 1] - (*axis)[p]);
    check_blocks({&t}, g, {4, 6, 2});
}

TEST(GridBlock, TwoOverlappingBodiesUnionAndIntersection) {
    const Mesh a = generate::uv_sphere(16, 32, 1.0, 0, 0, 0), b = generate::uv_sphere(16, 32, 0.8, 0.7, 0.2, 0.1);
    const GridAxes g = uniform_axes({-1.2, -1.2, -1.2, 1.6, 1.2, 1.2}, {15, 11, 13});
    check_blocks({&a, &b}, g, {6, 4, 5});
}

TEST(GridBlock, RefusesABlockOutsideTheGrid) {
    const Mesh s = generate::uv_sphere(8, 16);
    const MeshView v = s.view();
    const GridAxes g = uniform_axes({-1, -1, -1, 1, 1, 1}, {4, 4, 4});
    std::vector<double> volumes(64);
    for (const GridBlock& b : {GridBlock{{0, 0, 0}, {5, 4, 4}}, GridBlock{{2, 0, 0}, {2, 4, 4}}}) {
        volumes.assign(b.cell_count(), 0);
        EXPECT_THROW(grid_block_volumes(std::span(&v, 1), g, b, GridOutput{.volumes = volumes}),
                     std::invalid_argument);
    }
}

}  // namespace

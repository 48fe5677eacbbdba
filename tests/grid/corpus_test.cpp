// Every closed mesh of the shared corpus (../shared/corpus/manifest.json):
// the cells sum to its exact reference volume within 1e-12 relative, every
// cell lies within [0, cell volume] (or [-cell volume, 0] for a mesh turned
// inside out) up to rounding — except where the mesh covers a region twice
// or folds over itself — and a grid refined by 2 along each axis has
// each coarse cell equal to the sum of its 8 children.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/manifest.hpp"
#include "grid_fixtures.hpp"
#include "polyvol/io.hpp"

namespace {

using namespace polyvol;
using nlohmann::json;

using polyvol::test::corpus_file;
using polyvol::test::manifest_entry;

// Entries read without error whose surface is a closed 2-cycle.
std::vector<std::string> closed_paths() {
    return test::manifest_paths([](const json& e) {
        return !test::invalid_entry(e) && e.contains("volume") && e.contains("topology") &&
               e["topology"].value("closed_2_cycle", false);
    });
}

TEST(GridCorpus, ManifestHasClosedMeshes) {
    EXPECT_GE(closed_paths().size(), 50u) << "corpus missing at " << test::corpus_dir();
}

class GridCorpusMesh : public ::testing::TestWithParam<std::string> {};

TEST_P(GridCorpusMesh, CellsSumToTheVolumeAndStayInBounds) {
    const json& e = manifest_entry(GetParam());
    const LoadedMesh loaded = read_mesh_file(corpus_file(GetParam()));
    const MeshView view = loaded.mesh.view();
    const MeshView views[1] = {view};
    if (view.triangle_count() == 0) {
        EXPECT_THROW(make_grid(views, {.cells = 16}), std::invalid_argument);
        return;
    }
    const double want = test::corpus_reference(e["volume"]);
    // 24 cells along the longest side, padded, and an odd grid whose planes
    // fall anywhere
    const GridAxes grids[2] = {make_grid(views, {.cells = 24}), make_grid(views, {.cells = 17})};
    for (const GridAxes& g : grids) {
        const auto r = test::run_grid(loaded.mesh, g);
        EXPECT_NEAR(r.summary.bodies[0].volume, want, 1e-12 * std::abs(want)) << g.nx();
        const double sign = want < 0 ? -1 : 1;
        // Where the mesh itself covers a region more than once, the cell
        // values are the winding-number-weighted volumes: up to (1 + nested
        // solids) cells where solids overlap, and below 0 in the thin pockets
        // a non-planar concave polygon's fan folds over (no thicker than the
        // face's distance from its plane).
        const double overlap = 1.0 + e.value("nesting", json::object())
                                         .value("positive_inside_positive(overlapping_or_nested_solids)", 0);
        double fold = 0;
        if (e["planarity"].value("nonplanar_faces_1e-9", 0) > 0) {
            const auto& lo = e["bbox"]["min"];
            const auto& hi = e["bbox"]["max"];
            double d2 = 0;
            for (int a = 0; a < 3; ++a) d2 += std::pow(hi[a].get<double>() - lo[a].get<double>(), 2);
            fold = e["planarity"]["max_relative_deviation"].get<double>() * std::sqrt(d2);
        }
        for (std::size_t i = 0; i < g.nx(); ++i)
            for (std::size_t j = 0; j < g.ny(); ++j)
                for (std::size_t k = 0; k < g.nz(); ++k) {
                    const double cell = g.cell_volume(i, j, k);
                    const double area = (g.x[i + 1] - g.x[i]) * (g.y[j + 1] - g.y[j]);
                    const double v = sign * r.volumes[g.cell(i, j, k)];
                    ASSERT_GE(v, -1e-12 * cell - fold * area) << i << " " << j << " " << k;
                    ASSERT_LE(v, overlap * cell * (1 + 1e-12)) << i << " " << j << " " << k;
                }
    }
}

// Coarse planes with the midpoints inserted.
std::vector<double> refine(const std::vector<double>& c) {
    std::vector<double> f;
    for (std::size_t i = 0; i + 1 < c.size(); ++i) {
        f.push_back(c[i]);
        f.push_back(0.5 * (c[i] + c[i + 1]));
    }
    f.push_back(c.back());
    return f;
}

TEST_P(GridCorpusMesh, RefinedGridChildrenSumToTheirParent) {
    const LoadedMesh loaded = read_mesh_file(corpus_file(GetParam()));
    const MeshView views[1] = {loaded.mesh.view()};
    if (views[0].triangle_count() == 0) return;
    const GridAxes coarse = make_grid(views, {.cells = 11});
    const GridAxes fine{refine(coarse.x), refine(coarse.y), refine(coarse.z)};
    const auto rc = test::run_grid(loaded.mesh, coarse, true);
    const auto rf = test::run_grid(loaded.mesh, fine, true);
    for (std::size_t i = 0; i < coarse.nx(); ++i)
        for (std::size_t j = 0; j < coarse.ny(); ++j)
            for (std::size_t k = 0; k < coarse.nz(); ++k) {
                double sum = 0, msum[3] = {0, 0, 0};
                for (int c = 0; c < 8; ++c) {
                    const std::size_t f = fine.cell(2 * i + (c & 1), 2 * j + ((c >> 1) & 1), 2 * k + (c >> 2));
                    sum += rf.volumes[f];
                    for (int a = 0; a < 3; ++a) msum[a] += rf.moments[3 * f + a];
                }
                const std::size_t p = coarse.cell(i, j, k);
                const double cell = coarse.cell_volume(i, j, k);
                ASSERT_NEAR(rc.volumes[p], sum, 1e-13 * cell) << i << " " << j << " " << k;
                // moments: relative to the cell's volume times its distance from the origin
                const double reach = std::max({std::abs(coarse.x[i]), std::abs(coarse.x[i + 1]), std::abs(coarse.y[j]),
                                               std::abs(coarse.y[j + 1]), std::abs(coarse.z[k]),
                                               std::abs(coarse.z[k + 1])});
                for (int a = 0; a < 3; ++a)
                    ASSERT_NEAR(rc.moments[3 * p + a], msum[a], 1e-13 * cell * reach) << i << " " << j << " " << k;
            }
}

INSTANTIATE_TEST_SUITE_P(Closed, GridCorpusMesh, ::testing::ValuesIn(closed_paths()), test::corpus_param_name);

}  // namespace

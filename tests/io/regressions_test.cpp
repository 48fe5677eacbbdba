// Every file of tests/data/regressions (inputs that once crashed, hung or
// exhausted memory) read serially and in parallel with tiny chunks, then
// analysed and measured as fuzz/pipeline_target.cpp and fuzz/grid_target.cpp
// do (the solid, self-crossings, a grid with the mesh and a moved copy):
// a ReadError, a status or numbers, the reading the same either way.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/chunks.hpp"
#include "parse_helpers.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/grid.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"

namespace {

namespace fs = std::filesystem;
using namespace polyvol;

TEST(Regressions, EveryFileReadsOrFailsTheSameWayAndMeasures) {
    std::size_t files = 0;
    for (const auto& entry : fs::directory_iterator(fs::path(POLYVOL_TEST_DATA) / "regressions")) {
        if (entry.path().extension() == ".md") continue;
        ++files;
        std::ifstream in(entry.path(), std::ios::binary);
        const std::vector<char> bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
        const std::span<const std::byte> data(reinterpret_cast<const std::byte*>(bytes.data()), bytes.size());
        const std::string name = entry.path().filename().string();
        std::string errors[2];
        std::optional<LoadedMesh> meshes[2];
        for (int parallel = 0; parallel < 2; ++parallel) {
            io::ScopedParseOptions scope(parallel ? iotest::chunked(16) : iotest::kSerial);
            try {
                meshes[parallel] = read_mesh_memory(data, name);
            } catch (const ReadError& e) {
                errors[parallel] = e.what();
            }
        }
        EXPECT_EQ(errors[0], errors[1]) << name;
        ASSERT_EQ(meshes[0].has_value(), meshes[1].has_value()) << name;
        if (!meshes[0]) continue;
        iotest::expect_same_mesh(meshes[1]->mesh, meshes[0]->mesh, name);
        const MeshView v = meshes[0]->mesh.view();
        if (!analyze_topology(v).closed_2_cycle) continue;
        (void)mass_properties(v);
        (void)solid_volume(v, {.moments = true, .within_shells = true});
        (void)self_crossings(v);
        Mesh moved = meshes[0]->mesh;
        for (std::size_t i = 0; i < moved.vertex_count(); ++i) moved.positions[3 * i] += 0.5;
        const MeshView bodies[2] = {v, moved.view()};
        try {
            const GridAxes g = make_grid(bodies, {.cells = 8});
            std::vector<double> volumes(2 * g.cell_count()), u(g.cell_count());
            (void)grid_volumes(bodies, g, {.volumes = volumes, .union_volumes = u});
        } catch (const std::invalid_argument&) {  // the union undefined, as here
        }
    }
    EXPECT_GE(files, 4u);
}

}  // namespace

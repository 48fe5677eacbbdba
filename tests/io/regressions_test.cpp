// Every file of tests/data/regressions (inputs that once crashed, hung or
// exhausted memory) read serially and in parallel with tiny chunks, then
// analysed and measured: a ReadError or numbers, the same either way.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "io/chunks.hpp"
#include "parse_helpers.hpp"
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
        (void)analyze_topology(v);
        (void)mass_properties(v);
    }
    EXPECT_GE(files, 2u);
}

}  // namespace

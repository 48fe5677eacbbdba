// The library called from many threads at once, as a server calls it
// (issue #23): 8 threads, each reading a different corpus file and running
// analyze_topology, mass_properties and grid_volumes on it, several rounds;
// every result must be the bits the same calls give on one thread alone.
#include <gtest/gtest.h>

#include <tbb/task_arena.h>

#include <atomic>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "common/manifest.hpp"
#include "common/opencl_device.hpp"
#include "polyvol/device.hpp"
#include "polyvol/grid.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"

#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define POLYVOL_UNDER_TSAN 1
#endif
#endif

namespace {

using namespace polyvol;

// Under ThreadSanitizer each caller runs the library in an arena of its own
// thread: Debian's oneTBB is not instrumented, so the happens-before edges
// of its scheduler are invisible and every hand-over between workers would
// be reported. What TSan checks here is the library's own state shared by
// concurrent callers (statics, caches, options), which this keeps whole.
template <class F>
auto as_caller(F&& f) {
#ifdef POLYVOL_UNDER_TSAN
    tbb::task_arena own(1);
    return own.execute(std::forward<F>(f));
#else
    return f();
#endif
}

struct Result {
    std::vector<double> positions;
    std::size_t edges = 0, shells = 0;
    bool closed = false;
    std::array<double, 10> mass{};  // volume, area, centroid, second moments
    std::vector<double> grid;
};

Result compute(const std::string& path) {
    Result r;
    const LoadedMesh m = read_mesh_file(test::corpus_file(path));
    r.positions = m.mesh.positions;
    const MeshView v = m.mesh.view();
    const TopologyReport t = analyze_topology(v);
    r.edges = t.edges;
    r.shells = t.shells.size();
    r.closed = t.closed_2_cycle;
    const MassProperties p = mass_properties(v);
    r.mass = {p.volume, p.area, p.centroid[0], p.centroid[1], p.centroid[2], p.second_moments[0],
              p.second_moments[1], p.second_moments[2], p.second_moments[3], p.second_moments[4]};
    const MeshView bodies[1] = {v};
    const GridAxes g = make_grid(bodies, {.cells = 12});
    r.grid.assign(g.cell_count(), 0);
    (void)grid_volumes(bodies, g, {.volumes = r.grid});
    return r;
}

bool same(const Result& a, const Result& b) {
    auto bits = [](const auto& x, const auto& y) {
        return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(x[0])) == 0;
    };
    return bits(a.positions, b.positions) && a.edges == b.edges && a.shells == b.shells && a.closed == b.closed &&
           bits(a.mass, b.mass) && bits(a.grid, b.grid);
}

TEST(Threads, EightCallersGetTheBitsOfOne) {
    const std::vector<std::string> files = {
        "meshes/cura/weedo_x40.3mf",          "meshes/libcgal-demo/armadillo.off",
        "meshes/cura/diy220_platform.obj",    "meshes/prusa-slicer/aq_bed.stl",
        "meshes/openscad-testing-data/multi-volume-binary.amf", "meshes/libcgal-demo/sphere.ply",
        "meshes/libcgal-demo/mpi.off",        "meshes/minetest-data/boats_boat.obj"};
    std::vector<Result> alone;
    for (const std::string& f : files) alone.push_back(as_caller([&] { return compute(f); }));
    std::atomic<int> mismatches{0};
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < files.size(); ++i)
        threads.emplace_back([&, i] {
            for (int round = 0; round < 3; ++round) {
                const std::size_t f = (i + round) % files.size();  // each file met by several threads
                if (!same(as_caller([&] { return compute(files[f]); }), alone[f])) ++mismatches;
            }
        });
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(mismatches.load(), 0);
}

// Eight callers of the grid on one OpenCL device at once (its queue is
// shared, one caller at a time): each gets the CPU's bits. Not under
// ThreadSanitizer (its filter is Threads.*): the driver is not instrumented.
TEST(DeviceThreads, EightCallersOnOneDeviceGetTheCpusBits) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const std::vector<std::string> files = {"meshes/libcgal-demo/sphere.ply", "meshes/libcgal-demo/mpi.off",
                                            "meshes/minetest-data/boats_boat.obj", "meshes/prusa-slicer/aq_bed.stl"};
    std::vector<LoadedMesh> meshes;
    std::vector<GridAxes> grids;
    std::vector<std::vector<double>> cpu;
    for (const std::string& f : files) {
        meshes.push_back(read_mesh_file(test::corpus_file(f)));
        const MeshView bodies[1] = {meshes.back().mesh.view()};
        grids.push_back(make_grid(bodies, {.cells = 20}));
        cpu.emplace_back(grids.back().cell_count());
        (void)grid_volumes(bodies, grids.back(), {.volumes = cpu.back()}, {.device = {DeviceKind::cpu, -1}});
    }
    std::atomic<int> mismatches{0}, off_device{0};
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < 8; ++i)
        threads.emplace_back([&, i] {
            for (int round = 0; round < 2; ++round) {
                const std::size_t f = (i + round) % files.size();
                const MeshView bodies[1] = {meshes[f].mesh.view()};
                std::vector<double> v(grids[f].cell_count());
                const GridSummary s = grid_volumes(bodies, grids[f], {.volumes = v}, {.device = {DeviceKind::opencl, -1}});
                if (!s.device.starts_with("opencl: ")) ++off_device;
                if (std::memcmp(v.data(), cpu[f].data(), v.size() * sizeof(double)) != 0) ++mismatches;
            }
        });
    for (std::thread& t : threads) t.join();
    EXPECT_EQ(mismatches.load(), 0);
    EXPECT_EQ(off_device.load(), 0);
}

}  // namespace

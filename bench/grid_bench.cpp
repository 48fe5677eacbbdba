// The grid: exact volume of a solid in every cell (polyvol/grid.hpp), on
// generated closed meshes. Reports cells/s (items) and triangles/s.
//   ./build/bench/polyvol_bench --benchmark_filter=Grid --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one line)
// GridR3dCase is the work r3d's published voxelization timing was measured
// on: a 100k-triangle torus on a 128 x 129 x 38 grid over its bounding box.
// GridTwoSpheres: two spheres offset by half a radius on one grid, with the
// union exact in every cell (union:1, one call), against the same two bodies
// each on its own (union:0, two calls: the per-body work without the union).
// Time is wall-clock; CPU is the process's, all threads (with threads:1 it is
// the one core's time, little affected by other load on the machine).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <vector>

#include <tbb/global_control.h>

#include "common/generate.hpp"
#include "polyvol/grid.hpp"

namespace {

using namespace polyvol;

enum Shape : int { kSphere = 0, kTorus = 1 };

const Mesh& mesh(int shape, std::size_t n) {
    static std::map<std::pair<int, std::size_t>, Mesh> cache;
    auto it = cache.find({shape, n});
    if (it == cache.end())
        it = cache.emplace(std::pair{shape, n}, shape == kSphere ? generate::sphere_with_triangles(n)
                                                                 : generate::torus_with_triangles(n))
                 .first;
    return it->second;
}

void run(benchmark::State& state, const Mesh& m, const GridAxes& g) {
    const int threads = static_cast<int>(state.range(2));
    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);
    std::vector<double> volumes(g.cell_count());
    const MeshView views[1] = {m.view()};
    for (auto _ : state) {
        const GridSummary s = grid_volumes(views, g, {.volumes = volumes});
        benchmark::DoNotOptimize(s.bodies[0].volume);
    }
    const auto tris = static_cast<double>(m.view().triangle_count());
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * g.cell_count()));
    state.counters["triangles/s"] = benchmark::Counter(tris * static_cast<double>(state.iterations()),
                                                       benchmark::Counter::kIsRate);
    state.counters["cells"] = static_cast<double>(g.cell_count());
    state.counters["triangles"] = tris;
}

// range(0): triangles, range(1): cells along the longest side, range(2): threads (0: all)
template <int kShape>
void Grid(benchmark::State& state) {
    const Mesh& m = mesh(kShape, static_cast<std::size_t>(state.range(0)));
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = static_cast<uint32_t>(state.range(1))});
    run(state, m, g);
}

void GridR3dCase(benchmark::State& state) {
    const Mesh& m = mesh(kTorus, static_cast<std::size_t>(state.range(0)));
    const double R = 1.0, r = 0.42;  // torus_with_triangles' radii
    const GridAxes g = uniform_axes({-(R + r), -(R + r), -r, R + r, R + r, r}, {128, 129, 38});
    run(state, m, g);
}

// range(0): triangles per sphere, range(1): cells along the longest side, range(2): union
void GridTwoSpheres(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const Mesh& a = mesh(kSphere, n);
    static std::map<std::size_t, Mesh> moved;
    auto it = moved.find(n);
    if (it == moved.end()) {
        Mesh b = a;
        for (std::size_t v = 0; v < b.vertex_count(); ++v) {
            b.positions[3 * v] += 0.5;
            b.positions[3 * v + 1] += 0.0625;
            b.positions[3 * v + 2] += 0.03125;
        }
        it = moved.emplace(n, std::move(b)).first;
    }
    const MeshView views[2] = {a.view(), it->second.view()};
    const GridAxes g = make_grid(views, {.cells = static_cast<uint32_t>(state.range(1))});
    std::vector<double> volumes(2 * g.cell_count()), union_volumes(g.cell_count());
    const std::span<double> all(volumes);
    GridSummary s;
    for (auto _ : state) {
        if (state.range(2) != 0) {
            s = grid_volumes(views, g, {.volumes = all, .union_volumes = union_volumes});
        } else {
            for (std::size_t b = 0; b < 2; ++b)
                s = grid_volumes(std::span<const MeshView>(views).subspan(b, 1), g,
                                 {.volumes = all.subspan(b * g.cell_count(), g.cell_count())});
        }
        benchmark::DoNotOptimize(s.union_volume);
    }
    state.counters["contact_cells"] = static_cast<double>(s.contact_cells);
    state.counters["crossing_pairs"] = static_cast<double>(s.crossing_pairs);
}

}  // namespace

BENCHMARK(GridTwoSpheres)
    ->ArgsProduct({{100'000, 1'000'000}, {128, 256}, {0, 1}})
    ->ArgNames({"tris", "cells", "union"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(Grid<kSphere>)
    ->ArgsProduct({{100'000, 1'000'000}, {128, 256}, {0}})
    ->ArgNames({"tris", "cells", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime();
BENCHMARK(Grid<kTorus>)
    ->ArgsProduct({{100'000, 1'000'000}, {128, 256}, {0}})
    ->ArgNames({"tris", "cells", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime();
BENCHMARK(GridR3dCase)
    ->ArgsProduct({{100'000}, {128}, {1, 0}})
    ->ArgNames({"tris", "cells", "threads"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime();

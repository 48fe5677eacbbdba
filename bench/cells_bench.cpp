// A body in the cells of a mesh (polyvol/cells.hpp), on the cases argo's
// SMCI/SMCA papers timed (Tolle, Gründing, Bothe, Marić), rebuilt here:
//   CellsArgo/16/j   a 16^3 hex mesh over [-1, 1]^3 (points moved by up to
//                    j % of a cell: 0 or 25) against a 7,080-triangle
//                    ellipsoid (semi-axes 0.7, 0.5, 0.4); argo: 7,032 triangles
//   CellsLarge/88    88^3 = 681,472 hexahedra against a 119,200-triangle
//                    sphere (argo's SMCA: 685,949 cells, 120,322 triangles)
//   CellsVsGrid/64   the same cells as a 64^3 rectilinear grid: body_in_cells
//                    against grid_volumes on the grid's planes
//   CellsMemory/216  216^3 = 10,077,696 hexahedra against the same sphere:
//                    the peak resident memory of the process (peak_rss_gib,
//                    the mesh's arrays included) and the time
// Both meshes in memory; the time is body_in_cells with the cells' own
// volumes included (cell_volumes). Wall-clock, all threads.
//   ./build/bench/polyvol_bench --benchmark_filter=Cells --benchmark_repetitions=3
//       --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <vector>

#include "common/generate.hpp"
#include "polyvol/cells.hpp"
#include "polyvol/grid.hpp"

namespace {

using namespace polyvol;

Mesh ellipsoid() {
    Mesh m = generate::uv_sphere(60, 60, 1.0);
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        m.positions[3 * v] *= 0.7;
        m.positions[3 * v + 1] *= 0.5;
        m.positions[3 * v + 2] *= 0.4;
    }
    return m;
}

void run(benchmark::State& state, const CellMesh& cells, const Mesh& body) {
    for (auto _ : state) {
        const CellVolumes own = cell_volumes(cells.view());
        const BodyInCells r = body_in_cells(cells.view(), body.view(),
                                            {.overlapping_shells = false, .within_shells = false,
                                             .reference = false, .own = own.volumes});
        benchmark::DoNotOptimize(r.total);
        state.counters["cut_cells"] = static_cast<double>(r.cut_cells);
    }
    state.counters["cells"] = static_cast<double>(cells.cells);
    state.counters["triangles"] = static_cast<double>(body.view().triangle_count());
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * cells.cells));
}

void CellsArgo(benchmark::State& state) {
    static const Mesh body = ellipsoid();
    const CellMesh cells = generate::hex_cells(static_cast<int>(state.range(0)), -1.0, 1.0,
                                               static_cast<double>(state.range(1)) / 100);
    run(state, cells, body);
}
// Two ellipsoids, the second moved by a quarter of its size: their union in
// every cell (union_in_cells from each body's result: a boolean against
// both bodies only where both come near a cell), each body's own included.
void CellsUnion(benchmark::State& state) {
    static const Mesh a = ellipsoid();
    static const Mesh b = [] {
        Mesh m = ellipsoid();
        for (std::size_t v = 0; v < m.vertex_count(); ++v) m.positions[3 * v] += 0.25;
        return m;
    }();
    const CellMesh cells = generate::hex_cells(static_cast<int>(state.range(0)), -1.0, 1.0, 0.0);
    const MeshView both[2] = {a.view(), b.view()};
    for (auto _ : state) {
        const BodyInCells each[2] = {body_in_cells(cells.view(), a.view()), body_in_cells(cells.view(), b.view())};
        const BodyInCells r = union_in_cells(cells.view(), both, each);
        benchmark::DoNotOptimize(r.total);
        state.counters["cut_cells"] = static_cast<double>(r.cut_cells);
        state.counters["both_cells"] = static_cast<double>(r.touched_cells);  // a boolean each
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * cells.cells));
}
BENCHMARK(CellsUnion)->Arg(16)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK(CellsArgo)->Args({16, 0})->Args({16, 25})->Unit(benchmark::kMillisecond)->UseRealTime();

void CellsLarge(benchmark::State& state) {
    static const Mesh body = generate::uv_sphere(150, 400, 0.8);
    const CellMesh cells = generate::hex_cells(static_cast<int>(state.range(0)), -1.0, 1.0, 0.0);
    run(state, cells, body);
}
BENCHMARK(CellsLarge)->Arg(88)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

void CellsMemory(benchmark::State& state) {
    static const Mesh body = generate::uv_sphere(150, 400, 0.8);
    const CellMesh cells = generate::hex_cells(static_cast<int>(state.range(0)), -1.0, 1.0, 0.0);
    state.counters["mesh_gib"] = static_cast<double>(cells.points.size() * sizeof(double) +
                                                     (cells.face_offsets.size() + cells.face_points.size() +
                                                      cells.owner.size() + cells.neighbour.size()) *
                                                         sizeof(uint32_t)) /
                                 0x1p30;
    run(state, cells, body);
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    state.counters["peak_rss_gib"] = static_cast<double>(usage.ru_maxrss) / (1024.0 * 1024.0);  // ru_maxrss in KiB
}
BENCHMARK(CellsMemory)->Arg(216)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

// range(0): cells per axis; range(1): 0 the cells, 1 the grid.
void CellsVsGrid(benchmark::State& state) {
    static const Mesh body = generate::uv_sphere(150, 400, 0.8);
    const int n = static_cast<int>(state.range(0));
    if (state.range(1) == 0) {
        run(state, generate::hex_cells(n, -1.0, 1.0, 0.0), body);
        return;
    }
    const auto u = static_cast<uint32_t>(n);
    const GridAxes g = uniform_axes({-1.0, -1.0, -1.0, 1.0, 1.0, 1.0}, {u, u, u});
    std::vector<double> volumes(g.cell_count());
    const MeshView views[1] = {body.view()};
    for (auto _ : state) {
        const GridSummary s = grid_volumes(views, g, {.volumes = volumes});
        benchmark::DoNotOptimize(s.bodies[0].volume);
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * g.cell_count()));
}
BENCHMARK(CellsVsGrid)->Args({64, 0})->Args({64, 1})->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

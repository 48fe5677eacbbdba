// Boolean volumes (polyvol/boolean.hpp) of two spheres of n triangles each,
// the second offset by half a radius: the in-memory call, meshes loaded.
#include <benchmark/benchmark.h>

#include "generate.hpp"
#include "polyvol/boolean.hpp"

namespace {

void BooleanSpheres(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const polyvol::Mesh a = polyvol::bench::sphere_with_triangles(n);
    polyvol::Mesh b = polyvol::bench::sphere_with_triangles(n);
    for (std::size_t v = 0; v < b.vertex_count(); ++v) {
        b.positions[3 * v] += 0.5;
        b.positions[3 * v + 1] += 0.0625;
        b.positions[3 * v + 2] += 0.03125;
    }
    polyvol::BooleanVolumes r;
    for (auto _ : state) {
        r = polyvol::boolean_volumes(a.view(), b.view());
        benchmark::DoNotOptimize(r.intersection);
    }
    state.counters["crossing_pairs"] = static_cast<double>(r.crossing_pairs);
    state.counters["triangles"] = static_cast<double>(r.triangles_a + r.triangles_b);
}
BENCHMARK(BooleanSpheres)->Arg(20000)->Arg(100000)->Arg(500000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

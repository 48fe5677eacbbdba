// Boolean volumes (polyvol/boolean.hpp) of two spheres of n triangles each,
// the second offset by half a radius: the in-memory call, meshes loaded.
// SolidTenSpheres: one mesh of ten spheres of n triangles in a row, each
// overlapping its neighbours: solid_volume (solid:1) against what `polyvol
// measure` computes without it, analyze_topology + mass_properties (solid:0).
#include <benchmark/benchmark.h>

#include "generate.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"

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
void SolidTenSpheres(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    polyvol::Mesh ten;
    for (int i = 0; i < 10; ++i) {
        const polyvol::Mesh s = polyvol::bench::sphere_with_triangles(n);
        const auto base = static_cast<uint32_t>(ten.vertex_count());
        for (std::size_t v = 0; v < s.vertex_count(); ++v)
            ten.add_vertex(s.positions[3 * v] + 1.2 * i, s.positions[3 * v + 1], s.positions[3 * v + 2]);
        for (uint32_t x : s.indices) ten.indices.push_back(base + x);
    }
    double v = 0;
    for (auto _ : state) {
        if (state.range(1) != 0) {
            v = polyvol::solid_volume(ten.view()).volume;
        } else {
            benchmark::DoNotOptimize(polyvol::analyze_topology(ten.view()).closed_2_cycle);
            v = polyvol::mass_properties(ten.view()).volume;
        }
        benchmark::DoNotOptimize(v);
    }
    state.counters["triangles"] = static_cast<double>(ten.view().triangle_count());
}
BENCHMARK(SolidTenSpheres)
    ->ArgsProduct({{100'000}, {0, 1}})
    ->ArgNames({"tris", "solid"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(BooleanSpheres)->Arg(20000)->Arg(100000)->Arg(500000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

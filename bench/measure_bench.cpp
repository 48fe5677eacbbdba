// Throughput of the hot paths on generated closed meshes (triangles/s).
//   ./build/bench/polyvol_bench --benchmark_filter=Volume
#include <benchmark/benchmark.h>

#include <map>

#include "generate.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"

namespace {

using namespace polyvol;

const Mesh& sphere(std::size_t n) {
    static std::map<std::size_t, Mesh> cache;
    auto it = cache.find(n);
    if (it == cache.end()) it = cache.emplace(n, bench::sphere_with_triangles(n, 1e6)).first;
    return it->second;
}

template <Method method, Accuracy accuracy>
void Volume(benchmark::State& state) {
    const Mesh& m = sphere(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(signed_volume(m.view(), method, accuracy));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * m.face_count()));
}

void AllMassProperties(benchmark::State& state) {
    const Mesh& m = sphere(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(mass_properties(m.view()));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * m.face_count()));
}

void Topology(benchmark::State& state) {
    const Mesh& m = sphere(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(analyze_topology(m.view()));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * m.face_count()));
}

}  // namespace

BENCHMARK(Volume<Method::cone, Accuracy::correctly_rounded>)->Arg(1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK(Volume<Method::cone, Accuracy::fast>)->Arg(1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK(Volume<Method::prism, Accuracy::fast>)->Arg(1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK(Volume<Method::pyramid, Accuracy::fast>)->Arg(1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK(Volume<Method::vtnb, Accuracy::fast>)->Arg(1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK(AllMassProperties)->Arg(1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK(Topology)->Arg(1 << 20)->Unit(benchmark::kMillisecond);

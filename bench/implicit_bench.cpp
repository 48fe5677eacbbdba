// Implicit surfaces (docs/implicit.md, docs/benchmarks.md "Implicit
// surfaces"): the cost of one PL surface and its volume against the number of
// lattice cells N across the box, for the unit ball in n = 3 and n = 4 (box
// [-1.25, 1.25]^n, no Richardson pass). The continuation visits only crossed
// cubes, so the cost grows like N^(n-1) (BigO below: N^2 in 3D, N^3 in 4D),
// not like the N^n lattice; the coarse scan is fixed (default cells).
//   ./build/bench/polyvol_bench --benchmark_filter=Implicit
// ImplicitVolumeBench is the default path (the volume streamed: no chain,
// determinants on oneTBB workers; wall time), ImplicitChainVolumeBench the
// chain built and measured by chain_volume (keep_chain), ImplicitSurfaceBench
// the chain alone. Counters: boundary simplices, crossed n-simplices, F
// evaluations.
#include <benchmark/benchmark.h>

#include <span>

#include "polyvol/implicit.hpp"

namespace {

using namespace polyvol;

double unit_ball(std::span<const double> x) {
    double s = 0;
    for (double v : x) s += v * v;
    return s - 1.0;
}

ImplicitOptions options(int n, int64_t cells) {
    ImplicitOptions o;
    o.dimension = n;
    o.lo = {-1.25};
    o.hi = {1.25};
    o.h = 2.5 / static_cast<double>(cells);
    o.error_estimate = false;
    return o;
}

void report(benchmark::State& state, const ImplicitPass& p, int64_t cells) {
    state.counters["boundary_simplices"] = static_cast<double>(p.boundary_simplices);
    state.counters["crossed"] = static_cast<double>(p.crossed_simplices);
    state.counters["evaluations"] = static_cast<double>(p.function_evaluations);
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * p.boundary_simplices));
    state.SetComplexityN(cells);
}

// The volume, streamed (the default).
template <int n>
void ImplicitVolumeBench(benchmark::State& state) {
    const ImplicitOptions o = options(n, state.range(0));
    polyvol::ImplicitVolume r;
    for (auto _ : state) r = implicit_volume(unit_ball, o);
    report(state, r.fine, state.range(0));
}

// The surface as a chain and its volume by chain_volume (keep_chain).
template <int n>
void ImplicitChainVolumeBench(benchmark::State& state) {
    ImplicitOptions o = options(n, state.range(0));
    o.keep_chain = true;
    polyvol::ImplicitVolume r;
    for (auto _ : state) r = implicit_volume(unit_ball, o);
    report(state, r.fine, state.range(0));
}

// The continuation walk alone (the PL surface as a chain, no volume).
template <int n>
void ImplicitSurfaceBench(benchmark::State& state) {
    const ImplicitOptions o = options(n, state.range(0));
    ImplicitPass p;
    for (auto _ : state) benchmark::DoNotOptimize(implicit_surface(unit_ball, o, &p));
    report(state, p, state.range(0));
}

}  // namespace

BENCHMARK(ImplicitVolumeBench<3>)->RangeMultiplier(2)->Range(16, 256)->Unit(benchmark::kMillisecond)->UseRealTime()->Complexity(benchmark::oNSquared);
BENCHMARK(ImplicitChainVolumeBench<3>)->RangeMultiplier(2)->Range(16, 256)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNSquared);
BENCHMARK(ImplicitSurfaceBench<3>)->RangeMultiplier(2)->Range(16, 256)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNSquared);
BENCHMARK(ImplicitVolumeBench<4>)->RangeMultiplier(2)->Range(8, 32)->Unit(benchmark::kMillisecond)->UseRealTime()->Complexity(benchmark::oNCubed);
BENCHMARK(ImplicitChainVolumeBench<4>)->RangeMultiplier(2)->Range(8, 32)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNCubed);
BENCHMARK(ImplicitSurfaceBench<4>)->RangeMultiplier(2)->Range(8, 32)->Unit(benchmark::kMillisecond)->Complexity(benchmark::oNCubed);

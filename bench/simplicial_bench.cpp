// n-D chains: the rank-one (LU column replacement) traversal against a fresh
// LU factorisation per simplex (docs/benchmarks.md, "n-D chains").
//   ./build/bench/polyvol_bench --benchmark_filter='^Chain(RankOne|Refactor|BareLu)/'
// Chains: the boundary of the cross-polytope in R^n (2^n simplices), grown by
// random stellar subdivisions (a simplex replaced by the cone from a point
// just outside its centroid: n - 1 more simplices, still closed) to the
// requested size, every coordinate then perturbed by up to 1% relative.
// The reported time is the determinant sweep (walk order given); the
// topology (welding, face matching, the walk) is a counter of its own.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "polyvol/simplicial.hpp"

namespace {

using namespace polyvol;

Chain make_chain(int n, std::size_t target) {
    Chain c;
    c.dimension = n;
    c.coordinates.assign(static_cast<std::size_t>(2 * n) * n, 0.0);
    for (int i = 0; i < n; ++i) {
        c.coordinates[static_cast<std::size_t>(2 * i) * n + i] = 1.0;
        c.coordinates[static_cast<std::size_t>(2 * i + 1) * n + i] = -1.0;
    }
    for (uint64_t mask = 0; mask < (uint64_t{1} << n); ++mask) {
        std::vector<uint32_t> f;
        int neg = 0;
        for (int i = 0; i < n; ++i) {
            f.push_back(static_cast<uint32_t>(2 * i + ((mask >> i) & 1)));
            neg += static_cast<int>((mask >> i) & 1);
        }
        if (neg % 2) std::swap(f[0], f[1]);
        c.simplices.insert(c.simplices.end(), f.begin(), f.end());
    }
    std::mt19937_64 rng(static_cast<uint64_t>(n) * 1000003u + target);
    std::uniform_real_distribution<double> u(0, 1);
    while (c.simplex_count() + static_cast<std::size_t>(n) - 1 <= target) {
        const std::size_t s = std::uniform_int_distribution<std::size_t>(0, c.simplex_count() - 1)(rng);
        const std::vector<uint32_t> f(c.simplices.begin() + static_cast<std::ptrdiff_t>(s * n),
                                      c.simplices.begin() + static_cast<std::ptrdiff_t>((s + 1) * n));
        const auto nv = static_cast<uint32_t>(c.vertex_count());
        const double push = 1 + 0.02 * u(rng);
        for (int i = 0; i < n; ++i) {
            double x = 0;
            for (uint32_t v : f) x += c.coordinates[std::size_t{v} * n + i];
            c.coordinates.push_back(x / n * push);
        }
        for (int j = 0; j < n; ++j) {
            std::vector<uint32_t> g = f;
            g[j] = nv;
            if (j == 0) {
                std::copy(g.begin(), g.end(), c.simplices.begin() + static_cast<std::ptrdiff_t>(s * n));
            } else {
                c.simplices.insert(c.simplices.end(), g.begin(), g.end());
            }
        }
    }
    std::uniform_real_distribution<double> p(-0.01, 0.01);
    for (double& x : c.coordinates) x *= 1 + p(rng);
    return c;
}

const Chain& chain(int n, std::size_t k) {
    static std::map<std::pair<int, std::size_t>, Chain> cache;
    auto it = cache.find({n, k});
    if (it == cache.end()) it = cache.emplace(std::make_pair(n, k), make_chain(n, k)).first;
    return it->second;
}

// Manual time: the determinant sweep's processor time (ChainStats; on a
// loaded machine it is disturbed much less than the wall clock, which is
// reported as a counter). Counters: per-simplex sweep and topology times.
void ChainSweep(benchmark::State& state, Traversal traversal) {
    const int n = static_cast<int>(state.range(0));
    const Chain& c = chain(n, static_cast<std::size_t>(state.range(1)));
    ChainOptions o;
    o.accuracy = ChainAccuracy::bounded;
    o.traversal = traversal;
    o.centroid = false;  // the determinants, their bounds and the sum only
    ChainVolume v;
    for (auto _ : state) {
        v = chain_volume(c.view(), o);
        state.SetIterationTime(std::max(v.stats.cpu_seconds_sweep, 1e-6));
    }
    const double k = static_cast<double>(c.simplex_count());
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * c.simplex_count()));
    state.counters["simplices"] = k;
    state.counters["ns_per_simplex"] = v.stats.cpu_seconds_sweep / k * 1e9;
    state.counters["wall_ns_per_simplex"] = v.stats.seconds_sweep / k * 1e9;
    state.counters["topology_ns_per_simplex"] = v.stats.cpu_seconds_topology / k * 1e9;
    state.counters["factorizations"] = static_cast<double>(v.stats.factorizations);
    state.counters["stability_refactors"] = static_cast<double>(v.stats.stability_refactors);
    state.counters["jumps"] = static_cast<double>(v.stats.jumps);
    state.counters["eliminations_per_update"] =
        v.stats.updates ? static_cast<double>(v.stats.elimination_steps) / static_cast<double>(v.stats.updates) : 0.0;
    state.counters["rel_bound"] = v.volume_error_bound / std::abs(v.volume);
}

// The bare baseline: the cone rule with a plain Gaussian elimination (partial
// pivoting) per simplex on the raw coordinates, summed in double: no error
// bound, no topology, no moments — what a naive implementation pays.
void ChainBareLu(benchmark::State& state) {
    const int n = static_cast<int>(state.range(0));
    const Chain& c = chain(n, static_cast<std::size_t>(state.range(1)));
    std::vector<double> m(static_cast<std::size_t>(n) * n);
    double volume = 0;
    for (auto _ : state) {
        const std::clock_t t0 = std::clock();
        double sum = 0;
        for (std::size_t s = 0; s < c.simplex_count(); ++s) {
            for (int j = 0; j < n; ++j) {
                const double* x = &c.coordinates[std::size_t{c.simplices[s * n + j]} * n];
                for (int i = 0; i < n; ++i) m[i * n + j] = x[i];
            }
            double det = 1;
            for (int k = 0; k < n; ++k) {
                int p = k;
                for (int r = k + 1; r < n; ++r)
                    if (std::abs(m[r * n + k]) > std::abs(m[p * n + k])) p = r;
                if (p != k) {
                    for (int j = 0; j < n; ++j) std::swap(m[k * n + j], m[p * n + j]);
                    det = -det;
                }
                const double piv = m[k * n + k];
                det *= piv;
                if (piv == 0) break;
                for (int r = k + 1; r < n; ++r) {
                    const double l = m[r * n + k] / piv;
                    for (int j = k + 1; j < n; ++j) m[r * n + j] -= l * m[k * n + j];
                }
            }
            sum += det;
        }
        volume = sum;
        benchmark::DoNotOptimize(volume);
        state.SetIterationTime(std::max(static_cast<double>(std::clock() - t0) / CLOCKS_PER_SEC, 1e-6));
    }
    const double k = static_cast<double>(c.simplex_count());
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * c.simplex_count()));
    state.counters["simplices"] = k;
}

// Sizes: 10^4 .. 10^6 for n = 4, 8, 12; 10^5, 10^6 for n = 16 (its
// cross-polytope alone has 65536 simplices); 2^20 for n = 20. Then a
// dimension sweep at about 10^5 simplices for the crossover. Both traversals
// of one chain are registered one after the other, so that they meet the
// same load on a shared machine.
const bool registered = [] {
    std::vector<std::pair<int, int64_t>> sizes;
    for (int n : {4, 8, 12})
        for (int64_t k : {10000, 100000, 1000000}) sizes.push_back({n, k});
    for (int64_t k : {100000, 1000000}) sizes.push_back({16, k});
    sizes.push_back({20, 1 << 20});
    for (int n : {3, 5, 6, 7, 10}) sizes.push_back({n, 100000});
    for (const auto& [n, k] : sizes) {
        for (Traversal t : {Traversal::rank_one, Traversal::refactor})
            benchmark::RegisterBenchmark(t == Traversal::rank_one ? "ChainRankOne" : "ChainRefactor", ChainSweep, t)
                ->Args({n, k})
                ->UseManualTime()
                ->Iterations(1)
                ->Repetitions(3)
                ->ReportAggregatesOnly(true)
                ->Unit(benchmark::kMillisecond);
        benchmark::RegisterBenchmark("ChainBareLu", ChainBareLu)
            ->Args({n, k})
            ->UseManualTime()
            ->Iterations(1)
            ->Repetitions(3)
            ->ReportAggregatesOnly(true)
            ->Unit(benchmark::kMillisecond);
    }
    return true;
}();

}  // namespace

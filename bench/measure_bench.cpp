// Throughput of the hot paths on generated closed meshes (triangles/s).
//   ./build/bench/polyvol_bench --benchmark_filter=Volume
#include <benchmark/benchmark.h>

#include <algorithm>
#include <map>
#include <random>

#include "common/generate.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"

namespace {

using namespace polyvol;

// A sphere of radius 1 with about n triangles, centred at (offset, offset,
// offset): 1e6 by default (far from the origin: the translated form of the
// correctly rounded volume); 0 takes the origin form (measure/cone.hpp).
const Mesh& sphere(std::size_t n, int64_t offset = 1000000) {
    static std::map<std::pair<std::size_t, int64_t>, Mesh> cache;
    const auto key = std::make_pair(n, offset);
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, generate::sphere_with_triangles(n, static_cast<double>(offset))).first;
    return it->second;
}

// Args: triangles, offset of the sphere.
template <Method method, Accuracy accuracy>
void Volume(benchmark::State& state) {
    const Mesh& m = sphere(static_cast<std::size_t>(state.range(0)), state.range(1));
    for (auto _ : state) benchmark::DoNotOptimize(signed_volume(m.view(), method, accuracy));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * m.face_count()));
}

void AllMassProperties(benchmark::State& state) {
    const Mesh& m = sphere(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(mass_properties(m.view()));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * m.face_count()));
}

// What `polyvol volume`'s table computes of a loaded mesh: volume, area,
// first moments and centroid (no second moments, no edge length). Args:
// triangles, offset of the sphere (0: its first moments cancel, and the
// exact pass decides the centroid).
void TableMassProperties(benchmark::State& state) {
    const Mesh& m = sphere(static_cast<std::size_t>(state.range(0)), state.range(1));
    MeasureOptions options;
    options.second_moments = false;
    options.edge_length = false;
    for (auto _ : state) benchmark::DoNotOptimize(mass_properties(m.view(), options));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * m.face_count()));
}

void Topology(benchmark::State& state) {
    const Mesh& m = sphere(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(analyze_topology(m.view()));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * m.face_count()));
}

// The sphere as an STL file lists it: three vertices per triangle, the
// triangles in the generator's order (strips: a position's copies close
// together, as exporters write them) or shuffled (arg 1: no order to use).
Mesh sphere_soup(std::size_t n, bool shuffled) {
    const Mesh& m = sphere(n, 0);
    std::vector<std::size_t> order(m.face_count());
    for (std::size_t f = 0; f < order.size(); ++f) order[f] = f;
    if (shuffled) std::shuffle(order.begin(), order.end(), std::mt19937_64(42));
    Mesh soup;
    for (const std::size_t f : order) {
        uint32_t v[3];
        for (int k = 0; k < 3; ++k) {
            const double* p = &m.positions[3 * std::size_t{m.indices[3 * f + k]}];
            v[k] = soup.add_vertex(p[0], p[1], p[2]);
        }
        soup.add_triangle(v[0], v[1], v[2]);
    }
    return soup;
}

// The correctly rounded volume of the sphere's soup (arg: triangles), every
// corner its own vertex (as an STL file lists them; the reader welds them):
// the pass checks the coordinates it reads (a position is read once)
// instead of every position beside the faces.
void VolumeOfSoup(benchmark::State& state) {
    const Mesh soup = sphere_soup(static_cast<std::size_t>(state.range(0)), false);
    for (auto _ : state) benchmark::DoNotOptimize(signed_volume(soup.view()));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * soup.face_count()));
}

// welded() of a triangle soup (weld_vertices, then the indexed mesh). Args:
// triangles, shuffled.
void WeldSoup(benchmark::State& state) {
    const Mesh soup = sphere_soup(static_cast<std::size_t>(state.range(0)), state.range(1) != 0);
    for (auto _ : state) benchmark::DoNotOptimize(welded(soup.view()));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * soup.vertex_count()));
}

// fingerprint_closedness (the volume table's closedness check) on the
// indexed sphere (arg 1 = 0: a hash per vertex) or on its soup (arg 1 = 1:
// a hash per corner), against Topology's full analysis.
void FingerprintClosedness(benchmark::State& state) {
    const bool as_soup = state.range(1) != 0;
    const Mesh soup = as_soup ? sphere_soup(static_cast<std::size_t>(state.range(0)), false) : Mesh{};
    const Mesh& m = as_soup ? soup : sphere(static_cast<std::size_t>(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(fingerprint_closedness(m.view(), 1));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * m.face_count()));
}

}  // namespace

BENCHMARK(Volume<Method::cone, Accuracy::correctly_rounded>)
    ->ArgNames({"tris", "offset"})
    ->Args({1 << 20, 1000000})
    ->Args({1 << 20, 0})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(VolumeOfSoup)->ArgNames({"tris"})->Arg(1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK(Volume<Method::cone, Accuracy::fast>)->Args({1 << 20, 1000000})->Unit(benchmark::kMillisecond);
BENCHMARK(Volume<Method::prism, Accuracy::fast>)->Args({1 << 20, 1000000})->Unit(benchmark::kMillisecond);
BENCHMARK(Volume<Method::prism, Accuracy::correctly_rounded>)
    ->Args({1 << 20, 1000000})
    ->Args({1 << 20, 0})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(Volume<Method::pyramid, Accuracy::fast>)->Args({1 << 20, 1000000})->Unit(benchmark::kMillisecond);
BENCHMARK(Volume<Method::vtnb, Accuracy::fast>)->Args({1 << 20, 1000000})->Unit(benchmark::kMillisecond);
BENCHMARK(AllMassProperties)->Arg(1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK(TableMassProperties)
    ->ArgNames({"tris", "offset"})
    ->Args({1 << 20, 1000})
    ->Args({1 << 20, 0})
    ->Unit(benchmark::kMillisecond);
BENCHMARK(Topology)->Arg(1 << 20)->Unit(benchmark::kMillisecond);
BENCHMARK(FingerprintClosedness)->ArgNames({"tris", "soup"})->Args({1 << 20, 0})->Args({1 << 20, 1})->Unit(benchmark::kMillisecond);
BENCHMARK(WeldSoup)->ArgNames({"tris", "shuffled"})->Args({1 << 20, 0})->Args({1 << 20, 1})->Unit(benchmark::kMillisecond);

// Boolean volumes (polyvol/boolean.hpp) of two spheres of n triangles each,
// the second offset by half a radius: the in-memory call, meshes loaded.
// SolidTenSpheres: one mesh of ten spheres of n triangles in a row, each
// overlapping its neighbours: solid_volume (solid:1) against what `polyvol
// measure` computes without it, analyze_topology + mass_properties (solid:0).
// SelfCrossings: self_crossings of one sphere or torus of n triangles, the
// cost of looking for a surface crossing itself. SolidSelfCrossing: the
// cost of resolving one.
#include <benchmark/benchmark.h>

#include "common/generate.hpp"
#include "common/real_pairs.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"

namespace {

void BooleanSpheres(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const polyvol::Mesh a = polyvol::generate::sphere_with_triangles(n);
    polyvol::Mesh b = polyvol::generate::sphere_with_triangles(n);
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
        const polyvol::Mesh s = polyvol::generate::sphere_with_triangles(n);
        const auto base = static_cast<uint32_t>(ten.vertex_count());
        for (std::size_t v = 0; v < s.vertex_count(); ++v)
            ten.add_vertex(s.positions[3 * v] + 1.2 * i, s.positions[3 * v + 1], s.positions[3 * v + 2]);
        for (uint32_t x : s.indices) ten.indices.push_back(base + x);
    }
    double v = 0;
    for (auto _ : state) {
        if (state.range(1) != 0) {
            v = polyvol::solid_volume(ten.view()).properties.volume;
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

// SolidSelfCrossing: one shell crossing itself, two spheres of n triangles
// each joined by a tube through both (generate::join_by_tube). mode 0: what
// `polyvol measure` computes without the solid (analyze_topology +
// mass_properties); 1: solid_volume resolving it (within_shells, the search
// within shells included); 2: solid_volume of the same chain as three shells.
void SolidSelfCrossing(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    polyvol::Mesh b = polyvol::generate::sphere_with_triangles(n);
    for (std::size_t v = 0; v < b.vertex_count(); ++v) {
        b.positions[3 * v] = 0.8 * b.positions[3 * v] + 0.9;
        b.positions[3 * v + 1] = 0.8 * b.positions[3 * v + 1] + 0.0625;
        b.positions[3 * v + 2] = 0.8 * b.positions[3 * v + 2] + 0.03125;
    }
    const polyvol::generate::Joined j = polyvol::generate::join_by_tube(polyvol::generate::sphere_with_triangles(n), b);
    double v = 0;
    for (auto _ : state) {
        if (state.range(1) == 0) {
            benchmark::DoNotOptimize(polyvol::analyze_topology(j.one.view()).closed_2_cycle);
            v = polyvol::mass_properties(j.one.view()).volume;
        } else {
            const polyvol::SolidVolume s = state.range(1) == 1 ? polyvol::solid_volume(j.one.view(), {.within_shells = true})
                                                               : polyvol::solid_volume(j.three.view());
            if (s.status != polyvol::BooleanStatus::ok) state.SkipWithError("no solid");
            v = s.properties.volume;
        }
        benchmark::DoNotOptimize(v);
    }
    state.counters["triangles"] = static_cast<double>(j.one.view().triangle_count());
}
BENCHMARK(SolidSelfCrossing)
    ->ArgsProduct({{100'000, 1'000'000}, {0, 1, 2}})
    ->ArgNames({"tris", "mode"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// range(0): triangles, range(1): 0 sphere, 1 torus
void SelfCrossings(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const polyvol::Mesh m = state.range(1) == 0 ? polyvol::generate::sphere_with_triangles(n)
                                                : polyvol::generate::torus_with_triangles(n);
    std::size_t pairs = 0;
    for (auto _ : state) {
        pairs = polyvol::self_crossings(m.view()).candidate_pairs;
        benchmark::DoNotOptimize(pairs);
    }
    state.counters["candidate_pairs"] = static_cast<double>(pairs);
}
BENCHMARK(SelfCrossings)
    ->ArgsProduct({{100'000, 1'000'000}, {0, 1}})
    ->ArgNames({"tris", "torus"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

BENCHMARK(BooleanSpheres)->Arg(20000)->Arg(100000)->Arg(500000)->Unit(benchmark::kMillisecond)->UseRealTime();

// BooleanPairs: the real pairs of the CGAL oracle test (common/real_pairs.hpp),
// in process: boolean_volumes on a corpus part and a moved copy of it.
// part: the index in kRealParts; move: 0 exact offset, 1 exact offset along x
// (coplanar faces), 2 generic rotation.
constexpr const char* kRealParts[] = {
    "meshes/netgen-doc/hinge.stl",         "meshes/prusa-slicer/printbed-v2-250.stl", "meshes/gmsh-doc/t13_data.stl.gz",
    "meshes/cura/FelixPro2_platform.obj",  "meshes/stl-models/gearwheel.ascii.stl",   "meshes/prusa-slicer/torus.stl",
    "meshes/libcgal-demo/armadillo.off"};
void BooleanPairs(benchmark::State& state) {
    const polyvol::Mesh part =
        polyvol::read_mesh_file(std::string(POLYVOL_CORPUS_DIR) + "/" + kRealParts[state.range(0)]).mesh;
    const auto [a, b] = polyvol::test::real_pair(part, static_cast<polyvol::test::Move>(state.range(1)));
    polyvol::BooleanVolumes r;
    for (auto _ : state) {
        r = polyvol::boolean_volumes(a.view(), b.view());
        benchmark::DoNotOptimize(r.intersection);
    }
    if (r.status != polyvol::BooleanStatus::ok) state.SkipWithError(polyvol::boolean_status_message(r.status));
    state.counters["crossing_pairs"] = static_cast<double>(r.crossing_pairs);
    state.counters["triangles"] = static_cast<double>(r.triangles_a + r.triangles_b);
}
BENCHMARK(BooleanPairs)
    ->ArgsProduct({{0, 1, 2, 3, 4, 5, 6}, {0, 1, 2}})
    ->ArgNames({"part", "move"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

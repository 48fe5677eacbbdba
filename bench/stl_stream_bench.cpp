// Throughput of the streaming soup accumulator (polyvol/soup.hpp) on binary
// STL records held in memory (triangles/s), against a naive single-threaded
// det/6 loop over the same records.
//   ./build/bench/polyvol_bench --benchmark_filter='Soup|NaiveRecords'
// Args: triangles, offset of the sphere's centre (0: pass 1 decides; 1000: the
// float32 sphere is 1000 radii from the origin, pass 2 decides).
#include <benchmark/benchmark.h>

#include <cstring>
#include <map>
#include <utility>
#include <vector>

#include "common/generate.hpp"
#include "polyvol/soup.hpp"

namespace {

using namespace polyvol;

// Binary STL records (without the 84-byte header) of a sphere.
const std::vector<std::byte>& records(std::size_t n, int offset) {
    static std::map<std::pair<std::size_t, int>, std::vector<std::byte>> cache;
    auto it = cache.find({n, offset});
    if (it != cache.end()) return it->second;
    const Mesh m = generate::sphere_with_triangles(n, offset);
    const std::size_t tris = m.face_count();
    std::vector<std::byte> out(50 * tris);
    for (std::size_t t = 0; t < tris; ++t)
        for (int v = 0; v < 3; ++v)
            for (int k = 0; k < 3; ++k) {
                const auto f = static_cast<float>(m.positions[3 * m.indices[3 * t + v] + k]);
                std::memcpy(&out[50 * t + 12 + 12 * v + 4 * k], &f, 4);
            }
    return cache.emplace(std::make_pair(n, offset), std::move(out)).first->second;
}

// What polyvol volume's table asks of a streamed binary STL: the volume,
// area, first moments within pass 1's bound, closedness; on the records.
// (arg 2 = 1: the first moments correctly rounded, as --json --stream asks:
// the sphere centred at the origin takes the exact pass for them, the one
// at (2, 2, 2) is decided by pass 1, the one at 1000 by the translated pass 2.)
void SoupVolume(benchmark::State& state) {
    const auto& r = records(static_cast<std::size_t>(state.range(0)), static_cast<int>(state.range(1)));
    const SoupWants wants{.moments = state.range(2) == 1 ? Accuracy::correctly_rounded : Accuracy::fast};
    int passes = 0;
    for (auto _ : state) {
        const SoupResult s = soup_properties(stl_records(r), wants);
        passes = s.passes;
        benchmark::DoNotOptimize(s.properties.volume);
    }
    state.counters["passes"] = passes;
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * (r.size() / 50)));
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * r.size()));
}

// The same triangles packed: nine floats each (36 bytes), as
// read_binary_stl_triangles holds them.
const std::vector<float>& packed(std::size_t n, int offset) {
    static std::map<std::pair<std::size_t, int>, std::vector<float>> cache;
    auto it = cache.find({n, offset});
    if (it != cache.end()) return it->second;
    const auto& r = records(n, offset);
    std::vector<float> out(9 * (r.size() / 50));
    for (std::size_t t = 0; t < r.size() / 50; ++t) std::memcpy(&out[9 * t], &r[50 * t + 12], 36);
    return cache.emplace(std::make_pair(n, offset), std::move(out)).first->second;
}

// What polyvol volume's table needs when only the volume is asked for: the
// volume and the closedness fingerprint, on the records.
void SoupVolumeClosed(benchmark::State& state) {
    const auto& r = records(static_cast<std::size_t>(state.range(0)), static_cast<int>(state.range(1)));
    for (auto _ : state) {
        const SoupResult s = soup_properties(stl_records(r), SoupWants{.closedness = true, .moments_and_area = false});
        benchmark::DoNotOptimize(s.properties.volume);
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * (r.size() / 50)));
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * r.size()));
}

// soup_volume (the volume alone) on packed triangles: the in-memory call of
// bench/peers/polyvol_volume.cpp for a binary STL.
void SoupVolumeOnlyPacked(benchmark::State& state) {
    const auto& p = packed(static_cast<std::size_t>(state.range(0)), static_cast<int>(state.range(1)));
    for (auto _ : state) benchmark::DoNotOptimize(soup_volume(packed_triangles(p)));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * (p.size() / 9)));
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * p.size() * sizeof(float)));
}

void NaiveRecords(benchmark::State& state) {
    const auto& r = records(static_cast<std::size_t>(state.range(0)), static_cast<int>(state.range(1)));
    const std::size_t n = r.size() / 50;
    for (auto _ : state) {
        double sum = 0;
        for (std::size_t t = 0; t < n; ++t) {
            float v[9];
            std::memcpy(v, &r[50 * t + 12], sizeof v);
            const double ax = v[0], ay = v[1], az = v[2], bx = v[3], by = v[4], bz = v[5], cx = v[6], cy = v[7], cz = v[8];
            sum += ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
        }
        benchmark::DoNotOptimize(sum / 6);
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * n));
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * r.size()));
}

}  // namespace

BENCHMARK(SoupVolume)
    ->Args({1 << 20, 0, 0})
    ->Args({8 << 20, 0, 0})
    ->Args({1 << 20, 1000, 0})
    ->Args({1 << 20, 0, 1})
    ->Args({1 << 20, 2, 0})
    ->Args({1 << 20, 2, 1})
    ->Args({1 << 20, 1000, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(SoupVolumeClosed)->Args({1 << 20, 0})->Args({8 << 20, 0})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(SoupVolumeOnlyPacked)->Args({1 << 20, 0})->Args({1 << 20, 1000})->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(NaiveRecords)->Args({1 << 20, 0})->Args({8 << 20, 0})->Unit(benchmark::kMillisecond)->UseRealTime();

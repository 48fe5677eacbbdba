// Reading throughput (MB/s and triangles/s) of in-memory files of a
// generated closed mesh of about 1M triangles, through read_mesh_memory:
// ASCII STL, binary STL, OBJ, OFF, ASCII PLY and binary PLY, with the
// serial readers and with the parallel ones (src/io/chunks.hpp; binary STL:
// blocks of records). Both STL readers weld the facets' corners.
//   ./build/bench/polyvol_bench --benchmark_filter=Read
// Coordinates are float32 values written as their shortest decimal (as most
// exporters write them). Wall-clock time (the parallel readers use other
// threads) and the process's CPU time over all threads.
#include <benchmark/benchmark.h>

#include <charconv>
#include <cstdint>
#include <cstring>
#include <map>
#include <string>

#include "common/generate.hpp"
#include "polyvol/io.hpp"
#include "polyvol/parse_options.hpp"  // the serial or the parallel readers

namespace {

using namespace polyvol;

enum class File { stl_ascii, stl_binary, obj, off, ply_ascii, ply_binary };

const Mesh& source() {
    static const Mesh m = [] {
        Mesh s = generate::sphere_with_triangles(1'000'000, 3.25);
        for (double& c : s.positions) c = static_cast<double>(static_cast<float>(c));
        return s;
    }();
    return m;
}

void put(std::string& s, double v) {
    char b[32];
    const auto r = std::to_chars(b, b + sizeof b, static_cast<float>(v));
    s.append(b, r.ptr);
}
void put(std::string& s, std::size_t v) {
    char b[24];
    const auto r = std::to_chars(b, b + sizeof b, v);
    s.append(b, r.ptr);
}
void put_xyz(std::string& s, const Mesh& m, uint32_t i) {
    put(s, m.positions[3 * i]);
    s += ' ';
    put(s, m.positions[3 * i + 1]);
    s += ' ';
    put(s, m.positions[3 * i + 2]);
}

std::string write(File f) {
    const Mesh& m = source();
    const std::size_t nv = m.vertex_count(), nf = m.face_count();
    std::string s;
    switch (f) {
        case File::stl_ascii:
            s = "solid sphere\n";
            for (std::size_t t = 0; t < nf; ++t) {
                s += "  facet normal 0 0 0\n    outer loop\n";
                for (int k = 0; k < 3; ++k) {
                    s += "      vertex ";
                    put_xyz(s, m, m.indices[3 * t + k]);
                    s += '\n';
                }
                s += "    endloop\n  endfacet\n";
            }
            s += "endsolid sphere\n";
            break;
        case File::stl_binary: {
            s = std::string(80, ' ');
            const auto n = static_cast<uint32_t>(nf);
            char b[4];
            std::memcpy(b, &n, 4);  // little-endian hosts only, as the benchmarks run
            s.append(b, 4);
            for (std::size_t t = 0; t < nf; ++t) {
                s.append(12, '\0');  // normal
                for (int k = 0; k < 3; ++k)
                    for (int c = 0; c < 3; ++c) {
                        const auto x = static_cast<float>(m.positions[3 * std::size_t{m.indices[3 * t + k]} + c]);
                        std::memcpy(b, &x, 4);
                        s.append(b, 4);
                    }
                s.append(2, '\0');  // attribute bytes
            }
            break;
        }
        case File::obj:
            s = "# sphere\no sphere\n";
            for (uint32_t v = 0; v < nv; ++v) {
                s += "v ";
                put_xyz(s, m, v);
                s += '\n';
            }
            for (std::size_t t = 0; t < nf; ++t) {
                s += 'f';
                for (int k = 0; k < 3; ++k) {
                    s += ' ';
                    put(s, std::size_t{m.indices[3 * t + k]} + 1);
                }
                s += '\n';
            }
            break;
        case File::off:
        case File::ply_ascii:
            if (f == File::off) {
                s = "OFF\n";
                put(s, nv);
                s += ' ';
                put(s, nf);
                s += " 0\n";
            } else {
                s = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(nv) +
                    "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(nf) +
                    "\nproperty list uchar int vertex_indices\nend_header\n";
            }
            for (uint32_t v = 0; v < nv; ++v) {
                put_xyz(s, m, v);
                s += '\n';
            }
            for (std::size_t t = 0; t < nf; ++t) {
                s += '3';
                for (int k = 0; k < 3; ++k) {
                    s += ' ';
                    put(s, std::size_t{m.indices[3 * t + k]});
                }
                s += '\n';
            }
            break;
        case File::ply_binary: {
            s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(nv) +
                "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(nf) +
                "\nproperty list uchar int vertex_indices\nend_header\n";
            for (double c : m.positions) {
                const auto x = static_cast<float>(c);
                char b[4];
                std::memcpy(b, &x, 4);  // little-endian hosts only, as the benchmarks run
                s.append(b, 4);
            }
            for (std::size_t t = 0; t < nf; ++t) {
                s += '\3';
                for (int k = 0; k < 3; ++k) {
                    const auto i = static_cast<int32_t>(m.indices[3 * t + k]);
                    char b[4];
                    std::memcpy(b, &i, 4);
                    s.append(b, 4);
                }
            }
            break;
        }
    }
    return s;
}

const std::string& file(File f) {
    static std::map<File, std::string> cache;
    auto it = cache.find(f);
    if (it == cache.end()) it = cache.emplace(f, write(f)).first;
    return it->second;
}

const char* name_of(File f) {
    switch (f) {
        case File::stl_ascii:
        case File::stl_binary: return "sphere.stl";
        case File::obj: return "sphere.obj";
        case File::off: return "sphere.off";
        case File::ply_ascii:
        case File::ply_binary: return "sphere.ply";
    }
    return "";
}

template <File f, bool parallel>
void Read(benchmark::State& state) {
    const std::string& s = file(f);
    const std::span<const std::byte> bytes(reinterpret_cast<const std::byte*>(s.data()), s.size());
    io::ParseOptions options;
    options.parallel = parallel;
    const io::ScopedParseOptions scope(options);
    std::size_t triangles = 0;
    for (auto _ : state) {
        const LoadedMesh m = read_mesh_memory(bytes, name_of(f));
        triangles = m.mesh.face_count();
        benchmark::DoNotOptimize(m.mesh.positions.data());
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations() * s.size()));
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * triangles));
    state.counters["MB"] = static_cast<double>(s.size()) / 1e6;
    state.counters["chunks"] = static_cast<double>(io::thread_parse_report().chunks);
}

}  // namespace

// Time: wall clock; CPU: the process's CPU time over all threads.
#define POLYVOL_READ_BENCH(f)                                                                                   \
    BENCHMARK(Read<File::f, false>)                                                                             \
        ->Name("Read/" #f "/serial")                                                                            \
        ->Unit(benchmark::kMillisecond)                                                                         \
        ->MeasureProcessCPUTime()                                                                               \
        ->UseRealTime();                                                                                        \
    BENCHMARK(Read<File::f, true>)                                                                              \
        ->Name("Read/" #f "/parallel")                                                                          \
        ->Unit(benchmark::kMillisecond)                                                                         \
        ->MeasureProcessCPUTime()                                                                               \
        ->UseRealTime()

POLYVOL_READ_BENCH(stl_ascii);
POLYVOL_READ_BENCH(stl_binary);
POLYVOL_READ_BENCH(obj);
POLYVOL_READ_BENCH(off);
POLYVOL_READ_BENCH(ply_ascii);
POLYVOL_READ_BENCH(ply_binary);

// fuzz/read_target.cpp — one reader on arbitrary bytes (POLYVOL_FUZZ_READER,
// set per target by fuzz/CMakeLists.txt). The contract: a LoadedMesh or a
// ReadError, never a crash, leak, hang or huge allocation. The mesh readers
// run twice, serially and in parallel with chunks of a few bytes (the
// parallel paths otherwise start at 1 MiB, beyond what a fuzzer generates),
// and must agree: the same mesh, bit for bit, or the same error.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "polyvol/parse_options.hpp"
#include "io/readers.hpp"
#include "polyvol/chain_io.hpp"
#include "polyvol/io.hpp"

namespace {

using namespace polyvol;

constexpr std::string_view kReader = POLYVOL_FUZZ_READER;

struct Outcome {
    std::optional<LoadedMesh> mesh;
    std::string error;
};

Outcome read_with(std::span<const std::byte> data, const std::string& name, Format hint, const io::ParseOptions& o) {
    io::ScopedParseOptions scope(o);
    Outcome r;
    try {
        r.mesh = read_mesh_memory(data, name, hint);
    } catch (const ReadError& e) {
        r.error = e.what();
    }
    return r;
}

template <class T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Serial and parallel readings of one input disagree: a bug either way.
void expect_same(const Outcome& serial, const Outcome& parallel) {
    const bool agree = serial.mesh.has_value() == parallel.mesh.has_value() &&
                       (serial.mesh ? same_bytes(serial.mesh->mesh.positions, parallel.mesh->mesh.positions) &&
                                          same_bytes(serial.mesh->mesh.indices, parallel.mesh->mesh.indices) &&
                                          same_bytes(serial.mesh->mesh.face_offsets, parallel.mesh->mesh.face_offsets)
                                    : serial.error == parallel.error);
    if (!agree) __builtin_trap();
}

void read_mesh(std::span<const std::byte> data, const std::string& name, Format hint) {
    const Outcome serial = read_with(data, name, hint, {.parallel = false});
    for (const std::size_t chunk : {std::size_t{1}, std::size_t{64}})
        expect_same(serial, read_with(data, name, hint, {.parallel = true, .chunk_bytes = chunk, .min_parallel_bytes = 0}));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
    const std::span<const std::byte> data(reinterpret_cast<const std::byte*>(bytes), size);
    if (kReader == "stl") read_mesh(data, "f.stl", Format::stl);
    if (kReader == "obj") read_mesh(data, "f.obj", Format::obj);
    if (kReader == "off") read_mesh(data, "f.off", Format::off);
    if (kReader == "ply") read_mesh(data, "f.ply", Format::ply);
    if (kReader == "3mf") read_mesh(data, "f.3mf", Format::threemf);
    if (kReader == "amf") read_mesh(data, "f.amf", Format::amf);
    if (kReader == "gzip") read_mesh(data, "f.gz", Format::unknown);
    if (kReader == "gltf") read_mesh(data, "<stdin>", Format::gltf);  // as standard input: no buffer files read
    if (kReader == "archive") {  // bzip2 and tar (plain or compressed): the whole file, then each member
        read_mesh(data, "f.tar", Format::unknown);
        try {
            for (const std::string& m : io::tar_members(data, "f.tar"))
                read_mesh(io::tar_member(data, "f.tar", m, io::decompression_limit(data.size())), "f.tar:" + m,
                          Format::unknown);
        } catch (const ReadError&) {
        }
    }
    try {
        if (kReader == "chain" || kReader == "qhull") (void)read_chain_memory(data, "f.chain");
        if (kReader == "polygons") (void)read_polygons_memory(data, "f.txt");
    } catch (const ReadError&) {
    }
    return 0;
}

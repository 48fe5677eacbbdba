// The native Manifold peer for the boolean benchmark (bench/boolean_compare.sh,
// issue #36): Manifold built from its public source with its oneTBB backend
// (bench/peers/build_manifold.sh), a benchmark peer only — neither a
// dependency of polyvol nor built in CI. The same work as manifold_boolean.mjs
// (its WebAssembly build): two binary STL files (float32) become MeshGL with
// one vertex per corner, MeshGL::Merge welds them, a Manifold of each is
// built (timed apart: halfedges, sort, collider), then ROUNDS calls of
// (A ^ B).Volume() are timed.
// Prints: manifold-boolean VOLUME BUILD_SECONDS CALL_SECONDS(median)
#include <manifold/manifold.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <vector>

#include "timing.hpp"

namespace {

// Binary STL -> MeshGL: 3 corners per facet, float32, as in the .mjs peer.
bool read_binary_stl(const char* path, manifold::MeshGL& mesh) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<char> buf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (buf.size() < 84) return false;
    uint32_t n = 0;
    std::memcpy(&n, buf.data() + 80, 4);
    if (buf.size() != 84 + 50 * std::size_t{n}) return false;
    mesh.numProp = 3;
    mesh.vertProperties.resize(9 * std::size_t{n});
    mesh.triVerts.resize(3 * std::size_t{n});
    for (std::size_t i = 0; i < n; ++i) {
        std::memcpy(&mesh.vertProperties[9 * i], buf.data() + 84 + 50 * i + 12, 36);  // skip the normal
        for (uint32_t k = 0; k < 3; ++k) mesh.triVerts[3 * i + k] = static_cast<uint32_t>(3 * i + k);
    }
    return true;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4) return 1;
    const int rounds = std::atoi(argv[3]);
    const auto t0 = std::chrono::steady_clock::now();
    manifold::Manifold solid[2];
    for (int i = 0; i < 2; ++i) {
        manifold::MeshGL mesh;
        if (!read_binary_stl(argv[1 + i], mesh)) {
            std::fprintf(stderr, "manifold-boolean: %s: not a binary STL\n", argv[1 + i]);
            return 2;
        }
        mesh.Merge();  // weld equal corners: the indexed mesh Manifold requires
        solid[i] = manifold::Manifold(mesh);
        if (solid[i].Status() != manifold::Manifold::Error::NoError) {
            std::fprintf(stderr, "manifold-boolean: %s: status %d\n", argv[1 + i], static_cast<int>(solid[i].Status()));
            return 3;
        }
    }
    const double build = peers::seconds_since(t0);
    double volume = 0;
    const double call = peers::median_seconds(rounds, [&] { return (solid[0] ^ solid[1]).Volume(); }, &volume);
    std::printf("manifold-boolean %.17g %.6f %.6f\n", volume, build, call);
    return 0;
}

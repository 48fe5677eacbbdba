#include "topology/welded.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <stdexcept>
#include <string>
#include <utility>

#include "core/classes.hpp"

namespace polyvol::topology {

void check_mesh_arrays(const MeshView& mesh) {
    if (mesh.positions.size() % 3 != 0)
        throw std::invalid_argument("positions: size " + std::to_string(mesh.positions.size()) +
                                    " is not a multiple of 3");
    if (mesh.vertex_count() > kNone)
        throw std::invalid_argument("positions: more than 2^32-1 vertices");
    if (mesh.face_count() >= (std::size_t{1} << 31))  // the edge table packs a face id and a bit in 32 bits
        throw std::invalid_argument("more than 2^31-1 faces");
    if (mesh.all_triangles()) {
        if (mesh.indices.size() % 3 != 0)
            throw std::invalid_argument("indices: size " + std::to_string(mesh.indices.size()) +
                                        " is not a multiple of 3 and face_offsets is empty");
    } else {
        if (mesh.face_offsets[0] != 0)
            throw std::invalid_argument("face_offsets[0] is not 0");
        for (std::size_t f = 1; f < mesh.face_offsets.size(); ++f)
            if (mesh.face_offsets[f] < mesh.face_offsets[f - 1])
                throw std::invalid_argument("face_offsets decreases at face " + std::to_string(f - 1));
        if (mesh.face_offsets.back() > mesh.indices.size())
            throw std::invalid_argument("face_offsets ends past the end of indices");
    }
    const std::size_t n = mesh.vertex_count();
    for (std::size_t i = 0; i < mesh.indices.size(); ++i)
        if (mesh.indices[i] >= n)
            throw std::invalid_argument("indices[" + std::to_string(i) + "] = " +
                                        std::to_string(mesh.indices[i]) + " is not < vertex count " +
                                        std::to_string(n));
}

namespace {

// A soup (as an STL file lists its facets; polyvol's reader welds them):
// all triangles, and corner i is vertex i.
bool corners_are_vertices(const MeshView& mesh) {
    if (!mesh.all_triangles() || mesh.indices.size() != mesh.vertex_count()) return false;
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, mesh.indices.size(), std::size_t{1} << 16), true,
        [&](const tbb::blocked_range<std::size_t>& r, bool ok) {
            for (std::size_t i = r.begin(); ok && i < r.end(); ++i) ok = mesh.indices[i] == i;
            return ok;
        },
        [](bool a, bool b) { return a && b; });
}

}  // namespace

WeldedMesh weld_polygons(const MeshView& mesh) {
    WeldedMesh w;
    w.mesh = mesh;
    const std::size_t n = mesh.vertex_count();
    // canonical[v]: smallest original index with v's position.
    std::vector<uint32_t> canonical = weld_vertices(mesh.positions);
    if (corners_are_vertices(mesh)) {
        // Every vertex is used, in index order, so a class is first used at
        // its first vertex: the dense ids are the classes numbered in the
        // order of their firsts (in parallel; the loop below is serial).
        core::number_classes(canonical, mesh.positions, w.id, w.xyz);
        w.welded = w.referenced();
        w.polygons = mesh.face_count();
        return w;
    }
    for (std::size_t v = 0; v < n; ++v) w.welded += canonical[v] == v;

    // Dense ids for canonical vertices, in order of first use.
    std::vector<uint32_t> dense(n, kNone);
    uint32_t next = 0;
    w.for_each_polygon([&](uint32_t, std::span<const uint32_t> corners) {
        ++w.polygons;
        for (uint32_t v : corners) {
            uint32_t& d = dense[canonical[v]];
            if (d == kNone) d = next++;
        }
    });
    w.xyz.resize(3 * std::size_t{next});
    w.id = std::move(canonical);  // rewritten in place: canonical[v] <= v
    for (std::size_t v = 0; v < n; ++v) {
        const uint32_t c = w.id[v];
        w.id[v] = dense[c];
        if (c == v && dense[c] != kNone)
            for (int k = 0; k < 3; ++k) w.xyz[3 * std::size_t{dense[c]} + k] = mesh.positions[3 * v + k];
    }
    return w;
}

}  // namespace polyvol::topology

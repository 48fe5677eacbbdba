// simplicial/orient_mesh.cpp — orient_mesh: a mesh's faces wound
// consistently and outward, by orient_chain on its fan triangles.
//
// The fan triangles of a face share its diagonals, each used by exactly two
// of them in opposite directions, so the walk gives them one flip; a face is
// reversed when its fan triangles were, as (v0, vk, ..., v1) (the same fan
// diagonals, so the same pieces). If a face's fan triangles end up with
// different flips (a diagonal that is also another face's edge), nothing
// changes and the mesh is reported not orientable.
#include "polyvol/simplicial.hpp"

#include <algorithm>

#include "core/fan_triangles.hpp"

namespace polyvol {

OrientResult orient_mesh(Mesh& mesh) {
    const MeshView view = mesh.view();
    Chain chain;
    chain.dimension = 3;
    chain.coordinates = mesh.positions;
    core::append_fan_triangles(view, chain.simplices);
    std::vector<std::size_t> first_triangle(view.face_count() + 1, 0);  // each face's first fan triangle
    for (std::size_t f = 0; f < view.face_count(); ++f)
        first_triangle[f + 1] = first_triangle[f] + (view.face_size(f) >= 3 ? view.face_size(f) - 2 : 0);
    const std::vector<uint32_t> before = chain.simplices;
    OrientResult r = orient_chain(chain);
    if (!r.orientable) return r;
    // orient_chain flips a triangle by exchanging its first two vertices
    auto flipped = [&](std::size_t t) { return chain.simplices[3 * t] != before[3 * t]; };
    std::vector<std::size_t> reverse;
    for (std::size_t f = 0; f < view.face_count(); ++f) {
        const std::size_t t0 = first_triangle[f], t1 = first_triangle[f + 1];
        if (t0 == t1 || !flipped(t0)) {
            for (std::size_t t = t0; t < t1; ++t)
                if (flipped(t)) return OrientResult{false, 0, r.components, r.undecided};
            continue;
        }
        for (std::size_t t = t0; t < t1; ++t)
            if (!flipped(t)) return OrientResult{false, 0, r.components, r.undecided};
        reverse.push_back(f);
    }
    const bool triangles = mesh.face_offsets.empty();
    for (const std::size_t f : reverse) {
        const std::size_t begin = triangles ? 3 * f : mesh.face_offsets[f];
        const std::size_t end = triangles ? begin + 3 : mesh.face_offsets[f + 1];
        std::reverse(mesh.indices.begin() + static_cast<std::ptrdiff_t>(begin) + 1,
                     mesh.indices.begin() + static_cast<std::ptrdiff_t>(end));
    }
    r.flipped = reverse.size();
    return r;
}

}  // namespace polyvol

// Private to the library: a mesh's faces as fan triangles.
#pragma once

#include <cstdint>
#include <vector>

#include "polyvol/mesh.hpp"

namespace polyvol::core {

// Appends the fan triangles (v0, vi, vi+1) of every face to out, 3 indices each.
inline void append_fan_triangles(const MeshView& mesh, std::vector<uint32_t>& out) {
    out.reserve(out.size() + 3 * mesh.triangle_count());
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
        const auto face = mesh.face(f);
        for (std::size_t i = 1; i + 1 < face.size(); ++i) out.insert(out.end(), {face[0], face[i], face[i + 1]});
    }
}

}  // namespace polyvol::core

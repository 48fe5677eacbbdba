#include "polyvol/mesh.hpp"

#include <algorithm>
#include <limits>

namespace polyvol {

std::size_t MeshView::triangle_count() const {
    if (face_offsets.empty()) return indices.size() / 3;
    std::size_t n = 0;
    for (std::size_t f = 0; f + 1 < face_offsets.size(); ++f) {
        const std::size_t k = face_offsets[f + 1] - face_offsets[f];
        if (k >= 3) n += k - 2;
    }
    return n;
}

void Mesh::add_face(std::span<const uint32_t> face) {
    if (face_offsets.empty() && face.size() != 3) {
        // Leave the all-triangle fast path: build the offsets of what is there.
        const std::size_t n = indices.size() / 3;
        face_offsets.reserve(n + 2);
        for (std::size_t f = 0; f <= n; ++f) face_offsets.push_back(static_cast<uint32_t>(3 * f));
    }
    indices.insert(indices.end(), face.begin(), face.end());
    if (!face_offsets.empty()) face_offsets.push_back(static_cast<uint32_t>(indices.size()));
}

void Mesh::add_triangle(uint32_t a, uint32_t b, uint32_t c) {
    indices.push_back(a);
    indices.push_back(b);
    indices.push_back(c);
    if (!face_offsets.empty()) face_offsets.push_back(static_cast<uint32_t>(indices.size()));
}

void Mesh::append(const Mesh& other) {
    const auto shift = static_cast<uint32_t>(vertex_count());
    positions.insert(positions.end(), other.positions.begin(), other.positions.end());
    const MeshView v = other.view();
    std::vector<uint32_t> face;
    for (std::size_t f = 0; f < v.face_count(); ++f) {
        face.clear();
        for (uint32_t i : v.face(f)) face.push_back(i + shift);
        add_face(face);
    }
}

Mesh to_mesh(const MeshView& view) {
    return Mesh{std::vector<double>(view.positions.begin(), view.positions.end()),
                std::vector<uint32_t>(view.face_offsets.begin(), view.face_offsets.end()),
                std::vector<uint32_t>(view.indices.begin(), view.indices.end())};
}

std::array<double, 6> face_bounds(const MeshView& view) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    std::array<double, 6> b{inf, inf, inf, -inf, -inf, -inf};
    for (const uint32_t v : view.indices) {
        const double* p = view.positions.data() + 3 * std::size_t{v};
        for (int k = 0; k < 3; ++k) {
            b[k] = std::min(b[k], p[k]);
            b[3 + k] = std::max(b[3 + k], p[k]);
        }
    }
    if (view.indices.empty()) b = {nan, nan, nan, nan, nan, nan};
    return b;
}

}  // namespace polyvol

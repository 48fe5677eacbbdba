// The cone rule as users write it in doubles, for tests that need a cheap
// reference where exactness is not the point, or a foil where it is.
#pragma once

#include <cstddef>

#include "polyvol/mesh.hpp"

namespace polyvol::test {

// Σ a·(b×c) / 6 over the fan triangles (a, b, c) of every face, summed in
// order with no error control (far from the origin it loses most bits).
inline double naive_volume(const MeshView& m) {
    double v = 0;
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const auto face = m.face(f);
        for (std::size_t i = 1; i + 1 < face.size(); ++i) {
            const double* a = &m.positions[3 * face[0]];
            const double* b = &m.positions[3 * face[i]];
            const double* c = &m.positions[3 * face[i + 1]];
            v += a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                 a[2] * (b[0] * c[1] - b[1] * c[0]);
        }
    }
    return v / 6;
}

}  // namespace polyvol::test

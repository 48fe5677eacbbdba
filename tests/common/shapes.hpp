// Small closed meshes shared by the test programs, with their exact figures.
#pragma once

#include "polyvol/mesh.hpp"

namespace polyvol::test {

// The corner tetrahedron (0, e1, e2, e3), outward: volume 1/6, first moments
// 1/24, second moments 1/60 on the diagonal and 1/120 off it.
inline Mesh unit_tetrahedron() {
    Mesh m;
    m.add_vertex(0, 0, 0);
    m.add_vertex(1, 0, 0);
    m.add_vertex(0, 1, 0);
    m.add_vertex(0, 0, 1);
    m.add_triangle(0, 2, 1);
    m.add_triangle(0, 1, 3);
    m.add_triangle(0, 3, 2);
    m.add_triangle(1, 2, 3);
    return m;
}

}  // namespace polyvol::test

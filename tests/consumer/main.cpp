// Measures a unit tetrahedron through the installed library; exit 0 iff the
// volume is exactly 1/6 rounded once.
#include <polyvol/measure.hpp>

int main() {
    polyvol::Mesh m;
    m.add_vertex(0, 0, 0);
    m.add_vertex(1, 0, 0);
    m.add_vertex(0, 1, 0);
    m.add_vertex(0, 0, 1);
    m.add_triangle(0, 2, 1);
    m.add_triangle(0, 1, 3);
    m.add_triangle(0, 3, 2);
    m.add_triangle(1, 2, 3);
    return polyvol::signed_volume(m.view()) == 1.0 / 6.0 ? 0 : 1;
}

// Peer harness: CGAL 5.5 (Debian libcgal-dev). Reads the file as
// Polygon_mesh_processing does for users (soup -> orient -> mesh), then
// PMP::volume with the Epick kernel (double). Prints:
//   cgal VOLUME LOAD_SECONDS VOLUME_SECONDS(median of 5)
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <cstdio>

#include "timing.hpp"

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv) {
    if (argc != 2) return 1;
    const auto t0 = std::chrono::steady_clock::now();
    Mesh mesh;
    if (!PMP::IO::read_polygon_mesh(argv[1], mesh)) {
        std::fprintf(stderr, "cgal: cannot read %s\n", argv[1]);
        return 2;
    }
    double v = PMP::volume(mesh);
    const double load = peers::seconds_since(t0);
    const double vol_s = peers::median_seconds(5, [&] { return PMP::volume(mesh); }, &v);
    std::printf("cgal %.17g %.6f %.6f %zu\n", v, load, vol_s, static_cast<std::size_t>(mesh.number_of_faces()));
    return 0;
}

// Peer harness for the boolean benchmark: CGAL 5.5's exact corefinement
// (Epeck: exact predicates and constructions, the only CGAL kernel whose
// boolean volume is exact). Reads both files as PMP does for users, then
// times ROUNDS calls of corefine_and_compute_intersection + PMP::volume on
// fresh copies (corefinement modifies its inputs; the copies are not timed).
// Prints: cgal-boolean VOLUME LOAD_SECONDS CALL_SECONDS(median)
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/IO/polygon_mesh_io.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <cstdio>
#include <cstdlib>

#include "timing.hpp"

using K = CGAL::Exact_predicates_exact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

int main(int argc, char** argv) {
    if (argc != 4) return 1;
    const int rounds = std::atoi(argv[3]);
    const auto t0 = std::chrono::steady_clock::now();
    Mesh a, b;
    if (!PMP::IO::read_polygon_mesh(argv[1], a) || !PMP::IO::read_polygon_mesh(argv[2], b)) {
        std::fprintf(stderr, "cgal-boolean: cannot read the inputs\n");
        return 2;
    }
    const double load = peers::seconds_since(t0);
    std::vector<double> calls;
    double volume = 0;
    for (int r = 0; r < rounds; ++r) {
        Mesh p = a, q = b, out;
        const auto t = std::chrono::steady_clock::now();
        if (!PMP::corefine_and_compute_intersection(p, q, out)) return 3;
        volume = CGAL::to_double(CGAL::exact(PMP::volume(out)));
        calls.push_back(peers::seconds_since(t));
    }
    std::sort(calls.begin(), calls.end());
    std::printf("cgal-boolean %.17g %.6f %.6f\n", volume, load, calls[calls.size() / 2]);
    return 0;
}

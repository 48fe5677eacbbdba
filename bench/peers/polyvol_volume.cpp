// polyvol through the same harness as the peers (bench/compare.sh): read the
// file into memory (read_mesh_file), one correctly rounded signed_volume,
// then the median of 5 more. Prints, like peer_cgal and peer_vtk:
//   polyvol VOLUME LOAD_SECONDS VOLUME_SECONDS(median of 5) FACES
// LOAD_SECONDS covers reading and the first volume call, as the peers' do.
#include <cstdio>

#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "timing.hpp"

int main(int argc, char** argv) {
    if (argc != 2) return 1;
    const auto t0 = std::chrono::steady_clock::now();
    polyvol::LoadedMesh loaded;
    try {
        loaded = polyvol::read_mesh_file(argv[1]);
    } catch (const polyvol::ReadError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    const polyvol::MeshView mesh = loaded.mesh.view();
    double v = polyvol::signed_volume(mesh);
    const double load = peers::seconds_since(t0);
    const double vol_s = peers::median_seconds(5, [&] { return polyvol::signed_volume(mesh); }, &v);
    std::printf("polyvol %.17g %.6f %.6f %zu\n", v, load, vol_s, mesh.face_count());
    return 0;
}

// Peer harness: Open3D 0.16 (Debian libopen3d-dev). ReadTriangleMesh, weld
// duplicated vertices (STL is a soup), then TriangleMesh::GetVolume (which
// checks watertightness first). Prints:
//   open3d VOLUME LOAD_SECONDS VOLUME_SECONDS(median of 3)
#include <open3d/geometry/TriangleMesh.h>
#include <open3d/io/TriangleMeshIO.h>

#include <cstdio>

#include "timing.hpp"

int main(int argc, char** argv) {
    if (argc != 2) return 1;
    const auto t0 = std::chrono::steady_clock::now();
    open3d::geometry::TriangleMesh mesh;
    if (!open3d::io::ReadTriangleMesh(argv[1], mesh)) return 2;
    mesh.RemoveDuplicatedVertices();
    double v = mesh.GetVolume();
    const double load = peers::seconds_since(t0);
    const double vol_s = peers::median_seconds(3, [&] { return mesh.GetVolume(); }, &v);
    std::printf("open3d %.17g %.6f %.6f %zu\n", v, load, vol_s, mesh.triangles_.size());
    return 0;
}

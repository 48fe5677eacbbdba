// polyvol through the same harness as the peers (bench/compare.sh): read the
// file into memory (read_mesh_file), one correctly rounded signed_volume,
// then the median of 5 more. Prints, like peer_cgal and peer_vtk:
//   polyvol VOLUME LOAD_SECONDS VOLUME_SECONDS(median of 5) FACES READ_SECONDS NAIVE_SECONDS
//           PACKED_LOAD_SECONDS PACKED_SECONDS
// LOAD_SECONDS covers reading and the first volume call, as the peers' do;
// the five timed calls follow it. An STL is read as an indexed mesh (the
// reader welds the facets' corners, as CGAL's and VTK's readers merge
// points), so every format's call is on the mesh the peers hold. (Until the
// eleventh session the STL reader kept three vertices per triangle, and this
// harness also timed welded(mesh) and its load.)
//
// PACKED_*: binary STL only (else -1): the file read as its own float32
// triangles (read_binary_stl_triangles, 36 bytes a triangle) plus one
// soup_volume, then soup_volume's median of 5. The same correctly rounded
// volume (checked bit for bit), from the representation an STL user holds
// (numpy-stl's (n, 3, 3) float32 array, VTK's float32 points).
//
// READ_SECONDS and NAIVE_SECONDS are two plain loops over the same arrays,
// on all cores (oneTBB, as polyvol), for scale: READ reads each face's three
// indices and nine coordinates and adds them (no determinant), NAIVE sums
// det(a, b, c) in plain double (no guarantee at all). They are what simple
// scalar code costs, not lower bounds: a vectorised gather reads faster.
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>
#include <tbb/partitioner.h>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <vector>

#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/soup.hpp"
#include "timing.hpp"

namespace {

// Σ over triangles of f(a, b, c), in parallel chunks of 8192 triangles;
// eight partial sums per chunk, so that the loop is bound by its loads and
// f, not by the latency of one chain of additions.
template <class F>
double sum_triangles(const polyvol::MeshView& mesh, F&& f) {
    const double* pos = mesh.positions.data();
    const uint32_t* idx = mesh.indices.data();
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, mesh.face_count(), 8192), 0.0,
        [&](const tbb::blocked_range<std::size_t>& r, double s) {
            double part[8] = {};
            for (std::size_t t = r.begin(); t < r.end(); ++t)
                part[t % 8] += f(pos + 3 * std::size_t{idx[3 * t]}, pos + 3 * std::size_t{idx[3 * t + 1]},
                                 pos + 3 * std::size_t{idx[3 * t + 2]});
            return s + (((part[0] + part[1]) + (part[2] + part[3])) + ((part[4] + part[5]) + (part[6] + part[7])));
        },
        std::plus<double>(), tbb::simple_partitioner());
}

}  // namespace

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
    double read_value = 0, naive_value = 0;
    double read_s = -1, naive_s = -1;
    if (mesh.all_triangles()) {
        read_s = peers::median_seconds(
            5,
            [&] {
                return sum_triangles(mesh, [](const double* a, const double* b, const double* c) {
                    return ((a[0] + a[1]) + (a[2] + b[0])) + ((b[1] + b[2]) + (c[0] + c[1])) + c[2];
                });
            },
            &read_value);
        naive_s = peers::median_seconds(
            5,
            [&] {
                return sum_triangles(mesh, [](const double* a, const double* b, const double* c) {
                           return a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                                  a[2] * (b[0] * c[1] - b[1] * c[0]);
                       }) /
                       6;
            },
            &naive_value);
    }
    double packed_load = -1, packed_s = -1;
    if (loaded.format == polyvol::Format::stl && loaded.encoding == "binary_le" && !loaded.gzip) {
        const auto t1 = std::chrono::steady_clock::now();
        const std::vector<float> tri = polyvol::read_binary_stl_triangles(argv[1]);
        double pv = polyvol::soup_volume(polyvol::packed_triangles(tri));
        packed_load = peers::seconds_since(t1);
        packed_s = peers::median_seconds(5, [&] { return polyvol::soup_volume(polyvol::packed_triangles(tri)); }, &pv);
        if (std::bit_cast<uint64_t>(pv) != std::bit_cast<uint64_t>(v)) {
            std::fprintf(stderr, "polyvol: the packed float32 triangles gave another volume\n");
            return 3;
        }
    }
    std::printf("polyvol %.17g %.6f %.6f %zu %.6f %.6f %.6f %.6f\n", v, load, vol_s, mesh.face_count(), read_s, naive_s,
                packed_load, packed_s);
    return 0;
}

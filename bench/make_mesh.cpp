// Writes a generated closed mesh (a UV sphere of about N triangles, centred at
// (offset, offset, offset), or with `torus` a torus of about N triangles about
// the z axis, moved by that offset) for the benchmarks:
//   make_mesh N OFFSET OUT.{stl,ascii.stl,ply,obj,off} [sphere|torus]
// .stl is binary STL (float32), .ascii.stl ASCII STL, .ply binary little-endian PLY.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "common/generate.hpp"

namespace {

bool ends_with(const std::string& s, const char* suffix) {
    const std::size_t n = std::strlen(suffix);
    return s.size() >= n && s.compare(s.size() - n, n, suffix) == 0;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 4 && argc != 5) {
        std::fprintf(stderr, "usage: make_mesh TRIANGLES OFFSET OUT [sphere|torus]\n");
        return 1;
    }
    const auto n = std::strtoull(argv[1], nullptr, 10);
    const double offset = std::strtod(argv[2], nullptr);
    const std::string out = argv[3];
    const bool torus = argc == 5 && std::strcmp(argv[4], "torus") == 0;
    polyvol::Mesh m = torus ? polyvol::generate::torus_with_triangles(n) : polyvol::generate::sphere_with_triangles(n, offset);
    if (torus)
        for (double& x : m.positions) x += offset;
    const auto& p = m.positions;
    const auto& idx = m.indices;
    const std::size_t tris = idx.size() / 3;
    FILE* f = std::fopen(out.c_str(), "wb");
    if (!f) return 2;
    if (ends_with(out, ".ascii.stl")) {
        std::fprintf(f, "solid sphere\n");
        for (std::size_t t = 0; t < tris; ++t) {
            std::fprintf(f, "facet normal 0 0 0\nouter loop\n");
            for (int k = 0; k < 3; ++k) {
                const double* v = &p[3 * idx[3 * t + k]];
                std::fprintf(f, "vertex %.9g %.9g %.9g\n", v[0], v[1], v[2]);
            }
            std::fprintf(f, "endloop\nendfacet\n");
        }
        std::fprintf(f, "endsolid sphere\n");
    } else if (ends_with(out, ".stl")) {
        char header[80] = "polyvol benchmark sphere";
        std::fwrite(header, 1, 80, f);
        const auto count = static_cast<uint32_t>(tris);
        std::fwrite(&count, 4, 1, f);
        std::vector<unsigned char> rec(50 * 4096);
        for (std::size_t t0 = 0; t0 < tris; t0 += 4096) {
            const std::size_t k = std::min<std::size_t>(4096, tris - t0);
            std::memset(rec.data(), 0, rec.size());
            for (std::size_t t = 0; t < k; ++t)
                for (int c = 0; c < 3; ++c)
                    for (int d = 0; d < 3; ++d) {
                        const auto v = static_cast<float>(p[3 * idx[3 * (t0 + t) + c] + d]);
                        std::memcpy(&rec[50 * t + 12 + 12 * c + 4 * d], &v, 4);
                    }
            std::fwrite(rec.data(), 50, k, f);
        }
    } else if (ends_with(out, ".ply")) {
        std::fprintf(f, "ply\nformat binary_little_endian 1.0\nelement vertex %zu\nproperty double x\nproperty double y\n"
                        "property double z\nelement face %zu\nproperty list uchar uint vertex_indices\nend_header\n",
                     m.vertex_count(), tris);
        std::fwrite(p.data(), sizeof(double), p.size(), f);
        for (std::size_t t = 0; t < tris; ++t) {
            const unsigned char three = 3;
            std::fwrite(&three, 1, 1, f);
            std::fwrite(&idx[3 * t], 4, 3, f);
        }
    } else if (ends_with(out, ".obj")) {
        for (std::size_t v = 0; v < m.vertex_count(); ++v) std::fprintf(f, "v %.17g %.17g %.17g\n", p[3 * v], p[3 * v + 1], p[3 * v + 2]);
        for (std::size_t t = 0; t < tris; ++t) std::fprintf(f, "f %u %u %u\n", idx[3 * t] + 1, idx[3 * t + 1] + 1, idx[3 * t + 2] + 1);
    } else if (ends_with(out, ".off")) {
        std::fprintf(f, "OFF\n%zu %zu 0\n", m.vertex_count(), tris);
        for (std::size_t v = 0; v < m.vertex_count(); ++v) std::fprintf(f, "%.17g %.17g %.17g\n", p[3 * v], p[3 * v + 1], p[3 * v + 2]);
        for (std::size_t t = 0; t < tris; ++t) std::fprintf(f, "3 %u %u %u\n", idx[3 * t], idx[3 * t + 1], idx[3 * t + 2]);
    } else {
        std::fprintf(stderr, "unknown output extension: %s\n", out.c_str());
        return 1;
    }
    std::fclose(f);
    return 0;
}

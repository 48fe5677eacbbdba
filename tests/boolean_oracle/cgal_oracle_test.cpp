// boolean_volumes against an exact oracle: CGAL's corefinement with exact
// rational constructions (Epeck). CGAL builds A ∩ B, A ∪ B, A − B and B − A
// as meshes over the same double coordinates, measures them in exact
// rationals (Polygon_mesh_processing::volume), and each value, rounded once
// to the nearest double, must equal polyvol's bit for bit. The pairs are
// curved surfaces in general position (spheres, a torus, far from the
// origin), identical and rotated copies, and corpus meshes against a
// translated copy of themselves.
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>
#include <gmp.h>
#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "exact/rational.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/io.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using CgalMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Vec3 = std::array<double, 3>;

// ---- Meshes -----------------------------------------------------------------

// The unit icosphere: the icosahedron's faces split `levels` times into four,
// every new vertex the normalized midpoint (in double) of its edge. Indexed
// (midpoints shared), outward; levels = 3 gives 642 vertices, 1280 triangles.
Mesh icosphere(int levels) {
    const double t = (1 + std::sqrt(5.0)) / 2;
    const double s = 1 / std::sqrt(1 + t * t);
    Mesh m;
    const double corners[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                   {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (const auto& c : corners) m.add_vertex(c[0] * s, c[1] * s, c[2] * s);
    std::vector<std::array<uint32_t, 3>> faces = {
        {0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
        {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
        {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
    for (int level = 0; level < levels; ++level) {
        std::map<std::pair<uint32_t, uint32_t>, uint32_t> midpoints;
        auto midpoint = [&](uint32_t a, uint32_t b) {
            const auto key = std::minmax(a, b);
            if (auto it = midpoints.find(key); it != midpoints.end()) return it->second;
            double p[3];
            for (int k = 0; k < 3; ++k) p[k] = m.positions[3 * a + k] + m.positions[3 * b + k];
            const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            const uint32_t v = m.add_vertex(p[0] / n, p[1] / n, p[2] / n);
            midpoints.emplace(key, v);
            return v;
        };
        std::vector<std::array<uint32_t, 3>> finer;
        for (const auto& f : faces) {
            const uint32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]), ca = midpoint(f[2], f[0]);
            finer.push_back({f[0], ab, ca});
            finer.push_back({f[1], bc, ab});
            finer.push_back({f[2], ca, bc});
            finer.push_back({ab, bc, ca});
        }
        faces = std::move(finer);
    }
    for (const auto& f : faces) m.add_triangle(f[0], f[1], f[2]);
    return m;
}

// The torus about the z axis with major radius R and minor radius r, on a
// (nu x nv) grid of its angles, each grid quad split into two triangles;
// indexed, outward ((d/du) x (d/dv) points away from the tube's core).
Mesh torus(double R, double r, uint32_t nu, uint32_t nv) {
    Mesh m;
    const double pi = std::acos(-1.0);
    for (uint32_t i = 0; i < nu; ++i) {
        const double u = 2 * pi * i / nu;
        for (uint32_t j = 0; j < nv; ++j) {
            const double v = 2 * pi * j / nv;
            m.add_vertex((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
        }
    }
    auto id = [&](uint32_t i, uint32_t j) { return (i % nu) * nv + j % nv; };
    for (uint32_t i = 0; i < nu; ++i)
        for (uint32_t j = 0; j < nv; ++j) {
            m.add_triangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
            m.add_triangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
        }
    return m;
}

// m with every vertex p replaced by rot(axis, angle) p + shift, each
// coordinate computed in double (so rounded): the doubles both tools see.
Mesh transformed(const Mesh& m, Vec3 axis, double angle, Vec3 shift) {
    const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const double x = axis[0] / n, y = axis[1] / n, z = axis[2] / n;
    const double c = std::cos(angle), s = std::sin(angle), d = 1 - c;
    const double rot[3][3] = {{c + x * x * d, x * y * d - z * s, x * z * d + y * s},
                              {y * x * d + z * s, c + y * y * d, y * z * d - x * s},
                              {z * x * d - y * s, z * y * d + x * s, c + z * z * d}};
    Mesh out = m;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        const double* p = &m.positions[3 * v];
        for (int k = 0; k < 3; ++k)
            out.positions[3 * v + k] = rot[k][0] * p[0] + rot[k][1] * p[1] + rot[k][2] * p[2] + shift[k];
    }
    return out;
}

// m translated by shift (each coordinate p + shift rounded to double).
Mesh translated(const Mesh& m, Vec3 shift) {
    Mesh out = m;
    for (std::size_t i = 0; i < out.positions.size(); ++i) out.positions[i] += shift[i % 3];
    return out;
}

// CGAL's copy of m: the same double coordinates (exact in Epeck), each face
// fan-triangulated from its first vertex as polyvol reads it. Empty, with
// the reason in why, when Surface_mesh refuses a face (a non-manifold vertex
// or edge).
std::optional<CgalMesh> to_cgal(const Mesh& m, std::string& why) {
    CgalMesh out;
    std::vector<CgalMesh::Vertex_index> vertex;
    vertex.reserve(m.vertex_count());
    for (std::size_t v = 0; v < m.vertex_count(); ++v)
        vertex.push_back(
            out.add_vertex(Kernel::Point_3(m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2])));
    const MeshView view = m.view();
    for (std::size_t f = 0; f < view.face_count(); ++f) {
        const auto face = view.face(f);
        for (std::size_t i = 1; i + 1 < face.size(); ++i)
            if (out.add_face(vertex[face[0]], vertex[face[i]], vertex[face[i + 1]]) == CgalMesh::null_face()) {
                why = "Surface_mesh::add_face refused face " + std::to_string(f) + " (non-manifold)";
                return std::nullopt;
            }
    }
    return out;
}

// ---- Exact values -----------------------------------------------------------

// GMP's mpq_t behind a value of Epeck's exact field type: mpq_class when
// CGAL is configured with gmpxx (CGAL_USE_GMPXX, Debian's CGAL 5.5), else
// CGAL::Gmpq or boost::multiprecision's gmp_rational.
template <class Exact>
mpq_srcptr mpq_of(const Exact& q) {
    if constexpr (requires { q.get_mpq_t(); })
        return q.get_mpq_t();
    else if constexpr (requires { q.mpq(); })
        return q.mpq();
    else
        return q.backend().data();
}

// The exact volume of a closed CGAL mesh as a GMP rational (the lazy value
// of PMP::volume forced to its exact rational).
mpq_class exact_volume(const CgalMesh& m) {
    const Kernel::FT v = PMP::volume(m);
    return mpq_class(mpq_of(CGAL::exact(v)));
}

// The six volumes of A, B, A ∩ B, A ∪ B, A − B, B − A, exactly.
struct ExactVolumes {
    mpq_class a, b, intersection, union_volume, a_minus_b, b_minus_a;
};

// Corefines copies of A and B once per operation (corefinement modifies its
// inputs) and measures each result exactly. Fails the test (and returns
// nothing) when CGAL cannot build a result.
std::optional<ExactVolumes> cgal_volumes(const CgalMesh& a, const CgalMesh& b) {
    using Op = bool (*)(CgalMesh&, CgalMesh&, CgalMesh&);
    auto run = [](Op op, const CgalMesh& first, const CgalMesh& second, const char* name) -> std::optional<mpq_class> {
        CgalMesh p = first, q = second, out;
        if (!op(p, q, out)) {
            ADD_FAILURE() << "CGAL could not build " << name << " (corefine_and_compute_* returned false)";
            return std::nullopt;
        }
        return exact_volume(out);
    };
    const Op intersection = [](CgalMesh& p, CgalMesh& q, CgalMesh& out) {
        return PMP::corefine_and_compute_intersection(p, q, out);
    };
    const Op union_op = [](CgalMesh& p, CgalMesh& q, CgalMesh& out) {
        return PMP::corefine_and_compute_union(p, q, out);
    };
    const Op difference = [](CgalMesh& p, CgalMesh& q, CgalMesh& out) {
        return PMP::corefine_and_compute_difference(p, q, out);
    };
    const auto i = run(intersection, a, b, "A ∩ B");
    const auto u = run(union_op, a, b, "A ∪ B");
    const auto ab = run(difference, a, b, "A − B");
    const auto ba = run(difference, b, a, "B − A");
    if (!i || !u || !ab || !ba) return std::nullopt;
    return ExactVolumes{exact_volume(a), exact_volume(b), *i, *u, *ab, *ba};
}

// %.17g of x.
std::string g17(double x) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return buf;
}

// Expects polyvol's value to be the exact value rounded once to the nearest
// double; on failure prints both (%.17g) and the rational when it is short.
void expect_rounded(const char* what, double polyvol_value, const mpq_class& exact) {
    const double oracle = exact::round_to_double(exact.get_mpq_t());
    const std::string q = exact.get_str();
    EXPECT_EQ(polyvol_value, oracle) << what << ": polyvol " << g17(polyvol_value) << ", CGAL rounded " << g17(oracle)
                                     << ", exact " << (q.size() <= 200 ? q : std::to_string(q.size()) + "-char rational");
}

// The whole comparison for one pair: polyvol's six volumes against CGAL's,
// and the oracle's own identity |A ∪ B| + |A ∩ B| = |A| + |B|.
void expect_matches_cgal(const Mesh& a, const Mesh& b) {
    using Clock = std::chrono::steady_clock;
    std::string why;
    const auto ca = to_cgal(a, why), cb = to_cgal(b, why);
    ASSERT_TRUE(ca && cb) << why;
    ASSERT_TRUE(CGAL::is_closed(*ca) && CGAL::is_closed(*cb));

    const auto t0 = Clock::now();
    const BooleanVolumes r = boolean_volumes(a.view(), b.view());
    const auto t1 = Clock::now();
    ASSERT_EQ(r.status, BooleanStatus::ok) << boolean_status_message(r.status);
    const auto oracle = cgal_volumes(*ca, *cb);
    const auto t2 = Clock::now();
    ASSERT_TRUE(oracle);
    const ExactVolumes& e = *oracle;

    EXPECT_EQ(e.union_volume + e.intersection, e.a + e.b) << "CGAL's volumes break |A ∪ B| + |A ∩ B| = |A| + |B|";
    EXPECT_EQ(e.a_minus_b + e.intersection, e.a) << "CGAL's volumes break |A − B| + |A ∩ B| = |A|";
    EXPECT_EQ(e.b_minus_a + e.intersection, e.b) << "CGAL's volumes break |B − A| + |A ∩ B| = |B|";

    expect_rounded("|A|", r.volume_a, e.a);
    expect_rounded("|B|", r.volume_b, e.b);
    expect_rounded("|A ∩ B|", r.intersection, e.intersection);
    expect_rounded("|A ∪ B|", r.union_volume, e.union_volume);
    expect_rounded("|A − B|", r.a_minus_b, e.a_minus_b);
    expect_rounded("|B − A|", r.b_minus_a, e.b_minus_a);

    const auto ms = [](auto d) { return std::chrono::duration<double, std::milli>(d).count(); };
    std::printf("    triangles %zu + %zu, crossing pairs %zu, polyvol %.1f ms, CGAL %.1f ms\n"
                "    |A| %s  |B| %s  |A ∩ B| %s\n    |A ∪ B| %s  |A − B| %s  |B − A| %s\n",
                r.triangles_a, r.triangles_b, r.crossing_pairs, ms(t1 - t0), ms(t2 - t1), g17(r.volume_a).c_str(),
                g17(r.volume_b).c_str(), g17(r.intersection).c_str(), g17(r.union_volume).c_str(),
                g17(r.a_minus_b).c_str(), g17(r.b_minus_a).c_str());
}

// ---- Pairs ------------------------------------------------------------------

// The unit icosphere of 1280 triangles, built once.
const Mesh& sphere() {
    static const Mesh s = icosphere(3);
    return s;
}

// A torus (R = 1, r = 0.35, 2304 triangles) tilted about a generic axis and
// shifted off the sphere's centre: general position against sphere().
const Mesh& tilted_torus() {
    static const Mesh t = transformed(torus(1, 0.35, 48, 24), {0.3, -0.7, 0.5}, 0.61, {0.13, -0.07, 0.05});
    return t;
}

TEST(BooleanCgalOracle, TwoSpheresGeneralPosition) {
    expect_matches_cgal(sphere(), translated(sphere(), {0.5, 0.3, 0.2}));
}

TEST(BooleanCgalOracle, SphereAndTorus) { expect_matches_cgal(sphere(), tilted_torus()); }

TEST(BooleanCgalOracle, TwoSpheresFarFromOrigin) {
    const Vec3 far = {1e6, -2e6, 3e6};
    expect_matches_cgal(translated(sphere(), far), translated(translated(sphere(), {0.5, 0.3, 0.2}), far));
}

TEST(BooleanCgalOracle, SphereAndTorusFarFromOrigin) {
    const Vec3 far = {1e6, -2e6, 3e6};
    expect_matches_cgal(translated(sphere(), far), translated(tilted_torus(), far));
}

TEST(BooleanCgalOracle, SphereAgainstItself) { expect_matches_cgal(sphere(), sphere()); }

TEST(BooleanCgalOracle, SphereAgainstRotatedCopy) {
    expect_matches_cgal(sphere(), transformed(sphere(), {0.42, 0.77, -0.31}, 0.37, {0, 0, 0}));
}

// solid_volume of one mesh holding several overlapping parts (three spheres
// meeting in a common region, and a torus through them) against CGAL's union
// of the parts, built one after another.
TEST(BooleanCgalOracle, OverlappingPartsOfOneFileAreTheirUnion) {
    const std::vector<Mesh> parts = {sphere(), translated(sphere(), {0.5, 0.3, 0.2}),
                                     translated(sphere(), {-0.2, 0.6, -0.35}), tilted_torus()};
    Mesh all;
    for (const Mesh& p : parts) all.append(p);
    std::string why;
    auto u = to_cgal(parts[0], why);
    ASSERT_TRUE(u) << why;
    mpq_class winding = exact_volume(*u);
    for (std::size_t i = 1; i < parts.size(); ++i) {
        auto next = to_cgal(parts[i], why);
        ASSERT_TRUE(next) << why;
        winding += exact_volume(*next);
        CgalMesh out;
        ASSERT_TRUE(PMP::corefine_and_compute_union(*u, *next, out));
        *u = out;
    }
    const SolidVolume r = solid_volume(all.view());
    ASSERT_EQ(r.status, BooleanStatus::ok) << boolean_status_message(r.status);
    EXPECT_EQ(r.shells, 4u);
    EXPECT_EQ(r.overlapping_shells, 4u);
    expect_rounded("|A ∪ B ∪ C ∪ D|", r.properties.volume, exact_volume(*u));
    expect_rounded("winding integral", r.winding_volume, winding);
    std::printf("    solid %s, winding %s, crossing pairs %zu\n", g17(r.properties.volume).c_str(),
                g17(r.winding_volume).c_str(), r.crossing_pairs);
}

// Corpus meshes (closed 2-cycles in the manifest, one edge-connected
// component, a few thousand triangles) against a copy translated by
// (0.31, 0.17, 0.23) times their bounding box's size.
class BooleanCgalOracleCorpus : public ::testing::TestWithParam<const char*> {};

TEST_P(BooleanCgalOracleCorpus, AgainstTranslatedCopy) {
    const std::filesystem::path file = std::filesystem::path(POLYVOL_CORPUS_DIR) / GetParam();
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    const Mesh a = read_mesh_file(file.string()).mesh;
    ASSERT_GT(a.vertex_count(), 0u);
    Vec3 lo = {a.positions[0], a.positions[1], a.positions[2]}, hi = lo;
    for (std::size_t i = 0; i < a.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], a.positions[i]);
        hi[i % 3] = std::max(hi[i % 3], a.positions[i]);
    }
    const Mesh b = translated(a, {0.31 * (hi[0] - lo[0]), 0.17 * (hi[1] - lo[1]), 0.23 * (hi[2] - lo[2])});

    // CGAL's corefinement needs closed, manifold, self-intersection-free input.
    std::string why;
    const auto ca = to_cgal(a, why), cb = to_cgal(b, why);
    if (!ca || !cb) GTEST_SKIP() << "CGAL refuses " << GetParam() << ": " << why;
    if (!CGAL::is_closed(*ca)) GTEST_SKIP() << "CGAL refuses " << GetParam() << ": not closed as a Surface_mesh";
    if (PMP::does_self_intersect(*ca) || PMP::does_self_intersect(*cb))
        GTEST_SKIP() << "CGAL refuses " << GetParam() << ": does_self_intersect";
    expect_matches_cgal(a, b);
}

INSTANTIATE_TEST_SUITE_P(Corpus, BooleanCgalOracleCorpus,
                         ::testing::Values("meshes/stl-models/gearwheel.ascii.stl",  // 2444 triangles
                                           "meshes/netgen-doc/hinge.stl",            // 1212 triangles
                                           "meshes/gmsh-doc/t13_data.stl.gz"),       // 1580 triangles
                         [](const ::testing::TestParamInfo<const char*>& param) {
                             std::string name = std::filesystem::path(param.param).filename().string();
                             std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
                             return name;
                         });

}  // namespace
}  // namespace polyvol

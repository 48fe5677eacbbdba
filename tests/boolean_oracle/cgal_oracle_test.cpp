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
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "boolean_oracle/cgal_support.hpp"
#include "common/real_pairs.hpp"
#include "exact/rational.hpp"
#include "polyvol/boolean.hpp"
#include "polyvol/io.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol {
namespace {

using namespace oracle;

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

// ---- Real pairs (issue #36) ------------------------------------------------
//
// Corpus parts against copies of themselves (common/real_pairs.hpp: an exact
// offset, an exact offset along x with coplanar faces everywhere, a generic
// rotation). Each pair is checked against CGAL bit for bit and against
// polyvol's own independent identities: the solid route
// (solid_boolean_volumes: three solids, no one-pass pieces) gives the same
// bits, swapping the operands swaps A − B and B − A, and moving both by an
// exact offset changes nothing.

using test::Move;

bool same_bits(double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; }

void expect_same_volumes(const BooleanVolumes& r, const BooleanVolumes& s, bool swapped, const char* what) {
    EXPECT_TRUE(same_bits(r.volume_a, swapped ? s.volume_b : s.volume_a)) << what;
    EXPECT_TRUE(same_bits(r.volume_b, swapped ? s.volume_a : s.volume_b)) << what;
    EXPECT_TRUE(same_bits(r.intersection, s.intersection)) << what;
    EXPECT_TRUE(same_bits(r.union_volume, s.union_volume)) << what;
    EXPECT_TRUE(same_bits(r.a_minus_b, swapped ? s.b_minus_a : s.a_minus_b)) << what;
    EXPECT_TRUE(same_bits(r.b_minus_a, swapped ? s.a_minus_b : s.b_minus_a)) << what;
}

using RealPair = std::tuple<const char*, Move>;
class BooleanRealPairs : public ::testing::TestWithParam<RealPair> {};

TEST_P(BooleanRealPairs, MatchCgalAndTheirIdentities) {
    const auto [path, move] = GetParam();
    const std::filesystem::path file = std::filesystem::path(POLYVOL_CORPUS_DIR) / path;
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    const Mesh part = read_mesh_file(file.string()).mesh;
    ASSERT_GT(part.vertex_count(), 0u);
    const auto [a, b] = test::real_pair(part, move);
    const int e = test::snap_exponent(part);
    const std::array<double, 3> size = test::size_of(part);
    if (move != Move::rotation) {
        const std::array<double, 3> f = move == Move::offset ? std::array<double, 3>{0.31, 0.17, 0.23}
                                                              : std::array<double, 3>{0.25, 0, 0};
        ASSERT_TRUE(test::moved_exactly(a, b, test::offset_on_grid(f, size, e))) << "the offset is not exact";
    }
    std::string why;
    const auto ca = to_cgal(a, why), cb = to_cgal(b, why);
    ASSERT_TRUE(ca && cb) << why;
    ASSERT_TRUE(CGAL::is_closed(*ca) && CGAL::is_closed(*cb));
    ASSERT_FALSE(PMP::does_self_intersect(*ca) || PMP::does_self_intersect(*cb)) << path << " crosses itself";
    expect_matches_cgal(a, b);

    const BooleanVolumes r = boolean_volumes(a.view(), b.view());
    ASSERT_EQ(r.status, BooleanStatus::ok);
    if (move != Move::rotation) {
        EXPECT_TRUE(same_bits(r.volume_a, r.volume_b)) << "B is A moved exactly";
    }
    expect_same_volumes(r, solid_boolean_volumes(a.view(), b.view()), false, "the solid route");
    expect_same_volumes(r, boolean_volumes(b.view(), a.view()), true, "B and A swapped");
    if (move != Move::rotation) {  // both moved by an exact offset: the same solids, moved
        const std::array<double, 3> far = test::offset_on_grid({8, -4, 2}, size, e);
        const Mesh fa = test::moved(a, far), fb = test::moved(b, far);
        ASSERT_TRUE(test::moved_exactly(a, fa, far) && test::moved_exactly(b, fb, far));
        expect_same_volumes(r, boolean_volumes(fa.view(), fb.view()), false, "both moved exactly");
    }
}

INSTANTIATE_TEST_SUITE_P(
    Corpus, BooleanRealPairs,
    ::testing::Combine(::testing::Values("meshes/netgen-doc/hinge.stl",              // 1212 triangles
                                         "meshes/prusa-slicer/printbed-v2-250.stl",  // 1408
                                         "meshes/gmsh-doc/t13_data.stl.gz",          // 1580
                                         "meshes/cura/FelixPro2_platform.obj",       // 1912
                                         "meshes/stl-models/gearwheel.ascii.stl",    // 2444
                                         "meshes/prusa-slicer/torus.stl"),           // 3072
                       ::testing::Values(Move::offset, Move::axis_offset, Move::rotation)),
    [](const ::testing::TestParamInfo<RealPair>& param) {
        std::string name = std::filesystem::path(std::get<0>(param.param)).filename().string();
        std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); }, '_');
        const Move m = std::get<1>(param.param);
        return name + (m == Move::offset ? "_offset" : m == Move::axis_offset ? "_axis_offset" : "_rotated");
    });

}  // namespace
}  // namespace polyvol

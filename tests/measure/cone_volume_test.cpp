// Tests of the double-double volume pass (measure/cone.cpp, volume_pass):
// filtered_volume with its range check on the referenced coordinates,
// filtered_volume_block, and signed_volume's fast path built on them. Every
// instruction-set level (cap_kernel_level) and thread count must give the
// same bits; coordinates outside the safe range on a used vertex must still
// give the exact answer (big integers), and unused vertices must not matter.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "common/kernel_levels.hpp"
#include "common/shapes.hpp"
#include "cone_fixtures.hpp"
#include "exact/rational.hpp"
#include "measure/cone.hpp"
#include "polyvol/measure.hpp"

using namespace polyvol;
using namespace polyvol::measure::cone;
using polyvol::fixtures::q;
using polyvol::fixtures::as_mpq;
using polyvol::fixtures::rnd;
namespace fx = polyvol::fixtures;

namespace {

bool same(double a, double b) {
    return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b) || (std::isnan(a) && std::isnan(b));
}

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

using polyvol::test::cap_kernel_level;
using polyvol::test::cpu_has_avx512;
using polyvol::test::LevelGuard;

// Meshes with every shape of work: partial blocks, several parallel tasks,
// polygon faces, the last vertex used early and late (the AVX2 gather leaves
// such blocks to the scalar one), far from and around the origin, and soups
// (fewer than two indices per vertex: with AVX-512 the range check then
// runs inside the pass).
std::vector<Mesh> meshes() {
    std::mt19937_64 rng(31);
    std::vector<Mesh> ms;
    ms.push_back(fx::unit_tetrahedron());
    ms.push_back(fx::box(-1, -2, -3, 0.5, 4, 7, /*quads=*/true));
    ms.push_back(fx::octahedron(3));
    ms.push_back(fx::random_sphere(rng, 3, 1.0, {0, 0, 0}));
    ms.push_back(fx::random_sphere(rng, 4, 1.0, {1e6, -2e6, 3e6}));
    ms.push_back(fx::random_sphere(rng, 6, 1.0, {1e6, 0, 0}));  // 32768 triangles: several tasks
    ms.push_back(fx::random_sphere(rng, 2, 1e-3, {1e8, 1e8, -1e8}));
    ms.push_back(fx::random_sphere(rng, 3, 1e50, {0, 3e49, 0}));
    // Faces in a random order and a count that is not a multiple of 32.
    Mesh shuffled = fx::random_sphere(rng, 5, 2.0, {-7, 1e3, 0});
    std::vector<std::size_t> order(shuffled.face_count());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    Mesh s2;
    s2.positions = shuffled.positions;
    for (std::size_t i = 0; i + 5 < order.size(); ++i) {
        const std::size_t f = order[i];
        s2.add_triangle(shuffled.indices[3 * f], shuffled.indices[3 * f + 1], shuffled.indices[3 * f + 2]);
    }
    ms.push_back(std::move(s2));
    // A polygon mesh with long fans (several blocks per face).
    Mesh fan;
    for (int i = 0; i < 100; ++i) {
        const double t = 2 * 3.141592653589793 * i / 100;
        fan.add_vertex(std::cos(t) + 10, std::sin(t) - 3, 0.25 * i);
    }
    std::vector<uint32_t> face;
    for (uint32_t i = 0; i < 100; ++i) face.push_back(i);
    fan.add_face(face);
    fan.add_face(face);
    ms.push_back(std::move(fan));
    ms.push_back(test::unwelded(fx::random_sphere(rng, 4, 1.0, {0.5, 0, -0.25})));
    ms.push_back(test::unwelded(fx::random_sphere(rng, 5, 1.0, {1e6, 2e6, 0})));
    return ms;
}

struct Volume {
    mpq_class sum;
    double bound;
    std::size_t triangles;
    bool safe;
};

Volume volume_of(const MeshView& m, VolumeForm form = VolumeForm::translated) {
    bool safe = false;
    const ConeSums s = filtered_volume(m, safe, form);
    return {as_mpq(s.sum[kV]), s.bound[kV], s.triangles, safe};
}

// Σ det over the fan triangles of faces [f0, f1), exactly (plain rationals,
// as fx::reference_sums); nullopt when one of their coordinates is NaN or
// infinite.
std::optional<mpq_class> det_sum(const MeshView& m, std::size_t f0, std::size_t f1) {
    mpq_class det = 0;
    for (std::size_t f = f0; f < f1; ++f) {
        const auto face = m.face(f);
        for (std::size_t i = 1; i + 1 < face.size(); ++i) {
            const uint32_t v[3] = {face[0], face[i], face[i + 1]};
            mpq_class p[3][3];
            for (int a = 0; a < 3; ++a)
                for (int k = 0; k < 3; ++k) {
                    const double x = m.positions[3 * std::size_t{v[a]} + static_cast<std::size_t>(k)];
                    if (!std::isfinite(x)) return std::nullopt;
                    p[a][k] = q(x);
                }
            det += p[0][0] * (p[1][1] * p[2][2] - p[1][2] * p[2][1]) + p[0][1] * (p[1][2] * p[2][0] - p[1][0] * p[2][2]) +
                   p[0][2] * (p[1][0] * p[2][1] - p[1][1] * p[2][0]);
        }
    }
    return det;
}

// Faces that share no vertex, with random coordinates in [-4, 4]: one per
// entry of sizes, vertices numbered up from 0, or down from the last one
// (reversed: the first face uses vertex nv - 1).
Mesh separate_faces(std::mt19937_64& rng, const std::vector<uint32_t>& sizes, bool reversed = false) {
    std::uniform_real_distribution<double> d(-4, 4);
    Mesh m;
    uint32_t nv = 0;
    for (uint32_t k : sizes) nv += k;
    for (uint32_t i = 0; i < nv; ++i) m.add_vertex(d(rng), d(rng), d(rng));
    uint32_t next = 0;
    for (uint32_t k : sizes) {
        std::vector<uint32_t> face;
        for (uint32_t j = 0; j < k; ++j, ++next) face.push_back(reversed ? nv - 1 - next : next);
        m.add_face(face);  // (only triangles: an all-triangle mesh)
    }
    return m;
}

}  // namespace

TEST(ConeVolume, BoundHoldsAndSameBitsOnEveryLevelAndThreadCount) {
    LevelGuard guard;
    for (const Mesh& m : meshes()) {
        const mpq_class ref = fx::reference_sums(m.view())[kV];
        cap_kernel_level(-1);
        const Volume best = volume_of(m.view());
        EXPECT_TRUE(best.safe);
        EXPECT_EQ(best.triangles, m.view().triangle_count());
        EXPECT_LE(abs(best.sum - ref), q(best.bound));
        EXPECT_EQ(coordinate_range(m.view()), Range::safe);
        for (int level : polyvol::test::kLevels) {
            cap_kernel_level(level);
            for (int threads : {1, 2, 3}) {
                tbb::global_control gc(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
                const Volume v = volume_of(m.view());
                EXPECT_EQ(v.sum, best.sum) << "level " << level << ", " << threads << " threads";
                EXPECT_EQ(v.bound, best.bound) << "level " << level << ", " << threads << " threads";
                EXPECT_EQ(v.triangles, best.triangles);
                EXPECT_TRUE(v.safe);
                // filtered_sums(.., 1, double_double) is the same pass.
                const ConeSums f = filtered_sums(m.view(), 1, Precision::double_double);
                EXPECT_EQ(as_mpq(f.sum[kV]), best.sum);
                EXPECT_EQ(f.bound[kV], best.bound);
                EXPECT_PRED2(same, signed_volume(m.view()), rnd(ref / 6));
            }
        }
    }
}

TEST(ConeVolume, OriginFormBoundHoldsAndSameBitsOnEveryLevelAndThreadCount) {
    LevelGuard guard;
    for (const Mesh& m : meshes()) {
        const mpq_class ref = fx::reference_sums(m.view())[kV];
        cap_kernel_level(-1);
        const Volume best = volume_of(m.view(), VolumeForm::origin);
        const Volume translated = volume_of(m.view(), VolumeForm::translated);
        EXPECT_TRUE(best.safe);
        EXPECT_EQ(best.triangles, m.view().triangle_count());
        EXPECT_LE(abs(best.sum - ref), q(best.bound));
        // Its bound grows with |a| |b| |c|: never below the translated one's
        // far from the origin (the meshes around 1e6 and 1e8).
        if (m.positions[0] > 1e5 && m.positions[0] < 1e20) {
            EXPECT_GT(best.bound, 100 * translated.bound);
        }
        for (int level : polyvol::test::kLevels) {
            cap_kernel_level(level);
            for (int threads : {1, 3}) {
                tbb::global_control gc(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
                const Volume v = volume_of(m.view(), VolumeForm::origin);
                EXPECT_EQ(v.sum, best.sum) << "level " << level << ", " << threads << " threads";
                EXPECT_EQ(v.bound, best.bound) << "level " << level << ", " << threads << " threads";
                EXPECT_TRUE(v.safe);
            }
        }
    }
}

TEST(ConeVolume, LikelyFormIsOriginNearTheOriginAndTranslatedFarFromIt) {
    std::mt19937_64 rng(5);
    EXPECT_EQ(likely_volume_form(fx::random_sphere(rng, 4, 1.0, {0, 0, 0}).view()), VolumeForm::origin);
    EXPECT_EQ(likely_volume_form(fx::random_sphere(rng, 4, 1.0, {3, -2, 1}).view()), VolumeForm::origin);
    EXPECT_EQ(likely_volume_form(fx::random_sphere(rng, 4, 1.0, {1e6, 0, 0}).view()), VolumeForm::translated);
    EXPECT_EQ(likely_volume_form(fx::random_sphere(rng, 2, 1e-3, {1e8, 1e8, -1e8}).view()), VolumeForm::translated);
    EXPECT_EQ(likely_volume_form(Mesh{}.view()), VolumeForm::translated);
    Mesh point;  // no extent
    point.add_vertex(1, 2, 3);
    EXPECT_EQ(likely_volume_form(point.view()), VolumeForm::translated);
}

TEST(ConeVolume, AWrongGuessFallsBackToTheTranslatedForm) {
    // A small sphere far from the origin, with unused vertices spread from
    // -1e6 to 1e6 in the sample: the guess is the origin form, whose bound
    // (about |x|^3 per triangle) cannot decide a volume of 4e-9; signed_volume
    // must then take the translated form and still round correctly.
    LevelGuard guard;
    std::mt19937_64 rng(8);
    Mesh m = fx::random_sphere(rng, 3, 1e-3, {1e6, 1e6, 1e6});
    std::uniform_real_distribution<double> d(-1e6, 1e6);
    Mesh spread;
    for (int i = 0; i < 5000; ++i) spread.add_vertex(d(rng), d(rng), d(rng));
    spread.append(m);
    ASSERT_EQ(likely_volume_form(spread.view()), VolumeForm::origin);
    const mpq_class ref = fx::reference_sums(spread.view())[kV];
    const Volume origin = volume_of(spread.view(), VolumeForm::origin);
    ASSERT_TRUE(origin.safe);
    EXPECT_GT(q(origin.bound), abs(ref) / 1e6);  // undecided by far
    // The translated form decides on its own (its bound far below an ulp):
    // what the fallback in signed_volume relies on before any exact work.
    const Volume translated = volume_of(spread.view(), VolumeForm::translated);
    EXPECT_LT(q(translated.bound), abs(ref) * std::ldexp(1.0, -60));
    for (int level : polyvol::test::kLevels) {
        cap_kernel_level(level);
        EXPECT_PRED2(same, signed_volume(spread.view()), rnd(ref / 6)) << "level " << level;
    }
}

TEST(ConeVolume, BlockKernelIsThePassOnOneBlock) {
    // filtered_volume_block (measure/soup.cpp's pass 2) on one block gives
    // the pass's sum, and its magnitude the pass's bound.
    LevelGuard guard;
    std::mt19937_64 rng(32);
    const Mesh ms[] = {fx::octahedron(2), fx::random_sphere(rng, 1, 1.0, {5e5, 1, 2})};  // 8 and 32 triangles
    for (const Mesh& m : ms) {
        ASSERT_LE(m.face_count(), static_cast<std::size_t>(kBlockTriangles));
        TriangleBlock b{};
        b.n = static_cast<int>(m.face_count());
        for (int i = 0; i < b.n; ++i)
            for (int v = 0; v < 3; ++v)
                for (int k = 0; k < 3; ++k)
                    b.c[3 * v + k][i] = m.positions[3 * std::size_t{m.indices[3 * static_cast<std::size_t>(i) + v]} + k];
        for (int level : polyvol::test::kLevels) {
            cap_kernel_level(level);
            exact::ExactSum sum, magnitude;
            filtered_volume_block(b, sum, magnitude);
            const Volume v = volume_of(m.view());
            EXPECT_EQ(as_mpq(sum), v.sum) << "level " << level;
            EXPECT_EQ(filtered_bound(kV, Precision::double_double, magnitude.round()), v.bound) << "level " << level;
            EXPECT_LE(abs(as_mpq(sum) - fx::reference_sums(m.view())[kV]), q(v.bound));
        }
    }
}

TEST(ConeVolume, RangeCheckIsRangeSafeOnTheReferencedCoordinates) {
    // One coordinate set to each boundary value, in every slot of the
    // blocks (vertex role, axis, triangle): the pass's verdict is
    // coordinate_range's, and signed_volume is the exact volume rounded once
    // (NaN for a NaN or infinity). The faces share no vertex, so each
    // coordinate is read in one slot (a polygon's first vertex: in each of
    // its fan triangles). Three layouts, for every way into a block:
    //   40 triangles: a whole block by the AVX2 gather, 8 through put();
    //   64 triangles numbered down from the last vertex: the first block
    //     uses vertex nv - 1, so the AVX2 gather leaves the whole block to
    //     the scalar one; the second block is gathered;
    //   polygons of 3 to 9 vertices: 56 fan triangles through put().
    // Below AVX-512 level 2 runs level 1, whose verdict is coordinate_range's
    // by construction: the test then reports itself skipped.
    LevelGuard guard;
    std::mt19937_64 rng(33);
    std::vector<Mesh> bases;
    bases.push_back(separate_faces(rng, std::vector<uint32_t>(40, 3)));
    bases.push_back(separate_faces(rng, std::vector<uint32_t>(64, 3), /*reversed=*/true));
    bases.push_back(separate_faces(rng, {5, 7, 4, 9, 6, 3, 8, 5, 7, 4, 9, 6, 3, 8}));
    ASSERT_TRUE(bases[1].view().all_triangles());
    ASSERT_FALSE(bases[2].view().all_triangles());
    ASSERT_EQ(bases[2].view().triangle_count(), 56u);
    const double values[] = {0.0,
                             -0.0,
                             0x1p-160,
                             -0x1p-160,
                             std::nextafter(0x1p-160, 0.0),
                             -std::nextafter(0x1p-160, 0.0),
                             0x1p190,
                             -0x1p190,
                             std::nextafter(0x1p190, kInf),
                             -std::nextafter(0x1p190, kInf),
                             1e-320,
                             DBL_MIN,
                             DBL_MAX,
                             -DBL_MAX,
                             kInf,
                             -kInf,
                             kNaN,
                             -kNaN};
    for (std::size_t layout = 0; layout < bases.size(); ++layout) {
        const MeshView base = bases[layout].view();
        // Each face's Σ det, and the face of each vertex.
        std::vector<mpq_class> face_det(base.face_count());
        std::vector<std::size_t> face_of(base.vertex_count());
        mpq_class total = 0;
        for (std::size_t f = 0; f < base.face_count(); ++f) {
            face_det[f] = *det_sum(base, f, f + 1);
            total += face_det[f];
            for (uint32_t v : base.face(f)) face_of[v] = f;
        }
        for (double x : values) {
            for (std::size_t slot = 0; slot < base.positions.size(); ++slot) {
                Mesh m = bases[layout];
                m.positions[slot] = x;
                const bool expect = coordinate_range(m.view()) == Range::safe;
                // The exact volume rounded once (only the changed face's Σ det
                // recomputed), NaN for a NaN or infinity.
                const std::size_t f = face_of[slot / 3];
                const std::optional<mpq_class> changed = det_sum(m.view(), f, f + 1);
                const double volume = changed ? rnd((total - face_det[f] + *changed) / 6) : kNaN;
                for (int level : polyvol::test::kLevels) {
                    cap_kernel_level(level);
                    SCOPED_TRACE(testing::Message()
                                 << "layout " << layout << ", x = " << x << ", slot " << slot << ", level " << level);
                    EXPECT_EQ(volume_of(m.view()).safe, expect);
                    EXPECT_PRED2(same, signed_volume(m.view()), volume);
                }
            }
        }
    }
    cap_kernel_level(-1);
    EXPECT_TRUE(volume_of(fx::box(0, 0, 0, 0x1p190, 0x1p-160, 1).view()).safe);
    EXPECT_FALSE(volume_of(fx::box(0, 0, 0, 0x1p191, 1, 1).view()).safe);
    EXPECT_FALSE(volume_of(fx::box(0, 0, 0, 0x1p-161, 1, 1).view()).safe);
    if (!cpu_has_avx512()) GTEST_SKIP() << "no AVX-512: the fused range check (level 3) did not run";
}

TEST(ConeVolume, OutsideTheSafeRangeOnAUsedVertexIsStillExact) {
    // The fused check sends these down the big-integer path: the exact
    // volume rounded once, as before.
    LevelGuard guard;
    std::mt19937_64 rng(34);
    std::vector<Mesh> ms;
    ms.push_back(fx::random_sphere(rng, 2, 1e-200, {3e-200, 0, 0}));
    ms.push_back(fx::random_sphere(rng, 2, 1e250, {0, 1e250, 0}));
    Mesh mixed = fx::random_sphere(rng, 3, 1.0, {0, 0, 0});
    mixed.positions[0] = 1e-300;  // used vertices
    mixed.positions[3 * 100 + 1] = 1e200;
    ms.push_back(std::move(mixed));
    Mesh one = fx::random_sphere(rng, 4, 1.0, {1e6, 0, 0});
    one.positions[3 * 501 + 2] = 0x1p-170;  // one coordinate below 2^-160
    ms.push_back(std::move(one));
    for (const Mesh& m : ms) {
        ASSERT_EQ(coordinate_range(m.view()), Range::unsafe);
        const double expect = rnd(fx::reference_sums(m.view())[kV] / 6);
        for (int level : polyvol::test::kLevels) {
            cap_kernel_level(level);
            EXPECT_FALSE(volume_of(m.view()).safe);
            EXPECT_PRED2(same, signed_volume(m.view()), expect) << "level " << level;
        }
    }
    // A used NaN or infinity: NaN.
    for (double bad : {kNaN, kInf, -kInf}) {
        Mesh m = fx::unit_tetrahedron();
        m.positions[7] = bad;
        EXPECT_TRUE(std::isnan(signed_volume(m.view())));
    }
}

TEST(ConeVolume, UnusedVerticesDoNotMatter) {
    // Vertices no face uses enter no sum: NaN, infinite or out-of-range
    // coordinates there change nothing. With AVX-512 the pass sees only used
    // vertices (safe); below it the range check is coordinate_range's, which
    // sees them (not safe: the exact path gives the same volume).
    LevelGuard guard;
    std::mt19937_64 rng(35);
    const Mesh clean = fx::random_sphere(rng, 5, 1.0, {1e6, 1e6, 1e6});
    const double expect = rnd(fx::reference_sums(clean.view())[kV] / 6);
    ASSERT_PRED2(same, signed_volume(clean.view()), expect);
    cap_kernel_level(-1);
    const Volume ref = volume_of(clean.view());
    const Volume ref_origin = volume_of(clean.view(), VolumeForm::origin);
    for (double bad : {kNaN, kInf, 1e300, 1e-300}) {
        Mesh m = clean;
        m.add_vertex(bad, 0, 1);
        // An unused vertex in the middle: renumber so that vertex 7 is unused.
        Mesh mid;
        mid.positions = clean.positions;
        mid.positions.insert(mid.positions.begin() + 21, {bad, bad, 0.5});
        for (uint32_t i : clean.indices) mid.indices.push_back(i >= 7 ? i + 1 : i);
        for (const Mesh* mm : {&m, &mid}) {
            EXPECT_NE(coordinate_range(mm->view()), Range::safe);
            for (int level : polyvol::test::kLevels) {
                cap_kernel_level(level);
                const Volume v = volume_of(mm->view());
                EXPECT_EQ(v.safe, level == 3 && cpu_has_avx512()) << "bad " << bad << ", level " << level;
                if (v.safe) {
                    EXPECT_EQ(v.sum, ref.sum);
                    EXPECT_EQ(v.bound, ref.bound);
                }
                // The origin form: the same check, and its M is the largest
                // used coordinate, not the unused vertex's.
                const Volume o = volume_of(mm->view(), VolumeForm::origin);
                EXPECT_EQ(o.safe, v.safe);
                if (o.safe) {
                    EXPECT_EQ(o.sum, ref_origin.sum);
                    EXPECT_EQ(o.bound, ref_origin.bound);
                }
                EXPECT_PRED2(same, signed_volume(mm->view()), expect) << "bad " << bad << ", level " << level;
            }
        }
    }
    if (!cpu_has_avx512()) GTEST_SKIP() << "no AVX-512: the fused range check (level 3) did not run";
}

TEST(ConeVolume, WeldingASoupChangesNoVolume) {
    // A sphere as a soup (three vertices per triangle, as STL files list it)
    // and welded again: the same volume, bit for bit, in both forms.
    std::mt19937_64 rng(12);
    for (const std::array<double, 3> t : {std::array<double, 3>{0, 0, 0}, std::array<double, 3>{1e6, -1e6, 1e6}}) {
        const Mesh indexed = fx::random_sphere(rng, 5, 1.0, t);
        const Mesh soup = test::unwelded(indexed);
        const Mesh w = welded(soup.view());
        EXPECT_EQ(w.vertex_count(), indexed.vertex_count());
        const double expect = rnd(fx::reference_sums(indexed.view())[kV] / 6);
        EXPECT_PRED2(same, signed_volume(soup.view()), expect);
        EXPECT_PRED2(same, signed_volume(w.view()), expect);
        for (VolumeForm form : {VolumeForm::translated, VolumeForm::origin})
            EXPECT_EQ(volume_of(soup.view(), form).sum, volume_of(w.view(), form).sum);
    }
}

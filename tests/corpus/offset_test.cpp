// Issue 3's accuracy test on real meshes: every closed corpus mesh, translated
// by 1e6 and by 1e8 (each coordinate x + t rounded to a double, as a file
// would store it), must give exactly the volume of those coordinates rounded
// once, by the cone, prism and pyramid formulas alike. The reference is
// computed here with GMP integers, independently of polyvol's exact module,
// and "rounded once" is checked by comparing the exact value with the
// midpoints to the result's neighbours.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/manifest.hpp"
#include "common/naive_volume.hpp"
#include "common/shapes.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"

namespace {

using polyvol::test::corpus_dir;
using polyvol::test::corpus_file;
using polyvol::test::corpus_manifest;
using polyvol::test::invalid_entry;
using polyvol::test::manifest_paths;

// x as an exact rational.
mpq_class exact(double x) {
    mpq_class q;
    mpq_set_d(q.get_mpq_t(), x);  // exact for finite doubles
    return q;
}

// The exact cone-rule volume Σ det(a,b,c)/6 over fan triangles, in rationals.
// Coordinates are scaled to integers first (all are multiples of 2^e), so the
// determinants are integer products.
mpq_class exact_volume(const polyvol::MeshView& m) {
    int e = 0;
    bool any = false;
    for (double x : m.positions) {
        if (x == 0) continue;
        int ex;
        std::frexp(x, &ex);
        const int lowest = ex - 53;  // x is a multiple of 2^(ex-53)
        e = any ? std::min(e, lowest) : lowest;
        any = true;
    }
    std::vector<mpz_class> p(m.positions.size());
    for (std::size_t i = 0; i < p.size(); ++i) {
        const double scaled = std::ldexp(m.positions[i], -e);  // an integer, exactly
        mpq_class q = exact(scaled);
        p[i] = q.get_num();
    }
    mpz_class sum = 0, t;
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const auto face = m.face(f);
        for (std::size_t i = 1; i + 1 < face.size(); ++i) {
            const mpz_class* a = &p[3 * face[0]];
            const mpz_class* b = &p[3 * face[i]];
            const mpz_class* c = &p[3 * face[i + 1]];
            t = a[0] * (b[1] * c[2] - b[2] * c[1]) + a[1] * (b[2] * c[0] - b[0] * c[2]) +
                a[2] * (b[0] * c[1] - b[1] * c[0]);
            sum += t;
        }
    }
    mpq_class v(sum, 6);
    v.canonicalize();
    if (e >= 0) v *= mpq_class(mpz_class(1) << (3 * e));
    else v /= mpq_class(mpz_class(1) << (-3 * e));
    return v;
}

// True when v is the double nearest to x (ties to even).
bool correctly_rounded(double v, const mpq_class& x) {
    const double lo = std::nextafter(v, -INFINITY), hi = std::nextafter(v, INFINITY);
    const mpq_class below = (exact(lo) + exact(v)) / 2, above = (exact(v) + exact(hi)) / 2;
    if (x > below && x < above) return true;
    if (x == below || x == above) {
        int ex;
        const double mant = std::frexp(v, &ex);
        const auto bits = static_cast<long long>(std::ldexp(mant, 53));
        return (bits & 1) == 0;  // v is the even neighbour
    }
    return false;
}

std::vector<std::string> closed_meshes() {
    if (corpus_manifest().empty()) return {"missing-corpus"};
    return manifest_paths([](const nlohmann::json& e) {
        return !invalid_entry(e) && e.value("exact", false) && e["topology"]["closed_2_cycle"].get<bool>() &&
               e["counts"]["triangles"].get<int>() > 0;
    });
}

class Offset : public ::testing::TestWithParam<std::string> {};

TEST_P(Offset, TranslatedMeshVolumeIsCorrectlyRounded) {
    ASSERT_NE(GetParam(), "missing-corpus") << "corpus missing at " << corpus_dir();
    const auto loaded = polyvol::read_mesh_file(corpus_file(GetParam()));
    for (double t : {1e6, 1e8}) {
        polyvol::Mesh m = loaded.mesh;
        for (double& x : m.positions) x += t;  // rounded to a double, as a file stores it
        const mpq_class want = exact_volume(m.view());
        const double got = polyvol::signed_volume(m.view());
        EXPECT_TRUE(correctly_rounded(got, want))
            << "offset " << t << ": got " << std::hexfloat << got << ", exact " << want.get_d();
        // The other rational formulas: the pyramid sum is the cone sum for
        // every mesh, the prism sum for every closed one.
        for (const auto method : {polyvol::Method::prism, polyvol::Method::pyramid}) {
            const double v = polyvol::signed_volume(m.view(), method);
            EXPECT_TRUE(correctly_rounded(v, want)) << polyvol::method_name(method) << " offset " << t << ": got "
                                                    << std::hexfloat << v << ", exact " << want.get_d();
        }
        // The fast path stays within its stated bound, or (a bound beyond
        // kFastRelativeLimit: the far offsets) is the correctly rounded value.
        const auto fast = polyvol::mass_properties(m.view(), {.accuracy = polyvol::Accuracy::fast});
        if (fast.volume_correctly_rounded) {
            EXPECT_EQ(fast.accuracy, polyvol::Accuracy::correctly_rounded);
            EXPECT_TRUE(correctly_rounded(fast.volume, want)) << "offset " << t;
            continue;
        }
        const mpq_class error = abs(mpq_class(exact(fast.volume) - want));
        EXPECT_LE(cmp(error, exact(fast.volume_error_bound)), 0) << "offset " << t << ": error " << error.get_d()
                                                                  << " > bound " << fast.volume_error_bound;
    }
}

INSTANTIATE_TEST_SUITE_P(Corpus, Offset, ::testing::ValuesIn(closed_meshes()), [](const auto& param_info) {
    std::string s = param_info.param;
    for (char& c : s)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return s;
});

// A synthetic case where the naive double sum is wrong by more than 10 %:
// a unit cube far from the origin. polyvol is exact.
TEST(Offset, NaiveSummationFailsWherePolyvolIsExact) {
    const double tx = 12345678.9, ty = 23456789.1, tz = 34567890.3;
    const polyvol::Mesh m = polyvol::test::box({tx, ty, tz}, {tx + 0.75, ty + 1.25, tz + 1}, {.quads = true});
    const auto v = m.view();
    const double naive = polyvol::test::naive_volume(v);
    EXPECT_GT(std::abs(naive - 1.0), 0.1) << "naive " << naive;
    const mpq_class want = exact_volume(v);
    EXPECT_NEAR(want.get_d(), 0.9375, 1e-8);  // 0.75 x 1.25 x 1 up to the rounding of the corners
    EXPECT_TRUE(correctly_rounded(polyvol::signed_volume(v), want));
}

}  // namespace

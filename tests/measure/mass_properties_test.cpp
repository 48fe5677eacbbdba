// Tests of polyvol/measure.hpp: closed-form values, exact identities, and
// bit-for-bit agreement with an independent GMP computation.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cfloat>
#include <cmath>
#include <random>
#include <utility>

#include "common/naive_volume.hpp"
#include "cone_fixtures.hpp"
#include "exact/rational.hpp"
#include "polyvol/measure.hpp"

using namespace polyvol;
using polyvol::fixtures::q;
using polyvol::fixtures::rnd;
namespace fx = polyvol::fixtures;

namespace {


bool same(double a, double b) {
    return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b) || (std::isnan(a) && std::isnan(b));
}

// Every result the correctly rounded mode promises, from the reference sums.
struct Expected {
    double volume, mass;
    std::array<double, 3> first, centroid;
    std::array<double, 6> second, inertia_origin, inertia_centroid;
};

Expected expected(const MeshView& m, double density = 1) {
    const auto s = fx::reference_sums(m);
    const mpq_class rho = q(density);
    Expected e{};
    const mpq_class V = s[0] / 6;
    e.volume = rnd(V);
    e.mass = rnd(rho * V);
    mpq_class M[3], S[6], C[6];
    for (int i = 0; i < 3; ++i) {
        M[i] = s[1 + static_cast<std::size_t>(i)] / 24;
        e.first[static_cast<std::size_t>(i)] = rnd(rho * M[i]);
        e.centroid[static_cast<std::size_t>(i)] = V == 0 ? NAN : rnd(M[i] / V);
    }
    const int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
    for (int k = 0; k < 6; ++k) {
        S[k] = s[4 + static_cast<std::size_t>(k)] / 120;
        e.second[static_cast<std::size_t>(k)] = rnd(rho * S[k]);
        if (V != 0) C[k] = S[k] - M[I[k]] * M[J[k]] / V;
    }
    auto inertia = [&](const mpq_class* X, std::array<double, 6>& out, bool nan) {
        const mpq_class t[6] = {X[1] + X[2], X[0] + X[2], X[0] + X[1], -X[3], -X[4], -X[5]};
        for (int k = 0; k < 6; ++k) out[static_cast<std::size_t>(k)] = nan ? NAN : rnd(rho * t[k]);
    };
    inertia(S, e.inertia_origin, false);
    inertia(C, e.inertia_centroid, V == 0);
    return e;
}

void expect_correctly_rounded(const MeshView& m, const MassProperties& p, double density = 1) {
    const Expected e = expected(m, density);
    EXPECT_TRUE(p.volume_correctly_rounded);
    EXPECT_TRUE(p.moments_correctly_rounded);
    EXPECT_EQ(p.volume_error_bound, 0.0);
    EXPECT_PRED2(same, p.volume, e.volume);
    EXPECT_PRED2(same, p.mass, e.mass);
    for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_PRED2(same, p.first_moments[i], e.first[i]) << i;
        EXPECT_PRED2(same, p.centroid[i], e.centroid[i]) << i;
    }
    for (std::size_t i = 0; i < 6; ++i) {
        EXPECT_PRED2(same, p.second_moments[i], e.second[i]) << i;
        EXPECT_PRED2(same, p.inertia_origin[i], e.inertia_origin[i]) << i;
        EXPECT_PRED2(same, p.inertia_centroid[i], e.inertia_centroid[i]) << i;
    }
}

MassProperties cr(const Mesh& m, double density = 1) {
    return mass_properties(m.view(), {.method = Method::cone, .accuracy = Accuracy::correctly_rounded, .density = density});
}

// Every field that the cone rule determines, bit for bit.
void expect_identical(const MassProperties& a, const MassProperties& b) {
    EXPECT_PRED2(same, a.volume, b.volume);
    for (std::size_t i = 0; i < 3; ++i) EXPECT_PRED2(same, a.first_moments[i], b.first_moments[i]);
    for (std::size_t i = 0; i < 6; ++i) {
        EXPECT_PRED2(same, a.second_moments[i], b.second_moments[i]);
        EXPECT_PRED2(same, a.inertia_centroid[i], b.inertia_centroid[i]);
    }
}

Mesh translated(const Mesh& m, double tx, double ty, double tz) {
    Mesh r = m;
    for (std::size_t v = 0; v < r.vertex_count(); ++v) {
        r.positions[3 * v] += tx;
        r.positions[3 * v + 1] += ty;
        r.positions[3 * v + 2] += tz;
    }
    return r;
}

using test::naive_volume;  // the naive double loop users write

}  // namespace

TEST(MassProperties, Names) {
    EXPECT_EQ(method_name(Method::cone), "cone");
    EXPECT_EQ(method_name(Method::prism), "prism");
    EXPECT_EQ(method_name(Method::pyramid), "pyramid");
    EXPECT_EQ(method_name(Method::vtnb), "vtnb");
    EXPECT_EQ(accuracy_name(Accuracy::correctly_rounded), "correctly-rounded");
    EXPECT_EQ(accuracy_name(Accuracy::fast), "fast");
    const auto I = inertia_from_second_moments({1, 2, 3, 4, 5, 6});
    EXPECT_EQ(I, (std::array<double, 6>{5, 4, 3, -4, -5, -6}));
}

TEST(MassProperties, UnitTetrahedron) {
    const Mesh m = fx::unit_tetrahedron();
    const MassProperties p = cr(m);
    EXPECT_EQ(p.volume, 1.0 / 6);
    EXPECT_EQ(p.mass, 1.0 / 6);
    for (double x : p.first_moments) EXPECT_EQ(x, 1.0 / 24);
    for (double x : p.centroid) EXPECT_EQ(x, 0.25);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(p.second_moments[static_cast<std::size_t>(i)], 1.0 / 60);
    for (int i = 3; i < 6; ++i) EXPECT_EQ(p.second_moments[static_cast<std::size_t>(i)], 1.0 / 120);
    for (int i = 0; i < 3; ++i) EXPECT_EQ(p.inertia_origin[static_cast<std::size_t>(i)], 1.0 / 30);
    for (int i = 3; i < 6; ++i) EXPECT_EQ(p.inertia_origin[static_cast<std::size_t>(i)], -1.0 / 120);
    // About the centroid: ∫x² - V c² = 1/60 - 1/96 = 1/160; xy: 1/120 - 1/96 = -1/480.
    for (int i = 0; i < 3; ++i) EXPECT_EQ(p.inertia_centroid[static_cast<std::size_t>(i)], 1.0 / 80);
    for (int i = 3; i < 6; ++i) EXPECT_EQ(p.inertia_centroid[static_cast<std::size_t>(i)], 1.0 / 480);
    expect_correctly_rounded(m.view(), p);
    EXPECT_EQ(signed_volume(m.view()), 1.0 / 6);
    // Density scales mass, moments and inertia, not volume or centroid.
    const MassProperties d = cr(m, 3);
    EXPECT_EQ(d.volume, 1.0 / 6);
    EXPECT_EQ(d.mass, 0.5);
    EXPECT_EQ(d.first_moments[0], 0.125);
    EXPECT_EQ(d.centroid[1], 0.25);
    EXPECT_EQ(d.inertia_origin[0], 0.1);
    expect_correctly_rounded(m.view(), d, 3);
}

TEST(MassProperties, AxisBoxes) {
    const double boxes[][6] = {{0, 0, 0, 2, 3, 5}, {-1, -2, -3, 0.5, 4, 7}, {1e6, 2e6, -3e6, 1e6 + 0.25, 2e6 + 8, -3e6 + 1}};
    for (const auto& b : boxes) {
        const Mesh m = fx::box(b[0], b[1], b[2], b[3], b[4], b[5]);
        const MassProperties p = cr(m);
        const double a = b[3] - b[0], w = b[4] - b[1], h = b[5] - b[2];  // exact here
        const double V = a * w * h;
        EXPECT_EQ(p.volume, V);
        for (int i = 0; i < 3; ++i)
            EXPECT_EQ(p.centroid[static_cast<std::size_t>(i)], (b[i] + b[i + 3]) / 2);
        // Inertia about the centroid: m (w² + h²) / 12 etc., products zero.
        const mpq_class mv = q(a) * q(w) * q(h);
        EXPECT_EQ(p.inertia_centroid[0], rnd(mv * (q(w) * q(w) + q(h) * q(h)) / 12));
        EXPECT_EQ(p.inertia_centroid[1], rnd(mv * (q(a) * q(a) + q(h) * q(h)) / 12));
        EXPECT_EQ(p.inertia_centroid[2], rnd(mv * (q(a) * q(a) + q(w) * q(w)) / 12));
        for (int i = 3; i < 6; ++i) EXPECT_PRED2(same, p.inertia_centroid[static_cast<std::size_t>(i)], 0.0);
        expect_correctly_rounded(m.view(), p);
        // Polygon faces (quads) give the same as their triangles.
        expect_identical(cr(fx::box(b[0], b[1], b[2], b[3], b[4], b[5], true)), p);
    }
}

TEST(MassProperties, Octahedron) {
    const Mesh m = fx::octahedron(1);
    const MassProperties p = cr(m);
    EXPECT_EQ(p.volume, 4.0 / 3);
    for (double c : p.centroid) EXPECT_EQ(c, 0.0);  // exact zeros: decided by the exact path
    for (double x : p.first_moments) EXPECT_PRED2(same, x, 0.0);
    // ∫x² over |x|+|y|+|z| <= 1 is 2/15; products vanish.
    EXPECT_EQ(p.second_moments[0], 2.0 / 15);
    EXPECT_PRED2(same, p.second_moments[3], 0.0);
    EXPECT_EQ(p.inertia_centroid[0], 4.0 / 15);
    expect_correctly_rounded(m.view(), p);
}

TEST(MassProperties, ExactIdentities) {
    std::mt19937_64 rng(21);
    Mesh m = fx::random_sphere(rng, 3, 1.0, {0.25, -3, 1e3});
    // Coordinates on a grid of 2^-20, so that translations by 2^k stay exact.
    for (double& x : m.positions) x = std::round(x * 0x1p20) / 0x1p20;
    const MassProperties p = cr(m);
    expect_correctly_rounded(m.view(), p);

    // Rotating the vertex order within each triangle.
    Mesh r = m;
    for (std::size_t f = 0; f < r.face_count(); ++f)
        std::rotate(r.indices.begin() + static_cast<long>(3 * f), r.indices.begin() + static_cast<long>(3 * f + 1),
                    r.indices.begin() + static_cast<long>(3 * f + 3));
    expect_identical(cr(r), p);

    // Permuting the faces.
    Mesh perm;
    perm.positions = m.positions;
    std::vector<std::size_t> order(m.face_count());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), rng);
    for (std::size_t f : order) perm.add_triangle(m.indices[3 * f], m.indices[3 * f + 1], m.indices[3 * f + 2]);
    expect_identical(cr(perm), p);

    // Translating by exact powers of two (all coordinates stay exact):
    // the volume and the inertia about the centroid are unchanged, bit for bit.
    for (double t : {0x1p10, -0x1p20, 0x1p30}) {
        const MassProperties pt = cr(translated(m, t, -t, t));
        EXPECT_PRED2(same, pt.volume, p.volume);
        for (std::size_t i = 0; i < 6; ++i) EXPECT_PRED2(same, pt.inertia_centroid[i], p.inertia_centroid[i]);
    }

    // Reflection x -> -x reverses orientation: the volume is negated.
    Mesh refl = m;
    for (std::size_t v = 0; v < refl.vertex_count(); ++v) refl.positions[3 * v] = -refl.positions[3 * v];
    const MassProperties pr = cr(refl);
    EXPECT_EQ(pr.volume, -p.volume);
    EXPECT_EQ(pr.second_moments[0], -p.second_moments[0]);

    // Splitting a triangle at a point of one of its edges: the cone over it is
    // split in two, every sum is unchanged.
    Mesh split = fx::box(0, 0, 0, 4, 2, 1);
    const MassProperties before = cr(split);
    const uint32_t a = split.indices[0], b = split.indices[1], c = split.indices[2];
    const double* pa = &split.positions[3 * a];
    const double* pb = &split.positions[3 * b];
    const uint32_t s = split.add_vertex(pa[0] + (pb[0] - pa[0]) * 0.375, pa[1] + (pb[1] - pa[1]) * 0.375,
                                        pa[2] + (pb[2] - pa[2]) * 0.375);
    split.indices[1] = s;              // (a, s, c)
    split.add_triangle(s, b, c);       // (s, b, c)
    expect_identical(cr(split), before);
}

TEST(MassProperties, FarFromTheOrigin) {
    // A unit cube translated far away has volume exactly 1.
    for (double t : {1e6, 1e8, 0x1p52}) {
        const Mesh m = fx::box(t, t, t, t + 1, t + 1, t + 1);
        const MassProperties p = cr(m);
        EXPECT_EQ(p.volume, 1.0) << t;
        EXPECT_EQ(signed_volume(m.view()), 1.0);
        EXPECT_EQ(p.inertia_centroid[0], 1.0 / 6);
        EXPECT_PRED2(same, p.inertia_centroid[3], 0.0);
        expect_correctly_rounded(m.view(), p);
    }
    // At 2^60 the spacing of doubles is 256: a cube of side 512.
    const double t = 0x1p60;
    const Mesh m = fx::box(t, t, t, t + 512, t + 512, t + 512);
    EXPECT_EQ(cr(m).volume, 0x1p27);
    expect_correctly_rounded(m.view(), cr(m));
}

TEST(MassProperties, NaiveSummationFailsPolyvolIsExact) {
    std::mt19937_64 rng(22);
    const Mesh m = fx::random_sphere(rng, 4, 1.0, {3e7, -2e7, 1e7});  // 2048 triangles
    const auto s = fx::reference_sums(m.view());
    const double exact = rnd(s[0] / 6);
    const double naive = naive_volume(m.view());
    EXPECT_GT(std::fabs(naive - exact), 0.1 * std::fabs(exact)) << naive << " vs " << exact;
    const MassProperties p = cr(m);
    EXPECT_PRED2(same, p.volume, exact);
    expect_correctly_rounded(m.view(), p);
}

TEST(MassProperties, RandomMeshesMatchGmpBitForBit) {
    std::mt19937_64 rng(23);
    int stayed_fast = 0, fell_back = 0;
    for (int trial = 0; trial < 12; ++trial) {
        const double offset = trial % 3 == 0 ? 0 : (trial % 3 == 1 ? 1e6 : 1e9);
        std::uniform_real_distribution<double> d(-offset, offset);
        const double r = std::ldexp(1.0, static_cast<int>(rng() % 10) - 3);
        Mesh m = fx::random_sphere(rng, 1 + trial % 4, r, {d(rng), d(rng), d(rng)}, 0.3);
        if (trial % 4 == 3) {  // as polygons: pairs of triangles (non-planar quads are fans too)
            Mesh p;
            p.positions = m.positions;
            for (std::size_t f = 0; f < m.face_count(); ++f) {
                const uint32_t t[3] = {m.indices[3 * f], m.indices[3 * f + 1], m.indices[3 * f + 2]};
                p.add_face(t);
            }
            const uint32_t degenerate[2] = {0, 1};
            p.add_face(degenerate);  // < 3 vertices: contributes nothing
            m = std::move(p);
        }
        const double density = trial % 2 ? 1.0 : 0.7;
        const MassProperties p = cr(m, density);
        expect_correctly_rounded(m.view(), p, density);

        // Fast mode: within its stated bounds, or, when those exceed
        // kFastRelativeLimit, the correctly rounded results themselves.
        const MassProperties f =
            mass_properties(m.view(), {.method = Method::cone, .accuracy = Accuracy::fast, .density = density});
        if (f.accuracy == Accuracy::correctly_rounded) {
            ++fell_back;
            EXPECT_EQ(f.volume, p.volume);
            EXPECT_EQ(f.inertia_centroid, p.inertia_centroid);
            EXPECT_TRUE(f.moments_correctly_rounded);
            continue;
        }
        ++stayed_fast;
        EXPECT_FALSE(f.volume_correctly_rounded);
        EXPECT_LE(f.moments_relative_error, kFastRelativeLimit);
        const auto s = fx::reference_sums(m.view());
        EXPECT_LE(abs(q(f.volume) - s[0] / 6), q(f.volume_error_bound));
        EXPECT_LT(f.volume_error_bound, 1e-2 * std::fabs(f.volume));
        double mx = 0;
        for (double x : p.second_moments) mx = std::max(mx, std::fabs(x));
        for (std::size_t i = 0; i < 6; ++i)
            EXPECT_LE(std::fabs(f.second_moments[i] - p.second_moments[i]),
                      (f.moments_relative_error + 0x1p-52) * mx);
        EXPECT_EQ(signed_volume(m.view(), Method::cone, Accuracy::correctly_rounded), p.volume / 1.0);

        // Without second moments and edge length (the volume table): the
        // same bits for what is computed, NaN for the rest.
        MeasureOptions light{.method = Method::cone, .accuracy = Accuracy::correctly_rounded, .density = density};
        light.second_moments = false;
        light.edge_length = false;
        const MassProperties l = mass_properties(m.view(), light);
        EXPECT_EQ(l.volume, p.volume);
        EXPECT_EQ(l.mass, p.mass);
        EXPECT_EQ(l.area, p.area);
        EXPECT_TRUE(l.moments_correctly_rounded);
        for (int i = 0; i < 3; ++i) {
            EXPECT_EQ(l.first_moments[i], p.first_moments[i]);
            EXPECT_EQ(l.centroid[i], p.centroid[i]);
        }
        EXPECT_TRUE(std::isnan(l.second_moments[0]) && std::isnan(l.inertia_centroid[5]) && std::isnan(l.edge_length));
        light.accuracy = Accuracy::fast;
        const MassProperties lf = mass_properties(m.view(), light);
        EXPECT_EQ(lf.accuracy, Accuracy::fast);  // fewer moments: within the limit when all of them were
        EXPECT_EQ(lf.volume, f.volume);
        EXPECT_EQ(lf.centroid, f.centroid);
        EXPECT_LE(lf.moments_relative_error, f.moments_relative_error);
    }
    EXPECT_GT(stayed_fast, 0);
    EXPECT_GT(fell_back, 0);
}

TEST(MassProperties, TiesAndZeros) {
    // Box of exact volume 1 + 3·2^-53 (a tie): rounds to even, 1 + 2^-51.
    const double b = 1801439850948199.0 / 0x1p51;
    const Mesh m = fx::box(1e6, 0, 0, 1e6 + 1.25, b, 1);
    EXPECT_EQ(cr(m).volume, 1.0 + 0x1p-51);
    // Box of exact volume 1 + 2^-53 (a tie): rounds to even, 1.
    const double b2 = 3002399751580331.0 / 0x1p52;
    EXPECT_EQ(cr(fx::box(0, 0, -1e7, 1.5, b2, -1e7 + 1)).volume, 1.0);

    // An open surface through the origin: every sum is exactly 0.
    const MassProperties z = cr(test::triangle({0, 0, 0}, {1e6, 0, 0}, {0, 1e6, 0}));
    EXPECT_PRED2(same, z.volume, 0.0);
    EXPECT_TRUE(std::isnan(z.centroid[0]));
    EXPECT_TRUE(std::isnan(z.inertia_centroid[0]));
    // Two copies with opposite orientations: volume 0, far from the origin.
    Mesh two = fx::box(1e6, 1e6, 1e6, 1e6 + 1, 1e6 + 3, 1e6 + 7);
    Mesh rev = two;
    for (std::size_t f = 0; f < rev.face_count(); ++f) std::swap(rev.indices[3 * f], rev.indices[3 * f + 1]);
    two.append(rev);
    EXPECT_PRED2(same, cr(two).volume, 0.0);
    expect_correctly_rounded(two.view(), cr(two));

    // Empty mesh.
    const Mesh empty;
    EXPECT_EQ(cr(empty).volume, 0.0);
}

TEST(MassProperties, OutsideTheSafeRangeAndNonFinite) {
    std::mt19937_64 rng(24);
    for (double scale : {1e-120, 1e-60, 1e70}) {
        const Mesh m = fx::random_sphere(rng, 2, scale, {scale * 3, 0, 0});
        expect_correctly_rounded(m.view(), cr(m));
        // Fast mode takes the big-integer path here too: correctly rounded.
        const MassProperties f = mass_properties(m.view(), {.accuracy = Accuracy::fast});
        EXPECT_TRUE(f.volume_correctly_rounded);
        EXPECT_PRED2(same, f.volume, rnd(fx::reference_sums(m.view())[0] / 6));
    }
    Mesh bad = fx::unit_tetrahedron();
    bad.positions[4] = NAN;
    EXPECT_TRUE(std::isnan(cr(bad).volume));
    EXPECT_TRUE(std::isnan(signed_volume(bad.view())));
}

TEST(MassProperties, OtherMethodsReportTheirBounds) {
    const Mesh m = fx::box(-1, -2, -3, 0.5, 4, 7, /*quads=*/true);  // 12 edges
    // Prism and pyramid are correctly rounded by default (their sums are
    // rational); vtnb (unit vectors) and --accuracy fast carry a bound.
    for (Method method : {Method::prism, Method::pyramid}) {
        const MassProperties p = mass_properties(m.view(), {.method = method});
        EXPECT_TRUE(p.volume_correctly_rounded);
        EXPECT_EQ(p.volume, 90.0);
        EXPECT_EQ(p.volume_error_bound, 0.0);
        EXPECT_EQ(p.mass, 90.0);
        EXPECT_EQ(signed_volume(m.view(), method), 90.0);
    }
    for (const auto& [method, accuracy] : {std::pair{Method::prism, Accuracy::fast},
                                           std::pair{Method::pyramid, Accuracy::fast},
                                           std::pair{Method::vtnb, Accuracy::correctly_rounded}}) {
        const MassProperties p = mass_properties(m.view(), {.method = method, .accuracy = accuracy});
        EXPECT_EQ(p.method, method);
        EXPECT_FALSE(p.volume_correctly_rounded);
        EXPECT_NEAR(p.volume, 1.5 * 6 * 10, 1e-12);
        EXPECT_LE(std::fabs(p.volume - 90), p.volume_error_bound + 1e-300);
        EXPECT_NEAR(p.area, 2 * (1.5 * 6 + 6 * 10 + 1.5 * 10), 1e-10);
        EXPECT_NEAR(p.edge_length, 4 * (1.5 + 6 + 10), 1e-10);
        // Moments from the cone rule, with the same accuracy: correctly
        // rounded, the centroid is exact here.
        EXPECT_EQ(p.moments_correctly_rounded, accuracy == Accuracy::correctly_rounded);
        if (accuracy == Accuracy::correctly_rounded) {
            EXPECT_EQ(p.centroid[0], -0.25);
        } else {
            EXPECT_NEAR(p.centroid[0], -0.25, 1e-15);
        }
    }
    EXPECT_NEAR(surface_area(m.view()), 2 * (1.5 * 6 + 6 * 10 + 1.5 * 10), 1e-10);
    EXPECT_NEAR(total_edge_length(m.view()), 4 * (1.5 + 6 + 10), 1e-10);
}

// scale_mass_properties: the figures of the scaled mesh, within the widened
// bounds of the exact scaled values (GMP), and exactly for a power of two.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <cmath>

#include "polyvol/measure.hpp"

namespace {

using polyvol::MassProperties;
using polyvol::Mesh;

// A box [0, a] x [0, b] x [0, c], outward.
Mesh box(double a, double b, double c) {
    Mesh m;
    for (int i = 0; i < 8; ++i) m.add_vertex(i & 1 ? a : 0, i & 2 ? b : 0, i & 4 ? c : 0);
    const uint32_t q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& f : q) {
        m.add_triangle(f[0], f[1], f[2]);
        m.add_triangle(f[0], f[2], f[3]);
    }
    return m;
}

TEST(ScaleMassProperties, PowerOfTwoIsExact) {
    const Mesh m = box(0.3, 0.7, 1.1);
    MassProperties p = polyvol::mass_properties(m.view());
    const MassProperties before = p;
    polyvol::scale_mass_properties(p, 0.25);
    EXPECT_TRUE(p.volume_correctly_rounded);
    EXPECT_TRUE(p.moments_correctly_rounded);
    EXPECT_EQ(p.volume, before.volume / 64);
    EXPECT_EQ(p.inertia_centroid[0], before.inertia_centroid[0] / 1024);
    EXPECT_EQ(p.centroid[2], before.centroid[2] / 4);
}

// A density converted once (1.24 g/cm³ in g/mm³) widens the density-scaled
// figures' bounds only: the volume, area and edge length of an exact length
// factor keep their guarantee.
TEST(ScaleMassProperties, AnInexactDensityLeavesTheLengthsExact) {
    const Mesh m = box(0.3, 0.7, 1.1);
    MassProperties p = polyvol::mass_properties(m.view());
    const MassProperties before = p;
    polyvol::scale_mass_properties(p, 1.0, 0.0, 0x1p-52);
    EXPECT_TRUE(p.volume_correctly_rounded);
    EXPECT_EQ(p.volume, before.volume);
    EXPECT_LE(p.area_relative_error, before.area_relative_error * (1 + 0x1p-19));  // no (k + 1) u added
    EXPECT_FALSE(p.moments_correctly_rounded);
    EXPECT_GE(p.moments_relative_error, 0x1p-52);
    polyvol::scale_mass_properties(p, 0.5, 0.0, 0x1p-52);
    EXPECT_TRUE(p.volume_correctly_rounded);
    EXPECT_EQ(p.volume, before.volume / 8);
}

TEST(ScaleMassProperties, BoundsHoldForAnInexactFactor) {
    // mm to m: the factor meant is 1/1000 exactly, the double 0.001 is within u of it
    const double a = 0.3, b = 0.7, c = 1.1;
    const Mesh m = box(a, b, c);
    MassProperties p = polyvol::mass_properties(m.view());
    polyvol::scale_mass_properties(p, 0.001, 0x1p-53);
    EXPECT_FALSE(p.volume_correctly_rounded);
    const mpq_class k(1, 1000);
    const mpq_class exact_volume = mpq_class(a) * mpq_class(b) * mpq_class(c) * k * k * k;
    const mpq_class error = abs(mpq_class(p.volume) - exact_volume);
    EXPECT_LE(error, mpq_class(p.volume_error_bound));
    EXPECT_LT(p.volume_error_bound, 1e-15 * p.volume);
    // Ixx about the centroid = V (b² + c²) / 12, scaled by k^5
    const mpq_class exact_ixx = mpq_class(a) * mpq_class(b) * mpq_class(c) *
                                (mpq_class(b) * mpq_class(b) + mpq_class(c) * mpq_class(c)) / 12 * k * k * k * k * k;
    double largest = 0;
    for (double x : p.inertia_centroid) largest = std::max(largest, std::fabs(x));
    EXPECT_LE(abs(mpq_class(p.inertia_centroid[0]) - exact_ixx), mpq_class(p.moments_relative_error * largest));
    const mpq_class exact_area = 2 * (mpq_class(a) * mpq_class(b) + mpq_class(b) * mpq_class(c) + mpq_class(c) * mpq_class(a)) * k * k;
    EXPECT_LE(abs(mpq_class(p.area) - exact_area), mpq_class(p.area * p.area_relative_error));
}

}  // namespace

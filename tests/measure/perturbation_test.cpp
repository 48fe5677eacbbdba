// perturbation_bounds: moving every coordinate by at most δ moves each
// measure by no more than its bound (random moves of a sphere and a torus,
// the measures correctly rounded before and after), and the volume's bound
// is not vacuous: within 20 times what scaling the sphere outward by δ does.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "common/generate.hpp"
#include "polyvol/measure.hpp"

namespace polyvol {
namespace {

TEST(PerturbationBounds, RandomMovesStayWithinThem) {
    std::mt19937_64 rng(11);
    for (const Mesh& base : {generate::uv_sphere(16, 32, 2.0, 10, -3, 4), generate::torus(32, 12)}) {
        const double delta = 1e-7;
        const PerturbationBounds b = perturbation_bounds(base.view(), delta, true);
        const MassProperties m0 = mass_properties(base.view());
        ASSERT_TRUE(m0.volume_correctly_rounded && m0.moments_correctly_rounded);
        double seen_v = 0, seen_f = 0, seen_s = 0;
        std::uniform_real_distribution<double> move(-delta, delta);
        for (int round = 0; round < 20; ++round) {
            Mesh m = base;
            for (double& x : m.positions) x += move(rng) * (round % 2 ? 1.0 : 0.999);  // |Δx| <= delta, and rounding
            const MassProperties m1 = mass_properties(m.view());
            const double ulp_v = std::nextafter(std::fabs(m0.volume), INFINITY) - std::fabs(m0.volume);
            EXPECT_LE(std::fabs(m1.volume - m0.volume), b.volume + 2 * ulp_v);
            EXPECT_LE(std::fabs(m1.volume - m0.volume), b.swept_volume + 2 * ulp_v);
            for (int i = 0; i < 3; ++i)
                EXPECT_LE(std::fabs(m1.first_moments[i] - m0.first_moments[i]), b.first_moments + 1e-15 * std::fabs(m0.first_moments[i]));
            for (int k = 0; k < 6; ++k)
                EXPECT_LE(std::fabs(m1.second_moments[k] - m0.second_moments[k]), b.second_moments + 1e-15 * std::fabs(m0.second_moments[k]));
            EXPECT_LE(std::fabs(m1.area - m0.area), b.area + 1e-14 * m0.area);
            EXPECT_LE(std::fabs(m1.edge_length - m0.edge_length), b.edge_length + 1e-14 * m0.edge_length);
            seen_v = std::max(seen_v, std::fabs(m1.volume - m0.volume));
            seen_f = std::max(seen_f, std::fabs(m1.first_moments[0] - m0.first_moments[0]));
            seen_s = std::max(seen_s, std::fabs(m1.second_moments[0] - m0.second_moments[0]));
        }
        EXPECT_GT(seen_v + seen_f + seen_s, 0);
    }
    // Scaling the sphere of radius 2 about its centre by 1 + δ/2 moves no
    // coordinate by more than δ and its volume by about 4π r² δ/2 · 2.
    const Mesh sphere = generate::uv_sphere(16, 32, 2.0, 10, -3, 4);
    const double delta = 1e-7;
    Mesh grown = sphere;
    const double centre[3] = {10, -3, 4};
    for (std::size_t i = 0; i < grown.positions.size(); ++i)
        grown.positions[i] = centre[i % 3] + (grown.positions[i] - centre[i % 3]) * (1 + 0.999 * delta / 2);
    const double moved = mass_properties(grown.view()).volume - mass_properties(sphere.view()).volume;
    const PerturbationBounds b = perturbation_bounds(sphere.view(), delta, true);
    EXPECT_LE(moved, b.volume);
    EXPECT_LT(b.volume, 20 * moved);
    EXPECT_LT(b.volume, perturbation_bounds(sphere.view(), delta, false).volume);  // about the origin: looser
}

// widen_for_coordinate_error turns the claims into bounds that hold.
TEST(PerturbationBounds, WidenedGuaranteesAreBounds) {
    const Mesh sphere = generate::uv_sphere(12, 24, 1.5, 2, 2, 2);
    MassProperties m = mass_properties(sphere.view());
    const double v = m.volume;
    widen_for_coordinate_error(sphere.view(), 1e-12, 2.0, true, false, m);
    EXPECT_FALSE(m.volume_correctly_rounded);
    EXPECT_FALSE(m.moments_correctly_rounded);
    EXPECT_EQ(m.volume, v);
    EXPECT_GT(m.volume_error_bound, 0);
    EXPECT_LT(m.volume_error_bound, 1e-9);
    EXPECT_GT(m.moments_relative_error, 0x1p-53);
    EXPECT_LT(m.moments_relative_error, 1e-8);
    MassProperties same = mass_properties(sphere.view());
    widen_for_coordinate_error(sphere.view(), 0, 2.0, true, false, same);
    EXPECT_TRUE(same.volume_correctly_rounded);
}

}  // namespace
}  // namespace polyvol

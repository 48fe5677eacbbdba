// Polygons with holes and islands: (3.1) and (3.2), exact areas and
// centroids, orientation by nesting.
#include <gtest/gtest.h>

#include <gmpxx.h>

#include <cmath>
#include <random>

#include "exact/rational.hpp"
#include "polyvol/simplicial.hpp"

using namespace polyvol;

namespace {

std::vector<double> square(double x0, double y0, double side, bool ccw) {
    std::vector<double> s{x0, y0, x0 + side, y0, x0 + side, y0 + side, x0, y0 + side};
    if (!ccw) s = {x0, y0, x0, y0 + side, x0 + side, y0 + side, x0 + side, y0};
    return s;
}

ChainOptions with(SimplexFormula f) {
    ChainOptions o;
    o.formula = f;
    return o;
}

}  // namespace

TEST(Polygon, HolesAndIslandsAddUp) {
    Polygons p;
    p.add_loop(square(0, 0, 10, true));   // 100
    p.add_loop(square(2, 2, 6, false));   // -36
    p.add_loop(square(4, 4, 2, true));    // +4 island in the hole
    p.add_loop(square(20, 0, 1, true));   // +1 separate
    for (SimplexFormula f : {SimplexFormula::cone, SimplexFormula::prism}) {
        const ChainVolume a = polygon_area(p.view(), with(f));
        EXPECT_TRUE(a.volume_correctly_rounded);
        EXPECT_EQ(a.volume, 69.0);
        EXPECT_EQ(a.topology.unmatched_faces, 0u);
        EXPECT_EQ(a.topology.components, 4u);
        // centroid: (100*5 - 36*5 + 4*5 + 1*20.5) / 69
        EXPECT_EQ(a.centroid[0], (500.0 - 180 + 20 + 20.5) / 69);
        EXPECT_EQ(a.centroid[1], (500.0 - 180 + 20 + 0.5) / 69);
        EXPECT_TRUE(a.centroid_correctly_rounded);
    }
}

// A hole wound like its outer loop counts as land: the loops against the
// rule are found by nesting (#33 item 14), islands in holes included.
TEST(Polygon, LoopsWoundLikeTheirContainer) {
    Polygons right;
    right.add_loop(square(0, 0, 10, true));
    right.add_loop(square(2, 2, 6, false));
    right.add_loop(square(4, 4, 2, true));
    right.add_loop(square(20, 0, 1, true));
    EXPECT_TRUE(loops_wound_like_their_container(right.view()).empty());
    Polygons wrong;
    wrong.add_loop(square(0, 0, 10, true));
    wrong.add_loop(square(2, 2, 6, true));    // a hole wound like its outer loop
    wrong.add_loop(square(4, 4, 2, true));    // an island wound like that hole
    wrong.add_loop(square(12, 0, 4, false));  // outside everything: clockwise, but no container
    EXPECT_EQ(loops_wound_like_their_container(wrong.view()), (std::vector<uint32_t>{1, 2}));
    EXPECT_EQ(polygon_area(wrong.view()).volume, 100.0 + 36 + 4 - 16);  // what the rule gives for it
    Polygons all_clockwise;
    all_clockwise.add_loop(square(0, 0, 10, false));
    all_clockwise.add_loop(square(2, 2, 6, false));
    EXPECT_EQ(loops_wound_like_their_container(all_clockwise.view()), (std::vector<uint32_t>{1}));
}

TEST(Polygon, OrientByNesting) {
    Polygons p;
    p.add_loop(square(0, 0, 10, false));  // every loop clockwise
    p.add_loop(square(2, 2, 6, false));
    p.add_loop(square(4, 4, 2, false));
    Chain c = polygon_chain(p.view());
    const OrientResult o = orient_chain(c);
    EXPECT_TRUE(o.orientable);
    EXPECT_EQ(o.components, 3u);
    EXPECT_EQ(o.undecided, 0u);
    EXPECT_EQ(o.flipped, 8u);  // the outer square and the island
    EXPECT_EQ(chain_volume(c.view()).volume, 68.0);
}

TEST(Polygon, CorrectlyRoundedWhereNaiveSumsFail) {
    // A random star polygon translated by 1e9: the exact area rounded once,
    // the same by both formulas and equal to an independent GMP shoelace.
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.5, 1.5);
    std::vector<double> xy;
    const int k = 1000;
    for (int i = 0; i < k; ++i) {
        const double t = 2 * M_PI * i / k;
        xy.push_back(1e9 + u(rng) * std::cos(t));
        xy.push_back(-1e9 + u(rng) * std::sin(t));
    }
    Polygons p;
    p.add_loop(xy);
    mpq_class twice = 0;
    for (int i = 0; i < k; ++i) {
        const int j = (i + 1) % k;
        twice += mpq_class(xy[2 * i]) * mpq_class(xy[2 * j + 1]) - mpq_class(xy[2 * j]) * mpq_class(xy[2 * i + 1]);
    }
    const mpq_class area = twice / 2;
    const double want = exact::round_to_double(area.get_mpq_t());
    EXPECT_EQ(polygon_area(p.view(), with(SimplexFormula::cone)).volume, want);
    EXPECT_EQ(polygon_area(p.view(), with(SimplexFormula::prism)).volume, want);
    ChainOptions bounded;
    bounded.accuracy = ChainAccuracy::bounded;
    const ChainVolume b = polygon_area(p.view(), bounded);
    mpq_class diff = mpq_class(b.volume) - area;
    if (diff < 0) diff = -diff;
    EXPECT_LE(diff, mpq_class(b.volume_error_bound));
}

TEST(Polygon, DegenerateLoopsContributeNothing) {
    Polygons p;
    p.add_loop(std::vector<double>{1, 1});
    p.add_loop(std::vector<double>{0, 0, 3, 3});
    p.add_loop(square(0, 0, 1, true));
    const ChainVolume a = polygon_area(p.view());
    EXPECT_EQ(a.volume, 1.0);
    EXPECT_EQ(a.topology.unmatched_faces, 0u);
}

// The union and the intersection of several bodies per cell: exact in every
// cell, contact cells included, against closed forms (boxes: inclusion–
// exclusion per cell; integer boxes: unit cubes counted per cell), against
// boolean_volumes (cells add up to the exact union and intersection, and
// the union's surface to its area), under refinement (8 children add up to
// their parent), and for any number of threads.
#include <gtest/gtest.h>

#include <tbb/global_control.h>

#include <random>

#include "common/generate.hpp"
#include "grid_fixtures.hpp"
#include "polyvol/boolean.hpp"

namespace {

using namespace polyvol;
using test::box;
using test::box_overlap;
using Box = std::array<std::array<double, 3>, 2>;

// Does the surface of box [lo, hi] enter the open cell (c0, c1)?
bool surface_enters(const Box& b, const double c0[3], const double c1[3]) {
    bool overlaps = true, inside = true;
    for (int a = 0; a < 3; ++a) {
        overlaps = overlaps && b[0][a] < c1[a] && b[1][a] > c0[a];
        inside = inside && b[0][a] <= c0[a] && b[1][a] >= c1[a];
    }
    return overlaps && !inside;
}

double overlap(const Box& b, const double c0[3], const double c1[3]) { return box_overlap(b[0], b[1], c0, c1); }

Box common(const Box& a, const Box& b) {
    Box r;
    for (int d = 0; d < 3; ++d) {
        r[0][d] = std::max(a[0][d], b[0][d]);
        r[1][d] = std::max(r[0][d], std::min(a[1][d], b[1][d]));
    }
    return r;
}

// Two boxes on grid g: every cell's union and intersection equal
// V_a + V_b - V_ab and V_ab (each within 1e-15 of the cell's volume), the
// cells where both surfaces enter are the contact cells, and the totals are
// the closed forms. Returns the number of contact cells.
std::size_t check_two_boxes(const Box& ba, const Box& bb, const GridAxes& g) {
    const Mesh a = box(ba[0], ba[1]), b = box(bb[0], bb[1]);
    const auto r = test::run_grid({&a, &b}, g, false, true);
    const Box both = common(ba, bb);
    std::size_t contact = 0;
    for (std::size_t i = 0; i < g.nx(); ++i)
        for (std::size_t j = 0; j < g.ny(); ++j)
            for (std::size_t k = 0; k < g.nz(); ++k) {
                const double c0[3] = {g.x[i], g.y[j], g.z[k]}, c1[3] = {g.x[i + 1], g.y[j + 1], g.z[k + 1]};
                const std::size_t c = g.cell(i, j, k);
                const double cell = g.cell_volume(i, j, k), tol = 1e-15 * cell;
                const double va = overlap(ba, c0, c1), vb = overlap(bb, c0, c1), vab = overlap(both, c0, c1);
                EXPECT_NEAR(r.union_volumes[c], va + vb - vab, tol) << i << " " << j << " " << k;
                EXPECT_NEAR(r.intersection[c], vab, tol) << i << " " << j << " " << k;
                const bool two = surface_enters(ba, c0, c1) && surface_enters(bb, c0, c1);
                const bool full = va == cell || vb == cell;
                if (two && !full) ++contact;
                EXPECT_EQ(r.cls[c] == CellClass::contact, two && !full) << i << " " << j << " " << k;
            }
    auto vol = [](const Box& x) { return (x[1][0] - x[0][0]) * (x[1][1] - x[0][1]) * (x[1][2] - x[0][2]); };
    const auto& s = r.summary;
    EXPECT_EQ(s.contact_cells, contact);
    EXPECT_EQ(s.full_cells + s.empty_cells + s.cut_cells + s.contact_cells, g.cell_count());
    EXPECT_NEAR(s.union_volume, vol(ba) + vol(bb) - vol(both), 1e-15);
    EXPECT_NEAR(s.intersection_volume, vol(both), 1e-15);
    return contact;
}

TEST(GridUnion, TwoOverlappingBoxesExactInEveryCell) {
    const Box a{{{0.11, 0.13, 0.17}, {0.63, 0.71, 0.59}}}, b{{{0.37, 0.29, 0.41}, {0.93, 0.83, 0.87}}};
    EXPECT_GT(check_two_boxes(a, b, uniform_axes({0, 0, 0, 1, 1, 1}, {9, 10, 11})), 10u);
    EXPECT_GT(check_two_boxes(a, b, uniform_axes({0, 0, 0, 1, 1, 1}, {4, 4, 4})), 3u);
}

TEST(GridUnion, TouchingSharingNestedAndIdenticalBoxes) {
    // Faces off the grid planes, so that the contact cells hold them.
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {7, 6, 5});
    const Box a{{{0.1, 0.15, 0.2}, {0.5, 0.6, 0.7}}};
    check_two_boxes(a, {{{0.5, 0.2, 0.3}, {0.9, 0.55, 0.65}}}, g);  // touching at a face
    check_two_boxes(a, {{{0.5, 0.6, 0.2}, {0.9, 0.8, 0.4}}}, g);    // touching along an edge
    check_two_boxes(a, {{{0.5, 0.6, 0.7}, {0.8, 0.9, 0.95}}}, g);   // at a corner
    check_two_boxes(a, {{{0.3, 0.15, 0.2}, {0.9, 0.6, 0.45}}}, g);  // overlapping, three faces in common planes
    check_two_boxes(a, {{{0.2, 0.3, 0.35}, {0.4, 0.5, 0.55}}}, g);  // nested
    check_two_boxes(a, a, g);                                       // identical
}

TEST(GridUnion, RandomIntegerBoxesCountedCubeByCube) {
    std::mt19937 rng(20261126);
    std::uniform_int_distribution<int> lo(0, 4), len(1, 3);
    // Cells of 6.7 / 9 that no integer plane meets at a cell face.
    const GridAxes g = uniform_axes({-0.35, -0.35, -0.35, 6.35, 6.35, 6.35}, {9, 9, 9});
    for (int round = 0; round < 4; ++round) {
        std::vector<Box> boxes;
        std::vector<Mesh> meshes;
        for (int n = 0; n < 3 + round % 2; ++n) {
            Box b;
            for (int d = 0; d < 3; ++d) {
                b[0][d] = lo(rng);
                b[1][d] = b[0][d] + len(rng);
            }
            boxes.push_back(b);
            meshes.push_back(box(b[0], b[1]));
        }
        std::vector<const Mesh*> ptrs;
        for (const Mesh& m : meshes) ptrs.push_back(&m);
        const auto r = test::run_grid(ptrs, g, false, true);
        // Each unit cube [x, x+1]^3 is in the union (all) when some (every) box holds it.
        std::vector<double> uni(g.cell_count(), 0), all(g.cell_count(), 0);
        for (int x = 0; x < 7; ++x)
            for (int y = 0; y < 7; ++y)
                for (int z = 0; z < 7; ++z) {
                    int holders = 0;
                    for (const Box& b : boxes)
                        holders += b[0][0] <= x && x + 1 <= b[1][0] && b[0][1] <= y && y + 1 <= b[1][1] &&
                                   b[0][2] <= z && z + 1 <= b[1][2];
                    if (holders == 0) continue;
                    const Box cube{{{double(x), double(y), double(z)}, {x + 1.0, y + 1.0, z + 1.0}}};
                    for (std::size_t i = 0; i < g.nx(); ++i)
                        for (std::size_t j = 0; j < g.ny(); ++j)
                            for (std::size_t k = 0; k < g.nz(); ++k) {
                                const double c0[3] = {g.x[i], g.y[j], g.z[k]};
                                const double c1[3] = {g.x[i + 1], g.y[j + 1], g.z[k + 1]};
                                const double v = overlap(cube, c0, c1);
                                uni[g.cell(i, j, k)] += v;
                                if (holders == static_cast<int>(boxes.size())) all[g.cell(i, j, k)] += v;
                            }
                }
        for (std::size_t c = 0; c < g.cell_count(); ++c) {
            ASSERT_NEAR(r.union_volumes[c], uni[c], 1e-14) << round << " " << c;
            ASSERT_NEAR(r.intersection[c], all[c], 1e-14) << round << " " << c;
        }
    }
}

TEST(GridUnion, SpheresAddUpToTheBooleanVolumesAndRefine) {
    const Mesh a = generate::uv_sphere(20, 40), b = generate::uv_sphere(18, 36, 0.8, 0.5, 0.3, 0.2);
    const BooleanVolumes exact = boolean_volumes(a.view(), b.view());
    ASSERT_EQ(exact.status, BooleanStatus::ok);
    const GridAxes coarse = uniform_axes({-1.1, -1.1, -1.1, 1.4, 1.4, 1.4}, {10, 10, 10});
    const GridAxes fine = uniform_axes({-1.1, -1.1, -1.1, 1.4, 1.4, 1.4}, {20, 20, 20});
    const auto rc = test::run_grid({&a, &b}, coarse, false, true);
    const auto rf = test::run_grid({&a, &b}, fine, false, true);
    for (const auto* r : {&rc, &rf}) {
        EXPECT_GT(r->summary.contact_cells, 20u);
        EXPECT_NEAR(r->summary.union_volume, exact.union_volume, 1e-14 * exact.union_volume);
        EXPECT_NEAR(r->summary.intersection_volume, exact.intersection, 1e-14 * exact.union_volume);
        // The union's surface: its area, and a closed surface's zero net normal.
        double area = 0, n[3] = {0, 0, 0};
        for (std::size_t c = 0; c < r->union_area.size(); ++c) {
            area += r->union_area[c];
            for (int k = 0; k < 3; ++k) n[k] += r->union_normal[3 * c + k];
        }
        EXPECT_NEAR(area, exact.area_union, exact.area_error_bound + 1e-13 * exact.area_union);
        for (double x : n) EXPECT_NEAR(x, 0, 1e-13);
    }
    // Each coarse cell is its 8 children.
    for (std::size_t i = 0; i < coarse.nx(); ++i)
        for (std::size_t j = 0; j < coarse.ny(); ++j)
            for (std::size_t k = 0; k < coarse.nz(); ++k) {
                double u = 0, x = 0;
                for (std::size_t d = 0; d < 8; ++d) {
                    const std::size_t f = fine.cell(2 * i + (d & 1), 2 * j + (d >> 1 & 1), 2 * k + (d >> 2));
                    u += rf.union_volumes[f];
                    x += rf.intersection[f];
                }
                const std::size_t c = coarse.cell(i, j, k);
                const double tol = 1e-14 * coarse.cell_volume(i, j, k);
                EXPECT_NEAR(rc.union_volumes[c], u, tol) << i << " " << j << " " << k;
                EXPECT_NEAR(rc.intersection[c], x, tol) << i << " " << j << " " << k;
            }
}

TEST(GridUnion, TheSameBitsOnOneThread) {
    const Mesh a = generate::uv_sphere(16, 32), b = generate::uv_sphere(14, 28, 0.8, 0.5, 0.3, 0.2);
    const GridAxes g = uniform_axes({-1.1, -1.1, -1.1, 1.4, 1.4, 1.4}, {24, 24, 24});
    const auto many = test::run_grid({&a, &b}, g, false, true);
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const auto single = test::run_grid({&a, &b}, g, false, true);
    EXPECT_EQ(many.union_volumes, single.union_volumes);
    EXPECT_EQ(many.intersection, single.intersection);
    EXPECT_EQ(many.union_area, single.union_area);
}

TEST(GridUnion, OneBodyIsItsOwnUnionAndIntersection) {
    const Mesh a = box({0.11, 0.13, 0.17}, {0.63, 0.71, 0.59});
    const GridAxes g = uniform_axes({0, 0, 0, 1, 1, 1}, {5, 6, 7});
    const auto r = test::run_grid({&a}, g, false, true);
    EXPECT_EQ(r.union_volumes, r.volumes);
    EXPECT_EQ(r.intersection, r.volumes);
    EXPECT_EQ(r.summary.contact_cells, 0u);
    EXPECT_EQ(r.summary.union_volume, r.summary.bodies[0].volume);
}

// Not closed: the windings of the other body disagree along its edges.
TEST(GridUnion, AnOpenBodyCrossingAnotherHasNoUnion) {
    Mesh open = box({0.1, 0.1, 0.1}, {0.6, 0.6, 0.6});
    open.indices.resize(open.indices.size() - 3);  // one face triangle less
    const Mesh b = box({0.3, 0.3, 0.3}, {0.9, 0.9, 0.9});
    EXPECT_THROW(test::run_grid({&open, &b}, uniform_axes({0, 0, 0, 1, 1, 1}, {4, 4, 4}), false, true),
                 std::invalid_argument);
}

}  // namespace

namespace {
// A body that is the union of two overlapping boxes (grid_union_volumes, a
// file whose shells overlap): its cells are the union's by inclusion–
// exclusion, within [0, cell volume], and the summary's counts are the
// union's cell classes.
TEST(GridUnion, ABodyOfOverlappingPartsIsTheirUnionInEveryCell) {
    const Box a{{{0.1, 0.2, 0.3}, {2.1, 2.2, 2.3}}}, b{{{1.05, 0.9, 1.3}, {3.05, 2.9, 3.3}}};
    const Mesh ma = box(a[0], a[1]), mb = box(b[0], b[1]);
    const std::vector<std::vector<MeshView>> parts{{ma.view(), mb.view()}};
    const GridAxes g = uniform_axes({-0.5, -0.5, -0.5, 3.5, 3.5, 3.5}, {9, 8, 7});
    std::vector<double> volumes(g.cell_count());
    std::vector<CellClass> classes(g.cell_count());
    const GridSummary s = grid_union_volumes(parts, g, GridBlock{{0, 0, 0}, {g.nx(), g.ny(), g.nz()}},
                                             GridOutput{.volumes = volumes, .cell_class = classes},
                                             test::test_options());
    test::expect_test_device(s);
    const Box k = common(a, b);
    double total = 0;
    std::size_t counted[4] = {0, 0, 0, 0};
    for (std::size_t i = 0; i < g.nx(); ++i)
        for (std::size_t j = 0; j < g.ny(); ++j)
            for (std::size_t l = 0; l < g.nz(); ++l) {
                const double c0[3] = {g.x[i], g.y[j], g.z[l]}, c1[3] = {g.x[i + 1], g.y[j + 1], g.z[l + 1]};
                const double want = overlap(a, c0, c1) + overlap(b, c0, c1) - overlap(k, c0, c1);
                const double v = volumes[g.cell(i, j, l)], cell = g.cell_volume(i, j, l);
                EXPECT_NEAR(v, want, 1e-15 * cell) << i << " " << j << " " << l;
                EXPECT_GE(v, -4e-16 * cell);
                EXPECT_LE(v, cell * (1 + 4e-16));
                total += v;
                ++counted[static_cast<int>(classes[g.cell(i, j, l)])];
            }
    const double exact = 8 + 8 - (k[1][0] - k[0][0]) * (k[1][1] - k[0][1]) * (k[1][2] - k[0][2]);
    EXPECT_NEAR(s.bodies[0].volume, exact, 1e-13);
    EXPECT_NEAR(total, exact, 1e-13);
    EXPECT_EQ(s.union_volume, s.bodies[0].volume);
    EXPECT_EQ(s.full_cells, counted[1]);
    EXPECT_EQ(s.empty_cells, counted[0]);
    EXPECT_EQ(s.cut_cells, counted[2]);
    EXPECT_EQ(s.contact_cells, counted[3]);
    EXPECT_GT(s.contact_cells, 0u);
    EXPECT_EQ(s.bodies[0].cut_cells, counted[2] + counted[3]);
}
}  // namespace

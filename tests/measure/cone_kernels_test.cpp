// The cone kernels (measure/cone_kernels.cpp) on every Highway target this
// CPU runs: each must give the scalar target's bits, sum for sum and bound
// for bound, on meshes with every shape of work (partial blocks, polygon
// faces, several parallel ranges, soups, far from and around the origin).
#include <gtest/gtest.h>

#include <bit>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "common/kernel_levels.hpp"
#include "cone_fixtures.hpp"
#include "exact/rational.hpp"
#include "measure/cone.hpp"
#include "measure/cone_kernels.hpp"

using namespace polyvol;
using namespace polyvol::measure::cone;
using polyvol::fixtures::as_mpq;
namespace fx = polyvol::fixtures;

namespace {

std::vector<Mesh> meshes() {
    std::mt19937_64 rng(5);
    std::vector<Mesh> ms;
    ms.push_back(fx::unit_tetrahedron());
    ms.push_back(fx::box(1e6, 1e6, 1e6, 1e6 + 1, 1e6 + 2, 1e6 + 3, true));  // quads
    ms.push_back(fx::random_sphere(rng, 3, 1.0, {0, 0, 0}));
    ms.push_back(fx::random_sphere(rng, 6, 2.0, {1e6, -2e6, 3e6}));  // 32768 faces: several ranges
    Mesh soup = fx::random_sphere(rng, 4, 1.0, {0.25, 0, 0});
    Mesh split;  // every corner its own vertex
    for (std::size_t f = 0; f < soup.face_count(); ++f) {
        uint32_t v[3];
        for (int c = 0; c < 3; ++c) {
            const double* p = &soup.positions[3 * std::size_t{soup.indices[3 * f + c]}];
            v[c] = split.add_vertex(p[0], p[1], p[2]);
        }
        split.add_triangle(v[0], v[1], v[2]);
    }
    ms.push_back(std::move(split));
    return ms;
}

// Everything the kernels compute on one mesh, as exact rationals and bounds.
struct Results {
    std::vector<std::string> values;
    void add(const ConeSums& s) {
        for (int k = 0; k < s.count; ++k) {
            values.push_back(as_mpq(s.sum[k]).get_str());
            values.push_back(std::to_string(std::bit_cast<uint64_t>(s.bound[k])));
        }
        values.push_back(std::to_string(s.triangles));
    }
};

Results run_all(const Mesh& m) {
    Results r;
    const MeshView v = m.view();
    for (int count : {1, static_cast<int>(kSxx), static_cast<int>(kSumCount)})
        for (Precision p : {Precision::fast, Precision::double_double}) r.add(filtered_sums(v, count, p));
    for (VolumeForm form : {VolumeForm::translated, VolumeForm::origin}) {
        bool safe = false;
        const ConeSums s = filtered_volume(v, safe, form);
        EXPECT_TRUE(safe);
        r.add(s);
    }
    ConeSums e = filtered_sums(v, kSumCount, Precision::double_double);
    exact_sums(v, (1u << kSumCount) - 1, e);
    r.add(e);
    // One block through the streamed path's entry points.
    TriangleBlock b;
    for (int i = 0; i < kBlockTriangles && static_cast<std::size_t>(i) < m.face_count(); ++i, ++b.n)
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) b.c[3 * c + k][i] = m.positions[3 * std::size_t{m.indices[3 * i + c]} + k];
    exact::ExactSum sum, magnitude, exact_volume;
    filtered_volume_block(b, sum, magnitude);
    exact_block_sums(b, 1u << kV, &exact_volume);
    r.values.push_back(as_mpq(sum).get_str());
    r.values.push_back(as_mpq(magnitude).get_str());
    r.values.push_back(as_mpq(exact_volume).get_str());
    return r;
}

}  // namespace

TEST(ConeKernels, EveryTargetGivesTheScalarTargetsBits) {
    polyvol::test::LevelGuard guard;
    const std::vector<simd::Level> levels = simd::available_levels();
    ASSERT_FALSE(levels.empty());
    ASSERT_EQ(levels.back(), simd::Level::scalar);
    for (const Mesh& m : meshes()) {
        simd::limit_to(simd::Level::scalar);
        const Results reference = run_all(m);
        for (simd::Level l : levels) {
            SCOPED_TRACE(simd::level_name(l));
            simd::limit_to(l);
            ASSERT_EQ(simd::level(), l);
            // Only AVX-512 checks what it reads cheaply: the dispatch followed.
            EXPECT_EQ(kernels_check_what_they_read(), l == simd::Level::avx512);
            const Results r = run_all(m);
            ASSERT_EQ(r.values.size(), reference.values.size());
            for (std::size_t i = 0; i < r.values.size(); ++i) EXPECT_EQ(r.values[i], reference.values[i]) << i;
        }
    }
}

// The targets this machine runs are named in the test log, so a run on an
// AVX2-only machine shows that it could not test AVX-512.
TEST(ConeKernels, TheMachinesTargetsAreListed) {
    std::string names;
    for (simd::Level l : simd::available_levels()) names += simd::level_name(l) + " ";
    std::cout << "kernel targets: " << names << "\n";
    EXPECT_TRUE(names.find("SCALAR") != std::string::npos || names.find("EMU128") != std::string::npos) << names;
}

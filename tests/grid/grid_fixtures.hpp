// Shared helpers for the grid tests: closed-form cell volumes and a runner
// (the solids are common/shapes.hpp's).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "common/opencl_device.hpp"
#include "common/shapes.hpp"
#include "polyvol/device.hpp"
#include "polyvol/grid.hpp"
#include "polyvol/mesh.hpp"

namespace polyvol::test {

// Volume of [lo, hi] ∩ [c0, c1].
inline double box_overlap(const std::array<double, 3>& lo, const std::array<double, 3>& hi, const double c0[3],
                          const double c1[3]) {
    double v = 1;
    for (int a = 0; a < 3; ++a) v *= std::max(0.0, std::min(hi[a], c1[a]) - std::max(lo[a], c0[a]));
    return v;
}

struct GridRun {
    std::vector<double> volumes, moments, union_volumes, intersection, union_area, union_normal;
    std::vector<CellClass> cls;
    GridSummary summary;
};

inline GridRun run_grid_on(const std::vector<const Mesh*>& meshes, const GridAxes& g, bool moments, bool with_union,
                           const DeviceRequest& device) {
    std::vector<MeshView> views;
    for (const Mesh* m : meshes) views.push_back(m->view());
    GridRun r;
    const std::size_t cells = g.cell_count();
    r.volumes.assign(views.size() * cells, -1);
    GridOutput out{.volumes = r.volumes};
    if (moments) {
        r.moments.assign(3 * views.size() * cells, -1);
        out.first_moments = r.moments;
    }
    if (with_union) {  // also the intersection and the union's surface
        r.union_volumes.assign(cells, -1);
        r.intersection.assign(cells, -1);
        r.union_area.assign(cells, -1);
        r.union_normal.assign(3 * cells, -1);
        r.cls.assign(cells, CellClass::empty);
        out.union_volumes = r.union_volumes;
        out.intersection_volumes = r.intersection;
        out.union_wetted_area = r.union_area;
        out.union_surface_normal = r.union_normal;
        out.cell_class = r.cls;
    }
    r.summary = grid_volumes(views, g, out, {.device = device});
    return r;
}

// The device of the opencl.* copies of the grid tests (POLYVOL_TEST_DEVICE),
// or null: unset, or no usable device where POLYVOL_TEST_ALLOW_NO_DEVICE=1
// (sanitizer builds; elsewhere a missing device fails the test).
inline const char* test_device() {
    const char* device = std::getenv("POLYVOL_TEST_DEVICE");
    if (!device || !*device) return nullptr;
    if (no_device_allowed() && !usable_opencl_device()) return nullptr;
    return device;
}

// The options of a test's direct grid calls: on the test device when there
// is one (their own checks then hold on the device), else the CPU.
inline GridOptions test_options() {
    const char* device = test_device();
    return {.device = device ? parse_device(device) : DeviceRequest{DeviceKind::cpu, -1}};
}

// With a test device, the summary of a direct call says the device computed.
inline void expect_test_device(const GridSummary& s) {
    if (test_device()) {
        EXPECT_TRUE(s.device.starts_with("opencl: ")) << s.device;
    }
}

inline bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

// The grid on the CPU; with POLYVOL_TEST_DEVICE set (ctest's opencl.* copies
// of these tests), also on that device, every output and summary field
// expected to be the CPU's bits.
inline GridRun run_grid(const std::vector<const Mesh*>& meshes, const GridAxes& g, bool moments = false,
                        bool with_union = false) {
    GridRun r = run_grid_on(meshes, g, moments, with_union, {DeviceKind::cpu, -1});
    if (const char* device = test_device()) {
        const GridRun d = run_grid_on(meshes, g, moments, with_union, parse_device(device));
        EXPECT_TRUE(d.summary.device.starts_with("opencl: ")) << d.summary.device;
        EXPECT_TRUE(same_bits(r.volumes, d.volumes) && same_bits(r.moments, d.moments) &&
                    same_bits(r.union_volumes, d.union_volumes) && same_bits(r.intersection, d.intersection) &&
                    same_bits(r.union_area, d.union_area) && same_bits(r.union_normal, d.union_normal) &&
                    r.cls == d.cls)
            << "the device's cells differ from the CPU's";
        const GridSummary &c = r.summary, &e = d.summary;
        EXPECT_EQ(c.bodies.size(), e.bodies.size());
        for (std::size_t b = 0; b < std::min(c.bodies.size(), e.bodies.size()); ++b) {
            EXPECT_EQ(std::memcmp(&c.bodies[b].volume, &e.bodies[b].volume, sizeof(double)), 0);
            EXPECT_EQ(c.bodies[b].triangles, e.bodies[b].triangles);
            EXPECT_EQ(c.bodies[b].pieces, e.bodies[b].pieces);
            EXPECT_EQ(c.bodies[b].full_cells, e.bodies[b].full_cells);
            EXPECT_EQ(c.bodies[b].empty_cells, e.bodies[b].empty_cells);
            EXPECT_EQ(c.bodies[b].cut_cells, e.bodies[b].cut_cells);
        }
        EXPECT_EQ(std::memcmp(&c.union_volume, &e.union_volume, sizeof(double)), 0);
        EXPECT_EQ(std::memcmp(&c.intersection_volume, &e.intersection_volume, sizeof(double)), 0);
        EXPECT_EQ(c.crossing_pairs, e.crossing_pairs);
        EXPECT_EQ(c.full_cells, e.full_cells);
        EXPECT_EQ(c.empty_cells, e.empty_cells);
        EXPECT_EQ(c.cut_cells, e.cut_cells);
        EXPECT_EQ(c.contact_cells, e.contact_cells);
    }
    return r;
}

inline GridRun run_grid(const Mesh& m, const GridAxes& g, bool moments = false) {
    return run_grid(std::vector<const Mesh*>{&m}, g, moments);
}

}  // namespace polyvol::test

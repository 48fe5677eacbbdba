// The grid on an OpenCL device (pocl on the CI's CPU): every output and every
// summary field bit for bit the CPU path's — corpus meshes on several grids,
// spheres and tori with moments and surfaces, blocks, non-uniform planes,
// several bodies — and the bad states: the kernel's capacity exceeded (the
// CPU runs), no fp64, a kernel that does not build, the union (on the CPU).
//
// Without a usable OpenCL device these tests fail, since the README installs
// pocl; POLYVOL_TEST_ALLOW_NO_DEVICE=1 makes them skip instead (sanitizer
// builds, whose runtime cannot see into the driver).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/generate.hpp"
#include "common/manifest.hpp"
#include "device/opencl.hpp"
#include "grid_fixtures.hpp"
#include "polyvol/device.hpp"
#include "polyvol/grid.hpp"
#include "polyvol/io.hpp"

namespace {

using namespace polyvol;

bool device_present() {
    for (const DeviceInfo& d : list_devices().devices)
        if (d.usable) return true;
    return false;
}

#define REQUIRE_DEVICE()                                                                           \
    do {                                                                                           \
        if (!device_present()) {                                                                   \
            const char* allow = std::getenv("POLYVOL_TEST_ALLOW_NO_DEVICE");                       \
            if (allow && std::string(allow) == "1") GTEST_SKIP() << "no usable OpenCL device";     \
            FAIL() << "no usable OpenCL device (install pocl-opencl-icd): " << list_devices().note; \
        }                                                                                          \
    } while (0)

// Every output a grid run can fill, for the comparison.
struct Outputs {
    std::vector<double> volumes, moments, area, normal, union_area, union_normal;
    GridSummary summary;
};

Outputs run(std::span<const MeshView> bodies, const GridAxes& g, const GridBlock& block, bool moments, bool surface,
            DeviceKind kind) {
    Outputs o;
    const std::size_t cells = block.cell_count(), nb = bodies.size();
    o.volumes.assign(nb * cells, -7);
    GridOutput out{.volumes = o.volumes};
    if (moments) {
        o.moments.assign(3 * nb * cells, -7);
        out.first_moments = o.moments;
    }
    if (surface) {
        o.area.assign(nb * cells, -7);
        o.normal.assign(3 * nb * cells, -7);
        out.wetted_area = o.area;
        out.surface_normal = o.normal;
        if (nb == 1) {
            o.union_area.assign(cells, -7);
            o.union_normal.assign(3 * cells, -7);
            out.union_wetted_area = o.union_area;
            out.union_surface_normal = o.union_normal;
        }
    }
    o.summary = grid_block_volumes(bodies, g, block, out, {.device = {kind, -1}});
    return o;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

std::size_t first_difference(const std::vector<double>& a, const std::vector<double>& b) {
    for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
        if (std::memcmp(&a[i], &b[i], sizeof(double)) != 0) return i;
    return a.size();
}

// The device's outputs and summary against the CPU's, bit for bit.
void expect_same_as_cpu(std::span<const MeshView> bodies, const GridAxes& g, const GridBlock& block, bool moments,
                        bool surface, const std::string& what) {
    const Outputs cpu = run(bodies, g, block, moments, surface, DeviceKind::cpu);
    const Outputs dev = run(bodies, g, block, moments, surface, DeviceKind::opencl);
    EXPECT_EQ(cpu.summary.device, "cpu") << what;
    EXPECT_TRUE(dev.summary.device.starts_with("opencl: ")) << what << ": " << dev.summary.device;
    const std::pair<const char*, std::pair<const std::vector<double>*, const std::vector<double>*>> arrays[] = {
        {"volumes", {&cpu.volumes, &dev.volumes}},         {"moments", {&cpu.moments, &dev.moments}},
        {"wetted area", {&cpu.area, &dev.area}},           {"normal", {&cpu.normal, &dev.normal}},
        {"union area", {&cpu.union_area, &dev.union_area}}, {"union normal", {&cpu.union_normal, &dev.union_normal}}};
    for (const auto& [name, pair] : arrays) {
        const std::size_t at = first_difference(*pair.first, *pair.second);
        EXPECT_TRUE(same_bits(*pair.first, *pair.second))
            << what << ": " << name << " differ first at " << at << ": "
            << (at < pair.first->size() ? (*pair.first)[at] : 0.0) << " vs "
            << (at < pair.second->size() ? (*pair.second)[at] : 0.0);
    }
    ASSERT_EQ(cpu.summary.bodies.size(), dev.summary.bodies.size());
    for (std::size_t b = 0; b < cpu.summary.bodies.size(); ++b) {
        const GridBodySummary &c = cpu.summary.bodies[b], &d = dev.summary.bodies[b];
        EXPECT_EQ(std::memcmp(&c.volume, &d.volume, sizeof(double)), 0) << what << ": " << c.volume << " " << d.volume;
        EXPECT_EQ(c.triangles, d.triangles) << what;
        EXPECT_EQ(c.pieces, d.pieces) << what;
        EXPECT_EQ(c.full_cells, d.full_cells) << what;
        EXPECT_EQ(c.empty_cells, d.empty_cells) << what;
        EXPECT_EQ(c.cut_cells, d.cut_cells) << what;
    }
    EXPECT_EQ(cpu.summary.full_cells, dev.summary.full_cells) << what;
    EXPECT_EQ(cpu.summary.empty_cells, dev.summary.empty_cells) << what;
    EXPECT_EQ(cpu.summary.cut_cells, dev.summary.cut_cells) << what;
    if (!std::isnan(cpu.summary.union_volume)) {
        EXPECT_EQ(std::memcmp(&cpu.summary.union_volume, &dev.summary.union_volume, sizeof(double)), 0) << what;
    }
}

GridBlock whole(const GridAxes& g) { return {{0, 0, 0}, {g.nx(), g.ny(), g.nz()}}; }

TEST(DeviceParse, NamesAndErrors) {
    EXPECT_EQ(parse_device("auto").kind, DeviceKind::automatic);
    EXPECT_EQ(parse_device("cpu").kind, DeviceKind::cpu);
    EXPECT_EQ(parse_device("opencl").kind, DeviceKind::opencl);
    EXPECT_EQ(parse_device("opencl").index, -1);
    EXPECT_EQ(parse_device("opencl:3").index, 3);
    for (const char* bad : {"", "gpu", "opencl:", "opencl:-1", "opencl:x", "opencl:1x", "CPU"})
        EXPECT_THROW(parse_device(bad), std::invalid_argument) << bad;
}

TEST(DeviceList, PoclIsListedAsACpuDeviceWithFp64) {
    REQUIRE_DEVICE();
    const DeviceList list = list_devices();
    EXPECT_TRUE(list.runtime);
    bool cpu_device = false;
    for (const DeviceInfo& d : list.devices) {
        EXPECT_FALSE(d.name.empty());
        EXPECT_GT(d.global_memory, 0u);
        EXPECT_GT(d.compute_units, 0u);
        if (d.type == "cpu" && d.usable) cpu_device = d.fp64;
    }
    EXPECT_TRUE(cpu_device) << "pocl's CPU device with cl_khr_fp64";
}

TEST(DeviceGrid, SphereAndTorusEveryOutputOnSeveralGrids) {
    REQUIRE_DEVICE();
    const Mesh meshes[2] = {generate::uv_sphere(24, 48, 1.0, 0.013, -0.021, 0.007), generate::torus(40, 24)};
    for (const Mesh& m : meshes) {
        const MeshView views[1] = {m.view()};
        for (const uint32_t n : {5u, 16u, 33u}) {
            const GridAxes g = make_grid(views, {.cells = n});
            expect_same_as_cpu(views, g, whole(g), false, false, "cells " + std::to_string(n));
            expect_same_as_cpu(views, g, whole(g), true, true, "moments and surfaces, cells " + std::to_string(n));
        }
    }
}

TEST(DeviceGrid, BlocksBelowTheTopAndAtAnOffset) {
    REQUIRE_DEVICE();
    const Mesh m = generate::torus(48, 20);
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 24});
    const GridBlock blocks[] = {{{0, 0, 0}, {g.nx(), g.ny(), g.nz() / 2}},
                                {{3, 5, 2}, {g.nx() - 4, g.ny() - 1, g.nz() - 3}},
                                {{7, 0, g.nz() / 2}, {8, g.ny(), g.nz()}}};
    for (const GridBlock& b : blocks) expect_same_as_cpu(views, g, b, true, true, "block");
}

TEST(DeviceGrid, PlanesThroughVerticesAndUnevenPlanes) {
    REQUIRE_DEVICE();
    // A box whose faces lie on grid planes, and uneven planes through a sphere.
    const Mesh box = test::box({0, 0, 0}, {2, 3, 1});
    const MeshView bv[1] = {box.view()};
    GridAxes on;
    on.x = {-1, 0, 0.5, 1, 2, 3};
    on.y = {-0.5, 0, 1, 1.5, 3, 3.5};
    on.z = {0, 0.25, 1, 2};
    expect_same_as_cpu(bv, on, whole(on), true, true, "planes through the box's faces");
    const Mesh sphere = generate::uv_sphere(16, 32);
    const MeshView sv[1] = {sphere.view()};
    GridAxes uneven;
    for (double v = -1.3; v < 1.3; v += 0.1 + 0.07 * std::abs(std::sin(7 * v))) {
        uneven.x.push_back(v);
        uneven.y.push_back(0.9 * v + 0.01);
        uneven.z.push_back(v * std::abs(v) + 0.003);
    }
    expect_same_as_cpu(sv, uneven, whole(uneven), true, true, "uneven planes");
}

TEST(DeviceGrid, SeveralBodiesWithoutTheUnion) {
    REQUIRE_DEVICE();
    const Mesh a = generate::uv_sphere(20, 40, 1.0), b = generate::uv_sphere(20, 40, 0.8, 0.5, 0.3, 0.1);
    const MeshView views[2] = {a.view(), b.view()};
    const GridAxes g = make_grid(views, {.cells = 20});
    expect_same_as_cpu(views, g, whole(g), true, true, "two bodies");
}

TEST(DeviceGrid, CorpusMeshesOnThreeGrids) {
    REQUIRE_DEVICE();
    const auto paths = test::manifest_paths([](const nlohmann::json& e) {
        return !test::invalid_entry(e) && e.contains("volume") && e.contains("topology") &&
               e["topology"].value("closed_2_cycle", false);
    });
    ASSERT_GE(paths.size(), 50u);
    std::size_t checked = 0;
    for (const std::string& p : paths) {
        const LoadedMesh loaded = read_mesh_file(test::corpus_file(p));
        const MeshView views[1] = {loaded.mesh.view()};
        if (views[0].triangle_count() == 0 || views[0].triangle_count() > 200000) continue;
        for (const uint32_t n : {17u, 24u})
            expect_same_as_cpu(views, make_grid(views, {.cells = n}), whole(make_grid(views, {.cells = n})), n == 24,
                               n == 17, p + " at " + std::to_string(n));
        ++checked;
    }
    EXPECT_GE(checked, 50u);
}

TEST(DeviceGrid, APolygonBeyondTheCapacityRunsOnTheCpuWithTheSameBits) {
    REQUIRE_DEVICE();
    const Mesh m = generate::uv_sphere(12, 24);
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 12});
    const Outputs cpu = run(views, g, whole(g), true, true, DeviceKind::cpu);
    device::fail_points().capacity = 3;  // a triangle cut by one plane has 4 vertices
    const Outputs dev = run(views, g, whole(g), true, true, DeviceKind::opencl);
    device::fail_points().capacity = 0;
    EXPECT_EQ(dev.summary.device, "cpu (a clipped polygon exceeded the device kernel's capacity)");
    EXPECT_TRUE(same_bits(cpu.volumes, dev.volumes));
    EXPECT_TRUE(same_bits(cpu.moments, dev.moments));
    EXPECT_TRUE(same_bits(cpu.area, dev.area)) << "the device's partial surface sums are cleared";
    EXPECT_TRUE(same_bits(cpu.normal, dev.normal));
}

TEST(DeviceGrid, NoFp64IsRefusedByName) {
    REQUIRE_DEVICE();
    const Mesh m = test::box({0, 0, 0}, {1, 1, 1});
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 4});
    device::fail_points().no_fp64 = true;
    try {
        (void)run(views, g, whole(g), false, false, DeviceKind::opencl);
        ADD_FAILURE() << "no DeviceError";
    } catch (const DeviceError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("cl_khr_fp64"), std::string::npos) << msg;
        EXPECT_NE(msg.find(list_devices().devices.front().name), std::string::npos) << msg;
    }
    device::fail_points().no_fp64 = false;
}

TEST(DeviceGrid, AKernelThatDoesNotBuildGivesTheCompilersLog) {
    REQUIRE_DEVICE();
    const Mesh m = test::box({0, 0, 0}, {1, 1, 1});
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 4});
    device::fail_points().bad_kernel = true;
    try {
        (void)run(views, g, whole(g), false, false, DeviceKind::opencl);
        ADD_FAILURE() << "no DeviceError";
    } catch (const DeviceError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("do not build"), std::string::npos) << msg;
        EXPECT_NE(msg.find("polyvol test: a kernel that does not build"), std::string::npos) << msg;
    }
    device::fail_points().bad_kernel = false;
}

TEST(DeviceGrid, TheUnionsCellsRunOnTheCpuAndSaySo) {
    REQUIRE_DEVICE();
    const Mesh a = test::box({0, 0, 0}, {2, 2, 2}), b = test::box({1, 1, 1}, {3, 3, 3});
    const std::vector<const Mesh*> meshes{&a, &b};
    std::vector<MeshView> views{a.view(), b.view()};
    const GridAxes g = make_grid(views, {.cells = 6});
    std::vector<double> vol(2 * g.cell_count()), uni(g.cell_count());
    const GridSummary s = grid_volumes(views, g, {.volumes = vol, .union_volumes = uni}, {.device = {DeviceKind::opencl, -1}});
    EXPECT_EQ(s.device, "cpu (the union's cells run on the CPU)");
    EXPECT_EQ(s.union_volume, 15.0);
    // One body's cell classes are the union's too: also the CPU's.
    std::vector<CellClass> cls(g.cell_count());
    std::vector<double> one(g.cell_count());
    const MeshView first[1] = {views[0]};
    EXPECT_EQ(grid_volumes(first, g, {.volumes = one, .cell_class = cls}, {.device = {DeviceKind::opencl, -1}}).device,
              "cpu (the union's cells run on the CPU)");
}

TEST(DeviceGrid, AnIndexBeyondTheDevicesIsAnError) {
    REQUIRE_DEVICE();
    const Mesh m = test::box({0, 0, 0}, {1, 1, 1});
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 4});
    std::vector<double> vol(g.cell_count());
    EXPECT_THROW(grid_volumes(views, g, {.volumes = vol}, {.device = {DeviceKind::opencl, 99}}), DeviceError);
}

}  // namespace

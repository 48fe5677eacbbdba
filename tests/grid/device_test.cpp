// The grid on an OpenCL device (pocl on the CI's CPU): every output and every
// summary field bit for bit the CPU path's — corpus meshes on several grids,
// spheres and tori with moments and surfaces, blocks, non-uniform planes,
// several bodies with their union and intersection — and the bad states: the
// kernel's capacity exceeded (the CPU runs), no fp64, a kernel that does not build.
//
// Without a usable OpenCL device these tests fail, since the README installs
// pocl; POLYVOL_TEST_ALLOW_NO_DEVICE=1 makes them skip instead (sanitizer
// builds, whose runtime cannot see into the driver).
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/generate.hpp"
#include "common/manifest.hpp"
#include "common/opencl_device.hpp"
#include "device/opencl.hpp"
#include "grid_fixtures.hpp"
#include "polyvol/device.hpp"
#include "polyvol/grid.hpp"
#include "polyvol/io.hpp"

namespace {

using namespace polyvol;


// Every output a grid run can fill, for the comparison.
struct Outputs {
    std::vector<double> volumes, moments, area, normal, union_area, union_normal, union_volumes, intersection;
    std::vector<CellClass> classes;
    GridSummary summary;
};

struct Asked {
    bool moments = false, surface = false, with_union = false;
};

Outputs run(std::span<const MeshView> bodies, const GridAxes& g, const GridBlock& block, Asked asked, DeviceKind kind) {
    const bool moments = asked.moments, surface = asked.surface;
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
        if (nb == 1 || asked.with_union) {
            o.union_area.assign(cells, -7);
            o.union_normal.assign(3 * cells, -7);
            out.union_wetted_area = o.union_area;
            out.union_surface_normal = o.union_normal;
        }
    }
    if (asked.with_union) {
        o.union_volumes.assign(cells, -7);
        o.classes.assign(cells, CellClass::contact);
        out.union_volumes = o.union_volumes;
        out.cell_class = o.classes;
        if (nb > 1) {
            o.intersection.assign(cells, -7);
            out.intersection_volumes = o.intersection;
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
void expect_same_as_cpu(std::span<const MeshView> bodies, const GridAxes& g, const GridBlock& block, Asked asked,
                        const std::string& what) {
    const Outputs cpu = run(bodies, g, block, asked, DeviceKind::cpu);
    const Outputs dev = run(bodies, g, block, asked, DeviceKind::opencl);
    EXPECT_EQ(cpu.summary.device, "cpu") << what;
    EXPECT_TRUE(dev.summary.device.starts_with("opencl: ")) << what << ": " << dev.summary.device;
    const std::pair<const char*, std::pair<const std::vector<double>*, const std::vector<double>*>> arrays[] = {
        {"volumes", {&cpu.volumes, &dev.volumes}},         {"moments", {&cpu.moments, &dev.moments}},
        {"wetted area", {&cpu.area, &dev.area}},           {"normal", {&cpu.normal, &dev.normal}},
        {"union area", {&cpu.union_area, &dev.union_area}}, {"union normal", {&cpu.union_normal, &dev.union_normal}},
        {"union volumes", {&cpu.union_volumes, &dev.union_volumes}},
        {"intersection", {&cpu.intersection, &dev.intersection}}};
    for (const auto& [name, pair] : arrays) {
        const std::size_t at = first_difference(*pair.first, *pair.second);
        EXPECT_TRUE(same_bits(*pair.first, *pair.second))
            << what << ": " << name << " differ first at " << at << ": "
            << (at < pair.first->size() ? (*pair.first)[at] : 0.0) << " vs "
            << (at < pair.second->size() ? (*pair.second)[at] : 0.0);
    }
    EXPECT_TRUE(cpu.classes == dev.classes) << what << ": cell classes differ";
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
    EXPECT_EQ(cpu.summary.contact_cells, dev.summary.contact_cells) << what;
    EXPECT_EQ(cpu.summary.crossing_pairs, dev.summary.crossing_pairs) << what;
    if (!std::isnan(cpu.summary.intersection_volume)) {
        EXPECT_EQ(std::memcmp(&cpu.summary.intersection_volume, &dev.summary.intersection_volume, sizeof(double)), 0)
            << what;
    }
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
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const DeviceList list = list_devices();
    EXPECT_TRUE(list.runtime);
    bool cpu_device = false;
    for (const DeviceInfo& d : list.devices) {
        EXPECT_FALSE(d.name.empty());
        EXPECT_GT(d.global_memory, 0u);
        EXPECT_GT(d.compute_units, 0u);
        EXPECT_EQ(d.usable, d.fp64) << d.name << ": usable exactly when it has IEEE double";
        EXPECT_EQ(d.reason.empty(), d.usable) << d.name;
        cpu_device = cpu_device || (d.type == "cpu" && d.usable);
    }
    EXPECT_TRUE(cpu_device) << "pocl's CPU device, usable";
}

TEST(DeviceGrid, SphereAndTorusEveryOutputOnSeveralGrids) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const Mesh meshes[2] = {generate::uv_sphere(24, 48, 1.0, 0.013, -0.021, 0.007), generate::torus(40, 24)};
    for (const Mesh& m : meshes) {
        const MeshView views[1] = {m.view()};
        for (const uint32_t n : {5u, 16u, 33u}) {
            const GridAxes g = make_grid(views, {.cells = n});
            expect_same_as_cpu(views, g, whole(g), {}, "cells " + std::to_string(n));
            expect_same_as_cpu(views, g, whole(g), {true, true}, "moments and surfaces, cells " + std::to_string(n));
        }
    }
}

TEST(DeviceGrid, BlocksBelowTheTopAndAtAnOffset) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const Mesh m = generate::torus(48, 20);
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 24});
    const GridBlock blocks[] = {{{0, 0, 0}, {g.nx(), g.ny(), g.nz() / 2}},
                                {{3, 5, 2}, {g.nx() - 4, g.ny() - 1, g.nz() - 3}},
                                {{7, 0, g.nz() / 2}, {8, g.ny(), g.nz()}}};
    for (const GridBlock& b : blocks) expect_same_as_cpu(views, g, b, {true, true}, "block");
}

TEST(DeviceGrid, PlanesThroughVerticesAndUnevenPlanes) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    // A box whose faces lie on grid planes, and uneven planes through a sphere.
    const Mesh box = test::box({0, 0, 0}, {2, 3, 1});
    const MeshView bv[1] = {box.view()};
    GridAxes on;
    on.x = {-1, 0, 0.5, 1, 2, 3};
    on.y = {-0.5, 0, 1, 1.5, 3, 3.5};
    on.z = {0, 0.25, 1, 2};
    expect_same_as_cpu(bv, on, whole(on), {true, true}, "planes through the box's faces");
    const Mesh sphere = generate::uv_sphere(16, 32);
    const MeshView sv[1] = {sphere.view()};
    GridAxes uneven;
    for (double v = -1.3; v < 1.3; v += 0.1 + 0.07 * std::abs(std::sin(7 * v))) {
        uneven.x.push_back(v);
        uneven.y.push_back(0.9 * v + 0.01);
        uneven.z.push_back(v * std::abs(v) + 0.003);
    }
    expect_same_as_cpu(sv, uneven, whole(uneven), {true, true}, "uneven planes");
}

TEST(DeviceGrid, SeveralBodiesWithoutTheUnion) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const Mesh a = generate::uv_sphere(20, 40, 1.0), b = generate::uv_sphere(20, 40, 0.8, 0.5, 0.3, 0.1);
    const MeshView views[2] = {a.view(), b.view()};
    const GridAxes g = make_grid(views, {.cells = 20});
    expect_same_as_cpu(views, g, whole(g), {true, true}, "two bodies without the union");
}

TEST(DeviceGrid, CorpusMeshesOnTwoGrids) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
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
            expect_same_as_cpu(views, make_grid(views, {.cells = n}), whole(make_grid(views, {.cells = n})),
                               {n == 24, n == 17, n == 17}, p + " at " + std::to_string(n));
        ++checked;
    }
    EXPECT_GE(checked, 50u);
}

TEST(DeviceGrid, APolygonBeyondTheCapacityRunsOnTheCpuWithTheSameBits) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    // One body: a small tetrahedron inside one cell of the first row (its
    // triangles are never split) and a box through later rows (split, so
    // beyond a capacity of 3). Batches of one row: the first batch writes the
    // tetrahedron's surface before the box's batch overflows.
    Mesh m = test::box({3.5, 0.5, 0.5}, {6.5, 2.5, 2.5});
    const auto base = static_cast<uint32_t>(m.positions.size() / 3);
    for (const double v : {0.2, 0.2, 0.2, 0.8, 0.2, 0.2, 0.2, 0.8, 0.2, 0.2, 0.2, 0.8}) m.positions.push_back(v);
    for (const uint32_t i : {0u, 2u, 1u, 0u, 1u, 3u, 0u, 3u, 2u, 1u, 2u, 3u}) m.indices.push_back(base + i);
    const MeshView views[1] = {m.view()};
    const GridAxes g = uniform_axes({0, 0, 0, 8, 3, 3}, {8, 3, 3});
    const Outputs cpu = run(views, g, whole(g), {true, true}, DeviceKind::cpu);
    EXPECT_GT(cpu.area[0 * 9 + 0], 0.0) << "the tetrahedron's cell has area";
    device::fail_points().capacity = 3;  // a triangle cut by one plane has 4 vertices
    device::fail_points().max_buffer = 2 << 10;  // batches of one row
    const Outputs dev = run(views, g, whole(g), {true, true}, DeviceKind::opencl);
    device::fail_points() = {};
    EXPECT_EQ(dev.summary.device, "cpu (a clipped polygon exceeded the device kernel's capacity)");
    EXPECT_TRUE(same_bits(cpu.volumes, dev.volumes));
    EXPECT_TRUE(same_bits(cpu.moments, dev.moments));
    EXPECT_TRUE(same_bits(cpu.area, dev.area)) << "the device's partial surface sums are cleared";
    EXPECT_TRUE(same_bits(cpu.normal, dev.normal));
    EXPECT_TRUE(same_bits(cpu.union_area, dev.union_area));
}

TEST(DeviceGrid, OutOfDeviceMemoryHalvesTheBatchesWithTheSameBits) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const Mesh m = generate::uv_sphere(20, 40);
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 24});
    const Outputs cpu = run(views, g, whole(g), {true, true}, DeviceKind::cpu);
    device::fail_points().max_buffer = 100 << 10;  // the whole grid's sums need about 1.3 MiB
    const Outputs dev = run(views, g, whole(g), {true, true}, DeviceKind::opencl);
    device::fail_points().max_buffer = 0;
    EXPECT_TRUE(dev.summary.device.starts_with("opencl: ")) << dev.summary.device;
    EXPECT_TRUE(same_bits(cpu.volumes, dev.volumes));
    EXPECT_TRUE(same_bits(cpu.moments, dev.moments));
    EXPECT_TRUE(same_bits(cpu.area, dev.area));
    EXPECT_TRUE(same_bits(cpu.normal, dev.normal));
    EXPECT_TRUE(same_bits(cpu.union_area, dev.union_area));
    EXPECT_TRUE(same_bits(cpu.union_normal, dev.union_normal));
    EXPECT_EQ(cpu.summary.bodies[0].pieces, dev.summary.bodies[0].pieces);
}

TEST(DeviceGrid, SeveralBatchesOfTwoBodiesWithTheirUnionMomentsAndSurfaces) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const Mesh s1 = generate::uv_sphere(20, 40), s2 = generate::uv_sphere(18, 36, 0.8, 0.5, 0.3, 0.2);
    const MeshView spheres[2] = {s1.view(), s2.view()};
    const GridAxes g = make_grid(spheres, {.cells = 20});
    device::fail_points().max_buffer = 200 << 10;  // several batches of rows
    expect_same_as_cpu(spheres, g, whole(g), {true, true, true}, "batches, union, moments, surfaces");
    expect_same_as_cpu(spheres, g, {{1, 2, 3}, {g.nx() - 2, g.ny() - 1, g.nz() - 4}}, {true, true, true},
                       "batches of a block");
    device::fail_points().max_buffer = 0;
}

TEST(DeviceGrid, OutOfDeviceMemoryBelowOneRowIsAClearError) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const Mesh m = generate::uv_sphere(20, 40);
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 24});
    device::fail_points().max_buffer = 20 << 10;  // the mesh fits, one row of sums does not
    try {
        (void)run(views, g, whole(g), {true, false}, DeviceKind::opencl);
        ADD_FAILURE() << "no DeviceError";
    } catch (const DeviceError& e) {
        EXPECT_NE(std::string(e.what()).find("CL_MEM_OBJECT_ALLOCATION_FAILURE"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("one row of"), std::string::npos) << e.what();
    }
    device::fail_points().max_buffer = 0;
}

TEST(DeviceGrid, NoFp64IsRefusedByName) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const Mesh m = test::box({0, 0, 0}, {1, 1, 1});
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 4});
    device::fail_points().no_fp64 = true;
    try {
        (void)run(views, g, whole(g), {}, DeviceKind::opencl);
        ADD_FAILURE() << "no DeviceError";
    } catch (const DeviceError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("cl_khr_fp64"), std::string::npos) << msg;
        EXPECT_NE(msg.find(list_devices().devices.front().name), std::string::npos) << msg;
    }
    device::fail_points().no_fp64 = false;
}

TEST(DeviceGrid, AKernelThatDoesNotBuildGivesTheCompilersLog) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const Mesh m = test::box({0, 0, 0}, {1, 1, 1});
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 4});
    device::fail_points().bad_kernel = true;
    try {
        (void)run(views, g, whole(g), {}, DeviceKind::opencl);
        ADD_FAILURE() << "no DeviceError";
    } catch (const DeviceError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("do not build"), std::string::npos) << msg;
        EXPECT_NE(msg.find("polyvol test: a kernel that does not build"), std::string::npos) << msg;
    }
    device::fail_points().bad_kernel = false;
}

TEST(DeviceGrid, TheUnionAndIntersectionOfTwoBodies) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    // Overlapping, touching at a face and nested boxes, and two spheres; one body's classes.
    const Mesh a = test::box({0.11, 0.13, 0.17}, {0.63, 0.71, 0.59}), b = test::box({0.37, 0.29, 0.41}, {0.93, 0.83, 0.87}),
               c = test::box({0.63, 0.2, 0.2}, {0.9, 0.5, 0.5}), inner = test::box({0.2, 0.2, 0.2}, {0.4, 0.4, 0.4});
    const Mesh s1 = generate::uv_sphere(20, 40), s2 = generate::uv_sphere(18, 36, 0.8, 0.5, 0.3, 0.2);
    const GridAxes boxes = uniform_axes({0, 0, 0, 1, 1, 1}, {9, 10, 11});
    const std::vector<std::pair<std::vector<const Mesh*>, std::string>> cases{
        {{&a, &b}, "overlapping"}, {{&a, &c}, "touching at a face"}, {{&a, &inner}, "nested"},
        {{&a, &a}, "identical"}, {{&a}, "one body's classes"}};
    for (const auto& [meshes, what] : cases) {
        std::vector<MeshView> views;
        for (const Mesh* m : meshes) views.push_back(m->view());
        expect_same_as_cpu(views, boxes, whole(boxes), {.surface = true, .with_union = true}, what);
    }
    const MeshView spheres[2] = {s1.view(), s2.view()};
    for (const uint32_t n : {12u, 31u}) {
        const GridAxes g = make_grid(spheres, {.cells = n});
        expect_same_as_cpu(spheres, g, whole(g), {.surface = true, .with_union = true}, "spheres " + std::to_string(n));
        expect_same_as_cpu(spheres, g, {{2, 1, 3}, {g.nx() - 1, g.ny(), g.nz() - 2}}, {.with_union = true},
                           "a block of the spheres " + std::to_string(n));
    }
}

TEST(DeviceGrid, AnIndexBeyondTheDevicesIsAnError) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const Mesh m = test::box({0, 0, 0}, {1, 1, 1});
    const MeshView views[1] = {m.view()};
    const GridAxes g = make_grid(views, {.cells = 4});
    std::vector<double> vol(g.cell_count());
    EXPECT_THROW(grid_volumes(views, g, {.volumes = vol}, {.device = {DeviceKind::opencl, 99}}), DeviceError);
}

}  // namespace

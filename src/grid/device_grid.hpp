// grid/device_grid.hpp — private: the grid's per-column work on an OpenCL
// device (grid_kernels.cl), the same bits as the CPU's tiles.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "device/opencl.hpp"
#include "exact/exact_sum.hpp"
#include "polyvol/grid.hpp"

namespace polyvol::grid {

// One body as the CPU path prepared it: positions, fan triangles (3 indices
// each), its triangles listed per tile (entries[offsets[t] .. offsets[t+1]))
// and, with the union, the levels each whole triangle lies on (bit l).
struct DeviceBody {
    std::span<const double> positions;
    std::span<const uint32_t> triangles;
    std::span<const std::size_t> offsets;
    std::span<const uint32_t> entries;
    std::span<const uint8_t> level_bits;
};

// The union's cells: the crossed triangles' parts of each level's boundary
// (level 0 the union, level 1 the intersection), every level's fan triangles
// in one mesh of unshared vertices; level l's triangles listed per tile at
// entries[offsets[l * (tiles + 1) + t] ...]. No levels: one body's union.
struct DeviceLevels {
    std::size_t count = 0;
    std::vector<double> positions, normals;  // normals: 3 per triangle
    std::vector<uint32_t> triangles;
    std::vector<std::size_t> offsets;
    std::vector<uint32_t> entries;
};

// The block's columns and the CPU path's tiles (grid_volumes.cpp Layout).
struct DeviceLayout {
    int i0, j0, k0;  // the block's first cell
    int nx, ny, bnz;
    int tile, nty;
};

struct DeviceCounts {
    std::size_t empty = 0, full = 0, cut = 0, pieces = 0;
};

struct DeviceResult {
    std::vector<DeviceCounts> bodies;
    // with the union's cells: its classes' counts and the exact sums of the
    // union's and the intersection's cells
    std::size_t full = 0, empty = 0, cut = 0, contact = 0;
    exact::ExactSum union_volume, intersection_volume;
    // wall seconds: building the kernels (once per device and process), the
    // kernels, copies to and from the device
    double build_seconds = 0, kernel_seconds = 0, transfer_seconds = 0;
};

// Writes what `out` asks for and returns the counts, or false when a
// clipped polygon exceeded the kernel's capacity (the caller then runs the
// CPU path over the whole block). `levels` null: no union cells asked for.
// Throws DeviceError for a device that fails (its canary, a build, memory).
bool device_columns(device::Device& d, const GridAxes& g, const DeviceLayout& l, std::span<const DeviceBody> bodies,
                    const DeviceLevels* levels, const GridOutput& out, DeviceResult& result);

}  // namespace polyvol::grid

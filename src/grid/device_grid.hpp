// grid/device_grid.hpp — private: the grid's per-column work on an OpenCL
// device (grid_kernels.cl), the same bits as the CPU's tiles.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "device/opencl.hpp"
#include "polyvol/grid.hpp"

namespace polyvol::grid {

// One body as the CPU path prepared it: positions, fan triangles (3 indices
// each) and its triangles listed per tile (entries[offsets[t] .. offsets[t+1])).
struct DeviceBody {
    std::span<const double> positions;
    std::span<const uint32_t> triangles;
    std::span<const std::size_t> offsets;
    std::span<const uint32_t> entries;
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

// Writes each body's volumes (and the moments and surfaces `out` asks for;
// the union's surface only for one body) and returns the cells' and pieces'
// counts per body, or false when a clipped polygon exceeded the kernel's
// capacity (the caller then runs the CPU path over the whole block). Throws
// DeviceError for a device that fails (its canary, a build, memory).
bool device_columns(device::Device& d, const GridAxes& g, const DeviceLayout& l, std::span<const DeviceBody> bodies,
                    const GridOutput& out, std::vector<DeviceCounts>& counts);

}  // namespace polyvol::grid

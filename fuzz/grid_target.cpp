// fuzz/grid_target.cpp — grid_volumes on a read mesh with a small grid
// (8 cells along the longest side, or the bounds and counts the input's
// first bytes choose), and with two bodies (the mesh and itself moved) the
// union. Invalid input is std::invalid_argument; nothing else may escape.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <vector>

#include "polyvol/grid.hpp"
#include "polyvol/io.hpp"
#include "polyvol/topology.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
    using namespace polyvol;
    if (size < 3) return 0;
    // Three bytes choose the grid: cells along the longest side (3..18), and
    // whether to use the union.
    const uint32_t cells = 3 + bytes[0] % 16;
    const bool two = (bytes[1] & 1) != 0;
    LoadedMesh loaded;
    try {
        loaded = read_mesh_memory({reinterpret_cast<const std::byte*>(bytes + 3), size - 3}, "f");
    } catch (const ReadError&) {
        return 0;
    }
    const MeshView view = loaded.mesh.view();
    if (!analyze_topology(view).closed_2_cycle) return 0;
    Mesh moved = loaded.mesh;
    for (std::size_t v = 0; v < moved.vertex_count(); ++v) moved.positions[3 * v] += 0.25 + bytes[2] / 64.0;
    std::vector<MeshView> bodies{view};
    if (two && view.triangle_count() <= 500) bodies.push_back(moved.view());
    try {
        const GridAxes g = make_grid(bodies, {.cells = cells});
        std::vector<double> volumes(bodies.size() * g.cell_count()), u(g.cell_count()), x(g.cell_count());
        std::vector<double> area(bodies.size() * g.cell_count()), normal(3 * area.size());
        GridOutput out{.volumes = volumes, .wetted_area = area, .surface_normal = normal};
        if (bodies.size() > 1) {
            out.union_volumes = u;
            out.intersection_volumes = x;
        }
        (void)grid_volumes(bodies, g, out);
    } catch (const std::invalid_argument&) {
    }
    return 0;
}

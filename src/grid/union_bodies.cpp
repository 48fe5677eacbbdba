// grid/union_bodies.cpp — polyvol/grid.hpp's grid_union_volumes: bodies
// that are unions of meshes, each as grid_volumes' union of its parts.
#include <algorithm>
#include <limits>
#include <optional>
#include <string>
#include <stdexcept>
#include <vector>

#include "polyvol/grid.hpp"

namespace polyvol {
namespace {

// Body b's slice of a per-body output of `n` values per cell (empty stays empty).
template <class T>
std::span<T> slice(std::span<T> all, std::size_t b, std::size_t cells, std::size_t n = 1) {
    return all.empty() ? all : all.subspan(b * cells * n, cells * n);
}

// Where the calls ran, each place named once ("opencl: X; cpu (why)"), and
// their device seconds added up.
void add_device(GridSummary& all, const GridSummary& one, bool first) {
    if (first)
        all.device = one.device;
    else if (("; " + all.device + "; ").find("; " + one.device + "; ") == std::string::npos)
        all.device += "; " + one.device;
    all.device_kernel_seconds += one.device_kernel_seconds;
    all.device_transfer_seconds += one.device_transfer_seconds;
    all.device_build_seconds += one.device_build_seconds;
}

}  // namespace

GridSummary grid_union_volumes(std::span<const std::vector<MeshView>> parts, const GridAxes& g, const GridBlock& block,
                               const GridOutput& out, const GridOptions& options) {
    std::vector<MeshView> all;
    for (const auto& p : parts) all.insert(all.end(), p.begin(), p.end());
    const bool unions = std::any_of(parts.begin(), parts.end(), [](const auto& p) { return p.size() > 1; });
    if (!unions) return grid_block_volumes(all, g, block, out, options);
    if (!out.first_moments.empty())
        throw std::invalid_argument("grid: the first moments of a body whose shells overlap are not computed "
                                    "(its solid's volumes are)");
    if (!out.intersection_volumes.empty())
        throw std::invalid_argument("grid: the intersection of bodies is not computed where a body's shells "
                                    "overlap (their union and each body's solid are)");
    const std::size_t nb = parts.size(), cells = block.cell_count();
    if (out.volumes.size() != nb * cells)
        throw std::invalid_argument("grid: volumes must hold bodies * cells = " + std::to_string(nb * cells) +
                                    " values, not " + std::to_string(out.volumes.size()));
    GridSummary s;
    std::vector<double> scratch;
    std::optional<GridSummary> one_union;  // one body of several parts: its union is the bodies' union
    for (std::size_t b = 0; b < nb; ++b) {
        GridOutput o;
        GridBodySummary body;
        if (parts[b].size() == 1) {
            o.volumes = slice(out.volumes, b, cells);
            o.wetted_area = slice(out.wetted_area, b, cells);
            o.surface_normal = slice(out.surface_normal, b, cells, 3);
            const GridSummary one = grid_block_volumes(parts[b], g, block, o, options);
            body = one.bodies[0];
            add_device(s, one, b == 0);
        } else {
            scratch.assign(parts[b].size() * cells, 0.0);
            o.volumes = scratch;
            o.union_volumes = slice(out.volumes, b, cells);
            o.union_wetted_area = slice(out.wetted_area, b, cells);
            o.union_surface_normal = slice(out.surface_normal, b, cells, 3);
            if (nb == 1) {
                o.cell_class = out.cell_class;
                if (o.union_wetted_area.empty()) o.union_wetted_area = out.union_wetted_area;
                if (o.union_surface_normal.empty()) o.union_surface_normal = out.union_surface_normal;
            }
            const GridSummary u = grid_block_volumes(parts[b], g, block, o, options);
            add_device(s, u, b == 0);
            body.volume = u.union_volume;
            for (const GridBodySummary& p : u.bodies) {
                body.triangles += p.triangles;
                body.pieces += p.pieces;
            }
            body.full_cells = u.full_cells;
            body.empty_cells = u.empty_cells;
            body.cut_cells = u.cut_cells + u.contact_cells;
            s.crossing_pairs += u.crossing_pairs;
            if (nb == 1) one_union = u;
        }
        s.bodies.push_back(body);
    }
    const bool union_outputs = !out.union_volumes.empty() || !out.cell_class.empty() ||
                               !out.union_wetted_area.empty() || !out.union_surface_normal.empty();
    if (one_union) {
        s.union_volume = one_union->union_volume;
        s.full_cells = one_union->full_cells;
        s.empty_cells = one_union->empty_cells;
        s.cut_cells = one_union->cut_cells;
        s.contact_cells = one_union->contact_cells;
        auto copy = [](std::span<const double> from, std::span<double> to) {
            if (!to.empty() && !from.empty() && from.data() != to.data()) std::copy(from.begin(), from.end(), to.begin());
        };
        copy(out.volumes, out.union_volumes);
        copy(out.wetted_area, out.union_wetted_area);
        copy(out.surface_normal, out.union_surface_normal);
    } else if (union_outputs) {
        scratch.assign(all.size() * cells, 0.0);
        GridOutput o = out;
        o.volumes = scratch;
        o.wetted_area = o.surface_normal = {};
        const GridSummary u = grid_block_volumes(all, g, block, o, options);
        add_device(s, u, false);
        s.union_volume = u.union_volume;
        s.full_cells = u.full_cells;
        s.empty_cells = u.empty_cells;
        s.cut_cells = u.cut_cells;
        s.contact_cells = u.contact_cells;
        s.crossing_pairs = u.crossing_pairs;  // every part against every other: the bodies' own pairs included
    } else {
        s.union_volume = std::numeric_limits<double>::quiet_NaN();
    }
    s.intersection_volume = std::numeric_limits<double>::quiet_NaN();
    return s;
}

}  // namespace polyvol

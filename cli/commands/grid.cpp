// `polyvol grid MESH... [--cells N | --cell-size H | --dims NX NY NZ]
//   [--bounds XMIN YMIN ZMIN XMAX YMAX ZMAX] [-o OUT] [--json] ...`
//
// Reads every mesh (exit 2 if one is unreadable), checks each is a closed
// 2-cycle (exit 3 otherwise), builds the grid, computes the volume of each
// body in every cell (polyvol/grid.hpp) and writes what was asked:
//   OUT.npy   float64, shape (nx, ny, nz), or (bodies, nx, ny, nz); index
//             [i][j][k] is the cell whose lower corner is (x_i, y_j, z_k)
//   OUT.vti   VTK ImageData with a cell array per body (+ the union's with
//             several bodies); OUT.vtr the same as RectilinearGrid (any planes)
//   --union / --intersection FILE.npy   (nx, ny, nz): the union's, the
//             intersection's volume per cell (exact in every cell)
//   OUT.json  the summary only (as --json prints it)
// Progress goes to stderr when the computation takes more than a second.
#include "commands/grid.hpp"
#include "grammar.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <string_view>

#include <nlohmann/json.hpp>

#include "polyvol/grid.hpp"
#include "polyvol/grid_io.hpp"
#include "polyvol/io.hpp"
#include "memory.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/solid.hpp"
#include "polyvol/topology.hpp"
#include "read_input.hpp"
#include "output/format.hpp"
#include "output/grid.hpp"

namespace polyvol::cli {
namespace {

int usage(const std::string& message) { return usage_error("grid", message); }

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

bool strictly_increasing(const std::vector<double>& c) {
    if (c.size() < 2) return false;
    for (std::size_t i = 0; i < c.size(); ++i)
        if (!std::isfinite(c[i]) || (i > 0 && !(c[i] > c[i - 1]))) return false;
    return true;
}

struct Slice {
    int axis = 2;
    double value = 0;
    bool given = false;
};

std::optional<Slice> parse_slice(const std::string& s) {
    Slice r;
    if (s.empty()) return r;
    if (s.size() < 3 || s[1] != '=' || (s[0] != 'x' && s[0] != 'y' && s[0] != 'z')) return std::nullopt;
    r.axis = s[0] - 'x';
    try {
        std::size_t used = 0;
        r.value = std::stod(s.substr(2), &used);
        if (used != s.size() - 2 || !std::isfinite(r.value)) return std::nullopt;
    } catch (const std::exception&) {
        return std::nullopt;
    }
    r.given = true;
    return r;
}

// The picture of one slice: fractions of the union (or the single body) in
// the cells the plane passes through, in world coordinates: columns along
// the first remaining axis, rows along the second, upwards; titled with the
// file(s) and the slice.
void write_slice_png(const std::string& path, const GridAxes& g, std::span<const double> occupancy, Slice slice,
                     const std::string& what) {
    const std::vector<double>* axes[3] = {&g.x, &g.y, &g.z};
    const std::vector<double>& c = *axes[slice.axis];
    if (!slice.given) slice.value = 0.5 * (c.front() + c.back());
    std::size_t s = static_cast<std::size_t>(std::upper_bound(c.begin(), c.end(), slice.value) - c.begin());
    s = s == 0 ? 0 : std::min(s - 1, c.size() - 2);
    const int a = slice.axis == 0 ? 1 : 0, b = slice.axis == 2 ? 1 : 2;  // picture's column and row axes
    const std::size_t n[3] = {g.nx(), g.ny(), g.nz()};
    const std::size_t w = n[a], h = n[b];
    std::vector<double> field(w * h);
    for (std::size_t j = 0; j < h; ++j)
        for (std::size_t i = 0; i < w; ++i) {
            std::size_t idx[3];
            idx[slice.axis] = s;
            idx[a] = i;
            idx[b] = j;
            field[j * w + i] = occupancy[g.cell(idx[0], idx[1], idx[2])] / g.cell_volume(idx[0], idx[1], idx[2]);
        }
    const char* names = "xyz";
    FieldPicture p;
    p.values = field;
    p.columns = *axes[a];
    p.rows = *axes[b];
    p.title = what + ": " + names[slice.axis] + " = " + shortest(slice.value) + " (cells " + shortest(c[s]) + " to " +
              shortest(c[s + 1]) + ")";
    p.column_label = std::string(1, names[a]);
    p.row_label = std::string(1, names[b]);
    p.value_label = "fraction";
    write_png_picture(path, p);
}

}  // namespace

CLI::App* add_grid_command(CLI::App& app, GridArgs& a) {
    auto* cmd = app.add_subcommand(
        "grid", "Exact volume of the solid(s) in every cell of a rectilinear grid (default: the bounding box "
                "padded by one cell, 128 cubic cells along the longest side)");
    cmd->add_option("meshes", a.files, "Closed meshes; several are several bodies (per-body volumes and their union)")
        ->required();
    auto* cells = cmd->add_option("--cells", a.cells, "Cells along the longest side, cubic cells")
                      ->check(whole_number(3, 1 << 20))
                      ->capture_default_str()
                      ->each([&a](const std::string&) { a.cells_given = true; });
    auto* size = cmd->add_option("--cell-size", a.cell_size, "Cubic cells of this edge length")
                     ->check(positive_number());
    auto* dims = cmd->add_option("--dims", a.dims, "Cells per axis: NX NY NZ")
                     ->expected(3)
                     ->check(whole_number(1, 1 << 20));
    cells->excludes(size)->excludes(dims);
    size->excludes(dims);
    cmd->add_option("--bounds", a.bounds, "Grid box XMIN YMIN ZMIN XMAX YMAX ZMAX (default: padded bounding box)")
        ->expected(6);
    cmd->add_option("--x-planes", a.x_planes, "Explicit x planes, comma-separated, increasing (non-uniform grids)")
        ->delimiter(',');
    cmd->add_option("--y-planes", a.y_planes, "Explicit y planes")->delimiter(',');
    cmd->add_option("--z-planes", a.z_planes, "Explicit z planes")->delimiter(',');
    cmd->add_option("-o,--output", a.out,
                    "OUT.npy (float64 (nx,ny,nz), body axis first with several), OUT.vti (VTK ImageData, "
                    "ParaView), OUT.vtr (VTK RectilinearGrid) or OUT.json (summary)");
    cmd->add_flag("--json", a.json, "Print the summary as JSON on stdout");
    cmd->add_flag("--fractions", a.fractions, "Write volume fractions (volume / cell volume) instead of volumes");
    cmd->add_option("--centroids", a.centroids, "Also write each cell's centroid of the solid: FILE.npy, shape (..., 3)");
    cmd->add_option("--union", a.union_out, "Also write the union's volume per cell: FILE.npy, shape (nx, ny, nz)");
    cmd->add_option("--intersection", a.intersection_out,
                    "Also write the volume per cell of the part inside every body: FILE.npy, shape (nx, ny, nz)");
    cmd->add_option("--surface", a.surface,
                    "Also write each cell's wetted area and area-weighted outward normal per body, the union's last "
                    "with several: FILE.npy, shape (..., 4): area, nx, ny, nz (and, with a .vti/.vtr output, the "
                    "arrays wetted_area and surface_normal)");
    cmd->add_option("--png", a.png, "Picture of one slice of the volume fractions (viridis)");
    add_solid_flags(cmd, a.solid_flags);
    add_unit_flags(cmd, a.unit_flags,
                   "The grid's unit: of --cell-size, --bounds and the planes typed, and of every length and volume "
                   "written (default: the first body's that is known); a body in another unit is converted into it");
    cmd->add_option("--max-memory", a.max_memory,
                    "Refuse a grid whose arrays would need more than SIZE (e.g. 8G, 512M; default: three quarters "
                    "of physical memory)");
    cmd->add_option("--device", a.device,
                    "Where the cells are computed: auto (the CPU), cpu, opencl, opencl:N (polyvol devices lists "
                    "them); the same bits on every device");
    cmd->add_option("--slice", a.slice, "The slice for --png: x=VALUE, y=VALUE or z=VALUE (default: middle z)");
    return cmd;
}

namespace {

// Everything about the arguments that can be checked before reading: the
// output names, the slice, the box, the planes. 0 when they are fine.
int check_arguments(const GridArgs& a, const std::string& out_ext, const std::optional<Slice>& slice) {
    if (!a.out.empty() && out_ext != ".npy" && out_ext != ".vti" && out_ext != ".vtr" && out_ext != ".json")
        return usage("-o needs a .npy, .vti, .vtr or .json file, not '" + a.out + "'");
    if (!a.centroids.empty() && lower_extension(a.centroids) != ".npy") return usage("--centroids needs a .npy file");
    if (!a.union_out.empty() && lower_extension(a.union_out) != ".npy") return usage("--union needs a .npy file");
    if (!a.intersection_out.empty() && lower_extension(a.intersection_out) != ".npy")
        return usage("--intersection needs a .npy file");
    if (!a.surface.empty() && lower_extension(a.surface) != ".npy") return usage("--surface needs a .npy file");
    if (!slice) return usage("--slice takes x=VALUE, y=VALUE or z=VALUE, not '" + a.slice + "'");
    try {
        (void)parse_device(a.device);
    } catch (const std::invalid_argument& e) {
        return usage(std::string("--") + e.what());
    }
    if (!a.slice.empty() && a.png.empty()) return usage("--slice goes with --png");
    if (!a.bounds.empty())
        for (int k = 0; k < 3; ++k)
            if (!(a.bounds[k] < a.bounds[k + 3]) || !std::isfinite(a.bounds[k]) || !std::isfinite(a.bounds[k + 3]))
                return usage("--bounds needs XMIN YMIN ZMIN XMAX YMAX ZMAX with each min < max");
    const std::vector<double>* planes[3] = {&a.x_planes, &a.y_planes, &a.z_planes};
    for (int k = 0; k < 3; ++k)
        if (!planes[k]->empty() && !strictly_increasing(*planes[k]))
            return usage(std::string("--") + static_cast<char>('x' + k) +
                               "-planes needs at least 2 finite, strictly increasing values");
    return Exit::ok;
}

// Explicit planes against the other grid options: a disagreement is an
// error, never a silent choice. 0 when they agree.
int check_planes(const GridArgs& a) {
    const std::vector<double>* planes[3] = {&a.x_planes, &a.y_planes, &a.z_planes};
    const char* axis = "xyz";
    for (int k = 0; k < 3; ++k) {
        const std::vector<double>& p = *planes[k];
        if (p.empty()) continue;
        const std::string flag = std::string("--") + axis[k] + "-planes";
        if (a.dims.size() == 3 && p.size() != std::size_t{a.dims[k]} + 1)
            return usage("--dims gives " + std::to_string(a.dims[k]) + " cells along " + axis[k] + " but " +
                               flag + " gives " + std::to_string(p.size()) + " planes (" +
                               std::to_string(p.size() - 1) + " cells): give one of them, or make them agree");
        if (a.bounds.size() == 6 && (p.front() != a.bounds[k] || p.back() != a.bounds[3 + k]))
            return usage("--bounds gives " + std::string(1, axis[k]) + " from " + shortest(a.bounds[k]) +
                               " to " + shortest(a.bounds[3 + k]) + " but " + flag + " runs from " +
                               shortest(p.front()) + " to " + shortest(p.back()));
    }
    if (!a.x_planes.empty() && !a.y_planes.empty() && !a.z_planes.empty() && (a.cells_given || a.cell_size > 0))
        return usage(std::string(a.cell_size > 0 ? "--cell-size" : "--cells") +
                           " has no effect when --x-planes, --y-planes and --z-planes give every plane");
    return Exit::ok;
}

// The bodies as the grid takes them: read, in one unit, each the solid it
// means (polyvol/solid.hpp's solid_body: the union of its parts where shells
// overlap). `meshes` and `bodies` own what the views point into.
struct Bodies {
    std::vector<LoadedMesh> meshes;
    std::vector<SolidBody> bodies;
    std::vector<MeshView> views;                // each body's mesh (its box sizes the grid)
    std::vector<std::vector<MeshView>> parts;   // each body's union parts
    std::vector<double> volumes;                // each body's own volume
    std::string unit;                           // the grid's ("" when no body's is known)
};

int read_bodies(const GridArgs& a, Bodies& r) {
    bool unreadable = false;  // every file is tried, each failure said
    for (const std::string& f : a.files) {
        if (std::optional<LoadedMesh> m = read_or_report(f, [&] { return read_mesh_file(f); }))
            r.meshes.push_back(std::move(*m));
        else
            unreadable = true;
    }
    if (unreadable) return Exit::unreadable;
    // The bodies in one unit, the grid's: every length typed and written is in it.
    std::vector<LoadedMesh*> in_unit;
    std::vector<double> read_error;  // the readers' own (3MF transforms), before any conversion
    for (LoadedMesh& m : r.meshes) {
        in_unit.push_back(&m);
        read_error.push_back(m.coordinate_error);
    }
    const std::optional<std::string> unit = put_in_common_unit(a.files, in_unit, a.unit_flags.units, a.unit_flags.to);
    if (!unit) return Exit::invalid;
    r.unit = *unit;
    int code = Exit::ok;
    for (std::size_t b = 0; b < r.meshes.size(); ++b) {
        r.bodies.push_back(solid_body(r.meshes[b].mesh, a.solid_flags.policy()));
        const SolidBody& body = r.bodies.back();
        for (const SolidNote& n : body.solid.notes) std::cerr << "polyvol: warning: " << a.files[b] << ": " << n.text << "\n";
        if (!body.ok()) {
            std::cerr << "polyvol: " << a.files[b] << ": "
                      << (body.not_split.empty() ? body.solid.message : body.not_split) << "\n";
            code = Exit::invalid;
            continue;
        }
        if (read_error[b] > 0)
            std::cerr << "polyvol: warning: " << a.files[b]
                      << ": its coordinates are computed in floating point (3MF transforms or a unit conversion; "
                      << "each within " << shortest(r.meshes[b].coordinate_error)
                      << " of the value meant): the cells are exact for the coordinates so rounded\n";
    }
    if (code != Exit::ok) return code;
    for (std::size_t b = 0; b < r.meshes.size(); ++b) {
        r.views.push_back(r.meshes[b].mesh.view());
        std::vector<MeshView> parts;
        for (const Mesh& m : r.bodies[b].parts) parts.push_back(m.view());
        if (parts.empty()) parts.push_back(r.views.back());
        r.parts.push_back(std::move(parts));
        r.volumes.push_back(r.bodies[b].volume);
    }
    return Exit::ok;
}

// The grid's planes from --dims, --cell-size or --cells, --bounds and the
// explicit planes; 0 when they make a grid the outputs can take.
int make_axes(const GridArgs& a, const Bodies& bodies, const std::string& out_ext, const Slice& slice, GridAxes& g) {
    try {
        GridSpec spec;
        if (a.dims.size() == 3)
            spec.dims = {a.dims[0], a.dims[1], a.dims[2]};
        else if (a.cell_size > 0)
            spec.cell_size = a.cell_size;
        else
            spec.cells = a.cells;
        if (a.bounds.size() == 6)
            spec.bounds = std::array<double, 6>{a.bounds[0], a.bounds[1], a.bounds[2], a.bounds[3], a.bounds[4], a.bounds[5]};
        const bool all_planes = !a.x_planes.empty() && !a.y_planes.empty() && !a.z_planes.empty();
        if (!all_planes) g = make_grid(bodies.views, spec);
        if (!a.x_planes.empty()) g.x = a.x_planes;
        if (!a.y_planes.empty()) g.y = a.y_planes;
        if (!a.z_planes.empty()) g.z = a.z_planes;
    } catch (const std::invalid_argument& e) {
        std::cerr << "polyvol: " << e.what() << "\n";
        return Exit::invalid;
    }
    if (out_ext == ".vti" && !g.uniform()) return usage("the grid is not uniform: write .vtr (RectilinearGrid) instead");
    if (slice.given) {
        const std::vector<double>& c = slice.axis == 0 ? g.x : (slice.axis == 1 ? g.y : g.z);
        if (slice.value < c.front() || slice.value > c.back())
            return usage("--slice " + a.slice + " lies outside the grid [" + shortest(c.front()) + ", " +
                               shortest(c.back()) + "]");
    }
    return Exit::ok;
}

// The arrays the outputs need, per cell, against --max-memory (default three
// quarters of this machine's memory), before anything is allocated.
int check_memory(const GridArgs& a, std::size_t cells, std::size_t nb) {
    if (cells > (std::size_t{1} << 34))
        return usage("too many cells (" + std::to_string(cells) + ", more than 2^34 = 17179869184): the volumes "
                           "alone would need about " + bytes_text(8.0 * static_cast<double>(cells * nb)) +
                           "; a coarser grid (--cells, --cell-size, --dims), or polyvol.dask.grid in blocks");
    const std::optional<uint64_t> limit =
        a.max_memory.empty() ? std::optional<uint64_t>(default_memory_limit()) : parse_bytes(a.max_memory);
    if (!limit) return usage("--max-memory takes a size such as 8G or 512M, not '" + a.max_memory + "'");
    // The bodies' volumes, centroids (moments and the written copy), surfaces
    // (the sums and the written copy), the union, its class and the .vti copy
    // of it, the intersection.
    const double surfaces = static_cast<double>(nb > 1 ? nb + 1 : 1);
    double per_cell = 8.0 * static_cast<double>(nb);
    if (!a.centroids.empty()) per_cell += 48.0 * static_cast<double>(nb);
    if (!a.surface.empty()) per_cell += 64.0 * surfaces;
    if (nb > 1) per_cell += 8 + 1 + 8 + (a.intersection_out.empty() ? 0 : 8);
    const double need = per_cell * static_cast<double>(cells);
    if (need > static_cast<double>(*limit))
        return usage("the grid of " + std::to_string(cells) + " cells needs about " + bytes_text(need) +
                           " for its arrays, more than " +
                           (a.max_memory.empty() ? "three quarters of this machine's memory (" +
                                                       bytes_text(static_cast<double>(*limit)) + ")"
                                                 : "--max-memory " + bytes_text(static_cast<double>(*limit))) +
                           ": use fewer cells, or raise --max-memory");
    return Exit::ok;
}

// The per-cell arrays of one run and the GridOutput that points into them.
struct Arrays {
    std::vector<double> volumes, moments, union_volumes, intersection_volumes, wetted, normals;
    std::vector<CellClass> cls;
    std::size_t surfaces = 1;  // --surface: the bodies' arrays, then (several bodies) the union's
    GridOutput out;
};

void allocate(const GridArgs& a, std::size_t nb, std::size_t cells, Arrays& r) {
    r.volumes.resize(nb * cells);
    r.out.volumes = r.volumes;
    if (!a.centroids.empty()) {
        r.moments.resize(3 * nb * cells);
        r.out.first_moments = r.moments;
    }
    r.surfaces = nb > 1 ? nb + 1 : 1;
    if (!a.surface.empty()) {
        r.wetted.resize(r.surfaces * cells);
        r.normals.resize(3 * r.surfaces * cells);
        r.out.wetted_area = std::span<double>(r.wetted).first(nb * cells);
        r.out.surface_normal = std::span<double>(r.normals).first(3 * nb * cells);
        if (nb > 1) {
            r.out.union_wetted_area = std::span<double>(r.wetted).subspan(nb * cells);
            r.out.union_surface_normal = std::span<double>(r.normals).subspan(3 * nb * cells);
        }
    }
    if (nb > 1 || !a.union_out.empty()) {
        r.union_volumes.resize(cells);
        r.cls.resize(cells);
        r.out.union_volumes = r.union_volumes;
        r.out.cell_class = r.cls;
    }
    if (!a.intersection_out.empty()) {
        r.intersection_volumes.resize(cells);
        r.out.intersection_volumes = r.intersection_volumes;
    }
}

// grid_union_volumes with progress on stderr (a terminal's, past a second).
// Several bodies: the union always (the summary gives it); where it is
// undefined and no output needs it, the bodies' cells alone, and
// `union_problem` says why. 0 when computed.
int compute(const GridArgs& a, const Bodies& bodies, const GridAxes& g, const std::string& out_ext, Arrays& arrays,
            GridSummary& summary, std::string& union_problem) {
    const std::size_t nb = bodies.parts.size();
    const bool union_needed = nb > 1 && (!a.union_out.empty() || !a.intersection_out.empty() || !a.png.empty() ||
                                         out_ext == ".vti" || out_ext == ".vtr" || !a.surface.empty());
    const auto t_grid = Clock::now();
    auto last_print = t_grid;
    bool printed = false;
    GridOptions options;
    options.device = parse_device(a.device);
    options.progress = [&](double fraction) {
        const auto now = Clock::now();
        if (seconds_since(t_grid) < 1.0 || (fraction < 1 && std::chrono::duration<double>(now - last_print).count() < 0.25))
            return;
        last_print = now;
        printed = true;
        std::fprintf(stderr, "\rpolyvol grid: %3.0f%%", 100 * fraction);
        std::fflush(stderr);
    };
    const GridBlock whole{{0, 0, 0}, {g.nx(), g.ny(), g.nz()}};
    try {
        try {
            summary = grid_union_volumes(bodies.parts, g, whole, arrays.out, options);
        } catch (const std::invalid_argument& e) {
            if (union_needed || std::string_view(e.what()).find("the union is undefined") == std::string_view::npos)
                throw;
            union_problem = e.what();
            arrays.out.union_volumes = {};
            arrays.out.cell_class = {};
            arrays.union_volumes.clear();
            arrays.cls.clear();
            summary = grid_union_volumes(bodies.parts, g, whole, arrays.out, options);
        }
    } catch (const std::invalid_argument& e) {
        if (printed) std::cerr << "\n";
        std::cerr << "polyvol: " << e.what() << "\n";
        return Exit::invalid;
    } catch (const DeviceError& e) {
        if (printed) std::cerr << "\n";
        std::cerr << "polyvol grid: " << e.what() << "\n";
        return Exit::device_failed;
    }
    if (printed) std::cerr << "\n";
    if (options.device.kind == DeviceKind::opencl && summary.device.find("cpu (") != std::string::npos)
        std::cerr << "polyvol grid: note: computed on the CPU, not OpenCL: " << summary.device << "\n";
    if (!union_problem.empty()) std::cerr << "polyvol: warning: " << union_problem << "; the bodies' cells are given\n";
    return Exit::ok;
}

// The VTK image or rectilinear grid: each body's volumes (or fractions), the
// union's, the intersection's and the cell classes, the surfaces.
void write_vtk(const GridArgs& a, const GridAxes& g, const Arrays& r, std::size_t nb, const std::string& out_ext) {
    const std::size_t cells = g.cell_count();
    const std::string what = a.fractions ? "fraction" : "volume";
    const auto body_name = [&](std::size_t b) {
        return "_" + std::to_string(b) + "_" + std::filesystem::path(a.files[b]).stem().string();
    };
    std::vector<CellArray> arrays;
    for (std::size_t b = 0; b < nb; ++b)
        arrays.push_back({what + (nb > 1 ? body_name(b) : ""), std::span<const double>(r.volumes).subspan(b * cells, cells), 1});
    std::vector<double> contact;
    if (nb > 1 && !r.union_volumes.empty()) {
        arrays.push_back({"union_" + what, r.union_volumes, 1});
        if (!r.intersection_volumes.empty()) arrays.push_back({"intersection_" + what, r.intersection_volumes, 1});
        contact.resize(cells);
        for (std::size_t c = 0; c < cells; ++c) contact[c] = static_cast<double>(r.cls[c]);
        arrays.push_back({"cell_class", contact, 1, true});  // UInt8: 0 empty, 1 full, 2 cut, 3 contact
    }
    if (!a.surface.empty())
        for (std::size_t b = 0; b < r.surfaces; ++b) {
            const std::string suffix = nb == 1 ? "" : b == nb ? "_union" : body_name(b);
            arrays.push_back({"wetted_area" + suffix, std::span<const double>(r.wetted).subspan(b * cells, cells), 1});
            arrays.push_back({"surface_normal" + suffix, std::span<const double>(r.normals).subspan(3 * b * cells, 3 * cells), 3});
        }
    if (out_ext == ".vti")
        write_vti(a.out, g.x, g.y, g.z, arrays);
    else
        write_vtr(a.out, g.x, g.y, g.z, arrays);
}

// Every file asked for: the picture, centroids, surfaces, union and
// intersection, then -o (fractions in place of volumes with --fractions).
void write_outputs(const GridArgs& a, const GridAxes& g, Arrays& r, std::size_t nb, const std::string& out_ext,
                   const Slice& slice, const nlohmann::json& summary) {
    const std::size_t cells = g.cell_count();
    const auto shape = [&](std::size_t lead, std::size_t tail) {
        std::vector<std::size_t> s;
        if (lead > 1) s.push_back(lead);
        s.insert(s.end(), {g.nx(), g.ny(), g.nz()});
        if (tail > 1) s.push_back(tail);
        return s;
    };
    if (!a.png.empty()) {
        std::string what = std::filesystem::path(a.files[0]).filename().string();
        if (nb > 1) what = "union of " + std::to_string(nb) + " bodies (" + what + ", ...)";
        write_slice_png(a.png, g, nb > 1 ? std::span<const double>(r.union_volumes) : std::span<const double>(r.volumes),
                        slice, what);
    }
    if (!a.centroids.empty()) write_npy(a.centroids, cell_centroids(r.volumes, r.moments), shape(nb, 3));
    if (!a.surface.empty()) {
        std::vector<double> four(4 * r.surfaces * cells);
        for (std::size_t n = 0; n < r.surfaces * cells; ++n) {
            four[4 * n] = r.wetted[n];
            for (int k = 0; k < 3; ++k) four[4 * n + 1 + k] = r.normals[3 * n + k];
        }
        write_npy(a.surface, four, shape(r.surfaces, 4));
    }
    const bool keep_signed = a.solid_flags.keep_signed;
    if (!r.union_volumes.empty()) {
        if (a.fractions) to_fractions(r.union_volumes, g, 1, keep_signed);
        if (!a.union_out.empty()) write_npy(a.union_out, r.union_volumes, shape(1, 1));
    }
    if (!r.intersection_volumes.empty()) {
        if (a.fractions) to_fractions(r.intersection_volumes, g, 1, keep_signed);
        write_npy(a.intersection_out, r.intersection_volumes, shape(1, 1));
    }
    if (a.fractions) to_fractions(r.volumes, g, nb, keep_signed);
    if (out_ext == ".npy") {
        write_npy(a.out, r.volumes, shape(nb, 1));
    } else if (out_ext == ".vti" || out_ext == ".vtr") {
        write_vtk(a, g, r, nb, out_ext);
    } else if (out_ext == ".json") {
        std::ofstream f(a.out);
        f << summary.dump(2) << "\n";
        if (!f) throw std::runtime_error(a.out + ": write failed");
    }
}

}  // namespace

// Check the arguments, read the bodies (each its solid, in one unit), make
// the grid, compute every cell, write what was asked, print the summary.
int run_grid_command(const GridArgs& a) {
    const auto t_start = Clock::now();
    const std::string out_ext = a.out.empty() ? "" : lower_extension(a.out);
    const std::optional<Slice> slice = parse_slice(a.slice);
    if (const int code = check_arguments(a, out_ext, slice)) return code;
    Bodies bodies;
    if (const int code = read_bodies(a, bodies)) return code;
    if (const int code = check_planes(a)) return code;
    GridAxes g;
    if (const int code = make_axes(a, bodies, out_ext, *slice, g)) return code;
    const std::size_t nb = bodies.parts.size(), cells = g.cell_count();
    if (const int code = check_memory(a, cells, nb)) return code;
    Arrays arrays;
    allocate(a, nb, cells, arrays);
    GridSummary summary;
    std::string union_problem;  // why the union was not computed
    if (const int code = compute(a, bodies, g, out_ext, arrays, summary, union_problem)) return code;
    const nlohmann::json summary_j =
        grid_summary_json(a.files, bodies.volumes, g, summary, seconds_since(t_start), union_problem, bodies.unit);
    if (seconds_since(t_start) > 1.0 && (!a.out.empty() || !a.png.empty() || !a.centroids.empty() ||
                                          !a.union_out.empty() || !a.intersection_out.empty()))
        std::cerr << "polyvol grid: writing " << cells << " cells\n";
    try {
        write_outputs(a, g, arrays, nb, out_ext, *slice, summary_j);
    } catch (const std::exception& e) {
        std::cerr << "polyvol: " << e.what() << "\n";
        return Exit::usage;
    }
    if (a.json)
        std::cout << summary_j.dump(2) << "\n";
    else
        std::cout << grid_summary_text(a.files, bodies.volumes, g, summary, union_problem, bodies.unit);
    return Exit::ok;
}

}  // namespace polyvol::cli

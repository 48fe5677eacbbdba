// `polyvol cells MESH [BODY...] [--json] [-o OUT.npy|.vtu|.grdecl|.json]
//   [--fractions] [--field NAME] [--keyword NAME] [--cell-zone NAME] [--units U] [--mesh-units U]`
//
// Reads the mesh of cells (an OpenFOAM case or its constant/polyMesh, a
// .vtu, a .grdecl corner-point grid; exit 2 if unreadable), checks that every cell closes (exit 3), reads each body
// as the solid it means (exit 2 / 3 as `volume`), puts it in the mesh's
// unit, and gives each body's volume in every cell (polyvol/cells.hpp),
// correctly rounded:
//   OUT.npy     float64, shape (cells,) or (bodies, cells): the volumes, or
//               the fractions with --fractions; without a body, the cells'
//               own volumes
//   --field N   the fractions as the OpenFOAM field CASE/0/N (one body),
//               keeping the boundary conditions of an existing 0/N
//   OUT.vtu     VTK UnstructuredGrid (polyhedra) with cell_volume and, per
//               body, its volume, fraction and cell_class (ParaView opens it)
//   OUT.grdecl  (a corner-point grid, one body) the volumes, or fractions,
//               as one GRDECL keyword over every cell (--keyword; inactive 0)
//   OUT.json    the summary only (as --json prints it)
//   --union F.npy         several bodies: their union's volume per cell,
//                         correctly rounded (a boolean per cell two bodies touch)
//   --intersection F.npy  two bodies: their intersection's, within 2 ulp of
//                         each cell's volume (inclusion-exclusion)
//   --surface F.npy       each body's wetted area and area-weighted normal
//                         per cell, shape (cells, 4) or (bodies, cells, 4);
//                         with -o OUT.vtu also as cell arrays, with their bound
#include "commands/cells.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "output/format.hpp"
#include "polyvol/cell_mesh_io.hpp"
#include "polyvol/cells.hpp"
#include "polyvol/device.hpp"
#include "polyvol/grid_io.hpp"
#include "polyvol/io.hpp"
#include "polyvol/solid.hpp"
#include "polyvol/units.hpp"
#include "read_input.hpp"

namespace polyvol::cli {
namespace {

int usage(const std::string& message) { return usage_error("cells", message); }

using Clock = std::chrono::steady_clock;

// Progress of one step on stderr, when it is a terminal and the run has
// taken a second: "polyvol cells: WHAT: NN%", overwritten in place.
class ProgressLine {
public:
    ProgressLine(Clock::time_point start, std::string what) : start_(start), what_(std::move(what)) {}
    ~ProgressLine() {
        if (printed_) std::fputc('\n', stderr);
    }
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;
    std::function<void(double)> callback() {
        if (!::isatty(2)) return {};
        return [this](double fraction) {
            const auto now = Clock::now();
            if (now - start_ < std::chrono::seconds(1) ||
                (fraction < 1 && now - last_ < std::chrono::milliseconds(250)))
                return;
            last_ = now;
            printed_ = true;
            std::fprintf(stderr, "\rpolyvol cells: %s: %3.0f%%", what_.c_str(), 100 * fraction);
            std::fflush(stderr);
        };
    }

private:
    Clock::time_point start_, last_{};
    std::string what_;
    bool printed_ = false;
};

struct Body {
    std::string file;
    BodyInCells cells;
    std::vector<double> fractions;
};

int check_arguments(const CellsArgs& a) {
    const std::string out = lower_extension(a.out);
    if (!a.out.empty() && out != ".npy" && out != ".json" && out != ".vtu" && out != ".grdecl")
        return usage("-o " + a.out + ": expected a .npy, .vtu, .grdecl or .json file");
    if (out == ".grdecl" && a.bodies.size() != 1) return usage("-o " + a.out + " needs exactly one body");
    if (!a.keyword.empty() && out != ".grdecl") return usage("--keyword names the keyword of -o OUT.grdecl");
    if (!a.union_out.empty() && (lower_extension(a.union_out) != ".npy" || a.bodies.size() < 2))
        return usage("--union needs a .npy file and two bodies or more");
    if (!a.intersection_out.empty() && (lower_extension(a.intersection_out) != ".npy" || a.bodies.size() != 2))
        return usage("--intersection needs a .npy file and exactly two bodies");
    if (!a.surface_out.empty() && (lower_extension(a.surface_out) != ".npy" || a.bodies.empty()))
        return usage("--surface needs a .npy file and a body");
    if (!a.field.empty() && a.bodies.size() != 1) return usage("--field needs exactly one body");
    try {
        if (parse_device(a.device).kind == DeviceKind::opencl)
            std::cerr << "polyvol cells: note: computed on the CPU: the cells' exact booleans use big integers, "
                         "which the OpenCL kernels do not have\n";
    } catch (const std::invalid_argument& e) {
        return usage(std::string("--") + e.what());
    }
    if (a.fractions && a.bodies.empty()) return usage("--fractions needs a body");
    for (const std::string* u : {&a.units, &a.mesh_units})
        if (!u->empty() && !length_unit(*u))
            return usage("unknown unit '" + *u + "': expected " + kLengthUnitNames);
    return Exit::ok;
}

// A body read, made the solid it means and put in the mesh's unit; nothing
// after printing why not (exit in `code`).
std::optional<LoadedMesh> read_body(const std::string& file, const CellsArgs& a, const std::string& mesh_unit,
                                    std::optional<MeshSolid>& solid, int& code) {
    auto body = read_or_report(file, [&] { return read_mesh_file(file); });
    if (!body) {
        code = Exit::unreadable;
        return std::nullopt;
    }
    const UnitChange change = into_unit(body->unit, a.units, mesh_unit);
    if (!change.error.empty()) {
        std::cerr << "polyvol: " << file << ": " << change.error << "\n";
        code = Exit::invalid;
        return std::nullopt;
    }
    body->coordinate_error = scale_coordinates(body->mesh, change.factor, body->coordinate_error);
    if (!change.note.empty()) std::cerr << "polyvol: warning: " << file << ": " << change.note << "\n";
    solid = solid_or_report(file, body->mesh, a.solid_flags.policy());
    if (!solid) {
        code = Exit::invalid;
        return std::nullopt;
    }
    return body;
}

// Volume over the cell's own volume, within [0, 1] (each is correctly
// rounded, so the quotient is within 1.5 ulp of the exact fraction).
std::vector<double> fractions_of(const std::vector<double>& volumes, const std::vector<double>& own) {
    std::vector<double> f(volumes.size());
    for (std::size_t c = 0; c < f.size(); ++c) f[c] = own[c] > 0 ? std::clamp(volumes[c] / own[c], 0.0, 1.0) : 0.0;
    return f;
}

// The bodies' union and intersection per cell, when asked for.
struct Joined {
    std::optional<BodyInCells> union_;
    std::optional<IntersectionInCells> intersection;
};

nlohmann::json summary(const CellsArgs& a, const LoadedCellMesh& mesh, const std::string& unit,
                       const CellVolumes& own, const std::vector<Body>& bodies, const Joined& joined,
                       double seconds) {
    nlohmann::json j;
    const CellMeshView m = mesh.mesh.view();
    j["mesh"] = {{"file", a.mesh},
                 {"format", mesh.format},
                 {"encoding", mesh.encoding},
                 {"unit", unit},
                 {"cells", m.cell_count()},
                 {"faces", m.face_count()},
                 {"points", m.point_count()},
                 {"volume", json_number(own.total)}};
    if (!a.cell_zone.empty()) {
        j["mesh"]["cell_zone"] = a.cell_zone;
        j["mesh"]["case_cells"] = mesh.case_cells;
    }
    if (mesh.format == "grdecl")
        j["mesh"]["grid"] = {{"dims", mesh.grid_dims},
                             {"active_cells", mesh.grid_index.size()},
                             {"fault_faces", mesh.fault_faces}};
    j["accuracy"] = "correctly-rounded";  // every cell's volume and every total
    j["cells_tile"] = mesh.cells_tile;    // false: the cells may overlap; totals are of the region they cover
    if (!mesh.cells_tile) j["mesh"]["covered_volume"] = json_number(covered_volume(m));
    nlohmann::json list = nlohmann::json::array();
    for (const Body& b : bodies)
        list.push_back({{"file", b.file},
                        {"volume", json_number(b.cells.body_volume)},
                        {"inside_mesh", json_number(b.cells.total)},
                        {"cells_sum", json_number(b.cells.cells_sum)},
                        {"full_cells", b.cells.full_cells},
                        {"cut_cells", b.cells.cut_cells},
                        {"empty_cells", b.cells.empty_cells},
                        {"cells_intersected", b.cells.touched_cells}});
    if (!mesh.cells_tile)
        for (std::size_t i = 0; i < bodies.size(); ++i) list[i]["in_overlaps"] = json_number(bodies[i].cells.in_overlaps);
    if (!a.surface_out.empty())
        for (std::size_t i = 0; i < bodies.size(); ++i) {
            list[i]["wetted_area"] = json_number(bodies[i].cells.wetted_area_total);
            list[i]["wetted_area_bound"] = json_number(bodies[i].cells.wetted_area_total_bound);
        }
    j["bodies"] = list;
    if (joined.union_)
        j["union"] = {{"inside_mesh", json_number(joined.union_->total)},
                      {"full_cells", joined.union_->full_cells},
                      {"cut_cells", joined.union_->cut_cells},
                      {"empty_cells", joined.union_->empty_cells}};
    if (joined.intersection)
        j["intersection"] = {{"inside_mesh", json_number(joined.intersection->total)},
                             {"accuracy", "bounded: within 2 ulp of each cell's volume (of the union's total)"}};
    // --device: the cells' work is exact booleans (GMP), which stay on the CPU.
    j["device"] = parse_device(a.device).kind == DeviceKind::opencl
                      ? "cpu (cells are exact booleans with big integers: computed on the CPU)"
                      : "cpu";
    j["seconds"] = seconds;
    return j;
}

void print_table(const nlohmann::json& j) {
    const auto& m = j["mesh"];
    const std::string unit = m["unit"].get<std::string>();
    const std::string cubed = unit.empty() ? "" : " " + unit + "3";
    std::cout << m["file"].get<std::string>() << ": ";
    if (m.contains("grid")) {
        const auto& d = m["grid"]["dims"];
        std::cout << "corner-point grid " << d[0].get<uint64_t>() << "x" << d[1].get<uint64_t>() << "x"
                  << d[2].get<uint64_t>() << ", active ";
    }
    std::cout << m["cells"].get<std::size_t>() << " cells, "
              << m["faces"].get<std::size_t>() << " faces, " << m["points"].get<std::size_t>()
              << " points; volume " << shortest(m["volume"].get<double>()) << cubed << "\n";
    for (const auto& b : j["bodies"])
        std::cout << b["file"].get<std::string>() << ": volume " << shortest(b["volume"].get<double>())
                  << ", inside the mesh " << shortest(b["inside_mesh"].get<double>()) << cubed << "; cells "
                  << b["full_cells"].get<std::size_t>() << " full, " << b["cut_cells"].get<std::size_t>()
                  << " cut, " << b["empty_cells"].get<std::size_t>() << " empty\n";
    if (m.contains("grid") && m["grid"]["fault_faces"].get<std::size_t>() > 0)
        std::cout << "faults: " << m["grid"]["fault_faces"].get<std::size_t>()
                  << " faces between neighbouring cells do not match; each cell keeps its own faces; "
                  << (j["cells_tile"].get<bool>()
                          ? "on vertical pillars the cells still tile, and every total is conserved\n"
                          : "off vertical pillars they may overlap or leave gaps\n");
    if (!j["cells_tile"].get<bool>()) {
        // null: the region the cells cover is not decided (docs/cells.md); the totals are then the cells' sums.
        const auto figure = [&](const nlohmann::json& v) {
            return v.is_null() ? std::string("not decided") : shortest(v.get<double>()) + cubed;
        };
        std::cout << "the cells cover " << figure(m["covered_volume"]) << ", each point once (their volumes add up to "
                  << shortest(m["volume"].get<double>()) << cubed << "); inside the mesh: the body in the region "
                  << "they cover\n";
        for (const auto& b : j["bodies"])
            std::cout << b["file"].get<std::string>() << ": counted more than once where cells overlap: "
                      << figure(b["in_overlaps"]) << " (its cells add up to " << shortest(b["cells_sum"].get<double>())
                      << cubed << ")\n";
    }
    if (j.contains("union"))
        std::cout << "union: inside the mesh " << shortest(j["union"]["inside_mesh"].get<double>()) << cubed
                  << "; cells " << j["union"]["full_cells"].get<std::size_t>() << " full, "
                  << j["union"]["cut_cells"].get<std::size_t>() << " cut, "
                  << j["union"]["empty_cells"].get<std::size_t>() << " empty\n";
    if (j.contains("intersection"))
        std::cout << "intersection: inside the mesh " << shortest(j["intersection"]["inside_mesh"].get<double>())
                  << cubed << " (each cell within 2 ulp of its volume, the total within 2 ulp of the union's)\n";
    std::cout << (j["cells_tile"].get<bool>() ? "volumes: correctly rounded, every cell and every total"
                                              : "volumes: correctly rounded, every cell and every total but the "
                                                "overlaps' (a difference of two)");
    char took[32];
    std::snprintf(took, sizeof took, "%.3g", j["seconds"].get<double>());
    std::cout << "; computed in " << took << " s\n";
}

int write_outputs(const CellsArgs& a, const LoadedCellMesh& mesh, const CellVolumes& own,
                  const std::vector<Body>& bodies, const Joined& joined, const nlohmann::json& j) {
    try {
        const std::size_t per_cell[1] = {own.volumes.size()};
        if (joined.union_) write_npy(a.union_out, joined.union_->volumes, per_cell);
        if (joined.intersection) write_npy(a.intersection_out, joined.intersection->volumes, per_cell);
        if (!a.surface_out.empty()) {
            // Per body and cell: the wetted area, then ∫ n dA.
            std::vector<double> data;
            for (const Body& b : bodies)
                for (std::size_t c = 0; c < own.volumes.size(); ++c) {
                    data.push_back(b.cells.wetted_area[c]);
                    data.insert(data.end(), &b.cells.surface_normal[3 * c], &b.cells.surface_normal[3 * c] + 3);
                }
            std::vector<std::size_t> shape;
            if (bodies.size() > 1) shape.push_back(bodies.size());
            shape.insert(shape.end(), {own.volumes.size(), 4});
            write_npy(a.surface_out, data, shape);
        }
        if (lower_extension(a.out) == ".npy") {
            std::vector<double> data;
            if (bodies.empty()) data = own.volumes;
            for (const Body& b : bodies) {
                const std::vector<double>& v = a.fractions ? b.fractions : b.cells.volumes;
                data.insert(data.end(), v.begin(), v.end());
            }
            std::vector<std::size_t> shape;
            if (bodies.size() > 1) shape.push_back(bodies.size());
            shape.push_back(own.volumes.size());
            write_npy(a.out, data, shape);
        } else if (lower_extension(a.out) == ".vtu") {
            // The cells' volumes, then per body its volume, fraction and class in each cell.
            std::vector<std::string> names{"cell_volume"};
            std::vector<std::vector<double>> classes(bodies.size());
            std::vector<CellArray> arrays{{names[0], own.volumes, 1, false}};
            for (std::size_t i = 0; i < bodies.size(); ++i) {
                const std::string prefix = bodies.size() == 1 ? "" : "body" + std::to_string(i) + "_";
                for (const CellClass c : bodies[i].cells.cell_class) classes[i].push_back(static_cast<double>(c));
                arrays.push_back({prefix + "volume", bodies[i].cells.volumes, 1, false});
                arrays.push_back({prefix + "fraction", bodies[i].fractions, 1, false});
                arrays.push_back({prefix + "cell_class", classes[i], 1, true});
                if (!bodies[i].cells.wetted_area.empty()) {
                    arrays.push_back({prefix + "wetted_area", bodies[i].cells.wetted_area, 1, false});
                    arrays.push_back({prefix + "surface_normal", bodies[i].cells.surface_normal, 3, false});
                    arrays.push_back({prefix + "surface_bound", bodies[i].cells.surface_bound, 1, false});
                }
            }
            write_vtu(a.out, mesh.mesh.view(), arrays);
        } else if (lower_extension(a.out) == ".grdecl") {
            const std::string keyword = !a.keyword.empty() ? a.keyword : a.fractions ? "BODYFRAC" : "BODYVOL";
            write_grdecl_keyword(a.out, keyword, a.fractions ? bodies[0].fractions : bodies[0].cells.volumes, mesh);
        } else if (lower_extension(a.out) == ".json") {
            std::ofstream(a.out) << j.dump(2) << "\n";
        }
        if (!a.field.empty()) {
            const std::string path = write_foam_field(mesh.location, a.field, in_case_cells(mesh, bodies[0].fractions));
            std::cerr << "polyvol: wrote " << path << "\n";
        }
    } catch (const std::exception& e) {
        std::cerr << "polyvol cells: " << e.what() << "\n";
        return Exit::usage;
    }
    return Exit::ok;
}

}  // namespace

CLI::App* add_cells_command(CLI::App& app, CellsArgs& a) {
    auto* cmd = app.add_subcommand("cells",
                                   "Volume of each body in every cell of a mesh of polyhedral cells (an OpenFOAM "
                                   "case, a .vtu, a GRDECL corner-point grid), correctly rounded, and the cells' "
                                   "own volumes");
    cmd->add_option("mesh", a.mesh,
                    "An OpenFOAM case directory or its constant/polyMesh, a VTK .vtu, or an Eclipse .grdecl")
        ->required();
    cmd->add_option("bodies", a.bodies, "Closed meshes (any format polyvol reads), each the solid it means");
    cmd->add_flag("--json", a.json, "Print the summary as JSON");
    cmd->add_option("--device", a.device,
                    "auto, cpu, opencl or opencl:N: accepted as for grid; the cells' exact booleans run on the CPU");
    cmd->add_option("-o,--output", a.out,
                    "OUT.npy: per-cell volumes (or fractions), shape (cells,) or (bodies, cells); "
                    "OUT.vtu: the cells with their volumes, fractions and classes; OUT.grdecl: one keyword "
                    "over the corner-point grid's cells (one body); OUT.json: the summary");
    cmd->add_flag("--fractions", a.fractions, "Write each cell's fraction inside the body, not its volume");
    cmd->add_option("--field", a.field,
                    "Write the fractions as the OpenFOAM field CASE/0/NAME (e.g. alpha.water), keeping the "
                    "boundary conditions of an existing one (one body)");
    cmd->add_option("--union", a.union_out,
                    "Several bodies: write their union's volume per cell, correctly rounded (FILE.npy; a boolean per "
                    "cell where two bodies come near it: slow there)");
    cmd->add_option("--intersection", a.intersection_out,
                    "Two bodies: write their intersection's volume per cell (FILE.npy), within 2 ulp of each "
                    "cell's volume");
    cmd->add_option("--surface", a.surface_out,
                    "Write each body's wetted area and area-weighted outward normal per cell: FILE.npy, shape "
                    "(cells, 4) or (bodies, cells, 4), with their bound in -o OUT.vtu");
    cmd->add_flag("--grid-axes", a.grid_axes,
                  "A corner-point grid in its own axes: its MAPAXES not applied (the points as COORD gives them)");
    cmd->add_option("--cell-zone", a.cell_zone,
                    "Only the cells of this OpenFOAM cellZone (its faces to other cells taken as boundary faces); "
                    "--field writes 0 in the other cells");
    cmd->add_option("--keyword", a.keyword,
                    "The GRDECL keyword -o OUT.grdecl writes (default BODYVOL, or BODYFRAC with --fractions)");
    cmd->add_option("--units", a.units, std::string("The bodies' length unit (") + kLengthUnitNames +
                        "); a 3MF or AMF file states its own, which this overrides (with a warning)");
    cmd->add_option("--mesh-units", a.mesh_units, "The mesh's unit (OpenFOAM: m; GRDECL: its unit keyword)");
    add_solid_flags(cmd, a.solid_flags);
    return cmd;
}

int run_cells_command(const CellsArgs& a) {
    if (const int code = check_arguments(a); code != Exit::ok) return code;
    auto mesh = read_or_report(a.mesh, [&] {
        LoadedCellMesh whole = read_cell_mesh(a.mesh, !a.grid_axes);
        return a.cell_zone.empty() ? whole : cell_zone(whole, a.cell_zone);
    });
    if (!mesh) return Exit::unreadable;
    const std::string unit = !a.mesh_units.empty() ? length_unit(a.mesh_units)->name : mesh->unit;
    for (const std::string& note : mesh->notes) std::cerr << "polyvol: note: " << a.mesh << ": " << note << "\n";
    const CellMeshView view = mesh->mesh.view();
    const auto t0 = Clock::now();
    CellVolumes own;
    try {
        own = cell_volumes(view);  // checks the cells (check_cell_mesh) first
    } catch (const std::invalid_argument& e) {
        std::cerr << "polyvol: " << a.mesh << ": " << e.what() << "\n";
        return Exit::invalid;
    }
    std::vector<Body> bodies;
    std::vector<Mesh> solids;  // kept for the union
    bool any_within = false;
    for (const std::string& file : a.bodies) {
        int code = Exit::ok;
        std::optional<MeshSolid> solid;
        const auto body = read_body(file, a, unit, solid, code);
        if (!body) return code;
        Body b{file, {}, {}};
        if (!a.surface_out.empty() && solid->resolved())
            std::cerr << "polyvol: warning: " << file << ": its shells overlap: its wetted area and normal are not "
                      << "computed (NaN in --surface)\n";
        try {
            const bool within = solid->solid && solid->solid->shells_crossing_themselves > 0;
            any_within = any_within || within;
            ProgressLine progress(t0, file);
            b.cells = body_in_cells(view, body->mesh.view(),
                                    {.overlapping_shells = solid->resolved(), .within_shells = within,
                                     .reference = false, .own = own.volumes, .cells_tile = mesh->cells_tile,
                                     .surface = !a.surface_out.empty(), .progress = progress.callback()});
        } catch (const std::invalid_argument& e) {
            std::cerr << "polyvol: " << file << " in " << a.mesh << ": " << e.what() << "\n";
            return Exit::invalid;
        }
        b.fractions = fractions_of(b.cells.volumes, own.volumes);
        bodies.push_back(std::move(b));
        if (!a.union_out.empty() || !a.intersection_out.empty()) solids.push_back(std::move(body->mesh));
    }
    Joined joined;
    if (!solids.empty()) {
        std::vector<MeshView> views;
        for (const Mesh& s : solids) views.push_back(s.view());
        try {
            ProgressLine progress(t0, "the union");
            std::vector<BodyInCells> each;
            for (const Body& b : bodies) each.push_back(b.cells);
            joined.union_ = union_in_cells(view, views, each,
                                           {.overlapping_shells = true, .within_shells = any_within,
                                            .reference = true, .own = own.volumes, .cells_tile = mesh->cells_tile,
                                            .surface = false, .progress = progress.callback()});
        } catch (const std::invalid_argument& e) {
            std::cerr << "polyvol: the bodies' union in " << a.mesh << ": " << e.what() << "\n";
            return Exit::invalid;
        }
        if (!a.intersection_out.empty())
            joined.intersection = intersection_in_cells(bodies[0].cells, bodies[1].cells, *joined.union_);
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const nlohmann::json j = summary(a, *mesh, unit, own, bodies, joined, seconds);
    if (const int code = write_outputs(a, *mesh, own, bodies, joined, j); code != Exit::ok) return code;
    if (a.json)
        std::cout << j.dump(2) << "\n";
    else
        print_table(j);
    return Exit::ok;
}

}  // namespace polyvol::cli

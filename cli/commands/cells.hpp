// `polyvol cells MESH [BODY...]`: the volume of each body in every cell of
// a mesh of polyhedral cells (an OpenFOAM case, a .vtu, a GRDECL
// corner-point grid), and the cells' own volumes
// (polyvol/cells.hpp).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "grammar.hpp"

namespace polyvol::cli {

struct CellsArgs {
    std::string mesh;
    std::vector<std::string> bodies;
    SolidFlags solid_flags;  // --orient, --weld-tolerance, --signed: each body the solid it means
    std::string units;       // the bodies' unit, where a file states none
    std::string mesh_units;  // the mesh's unit (OpenFOAM: metres)
    std::string out;         // -o OUT.npy, OUT.vtu, OUT.grdecl or OUT.json
    std::string field;       // --field NAME: an OpenFOAM volScalarField of the fractions
    std::string keyword;     // --keyword NAME: the GRDECL keyword -o OUT.grdecl writes
    std::string cell_zone;   // --cell-zone NAME: an OpenFOAM cellZone's cells only
    std::string union_out;         // --union FILE.npy: the bodies' union per cell
    std::string intersection_out;  // --intersection FILE.npy: two bodies' intersection per cell
    std::string surface_out;       // --surface FILE.npy: each body's wetted area and normal per cell
    bool grid_axes = false;  // --grid-axes: a corner-point grid's MAPAXES not applied
    bool fractions = false;
    bool json = false;
    std::string device = "auto";  // --device: accepted; the cells run on the CPU
};

CLI::App* add_cells_command(CLI::App& app, CellsArgs& args);

// Exit codes: 0 ok, 1 usage, 2 unreadable mesh or body, 3 a mesh whose
// cells do not close or a body that is not a solid.
int run_cells_command(const CellsArgs& args);

}  // namespace polyvol::cli

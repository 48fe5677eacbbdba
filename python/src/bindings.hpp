// python/src/bindings.hpp — the parts of the module, one per area of the C++ API.
#pragma once

#include <string>

#include <pybind11/pybind11.h>

#include "polyvol/measure.hpp"
#include "polyvol/solid.hpp"
#include "polyvol/units.hpp"

namespace polyvol::python {

// "cone", "prism", "pyramid", "vtnb" and "correctly-rounded", "fast", as the
// CLI spells them; anything else is a ValueError naming the choices.
Method parse_method(const std::string& s);
Accuracy parse_accuracy(const std::string& s);
// A density keyword: a number (mass per unit³) or a text with its unit
// ('2700kg/m3', '1.24g/cm3'), checked with mass_unit ('kg', 'g', 'lb'; not
// 'kg' only with a unit) as --density and --mass-unit are; ValueError else.
Density parse_density_arg(const py::object& density, const std::string& mass_unit);

// The solid policy's options from Python's keywords (signed, allow_open,
// orient, weld_tolerance, solid), and what it found: (status, message, notes).
SolidOptions solid_options(const pybind11::dict& keywords);
pybind11::tuple solid_verdict(const MeshSolid& solid);

void bind_io(pybind11::module_& m);       // io.hpp, grid_io.hpp: reading meshes, writing grids
void bind_measure(pybind11::module_& m);  // measure.hpp, topology.hpp, boolean.hpp
void bind_grid(pybind11::module_& m);     // grid.hpp
void bind_chain(pybind11::module_& m);    // chain.hpp, simplicial.hpp, implicit.hpp
void bind_cells(pybind11::module_& m);    // cell_mesh.hpp, cell_mesh_io.hpp, cells.hpp

}  // namespace polyvol::python

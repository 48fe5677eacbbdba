// polyvol/cell_class.hpp — how the bodies meet one cell, for the grid
// (polyvol/grid.hpp) and the cells of a mesh (polyvol/cells.hpp).
#pragma once

#include <cstdint>

namespace polyvol {

enum class CellClass : uint8_t {
    empty = 0,    // no surface enters the cell and no body fills it
    full = 1,     // some body fills the cell (the union is the cell)
    cut = 2,      // exactly one body's surface enters the cell (the union is that body's part)
    contact = 3,  // two or more bodies' surfaces enter it (the union's own pieces decide it)
};

}  // namespace polyvol

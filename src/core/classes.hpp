// Private to the library (core, io and topology): numbering the classes that
// weld_vertices (polyvol/mesh.hpp) found.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace polyvol::core {

// The classes of canonical (canonical[v] <= v, the first of v's class, as
// weld_vertices gives it) numbered in the order of their firsts: id[v] is
// v's class's number, xyz[3 k .. 3 k + 3) the position of class k's first
// (positions as weld_vertices was given them). In parallel (oneTBB); the
// result is the serial one.
void number_classes(std::span<const uint32_t> canonical, std::span<const double> positions,
                    std::vector<uint32_t>& id, std::vector<double>& xyz);

}  // namespace polyvol::core

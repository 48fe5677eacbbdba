// Private to the library (core and measure): the bit pattern that stands for
// a coordinate wherever points are compared as weld_vertices compares them
// (polyvol/mesh.hpp: bit-identical doubles, -0.0 == +0.0) — the weld's hash
// and the closedness fingerprint's (core/fingerprint.cpp) hash alike.
#pragma once

#include <bit>
#include <cstdint>
#include "core/bit_cast.hpp"

namespace polyvol::core {

// x's bit pattern with -0.0 mapped to +0.0.
inline uint64_t canonical_bits(double x) { return core::bit_cast<uint64_t>(x == 0.0 ? 0.0 : x); }

}  // namespace polyvol::core

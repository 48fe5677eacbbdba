// The real pairs of the booleans' tests and benchmark (issue #36): a corpus
// part A and a copy B of it, moved
//   offset       by an exact offset (0.31, 0.17, 0.23) × its size: B is A
//                translated exactly, |A| = |B| bit for bit;
//   axis_offset  by an exact offset 0.25 × its size along x: faces parallel
//                to x stay exactly coplanar (CAD parts meet in coplanar faces
//                everywhere: the symbolic perturbation's case);
//   rotation     about a generic axis through its centre, then by the first
//                offset, every coordinate rounded (B is another mesh).
// For the exact offsets A is the part snapped to multiples of 2^E, E = 40
// bits below its largest coordinate, so that every x + d is a double.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>

#include "polyvol/mesh.hpp"

namespace polyvol::test {

enum class Move { offset, axis_offset, rotation };

inline std::array<double, 3> size_of(const Mesh& m) {
    std::array<double, 3> lo = {m.positions[0], m.positions[1], m.positions[2]}, hi = lo;
    for (std::size_t i = 0; i < m.positions.size(); ++i) {
        lo[i % 3] = std::min(lo[i % 3], m.positions[i]);
        hi[i % 3] = std::max(hi[i % 3], m.positions[i]);
    }
    return {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
}

// The exponent of the grid the exact offsets use: 40 bits below m's largest coordinate.
inline int snap_exponent(const Mesh& m) {
    double largest = 0;
    for (const double x : m.positions) largest = std::max(largest, std::fabs(x));
    return std::ilogb(largest) - 40;
}

inline Mesh snapped(const Mesh& m, int e) {
    Mesh out = m;
    for (double& x : out.positions) x = std::ldexp(std::nearbyint(std::ldexp(x, -e)), e);
    return out;
}

// f · size, rounded to a multiple of 2^e.
inline std::array<double, 3> offset_on_grid(const std::array<double, 3>& f, const std::array<double, 3>& size, int e) {
    std::array<double, 3> d;
    for (int k = 0; k < 3; ++k) d[k] = std::ldexp(std::nearbyint(std::ldexp(f[k] * size[k], -e)), e);
    return d;
}

// m + d, each coordinate rounded to double (exact where the offsets above are used).
inline Mesh moved(const Mesh& m, const std::array<double, 3>& d) {
    Mesh out = m;
    for (std::size_t i = 0; i < out.positions.size(); ++i) out.positions[i] += d[i % 3];
    return out;
}

// Whether every coordinate of `to` is the one of `from` plus d exactly.
inline bool moved_exactly(const Mesh& from, const Mesh& to, const std::array<double, 3>& d) {
    for (std::size_t i = 0; i < from.positions.size(); ++i)
        if (to.positions[i] - d[i % 3] != from.positions[i] || to.positions[i] - from.positions[i] != d[i % 3])
            return false;
    return true;
}

// m with every vertex p replaced by R p + shift, R the rotation by `angle`
// about `axis`, each coordinate computed in double (so rounded).
inline Mesh transformed(const Mesh& m, std::array<double, 3> axis, double angle, const std::array<double, 3>& shift) {
    const double n = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    const double x = axis[0] / n, y = axis[1] / n, z = axis[2] / n;
    const double c = std::cos(angle), s = std::sin(angle), d = 1 - c;
    const double rot[3][3] = {{c + x * x * d, x * y * d - z * s, x * z * d + y * s},
                              {y * x * d + z * s, c + y * y * d, y * z * d - x * s},
                              {z * x * d - y * s, z * y * d + x * s, c + z * z * d}};
    Mesh out = m;
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
        const double* p = &m.positions[3 * v];
        for (int k = 0; k < 3; ++k)
            out.positions[3 * v + k] = rot[k][0] * p[0] + rot[k][1] * p[1] + rot[k][2] * p[2] + shift[k];
    }
    return out;
}

// p -> R (p - c) + c + t about m's vertex centroid c (transformed, above).
inline Mesh rotated_about_centre(const Mesh& m, std::array<double, 3> axis, double angle, const std::array<double, 3>& t) {
    std::array<double, 3> c{};
    for (std::size_t i = 0; i < m.positions.size(); ++i) c[i % 3] += m.positions[i] / double(m.vertex_count());
    return transformed(moved(m, {-c[0], -c[1], -c[2]}), axis, angle, {c[0] + t[0], c[1] + t[1], c[2] + t[2]});
}

// (A, B) for a corpus part and a move (above).
inline std::pair<Mesh, Mesh> real_pair(const Mesh& part, Move move) {
    const std::array<double, 3> size = size_of(part);
    const std::array<double, 3> f = {0.31, 0.17, 0.23};
    if (move == Move::rotation)
        return {part, rotated_about_centre(part, {0.42, 0.77, -0.31}, 0.37,
                                           {f[0] * size[0], f[1] * size[1], f[2] * size[2]})};
    const int e = snap_exponent(part);
    Mesh a = snapped(part, e);
    Mesh b = moved(a, offset_on_grid(move == Move::offset ? f : std::array<double, 3>{0.25, 0, 0}, size, e));
    return {std::move(a), std::move(b)};
}

}  // namespace polyvol::test

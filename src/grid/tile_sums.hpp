// grid/tile_sums.hpp — private: per-cell sums of the pieces' integrals over
// one tile of columns (the scatter of (P, Q) per piece).
//
// A tile is up to side × side columns of the grid; its cells are indexed
//     cell(ci, cj, k) = (ci * side + cj) * layers + k,   layers = nz + 1,
// where layer nz collects the pieces above the grid's top plane (only their
// P, Px, Py matter: they make the cross-section on the top face). Every sum
// is a double-double (hi + lo, TwoSum), in the order the pieces arrive
// (triangle order), so results do not depend on threads.
#pragma once

#include <algorithm>
#include <bit>
#include <cstdint>
#include <vector>

#include "exact/eft.hpp"
#include "grid/piece.hpp"

namespace polyvol::grid {

struct DD {
    double hi = 0, lo = 0;
    void add(double x) {
        double s, e;
        exact::two_sum(hi, x, s, e);
        hi = s;
        lo += e;
    }
    void add(const DD& x) {
        add(x.hi);
        lo += x.lo;
    }
    double value() const { return hi + lo; }
};

struct TileSums {
    int side = 0, layers = 0, words = 0;  // room for side × side columns of `layers` cells
    bool moments = false;
    std::vector<DD> P, Q, Px, Py, Qx, Qy, Qz;  // moments' vectors empty unless `moments`
    std::vector<uint8_t> interior;             // a piece enters the cell's interior
    // Which cells received a piece: bit k of word k / 64 of the column's
    // `words` words. Columns and their cells are sparse in practice; the
    // scan skips the others and reset() clears only these.
    std::vector<uint64_t> bits;
    std::vector<uint8_t> touched;  // per column: some bit set

    std::size_t column(int ci, int cj) const { return static_cast<std::size_t>(ci) * side + cj; }
    std::size_t index(int ci, int cj, int k) const { return column(ci, cj) * layers + k; }
    const uint64_t* column_bits(std::size_t col) const { return &bits[col * words]; }

    // Every sum zero, for tiles of up to tile_side × tile_side columns, in
    // O(cells touched since the last reset).
    void reset(int tile_side, int nlayers, bool with_moments) {
        if (tile_side != side || nlayers != layers || with_moments != moments) {
            side = tile_side;
            layers = nlayers;
            words = (layers + 63) / 64;
            moments = with_moments;
            const std::size_t n = static_cast<std::size_t>(side) * side * layers;
            for (auto* v : {&P, &Q, &Px, &Py, &Qx, &Qy, &Qz}) v->clear();
            P.assign(n, DD{});
            Q.assign(n, DD{});
            interior.assign(n, 0);
            if (moments)
                for (auto* v : {&Px, &Py, &Qx, &Qy, &Qz}) v->assign(n, DD{});
            bits.assign(static_cast<std::size_t>(side) * side * words, 0);
            touched.assign(static_cast<std::size_t>(side) * side, 0);
            return;
        }
        for (std::size_t col = 0; col < touched.size(); ++col) {
            if (!touched[col]) continue;
            touched[col] = 0;
            for (int w = 0; w < words; ++w) {
                uint64_t& word = bits[col * words + w];
                while (word != 0) {
                    const std::size_t c = col * layers + 64 * w + std::countr_zero(word);
                    word &= word - 1;
                    P[c] = Q[c] = DD{};
                    interior[c] = 0;
                    if (moments) Px[c] = Py[c] = Qx[c] = Qy[c] = Qz[c] = DD{};
                }
            }
        }
    }
    // The scatter: adds one piece's integrals to its cell.
    void scatter(int ci, int cj, int k, const PieceIntegrals& r) {
        const std::size_t col = column(ci, cj), cell = col * layers + k;
        touched[col] = 1;
        bits[col * words + static_cast<std::size_t>(k) / 64] |= uint64_t{1} << (static_cast<unsigned>(k) % 64);
        P[cell].add(r.P);
        Q[cell].add(r.Q);
        interior[cell] |= static_cast<uint8_t>(r.interior);
        if (moments) {
            Px[cell].add(r.Px);
            Py[cell].add(r.Py);
            Qx[cell].add(r.Qx);
            Qy[cell].add(r.Qy);
            Qz[cell].add(r.Qz);
        }
    }
};

}  // namespace polyvol::grid

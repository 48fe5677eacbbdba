// grid/piece.hpp — private: the integrals of one surface piece that the
// column scan needs, in cell-local coordinates.
//
// For a piece in cell (i, j, k) let (ξ, η, ζ) = (x - x_i, y - y_j, z - z_k)
// and n_z the z component of the outward unit normal. Over each fan triangle
// (v0, vt, vt+1) with c = 2 × its signed xy-projected area,
//     c = (ξt - ξ0)(ηt+1 - η0) - (ηt - η0)(ξt+1 - ξ0),
// and S_f = f0 + ft + ft+1, the integrals of linear and quadratic functions
// over a triangle (∫ g h dA = A/12 (Σ g_i h_i + Σ g_i Σ h_i)) give
//     P  = ∫ n_z dA       = Σ c / 2
//     Q  = ∫ ζ n_z dA     = Σ c S_ζ / 6
// and, for the first moments,
//     Px = ∫ ξ n_z dA     = Σ c S_ξ / 6              (Py likewise with η)
//     Qx = ∫ ξ ζ n_z dA   = Σ c (Σ ξ_v ζ_v + S_ξ S_ζ) / 24   (Qy likewise)
//     Qz = ∫ ζ²/2 n_z dA  = Σ c (Σ ζ_v² + S_ζ²) / 48.
// The cell then has (column_scan.hpp) V = Q + h A, ∫ξ dV = Qx + h Ax,
// ∫η dV = Qy + h Ay, ∫ζ dV = Qz + h²/2 A, with A, Ax, Ay the sums of P, Px,
// Py over the pieces above the cell in its column.
//
// Local coordinates are differences of doubles within one cell: each is the
// exact difference rounded once, so the terms' rounding is relative to the
// cell's size, not to the distance from the origin.
#pragma once

#include "grid/clip.hpp"

namespace polyvol::grid {

struct PieceIntegrals {
    double P = 0, Q = 0;
    double Px = 0, Py = 0, Qx = 0, Qy = 0, Qz = 0;
    // false when every vertex lies in one face plane of the cell: the piece is
    // part of the cell's boundary, not of its interior
    bool interior = false;
};

// corner = (x_i, y_j, z_k), far = (x_{i+1}, y_{j+1}, z_{k+1}).
template <bool kMoments>
inline PieceIntegrals piece_integrals(const Polygon& poly, const double corner[3], const double far[3]) {
    PieceIntegrals r;
    const int n = poly.n;
    double xi[kMaxVertices], eta[kMaxVertices], zeta[kMaxVertices];
    bool on_lo[3] = {true, true, true}, on_hi[3] = {true, true, true};
    for (int v = 0; v < n; ++v) {
        const Point& p = poly.p[v];
        xi[v] = p.v[0] - corner[0];
        eta[v] = p.v[1] - corner[1];
        zeta[v] = p.v[2] - corner[2];
        for (int a = 0; a < 3; ++a) {
            on_lo[a] = on_lo[a] && p.v[a] == corner[a];
            on_hi[a] = on_hi[a] && p.v[a] == far[a];
        }
    }
    r.interior = !(on_lo[0] || on_lo[1] || on_lo[2] || on_hi[0] || on_hi[1] || on_hi[2]);
    double c_sum = 0, q_sum = 0, px_sum = 0, py_sum = 0, qx_sum = 0, qy_sum = 0, qz_sum = 0;
    for (int t = 1; t + 1 < n; ++t) {
        const double c = (xi[t] - xi[0]) * (eta[t + 1] - eta[0]) - (eta[t] - eta[0]) * (xi[t + 1] - xi[0]);
        const double sz = zeta[0] + zeta[t] + zeta[t + 1];
        c_sum += c;
        q_sum += c * sz;
        if constexpr (kMoments) {
            const double sx = xi[0] + xi[t] + xi[t + 1];
            const double sy = eta[0] + eta[t] + eta[t + 1];
            px_sum += c * sx;
            py_sum += c * sy;
            qx_sum += c * ((xi[0] * zeta[0] + xi[t] * zeta[t] + xi[t + 1] * zeta[t + 1]) + sx * sz);
            qy_sum += c * ((eta[0] * zeta[0] + eta[t] * zeta[t] + eta[t + 1] * zeta[t + 1]) + sy * sz);
            qz_sum += c * ((zeta[0] * zeta[0] + zeta[t] * zeta[t] + zeta[t + 1] * zeta[t + 1]) + sz * sz);
        }
    }
    r.P = c_sum / 2;
    r.Q = q_sum / 6;
    if constexpr (kMoments) {
        r.Px = px_sum / 6;
        r.Py = py_sum / 6;
        r.Qx = qx_sum / 24;
        r.Qy = qy_sum / 24;
        r.Qz = qz_sum / 48;
    }
    return r;
}

// The vector area ∫ n dA = ½ Σ (p_t - p_0) × (p_t+1 - p_0) of a plane
// piece (its fan), from coordinates relative to `corner` (the cell's).
inline void piece_vector_area(const Polygon& poly, const double corner[3], double out[3]) {
    out[0] = out[1] = out[2] = 0;
    double q[kMaxVertices][3];
    for (int v = 0; v < poly.n; ++v)
        for (int a = 0; a < 3; ++a) q[v][a] = poly.p[v].v[a] - corner[a];
    for (int t = 1; t + 1 < poly.n; ++t) {
        const double u[3] = {q[t][0] - q[0][0], q[t][1] - q[0][1], q[t][2] - q[0][2]};
        const double w[3] = {q[t + 1][0] - q[0][0], q[t + 1][1] - q[0][1], q[t + 1][2] - q[0][2]};
        out[0] += 0.5 * (u[1] * w[2] - u[2] * w[1]);
        out[1] += 0.5 * (u[2] * w[0] - u[0] * w[2]);
        out[2] += 0.5 * (u[0] * w[1] - u[1] * w[0]);
    }
}

}  // namespace polyvol::grid

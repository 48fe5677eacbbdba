// measure/vtnb.cpp — Franklin's local-topology formulas for volume, area and
// edge length.
//
// Source: W. R. Franklin's note on polyhedron volume ("Polygon properties
// calculated from the vertex neighborhoods", ACM SoCG 1987, and his note on
// polyhedron volume). For every vertex–edge–face incidence (V, T, N, B):
// V the vertex, T the unit tangent along the edge away from V, N the unit
// normal to the edge in the face's plane pointing into the face, B the unit
// normal of the face pointing into the solid,
//   VOLUME = -1/6 Σ (V·T)(V·N)(V·B),  AREA = 1/2 Σ (V·T)(V·N),  LENGTH = -1/2 Σ V·T.
// Only local topology is needed: no edge has to be matched with its twin.
//
// What is summed here:
//   * VOLUME and AREA over the fan triangles (a polygon means its fan, also
//     when non-planar), each with its own plane: for a triangle (p0 p1 p2),
//     counter-clockwise seen from outside, n = (p1-p0)×(p2-p1), B = -n/|n|;
//     for the edge p_k -> p_{k+1}, T = ±(p_{k+1}-p_k)/|..| and N = T_k × B
//     (T_k the tangent from p_k; N is the same for both ends of the edge).
//     Per triangle the six incidences add up, in exact arithmetic, to
//     det(p0,p1,p2)/6 and |n|/2 (the two ends of an edge share V·N and V·B,
//     and Σ_edges (V·N) |edge| = -2 area): the cone volume and the area of
//     the triangle. Triangles whose computed normal is exactly 0 are skipped
//     (B is undefined; a zero-area triangle's exact contribution is 0, and
//     the bound covers a nearly degenerate one whose cross product rounded
//     to 0).
//   * LENGTH over the polygon's own edges (consecutive vertices, with the
//     closing edge; zero-length edges skipped), not over the fan triangles:
//     a fan diagonal is used by two fan triangles and both uses contribute
//     +|diagonal|/2 — the two ends of an edge give -(V1·T) - (V2·(-T)) =
//     |edge| whatever the direction of use — so diagonals do not cancel in
//     LENGTH (they do cancel in VOLUME and AREA when the face is planar: N
//     flips between the two triangles). Every edge use gives |edge|/2, so
//     LENGTH counts each edge once only when it is used by exactly two faces.
//
// Local origin. The three sums are origin-independent only for closed
// surfaces, and their terms grow with |V|^3, |V|^2, |V|. So V is taken
// relative to a local origin o, per axis: 0 when the bounding box of all
// positions contains 0 on that axis (then |V_j| <= the box's extent), else
// the box's centre rounded down to a multiple of ulp(max |coordinate|) and
// clamped to <= 2 min |coordinate|. With that choice x - o is exact for every
// coordinate x of the box (x and o are multiples of ulp(x), |x - o| <= |x|),
// so the shifted surface is the given one translated exactly: for a closed
// surface the formula's value, and the bound below, refer to the exact
// volume, area and length of the given doubles. For an open surface they
// refer to the formula about o.
//
// Error bound: docs/numerics.md, "Franklin's formulas' bounds" (a "frame"
// bound per triangle from the unit vectors' errors, or the fallback from
// the triangle's exact cone volume and area, whichever is smaller).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "exact/eft.hpp"
#include "measure/certified_sum.hpp"
#include "measure/methods.hpp"

namespace polyvol::measure {
namespace {

using namespace certified;

// u = v / |v| for v != 0 (each component within (1+θ10) of the exact one,
// up to underflow); returns |v| (relative error <= γ5). Non-finite v gives NaN.
double unit3(const double v[3], double out[3]) {
    const double m = std::max(std::max(std::fabs(v[0]), std::fabs(v[1])), std::fabs(v[2]));
    if (m > 0x1p-500 && m < 0x1p500) {
        const double r = std::sqrt((v[0] * v[0] + v[1] * v[1]) + v[2] * v[2]);
        for (int i = 0; i < 3; ++i) out[i] = v[i] / r;
        return r;
    }
    if (!std::isfinite(m) || v[0] != v[0] || v[1] != v[1] || v[2] != v[2]) {
        const double nan = std::numeric_limits<double>::quiet_NaN();
        out[0] = out[1] = out[2] = nan;
        return nan;
    }
    int e = 0;
    std::frexp(m, &e);
    const double s[3] = {std::ldexp(v[0], -e), std::ldexp(v[1], -e), std::ldexp(v[2], -e)};
    const double r = std::sqrt((s[0] * s[0] + s[1] * s[1]) + s[2] * s[2]);
    for (int i = 0; i < 3; ++i) out[i] = s[i] / r;
    return std::ldexp(r, e);
}

double dot(const double a[3], const double b[3]) { return (a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]; }

// The local origin along one axis whose coordinates lie in [lo, hi] (see the
// file comment): x - o is exact for every x in [lo, hi].
double positive_axis_origin(double lo, double hi) {  // 0 < lo <= hi, finite
    const double g = std::ldexp(1.0, std::max(std::ilogb(hi) - 52, -1074));  // ulp(hi)
    const double c = std::min(lo + (hi - lo) / 2, 2 * lo);
    return std::floor(c / g) * g;  // exact: c / g is a power-of-two scaling
}
double axis_origin(double lo, double hi) {
    if (!(std::isfinite(lo) && std::isfinite(hi)) || lo > hi) return 0;
    if (lo > 0) return positive_axis_origin(lo, hi);
    if (hi < 0) return -positive_axis_origin(-hi, -lo);
    return 0;
}

struct VtnbAcc {
    Acc vol, area, len;  // raw sums: Σ ±(V·T)(V·N)(V·B), Σ ±(V·T)(V·N), Σ ±V·T
    void merge(const VtnbAcc& o) {
        vol.merge(o.vol);
        area.merge(o.area);
        len.merge(o.len);
    }
};

constexpr double kTiny = 0x1p-1070;
constexpr double kEpsT = 2 * kU + gam(10) + kTiny;
constexpr double kAlphaT = kEpsT + gam(3) * (1 + kEpsT);

// The six incidences of the fan triangle (p0, p1, p2) (shifted coordinates).
void add_triangle(const double p[3][3], VtnbAcc& a) {
    double e[3][3];
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 3; ++j) e[k][j] = p[(k + 1) % 3][j] - p[k][j];
    const BoundedCross cross = bounded_cross(e[0], e[1]);
    const double* n = cross.n;  // (p1-p0)×(p2-p1), outward
    const double X = cross.X;
    const double rho[3] = {norm3(p[0][0], p[0][1], p[0][2]), norm3(p[1][0], p[1][1], p[1][2]),
                           norm3(p[2][0], p[2][1], p[2][2])};
    const double rmax2 = 2 * std::max(std::max(rho[0], rho[1]), rho[2]);
    a.vol.aux = std::max(a.vol.aux, rmax2);
    a.area.aux = std::max(a.area.aux, rmax2);
    ++a.vol.units;
    ++a.area.units;
    constexpr double g4 = gam(4), g5 = gam(5);
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) {  // skipped: exact raw sums are <= ρ0|n|, |n|
        a.vol.err += g4 * X * rho[0];
        a.area.err += g4 * X;
        return;
    }
    double B[3];
    const double nu = unit3(n, B);
    for (double& b : B) b = -b;  // into the solid
    const double c[3] = {dot(p[0], B), dot(p[1], B), dot(p[2], B)};  // V·B per vertex

    double vol_abs = 0, area_abs = 0;
    for (int k = 0; k < 3; ++k) {
        const int k1 = (k + 1) % 3;
        double T[3];
        unit3(e[k], T);  // from p_k towards p_{k1}; e[k] != 0 since n̂ != 0
        const double N[3] = {T[1] * B[2] - T[2] * B[1], T[2] * B[0] - T[0] * B[2],
                             T[0] * B[1] - T[1] * B[0]};  // into the triangle
        // V = p_k, tangent +T; V = p_k1, tangent -T.
        const double ab0 = dot(p[k], T) * dot(p[k], N);
        const double ab1 = -dot(p[k1], T) * dot(p[k1], N);
        const double t0 = ab0 * c[k], t1 = ab1 * c[k1];
        a.vol.add(t0, 0);
        a.vol.add(t1, 0);
        a.area.add(ab0, 0);
        a.area.add(ab1, 0);
        vol_abs += std::fabs(t0) + std::fabs(t1);
        area_abs += std::fabs(ab0) + std::fabs(ab1);
    }

    // Fallback bound: |computed| + |exact| of the triangle's raw sums.
    const double n_bound = (1 + g5) * nu + g4 * X;  // >= |n|
    double e_vol = vol_abs + rho[0] * n_bound;
    double e_area = area_abs + n_bound;
    // Frame bound, when B̂ is within 1 of B.
    const double eps_b = gam(10) + 2 * g5 * (1 + g5) * X / nu + kTiny;
    if (eps_b < 1 && X >= 0x1p-1000) {
        const double eps_n = 1.5 * gam(2) * (1 + kEpsT) * (1 + eps_b) + kEpsT * (1 + eps_b) + eps_b + kTiny;
        const double al_b = eps_b + gam(3) * (1 + eps_b);
        const double al_n = eps_n + gam(3) * (1 + eps_n);
        const double beta_v = (((kAlphaT + al_n) + al_b) + 2 * kU) * (1 + kAlphaT) * (1 + al_n) *
                              (1 + al_b) * kOnePlus2U * kOnePlus2U;
        const double beta_a = ((kAlphaT + al_n) + kU) * (1 + kAlphaT) * (1 + al_n) * kOnePlus2U;
        double r3 = 0, r2 = 0;
        for (double r : rho) {
            r2 += r * r;
            r3 += r * r * r;
        }
        e_vol = std::min(e_vol, 2 * beta_v * r3);
        e_area = std::min(e_area, 2 * beta_a * r2);
    }
    a.vol.err += e_vol;
    a.area.err += e_area;
}

}  // namespace

VtnbResult vtnb_measures(const MeshView& mesh) {
    // Local origin (see the file comment).
    double lo[3], hi[3];
    for (int j = 0; j < 3; ++j) {
        lo[j] = std::numeric_limits<double>::infinity();
        hi[j] = -lo[j];
    }
    const std::span<const double> pos = mesh.positions;
    for (std::size_t i = 0; i + 2 < pos.size(); i += 3)
        for (int j = 0; j < 3; ++j) {
            const double x = pos[i + static_cast<std::size_t>(j)];
            if (x < lo[j]) lo[j] = x;
            if (x > hi[j]) hi[j] = x;
        }
    const double o[3] = {axis_origin(lo[0], hi[0]), axis_origin(lo[1], hi[1]), axis_origin(lo[2], hi[2])};
    auto load = [&](uint32_t v, double out[3]) {
        for (int j = 0; j < 3; ++j) out[j] = pos[3 * std::size_t{v} + static_cast<std::size_t>(j)] - o[j];
    };

    const uint32_t* idx = mesh.indices.data();
    const VtnbAcc acc = reduce<VtnbAcc>(mesh.face_count(), [&](std::size_t f, VtnbAcc& a) {
        const std::size_t k = mesh.face_size(f);
        if (k < 3) return;
        const uint32_t* v = idx + mesh.face_begin(f);
        // LENGTH over the polygon's edges.
        for (std::size_t j = 0; j < k; ++j) {
            double pa[3], pb[3], e[3], T[3];
            load(v[j], pa);
            load(v[j + 1 == k ? 0 : j + 1], pb);
            for (int i = 0; i < 3; ++i) e[i] = pb[i] - pa[i];
            if (e[0] == 0 && e[1] == 0 && e[2] == 0) continue;
            unit3(e, T);
            const double ra = norm3(pa[0], pa[1], pa[2]), rb = norm3(pb[0], pb[1], pb[2]);
            a.len.add(dot(pa, T), kAlphaT * ra);
            a.len.add(-dot(pb, T), kAlphaT * rb);
            a.len.aux = std::max(a.len.aux, 2 * std::max(ra, rb));
            ++a.len.units;
        }
        // VOLUME and AREA over the fan triangles.
        double p[3][3];
        load(v[0], p[0]);
        load(v[1], p[2]);
        for (std::size_t i = 1; i + 1 < k; ++i) {
            std::copy(p[2], p[2] + 3, p[1]);
            load(v[i + 1], p[2]);
            add_triangle(p, a);
        }
    });
    return {finish(acc.vol, 6.0, 3, -1.0), finish(acc.area, 2.0, 2), finish(acc.len, 2.0, 1, -1.0)};
}

}  // namespace polyvol::measure

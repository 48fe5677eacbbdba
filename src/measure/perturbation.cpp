// measure/perturbation.cpp — how far the measures move when every coordinate
// moves by at most δ (measure.hpp, perturbation_bounds). Per fan triangle
// (a, b, c), ε = √3 δ bounding each vertex's displacement:
//   |ΔD| <= ε (|b×c| + |c×a| + |a×b|) + ε² (|a| + |b| + |c|) + ε³,  D = det(a, b, c)
//   V = Σ D / 6,  F_i = Σ D s_i / 24,  S_ij = Σ D (a_i a_j + b_i b_j + c_i c_j + s_i s_j) / 120,
// s = a + b + c, m = max |coordinate|: |Δ(D s_i)| <= |ΔD| 3m + (|D| + |ΔD|) 3δ and
// |Δ(D q_ij)| <= |ΔD| 12 m² + (|D| + |ΔD|)(24 δ m + 12 δ²), |D| <= |a| |b×c|
// A closed surface's volume takes the vertices relative to the middle of its
// box instead. A region bounded by pieces of the surface ({W >= 1}) changes
// only where a triangle sweeps: T ⊕ ball(ε) per triangle (docs/numerics.md,
// "Coordinates within delta").
#include <algorithm>
#include <cmath>
#include <limits>

#include "polyvol/measure.hpp"

namespace polyvol {
namespace {

struct V3 {
    double x, y, z;
};
V3 at(const MeshView& m, uint32_t v) {
    const double* p = m.positions.data() + 3 * std::size_t{v};
    return {p[0], p[1], p[2]};
}
double norm(const V3& a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
V3 cross(const V3& a, const V3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 minus(const V3& a, const V3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double largest(const V3& a) { return std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)}); }

// Each bound is a sum of nonnegative terms, each computed with a relative
// error below 10 u: the sums' rounding stays below (n + 10) u relative, which
// this factor covers for up to 2^30 terms.
constexpr double kRoundUp = 1 + 0x1p-20;

}  // namespace

PerturbationBounds perturbation_bounds(const MeshView& mesh, double delta, bool closed) {
    PerturbationBounds b;
    if (!(delta > 0)) return b;
    const double eps = std::sqrt(3.0) * delta * kRoundUp;
    // A closed surface's volume is Σ det(a - o, b - o, c - o) / 6 for any o,
    // before and after the move: o at the middle of its box keeps the factors
    // small. (o is rounded; the identity holds for any o.)
    V3 o{0, 0, 0};
    if (closed && mesh.vertex_count() > 0) {
        V3 lo = at(mesh, 0), hi = lo;
        for (uint32_t v = 1; v < mesh.vertex_count(); ++v) {
            const V3 p = at(mesh, v);
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        }
        o = {lo.x / 2 + hi.x / 2, lo.y / 2 + hi.y / 2, lo.z / 2 + hi.z / 2};
    }
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
        const auto c = mesh.face(f);
        b.edge_length += 2 * eps * static_cast<double>(c.size());
        for (std::size_t i = 1; i + 1 < c.size(); ++i) {
            const V3 p = at(mesh, c[0]), q = at(mesh, c[i]), r = at(mesh, c[i + 1]);
            // |y × z| computed, plus what cancellation in its components may
            // have lost (each within 2u |y| |z|): an upper bound.
            auto cross_norm = [](const V3& y, const V3& z) { return norm(cross(y, z)) + 4 * 0x1p-53 * norm(y) * norm(z); };
            auto det_movement = [&](const V3& x, const V3& y, const V3& z) {
                return eps * (cross_norm(y, z) + cross_norm(z, x) + cross_norm(x, y)) +
                       eps * eps * (norm(x) + norm(y) + norm(z)) + eps * eps * eps;
            };
            const double np = norm(p), nqr = cross_norm(q, r);
            const double dd = det_movement(p, q, r);  // about the origin, for the moments
            const double d = np * nqr;                 // >= |det(p, q, r)|
            const double m = std::max({largest(p), largest(q), largest(r)});
            b.volume += closed ? det_movement(minus(p, o), minus(q, o), minus(r, o)) : dd;
            b.first_moments += dd * 3 * m + (d + dd) * 3 * delta;
            b.second_moments += dd * 12 * m * m + (d + dd) * (24 * delta * m + 12 * delta * delta);
            const V3 u = minus(q, p), v = minus(r, p);
            b.area += 2 * eps * (norm(u) + norm(v)) + 4 * eps * eps;
            // What the triangle sweeps, moving its corners by at most ε: within
            // T ⊕ ball(ε), of volume 2εA + (π/2)ε²P + (4/3)πε³ (Steiner).
            const double area = cross_norm(u, v) / 2, perimeter = norm(u) + norm(v) + norm(minus(r, q));
            const double sweep = 2 * eps * area + 1.5708 * eps * eps * perimeter + 4.1888 * eps * eps * eps;
            b.swept_volume += sweep;
            b.swept_first_moments += sweep * (m + eps);
            b.swept_second_moments += sweep * (m + eps) * (m + eps);
        }
    }
    b.volume *= kRoundUp / 6;
    b.first_moments *= kRoundUp / 24;
    b.second_moments *= kRoundUp / 120;
    b.area *= kRoundUp / 2;
    b.edge_length *= kRoundUp;
    b.swept_volume *= kRoundUp;
    b.swept_first_moments *= kRoundUp;
    b.swept_second_moments *= kRoundUp;
    return b;
}

void widen_for_coordinate_error(const MeshView& mesh, double delta, double density, bool closed, bool region,
                                MassProperties& m) {
    if (!(delta > 0)) return;
    PerturbationBounds p = perturbation_bounds(mesh, delta, closed);
    if (region) {  // a region bounded by pieces of the surface: what the triangles sweep
        p.volume = p.swept_volume;
        p.first_moments = p.swept_first_moments;
        p.second_moments = p.swept_second_moments;
    }
    const double inf = std::numeric_limits<double>::infinity();
    const double u = 0x1p-53;
    // Volume: the rounding (half an ulp when correctly rounded) plus the movement.
    const double rounding = m.volume_correctly_rounded ? u * std::fabs(m.volume) : m.volume_error_bound;
    m.volume_error_bound = (rounding + p.volume) * kRoundUp;
    m.volume_correctly_rounded = false;
    auto widen_relative = [&](double& rel, double value, double moved) {
        rel = value != 0 ? (rel + moved / std::fabs(value)) * kRoundUp : inf;
    };
    widen_relative(m.area_relative_error, m.area, p.area);
    if (!std::isnan(m.edge_length)) widen_relative(m.edge_length_relative_error, m.edge_length, p.edge_length);
    if (std::isnan(m.first_moments[0])) return;
    // Moments: each array's bound relative to its largest magnitude.
    const double rho = std::fabs(density);
    const double vol = std::fabs(m.volume), dv = p.volume;
    const double dF = rho * p.first_moments, dS = rho * p.second_moments;
    double fmax = 0, smax = 0, icmax = 0;
    for (double x : m.first_moments) fmax = std::max(fmax, std::fabs(x));
    for (double x : m.second_moments) smax = std::max(smax, std::fabs(x));
    for (double x : m.inertia_centroid) icmax = std::max(icmax, std::fabs(x));
    const double rel_v = vol > dv ? dv / (vol - dv) : inf;
    const double rel_f = fmax > 0 ? dF / fmax : inf;
    const double rel_s = smax > 0 ? dS / smax : inf;
    // Centroid F / V: (ΔF + |c| ΔV) / (V - ΔV), relative to max |c| = max |F| / V:
    // rel_f V / (V - ΔV) + rel_v, and V / (V - ΔV) = 1 + rel_v.
    const double rel_c = rel_f * (1 + rel_v) + rel_v;
    // Inertia about the origin: entries S_jj + S_kk or -S_jk, and max |I| >= 2/3 max |S| (S >= 0).
    const double rel_io = 3 * rel_s;
    // About the centroid, S - F F^T / M with M = ρ V: the product's movement,
    // then twice that for a diagonal entry.
    const double mass = rho * vol, dm = rho * dv;
    const double d_ff = mass > dm ? (2 * fmax * dF + dF * dF) / (mass - dm) + fmax * fmax * dm / (mass * (mass - dm)) : inf;
    const double rel_ic = icmax > 0 ? 2 * (dS + d_ff) / icmax : inf;
    const double r0 = m.moments_correctly_rounded ? u : m.moments_relative_error;
    const bool second = !std::isnan(m.second_moments[0]);  // `polyvol volume` leaves them out
    const double worst = std::max({rel_f, rel_c, second ? std::max({rel_s, rel_io, rel_ic}) : 0.0});
    m.moments_relative_error = (r0 + worst) * kRoundUp;
    m.moments_correctly_rounded = false;
}

}  // namespace polyvol

// measure/cone_exact.cpp — the cone rule's sums exactly: each fan
// triangle's terms as integers when its coordinates share their leading
// exponents (integer_triangle, called by the kernels' exact pass), and the
// sums in big integers (GMP) for any finite coordinates.
//
// Integers: when each axis's three coordinates are k 2^e with |k| < 2^60,
// det is an integer times 2^(ex+ey+ez), det s_i one times 2^(.. + e_i) and
// det q_ij one times 2^(.. + e_i + e_j), in at most 384 bits, added to the
// superaccumulator at their exponent (ExactSum::add_wide).
// GMP: coordinates as integers times 2^E0 (E0 the lowest set bit of any used
// coordinate), the sums in mpz, then scaled: exact for any finite input.
#include <gmp.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "measure/cone_kernels.hpp"
#include "core/bit_cast.hpp"

namespace polyvol::measure::cone {
namespace {

using exact::ExactSum;

__extension__ typedef unsigned __int128 u128;
__extension__ typedef __int128 i128;

// out[0 .. nx+ny) = x * y (magnitudes).
POLYVOL_INLINE void wide_mul(const uint64_t* x, int nx, const uint64_t* y, int ny, uint64_t* out) {
    for (int i = 0; i < nx + ny; ++i) out[i] = 0;
    for (int i = 0; i < nx; ++i) {
        u128 c = 0;
        for (int j = 0; j < ny; ++j) {
            c += static_cast<u128>(x[i]) * y[j] + out[i + j];
            out[i + j] = static_cast<uint64_t>(c);
            c >>= 64;
        }
        out[i + ny] = static_cast<uint64_t>(c);
    }
}

POLYVOL_INLINE void split_i128(i128 v, uint64_t* mag, bool& negative) {
    negative = v < 0;
    const u128 m = negative ? static_cast<u128>(0) - static_cast<u128>(v) : static_cast<u128>(v);
    mag[0] = static_cast<uint64_t>(m);
    mag[1] = static_cast<uint64_t>(m >> 64);
}

// Coordinate x = k 2^e with an integer k: the exponent of x's lowest set bit
// and of its highest (x != 0, finite).
POLYVOL_INLINE void bit_range(double x, int& lowest, int& highest) {
    const uint64_t bits = core::bit_cast<uint64_t>(x);
    const int ex = static_cast<int>((bits >> 52) & 0x7FF);
    const uint64_t frac = bits & ((uint64_t{1} << 52) - 1);
    const uint64_t mant = ex != 0 ? (frac | (uint64_t{1} << 52)) : frac;
    const int e = (ex != 0 ? ex : 1) - 1075;  // x = mant 2^e
    lowest = e + std::countr_zero(mant);
    highest = e + 63 - std::countl_zero(mant);
}

// One triangle's exact terms as integers, when each axis's three
// coordinates are k 2^e_axis with |k| < 2^60 (the usual case: a triangle's
// coordinates share their leading exponents). det is then an integer times
// 2^(ex+ey+ez), det s_i one times 2^(ex+ey+ez+e_i), det q_ij one times
// 2^(ex+ey+ez+e_i+e_j) (det is trilinear with one coordinate of each axis
// per term). Bounds: |det| < 2^183, |s| < 2^62, |q| < 2^125, |det q| < 2^308.
// Returns false (nothing added) when some axis spans more than 60 bits.
}  // namespace

bool integer_triangle(const double* a, const double* b, const double* c, uint32_t mask, ExactSum* acc) {
    int e[3];
    for (int k = 0; k < 3; ++k) {
        int lo = std::numeric_limits<int>::max(), hi = std::numeric_limits<int>::min();
        for (double x : {a[k], b[k], c[k]}) {
            if (x == 0) continue;
            int l, h;
            bit_range(x, l, h);
            lo = std::min(lo, l);
            hi = std::max(hi, h);
        }
        if (lo == std::numeric_limits<int>::max()) {
            lo = 0;  // all three zero
        } else if (hi + 1 - lo > 60) {
            return false;
        }
        e[k] = lo;
    }
    int64_t A[3], B[3], C[3];
    for (int k = 0; k < 3; ++k) {  // exact: |x 2^-e| < 2^60; 2^-e is a normal double in the safe range
        const double scale = core::bit_cast<double>(static_cast<uint64_t>(1023 - e[k]) << 52);
        A[k] = static_cast<int64_t>(a[k] * scale);
        B[k] = static_cast<int64_t>(b[k] * scale);
        C[k] = static_cast<int64_t>(c[k] * scale);
    }
    // det = Σ A_k x_k, x_k = B_j C_l - B_l C_j (|x_k| < 2^121), as
    // hi 2^64 + lo: with x_k = xh_k 2^64 + xl_k (xl_k unsigned, |xh_k| <=
    // 2^57), Σ A_k xl_k (|.| < 3 2^124) and Σ A_k xh_k (< 2^119) in 128-bit
    // integers, the first's high word carried into the second (|hi| < 2^120).
    i128 lo_sum = 0, hi = 0;
    for (int k = 0; k < 3; ++k) {
        const int j = (k + 1) % 3, l = (k + 2) % 3;
        const i128 x = static_cast<i128>(B[j]) * C[l] - static_cast<i128>(B[l]) * C[j];
        lo_sum += static_cast<i128>(A[k]) * static_cast<i128>(static_cast<uint64_t>(x));
        hi += static_cast<i128>(A[k]) * static_cast<int64_t>(x >> 64);
    }
    hi += lo_sum >> 64;  // arithmetic shift: lo_sum = (lo_sum >> 64) 2^64 + its low word
    uint64_t lo = static_cast<uint64_t>(lo_sum);
    if (hi == 0 && lo == 0) return true;  // det == 0: every term is 0
    const bool dn = hi < 0;
    if (dn) {  // |det| = -(hi 2^64 + lo)
        hi = -hi - (lo != 0 ? 1 : 0);
        lo = static_cast<uint64_t>(0) - lo;
    }
    const uint64_t d[3] = {lo, static_cast<uint64_t>(hi), static_cast<uint64_t>(hi >> 64)};  // |det| < 2^183
    const int ev = e[0] + e[1] + e[2];
    if (mask & (1u << kV)) acc[kV].add_wide(d, 3, dn, ev);
    int64_t s[3];
    for (int k = 0; k < 3; ++k) s[k] = A[k] + B[k] + C[k];  // |s| < 2^62
    for (int k = 0; k < 3; ++k) {
        if (!(mask & (1u << (kMx + k)))) continue;
        const uint64_t sm[1] = {s[k] < 0 ? static_cast<uint64_t>(0) - static_cast<uint64_t>(s[k])
                                         : static_cast<uint64_t>(s[k])};
        uint64_t p[4];
        wide_mul(d, 3, sm, 1, p);
        acc[kMx + k].add_wide(p, 4, dn != (s[k] < 0), ev + e[k]);
    }
    constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
    for (int k = 0; k < 6; ++k) {
        if (!(mask & (1u << (kSxx + k)))) continue;
        const int x = I[k], y = J[k];
        const i128 q = static_cast<i128>(A[x]) * A[y] + static_cast<i128>(B[x]) * B[y] +
                       static_cast<i128>(C[x]) * C[y] + static_cast<i128>(s[x]) * s[y];  // |q| < 2^125
        uint64_t qm[2], p[5];
        bool qn;
        split_i128(q, qm, qn);
        wide_mul(d, 3, qm, 2, p);
        acc[kSxx + k].add_wide(p, 5, dn != qn, ev + e[x] + e[y]);
    }
    return true;
}

namespace {

struct Mpz {
    mpz_t z;
    Mpz() { mpz_init(z); }
    Mpz(const Mpz&) = delete;
    Mpz& operator=(const Mpz&) = delete;
    ~Mpz() { mpz_clear(z); }
};

// x = m 2^e with m an odd integer (x != 0, finite): returns e.
int lowest_bit_exponent(double x) {
    int e;
    const double m = std::frexp(x, &e);  // x = m 2^e, 0.5 <= |m| < 1
    auto mant = static_cast<uint64_t>(std::ldexp(std::fabs(m), 53));
    return e - 53 + std::countr_zero(mant);
}

// z = x 2^-e0 (an integer: e0 <= lowest_bit_exponent(x)).
void to_integer(double x, int e0, mpz_t z) {
    if (x == 0) {
        mpz_set_ui(z, 0);
        return;
    }
    int e;
    const double m = std::frexp(x, &e);
    mpz_set_d(z, std::ldexp(m, 53));  // exact integer, |.| < 2^53
    const int shift = e - 53 - e0;
    if (shift >= 0) {
        mpz_mul_2exp(z, z, static_cast<mp_bitcnt_t>(shift));
    } else {
        mpz_tdiv_q_2exp(z, z, static_cast<mp_bitcnt_t>(-shift));  // exact: low bits are zero
    }
}


// Calls fn(a, b, c) for each fan triangle of the faces (coordinates by pointer).
template <class Fn>
void for_each_triangle(const MeshView& mesh, Fn&& fn) {
    const double* pos = mesh.positions.data();
    const uint32_t* idx = mesh.indices.data();
    const auto at = [&](uint32_t v) { return pos + 3 * std::size_t{v}; };
    if (mesh.all_triangles()) {
        for (std::size_t f = 0; f < mesh.face_count(); ++f) fn(at(idx[3 * f]), at(idx[3 * f + 1]), at(idx[3 * f + 2]));
        return;
    }
    const uint32_t* off = mesh.face_offsets.data();
    for (std::size_t f = 0; f < mesh.face_count(); ++f) {
        const uint32_t begin = off[f], end = off[f + 1];
        for (uint32_t i = begin + 1; i + 1 < end; ++i) fn(at(idx[begin]), at(idx[i]), at(idx[i + 1]));
    }
}

}  // namespace

RationalSums gmp_sums(const MeshView& mesh, int count) {
    RationalSums out;
    // The common scale: the lowest set bit of any coordinate of a used vertex.
    int e0 = std::numeric_limits<int>::max();
    bool any = false;
    for_each_triangle(mesh, [&](const double* a, const double* b, const double* c) {
        for (const double* p : {a, b, c})
            for (int k = 0; k < 3; ++k) {
                const double x = p[k];
                if (!std::isfinite(x)) {
                    out.ok = false;
                } else if (x != 0) {
                    e0 = std::min(e0, lowest_bit_exponent(x));
                    any = true;
                }
            }
    });
    if (!out.ok || !any) return out;  // not finite, or every sum is 0

    Mpz sums[kSumCount];
    Mpz c[9], det, s[3], t1, t2, q;
    for_each_triangle(mesh, [&](const double* a, const double* b, const double* cc) {
        for (int k = 0; k < 3; ++k) {
            to_integer(a[k], e0, c[k].z);
            to_integer(b[k], e0, c[3 + k].z);
            to_integer(cc[k], e0, c[6 + k].z);
        }
        mpz_ptr A[3] = {c[0].z, c[1].z, c[2].z}, B[3] = {c[3].z, c[4].z, c[5].z},
                C[3] = {c[6].z, c[7].z, c[8].z};
        mpz_set_ui(det.z, 0);
        for (int k = 0; k < 3; ++k) {
            const int j = (k + 1) % 3, l = (k + 2) % 3;
            mpz_mul(t1.z, B[j], C[l]);
            mpz_submul(t1.z, B[l], C[j]);
            mpz_addmul(det.z, A[k], t1.z);
        }
        mpz_add(sums[kV].z, sums[kV].z, det.z);
        if (count == 1) return;
        for (int k = 0; k < 3; ++k) {
            mpz_add(s[k].z, A[k], B[k]);
            mpz_add(s[k].z, s[k].z, C[k]);
            mpz_addmul(sums[kMx + k].z, det.z, s[k].z);
        }
        if (count <= kSxx) return;
        constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
        for (int k = 0; k < 6; ++k) {
            const int x = I[k], y = J[k];
            mpz_mul(q.z, A[x], A[y]);
            mpz_addmul(q.z, B[x], B[y]);
            mpz_addmul(q.z, C[x], C[y]);
            mpz_addmul(q.z, s[x].z, s[y].z);
            mpz_addmul(sums[kSxx + k].z, det.z, q.z);
        }
    });
    for (int k = 0; k < count; ++k) {
        const int degree = k == kV ? 3 : (k <= kMz ? 4 : 5);
        mpq_ptr r = out.sum[k].get();
        mpq_set_z(r, sums[k].z);
        const long shift = static_cast<long>(degree) * e0;
        if (shift >= 0) {
            mpq_mul_2exp(r, r, static_cast<mp_bitcnt_t>(shift));
        } else {
            mpq_div_2exp(r, r, static_cast<mp_bitcnt_t>(-shift));
        }
    }
    return out;
}

}  // namespace polyvol::measure::cone

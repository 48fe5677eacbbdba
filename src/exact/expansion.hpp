// exact/expansion.hpp — floating-point expansions: a number held exactly as
// an unevaluated sum of doubles.
//
// Source: J. R. Shewchuk, "Adaptive precision floating-point arithmetic and
// fast robust geometric predicates", Discrete Comput. Geom. 18 (1997) —
// Grow-Expansion, Fast-Expansion-Sum, Scale-Expansion, Compress, and the
// exact 3x3 determinant as in his orient3d. The routines keep his
// conventions: components in increasing order of magnitude, zeros eliminated,
// nonoverlapping (strongly so under round-to-nearest-even).
//
// Exact under the conditions of eft.hpp (no overflow, every product's error
// representable: polyvol checks the coordinate range before using these).
#pragma once

#include <cmath>

#include "exact/eft.hpp"

namespace polyvol::exact {

// Upper bounds on component counts of the results below.
inline constexpr int kDetTerms = 24;

// h = e + b; e nonoverlapping with elen components; h has room for elen + 1.
// Returns the number of components of h.
POLYVOL_INLINE int grow_expansion(int elen, const double* e, double b, double* h) {
    double q = b;
    int hlen = 0;
    for (int i = 0; i < elen; ++i) {
        double qn, hh;
        two_sum(q, e[i], qn, hh);
        q = qn;
        if (hh != 0) h[hlen++] = hh;
    }
    if (q != 0 || hlen == 0) h[hlen++] = q;
    return hlen;
}

// h = e + f (Fast-Expansion-Sum with zero elimination). e and f strongly
// nonoverlapping; h has room for elen + flen. Returns h's length (>= 1).
inline int fast_expansion_sum(int elen, const double* e, int flen, const double* f, double* h) {
    if (elen == 0) {
        for (int i = 0; i < flen; ++i) h[i] = f[i];
        if (flen == 0) h[0] = 0;
        return flen == 0 ? 1 : flen;
    }
    if (flen == 0) {
        for (int i = 0; i < elen; ++i) h[i] = e[i];
        return elen;
    }
    double enow = e[0], fnow = f[0], q;
    int ei = 0, fi = 0, hi = 0;
    if ((fnow > enow) == (fnow > -enow)) {
        q = enow;
        enow = ++ei < elen ? e[ei] : 0;
    } else {
        q = fnow;
        fnow = ++fi < flen ? f[fi] : 0;
    }
    double qn, hh;
    if (ei < elen && fi < flen) {
        if ((fnow > enow) == (fnow > -enow)) {
            fast_two_sum(enow, q, qn, hh);
            enow = ++ei < elen ? e[ei] : 0;
        } else {
            fast_two_sum(fnow, q, qn, hh);
            fnow = ++fi < flen ? f[fi] : 0;
        }
        q = qn;
        if (hh != 0) h[hi++] = hh;
        while (ei < elen && fi < flen) {
            if ((fnow > enow) == (fnow > -enow)) {
                two_sum(q, enow, qn, hh);
                enow = ++ei < elen ? e[ei] : 0;
            } else {
                two_sum(q, fnow, qn, hh);
                fnow = ++fi < flen ? f[fi] : 0;
            }
            q = qn;
            if (hh != 0) h[hi++] = hh;
        }
    }
    while (ei < elen) {
        two_sum(q, enow, qn, hh);
        enow = ++ei < elen ? e[ei] : 0;
        q = qn;
        if (hh != 0) h[hi++] = hh;
    }
    while (fi < flen) {
        two_sum(q, fnow, qn, hh);
        fnow = ++fi < flen ? f[fi] : 0;
        q = qn;
        if (hh != 0) h[hi++] = hh;
    }
    if (q != 0 || hi == 0) h[hi++] = q;
    return hi;
}

// h = b * e (Scale-Expansion with zero elimination); h has room for 2 elen.
template <bool kFma>
inline int scale_expansion(int elen, const double* e, double b, double* h) {
    double q, hh, p, pe, sum;
    two_prod_t<kFma>(e[0], b, q, hh);
    int hi = 0;
    if (hh != 0) h[hi++] = hh;
    for (int i = 1; i < elen; ++i) {
        two_prod_t<kFma>(e[i], b, p, pe);
        two_sum(q, pe, sum, hh);
        if (hh != 0) h[hi++] = hh;
        fast_two_sum(p, sum, q, hh);
        if (hh != 0) h[hi++] = hh;
    }
    if (q != 0 || hi == 0) h[hi++] = q;
    return hi;
}

// Compress: h == e with fewer components, the largest one approximating the
// whole to within an ulp. e nonoverlapping. h may alias e.
inline int compress(int elen, const double* e, double* h) {
    double g[64];
    int bottom = elen - 1;
    double q = e[bottom];
    for (int i = elen - 2; i >= 0; --i) {
        double qn, qq;
        fast_two_sum(q, e[i], qn, qq);
        if (qq != 0) {
            g[bottom--] = qn;
            q = qq;
        } else {
            q = qn;
        }
    }
    int top = 0;
    for (int i = bottom + 1; i < elen; ++i) {
        double qn, qq;
        fast_two_sum(g[i], q, qn, qq);
        q = qn;
        if (qq != 0) h[top++] = qq;
    }
    h[top++] = q;
    return top;
}

// The 2x2 determinant a*d - b*c as a 4-component expansion (Two-Two-Diff of
// Two-Products; components may be zero).
template <bool kFma>
POLYVOL_INLINE void det2_exact(double a, double d, double b, double c, double* x) {
    double p1, e1, p2, e2;
    two_prod_t<kFma>(a, d, p1, e1);
    two_prod_t<kFma>(b, c, p2, e2);
    // Two-Two-Diff (Shewchuk): (p1 + e1) - (p2 + e2).
    double i, x0, j, k, x1, x2, x3;
    two_sum(e1, -e2, i, x0);
    two_sum(p1, i, j, k);
    two_sum(k, -p2, i, x1);
    two_sum(j, i, x3, x2);
    x[0] = x0;
    x[1] = x1;
    x[2] = x2;
    x[3] = x3;
}

// det(a, b, c) = a · (b × c) exactly, as a compressed nonoverlapping
// expansion of at most kDetTerms components (returns the count, >= 1).
template <bool kFma>
inline int det3_exact(const double* a, const double* b, const double* c, double* out) {
    double m[4], t0[8], t1[8], t2[8], s01[16];
    det2_exact<kFma>(b[1], c[2], b[2], c[1], m);
    const int n0 = scale_expansion<kFma>(4, m, a[0], t0);
    det2_exact<kFma>(b[2], c[0], b[0], c[2], m);
    const int n1 = scale_expansion<kFma>(4, m, a[1], t1);
    det2_exact<kFma>(b[0], c[1], b[1], c[0], m);
    const int n2 = scale_expansion<kFma>(4, m, a[2], t2);
    const int n01 = fast_expansion_sum(n0, t0, n1, t1, s01);
    const int n = fast_expansion_sum(n01, s01, n2, t2, out);
    return compress(n, out, out);
}

}  // namespace polyvol::exact

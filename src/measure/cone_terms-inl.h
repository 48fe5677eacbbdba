// measure/cone_terms-inl.h — what the cone rule sums, per fan triangle
// (a, b, c), written once in Highway operations for every instruction set:
//   det = a · (b × c)                          (= 6 × the cone's volume)
//   det s_i,  s = a + b + c                    (first moments, × 24)
//   det (a_i a_j + b_i b_j + c_i c_j + s_i s_j) (second moments, × 120)
// in double-double with a magnitude that bounds each term's error, or in
// plain double (Accuracy::fast). The error analysis, the two forms of det
// (translated: a · ((b - a) × (c - a)); origin: a · (b × c)) and the
// constants are derived in docs/numerics.md, "The cone rule's kernels".
//
// Every lane is rounded as the scalar code would round it (no contraction:
// -ffp-contract=off; an FMA only inside two_prod, whose result is exact
// either way), so every target gives the same bits.
//
// Included once per target by cone_kernels.cpp (Highway's foreach_target).
#if defined(POLYVOL_MEASURE_CONE_TERMS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef POLYVOL_MEASURE_CONE_TERMS_INL_H_
#undef POLYVOL_MEASURE_CONE_TERMS_INL_H_
#else
#define POLYVOL_MEASURE_CONE_TERMS_INL_H_
#endif

#include <hwy/highway.h>

#include "measure/cone.hpp"

HWY_BEFORE_NAMESPACE();
namespace polyvol::measure::cone::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Vectors of at most 8 doubles (the volume pass sums 8 lanes; every target
// here has a fixed width: 1, 2, 4 or 8).
constexpr std::size_t kLanesCap = 8;
using D = hn::CappedTag<double, kLanesCap>;
using V = hn::Vec<D>;
constexpr int kN = static_cast<int>(hn::MaxLanes(D()));
static_assert(kLanesCap % kN == 0);

// s + e == a + b exactly (Knuth), in vectors of any width.
template <class VT>
HWY_INLINE void two_sum(VT a, VT b, VT& s, VT& e) {
    s = a + b;
    const VT bb = s - a;
    e = (a - (s - bb)) + (b - bb);
}

// One step of Sum2 (Ogita–Rump–Oishi) in every lane: the sums S take in h
// by two_sum, whose errors and the low parts l go into E.
HWY_INLINE void sum2_add(V& S, V& E, V h, V l) {
    V ns, ne;
    two_sum(S, h, ns, ne);
    S = ns;
    E = E + (ne + l);
}

// p + e == a b exactly: e = fma(a, b, -p) where the target has an FMA, else
// Dekker's product of Veltkamp's 26-bit halves (|a|, |b| < 2^996).
HWY_INLINE void two_prod(V a, V b, V& p, V& e) {
    p = a * b;
#if HWY_NATIVE_FMA
    e = hn::MulSub(a, b, p);
#else
    const V c = hn::Set(D(), 134217729.0);  // 2^27 + 1
    const V ca = c * a, cb = c * b;
    const V ah = ca - (ca - a), bh = cb - (cb - b);
    const V al = a - ah, bl = b - bh;
    e = (((ah * bh - p) + ah * bl) + al * bh) + al * bl;
#endif
}

// (xh + xl)(yh + yl) without xl yl, not renormalised: hi = fl(xh yh).
HWY_INLINE void dd_mul(V xh, V xl, V yh, V yl, V& hi, V& lo) {
    V e;
    two_prod(xh, yh, hi, e);
    lo = e + (xh * yl + xl * yh);
}

// The terms of kN triangles in double-double: term k is h[k] + l[k], its
// error at most a constant times u² m[k] (docs/numerics.md). kCount: 1 (the
// volume), kSxx (and first moments) or kSumCount (all ten). kCount == 1
// leaves (h, l) as formed, not renormalised (the volume pass's Sum2 adds l
// to its error terms); kTranslate false is the origin form, without m (the
// caller bounds the magnitude by 6 M^3 per triangle).
template <int kCount, bool kTranslate = true>
HWY_INLINE void terms_dd(const V (&a)[3], const V (&b)[3], const V (&c)[3], V* h, V* l, V* m) {
    static_assert(kTranslate || kCount == 1);
    const D d;
    // u = b - a, w = c - a, each split exactly as uh + ul, wh + wl.
    V uh[3], ul[3], wh[3], wl[3];
    for (int k = 0; k < 3; ++k) {
        if constexpr (kTranslate) {
            two_sum(b[k], hn::Neg(a[k]), uh[k], ul[k]);
            two_sum(c[k], hn::Neg(a[k]), wh[k], wl[k]);
        } else {
            uh[k] = b[k];
            wh[k] = c[k];
            ul[k] = wl[k] = hn::Zero(d);
        }
    }
    // n = uh × wh as ns + nl; pn = |uh_j wh_l| + |uh_l wh_j|; corr = the
    // cross terms with the low parts, in double.
    V ns[3], nl[3], pn[3], corr[3];
    for (int k = 0; k < 3; ++k) {
        const int j = (k + 1) % 3, q = (k + 2) % 3;
        V p1, e1, p2, e2, t;
        two_prod(uh[j], wh[q], p1, e1);
        two_prod(uh[q], wh[j], p2, e2);
        two_sum(p1, hn::Neg(p2), ns[k], t);
        nl[k] = (e1 - e2) + t;
        pn[k] = hn::Abs(p1) + hn::Abs(p2);
        if constexpr (kTranslate) {
            corr[k] = ((uh[j] * wl[q] - uh[q] * wl[j]) + (ul[j] * wh[q] - ul[q] * wh[j])) +
                      (ul[j] * wl[q] - ul[q] * wl[j]);
        }
    }
    // det = a · ns (products exact, the first two additions exact) + the rest.
    V P[3], Q[3];
    for (int k = 0; k < 3; ++k) two_prod(a[k], ns[k], P[k], Q[k]);
    V h1, g1, dh, g2;
    two_sum(P[0], P[1], h1, g1);
    two_sum(h1, P[2], dh, g2);
    V dl = ((g1 + g2) + ((Q[0] + Q[1]) + Q[2])) + ((a[0] * nl[0] + a[1] * nl[1]) + a[2] * nl[2]);
    if constexpr (kTranslate) dl = dl + ((a[0] * corr[0] + a[1] * corr[1]) + a[2] * corr[2]);
    if constexpr (kCount > 1) {
        V rh, rl;
        two_sum(dh, dl, rh, rl);
        dh = rh;
        dl = rl;
    }
    const V perm = (hn::Abs(a[0]) * pn[0] + hn::Abs(a[1]) * pn[1]) + hn::Abs(a[2]) * pn[2];
    h[kV] = dh;
    l[kV] = dl;
    if constexpr (kTranslate) m[kV] = perm;
    if constexpr (kCount > 1) {
        // s = a + b + c as sh + sl; sigma = |a| + |b| + |c|.
        V sh[3], sl[3], sigma[3];
        for (int k = 0; k < 3; ++k) {
            V t, e, e2;
            two_sum(a[k], b[k], t, e);
            two_sum(t, c[k], sh[k], e2);
            sl[k] = e + e2;
            sigma[k] = (hn::Abs(a[k]) + hn::Abs(b[k])) + hn::Abs(c[k]);
            dd_mul(dh, dl, sh[k], sl[k], h[kMx + k], l[kMx + k]);
            m[kMx + k] = perm * sigma[k];
        }
        if constexpr (kCount > kSxx) {
            // q = a_x a_y + b_x b_y + c_x c_y + s_x s_y as a double-double.
            constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
            for (int k = 0; k < 6; ++k) {
                const int x = I[k], y = J[k];
                V pa, ea, pb, eb, pc, ec, ssh, ssl;
                two_prod(a[x], a[y], pa, ea);
                two_prod(b[x], b[y], pb, eb);
                two_prod(c[x], c[y], pc, ec);
                dd_mul(sh[x], sl[x], sh[y], sl[y], ssh, ssl);
                V q1, f1, q2, f2, q3, f3;
                two_sum(pa, pb, q1, f1);
                two_sum(q1, pc, q2, f2);
                two_sum(q2, ssh, q3, f3);
                const V qlo = ((f1 + f2) + f3) + (((ea + eb) + ec) + ssl);
                V qh, ql;
                two_sum(q3, qlo, qh, ql);
                const V mq = ((hn::Abs(pa) + hn::Abs(pb)) + hn::Abs(pc)) + sigma[x] * sigma[y];
                dd_mul(dh, dl, qh, ql, h[kSxx + k], l[kSxx + k]);
                m[kSxx + k] = perm * mq;
            }
        }
    }
}

// The same terms in plain double: term k is h[k], its error at most a
// constant times u m[k].
template <int kCount>
HWY_INLINE void terms_fast(const V (&a)[3], const V (&b)[3], const V (&c)[3], V* h, V* m) {
    const D d;
    V u[3], w[3];
    for (int k = 0; k < 3; ++k) {
        u[k] = b[k] - a[k];
        w[k] = c[k] - a[k];
    }
    V det = hn::Zero(d), perm = hn::Zero(d);
    for (int k = 0; k < 3; ++k) {
        const int j = (k + 1) % 3, q = (k + 2) % 3;
        const V p1 = u[j] * w[q], p2 = u[q] * w[j];
        det = det + a[k] * (p1 - p2);
        perm = perm + hn::Abs(a[k]) * (hn::Abs(p1) + hn::Abs(p2));
    }
    h[kV] = det;
    m[kV] = perm;
    if constexpr (kCount > 1) {
        V s[3], sigma[3];
        for (int k = 0; k < 3; ++k) {
            s[k] = (a[k] + b[k]) + c[k];
            sigma[k] = (hn::Abs(a[k]) + hn::Abs(b[k])) + hn::Abs(c[k]);
            h[kMx + k] = det * s[k];
            m[kMx + k] = perm * sigma[k];
        }
        if constexpr (kCount > kSxx) {
            constexpr int I[6] = {0, 1, 2, 0, 1, 2}, J[6] = {0, 1, 2, 1, 2, 0};
            for (int k = 0; k < 6; ++k) {
                const int x = I[k], y = J[k];
                const V pa = a[x] * a[y], pb = b[x] * b[y], pc = c[x] * c[y];
                const V q = ((pa + pb) + pc) + s[x] * s[y];
                h[kSxx + k] = det * q;
                m[kSxx + k] = perm * (((hn::Abs(pa) + hn::Abs(pb)) + hn::Abs(pc)) + sigma[x] * sigma[y]);
            }
        }
    }
}

}  // namespace polyvol::measure::cone::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // POLYVOL_MEASURE_CONE_TERMS_INL_H_

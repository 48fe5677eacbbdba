// simplicial/volume.cpp — chain_volume: Allgower & Schmidt's (2.1) and (2.2)
// in R^n, by three paths (see simplicial.hpp for the formulas):
//   small exact — n = 2, 3: each determinant (and moment term) as an exact
//                 expansion (Shewchuk) added to a superaccumulator, rounded
//                 once at the end;
//   gmp         — any n: Bareiss determinants over GMP integers, rational sums;
//   bounded     — n >= 4: double LU determinants along a walk over the dual
//                 graph, with column-replacement updates (lu_update.hpp) or a
//                 fresh factorisation per simplex, each with a rigorous error
//                 bound; terms summed exactly, bounds summed and inflated.
#include <algorithm>
#include <bit>
#include <chrono>
#include <ctime>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "exact/expansion.hpp"
#include "exact/rational.hpp"
#include "polyvol/simplicial.hpp"
#include "simplicial/exact_det.hpp"
#include "simplicial/lu_update.hpp"
#include "simplicial/topology.hpp"

namespace polyvol {

std::string_view simplex_formula_name(SimplexFormula f) { return f == SimplexFormula::prism ? "prism" : "cone"; }

std::string_view chain_accuracy_name(ChainAccuracy a) {
    switch (a) {
        case ChainAccuracy::bounded: return "bounded";
        case ChainAccuracy::exact: return "exact";
        case ChainAccuracy::automatic: break;
    }
    return "automatic";
}

std::string_view traversal_name(Traversal t) { return t == Traversal::refactor ? "refactor" : "rank-one"; }

namespace {

using namespace polyvol::simplicial;
using exact::ExactSum;
using exact::Rational;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Wall-clock and processor time since construction.
struct Clock {
    std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
    std::clock_t cpu = std::clock();
    void elapsed(double& wall_seconds, double& cpu_seconds) const {
        wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
        cpu_seconds = static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC;
    }
};

// n! in double (exact up to 22!, then within (n-22) u).
double factorial(int n) {
    double f = 1;
    for (int i = 2; i <= n; ++i) f *= i;
    return f;
}

Rational rational_factorial(int n) {
    Rational f(1L);
    for (long i = 2; i <= n; ++i) f = f * Rational(i);
    return f;
}

// Every coordinate of every vertex used by a non-degenerate simplex finite?
// And all of them 0 or within [2^-200, 2^200] (the small exact path's range)?
struct RangeCheck {
    bool finite = true;
    bool safe = true;
};
RangeCheck check_range(const ChainView& c, const Topology& t) {
    RangeCheck rc;
    const int n = c.dimension;
    const std::size_t k = c.simplex_count();
    std::vector<uint8_t> used(c.vertex_count(), 0);
    for (std::size_t s = 0; s < k; ++s)
        if (!t.degenerate[s])
            for (int i = 0; i < n; ++i) used[c.simplices[s * n + i]] = 1;
    for (std::size_t v = 0; v < used.size(); ++v) {
        if (!used[v]) continue;
        for (int i = 0; i < n; ++i) {
            const double x = std::abs(c.coordinates[v * n + i]);
            if (!std::isfinite(x)) rc.finite = false;
            if (x != 0 && !(x >= 0x1p-200 && x <= 0x1p200)) rc.safe = false;
        }
    }
    return rc;
}

void set_nan(ChainVolume& out, int n) {
    out.volume = kNaN;
    out.volume_error_bound = kInf;
    out.volume_correctly_rounded = false;
    out.centroid.assign(static_cast<std::size_t>(n), kNaN);
    out.centroid_error_bound = kInf;
    out.centroid_correctly_rounded = false;
}

// Adds x * (e[0] + ... + e[len-1]) exactly (Dekker products: the small path's
// range keeps every product's error representable).
void add_product(ExactSum& sum, double x, const double* e, int len) {
    for (int i = 0; i < len; ++i) {
        double p, q;
        exact::two_prod_dekker(x, e[i], p, q);
        sum.add(p);
        sum.add(q);
    }
}

// x0 + x1 + ... exactly, as an unevaluated sum of at most len doubles.
int exact_sum_of(const double* xs, int len, double* out) {
    double s = xs[0];
    int m = 0;
    for (int i = 1; i < len; ++i) {
        double e;
        exact::two_sum(s, xs[i], s, e);
        if (e != 0) out[m++] = e;
    }
    out[m++] = s;
    return m;
}

// n = 2, 3: exact expansions into superaccumulators.
void small_exact(const ChainView& c, const Topology& t, const ChainOptions& opt, ChainVolume& out) {
    const int n = c.dimension;
    const bool prism = opt.formula == SimplexFormula::prism;
    ExactSum vsum, vcone;
    std::vector<ExactSum> msum(opt.centroid ? n : 0);
    double det[exact::kDetTerms], comp[4];
    const std::size_t k = c.simplex_count();
    for (std::size_t s = 0; s < k; ++s) {
        if (t.degenerate[s]) continue;
        const double* v[3];
        for (int i = 0; i < n; ++i) v[i] = &c.coordinates[std::size_t{c.simplices[s * n + i]} * n];
        int len;
        if (n == 2) {
            exact::det2_exact<false>(v[0][0], v[1][1], v[0][1], v[1][0], det);
            len = 4;
        } else {
            len = exact::det3_exact<false>(v[0], v[1], v[2], det);
        }
        for (int i = 0; i < len; ++i) vcone.add(det[i]);
        if (prism) {
            if (n == 2) {
                // (y0 + y1)(x0 - x1), divided by 2 at the end.
                double a[2], b[2];
                exact::two_sum(v[0][1], v[1][1], a[0], a[1]);
                exact::two_sum(v[0][0], -v[1][0], b[0], b[1]);
                add_product(vsum, a[0], b, 2);
                add_product(vsum, a[1], b, 2);
            } else {
                // (z0 + z1 + z2) det[1 1 1; x; y], divided by 6 at the end.
                const double zs[3] = {v[0][2], v[1][2], v[2][2]};
                const int hl = exact_sum_of(zs, 3, comp);
                const int pairs[3][2] = {{1, 2}, {2, 0}, {0, 1}};  // det = sum of the three 2x2 minors (cyclic)
                for (const auto& pq : pairs) {
                    const double* a = v[pq[0]];
                    const double* b = v[pq[1]];
                    double p1, e1, p2, e2;
                    exact::two_prod_dekker(a[0], b[1], p1, e1);
                    exact::two_prod_dekker(-a[1], b[0], p2, e2);
                    const double terms[4] = {p1, e1, p2, e2};
                    for (double term : terms) add_product(vsum, term, comp, hl);
                }
            }
        }
        if (opt.centroid) {
            for (int i = 0; i < n; ++i) {
                double xs[3];
                for (int j = 0; j < n; ++j) xs[j] = v[j][i];
                const int sl = exact_sum_of(xs, n, comp);
                for (int a = 0; a < len; ++a) add_product(msum[i], det[a], comp, sl);
            }
        }
    }
    const uint32_t nfact = n == 2 ? 2u : 6u;
    out.volume = (prism ? vsum : vcone).round_div(nfact);
    out.volume_error_bound = 0;
    out.volume_correctly_rounded = true;
    if (opt.centroid) {
        const Rational vc(vcone);
        out.centroid.assign(static_cast<std::size_t>(n), kNaN);
        if (vc.sign() != 0) {
            const Rational denom = vc * Rational(static_cast<long>(n + 1));
            for (int i = 0; i < n; ++i) out.centroid[i] = (Rational(msum[i]) / denom).to_double();
            out.centroid_correctly_rounded = true;
        } else {
            out.centroid_error_bound = kInf;
        }
    }
}

// Any n: GMP.
void gmp_exact(const ChainView& c, const Topology& t, const ChainOptions& opt, ChainVolume& out) {
    const int n = c.dimension;
    const bool prism = opt.formula == SimplexFormula::prism;
    Rational vsum, vcone;
    std::vector<Rational> msum(opt.centroid ? n : 0);
    std::vector<const double*> cols(n);
    std::vector<double> bordered(static_cast<std::size_t>(n) * n);
    std::vector<const double*> bcols(n);
    const std::size_t k = c.simplex_count();
    for (std::size_t s = 0; s < k; ++s) {
        if (t.degenerate[s]) continue;
        for (int i = 0; i < n; ++i) cols[i] = &c.coordinates[std::size_t{c.simplices[s * n + i]} * n];
        const Rational dc = exact_det(n, cols.data());
        vcone = vcone + dc;
        if (prism) {
            Rational h;
            for (int j = 0; j < n; ++j) {
                double* b = &bordered[static_cast<std::size_t>(j) * n];
                b[0] = 1;
                for (int i = 0; i + 1 < n; ++i) b[i + 1] = cols[j][i];
                bcols[j] = b;
                h = h + Rational(cols[j][n - 1]);
            }
            vsum = vsum + exact_det(n, bcols.data()) * h;
        }
        if (opt.centroid) {
            for (int i = 0; i < n; ++i) {
                Rational si;
                for (int j = 0; j < n; ++j) si = si + Rational(cols[j][i]);
                msum[i] = msum[i] + dc * si;
            }
        }
    }
    Rational v = prism ? vsum / rational_factorial(n) : vcone / rational_factorial(n);
    if (prism && (n - 1) % 2 == 1) v = -v;
    out.volume = v.to_double();
    out.volume_error_bound = 0;
    out.volume_correctly_rounded = true;
    if (opt.centroid) {
        out.centroid.assign(static_cast<std::size_t>(n), kNaN);
        if (vcone.sign() != 0) {
            const Rational denom = vcone * Rational(static_cast<long>(n + 1));
            for (int i = 0; i < n; ++i) out.centroid[i] = (msum[i] / denom).to_double();
            out.centroid_correctly_rounded = true;
        } else {
            out.centroid_error_bound = kInf;
        }
    }
}

// The bounded path.
//
// Local coordinates. Hadamard's inequality, which turns the LU's backward
// error into a bound on the determinant (lu_update.hpp), is sharp only when
// the columns are far from parallel; the columns v_j of a small simplex far
// from the origin are nearly parallel (det ~ |v| h^(n-1), Hadamard's product
// ~ |v|^n). So every determinant is taken in coordinates centred at a point
// o near the simplex, with a power-of-two row scale s ~ h, through exact
// identities:
//   cone:  det(v_1..v_n) = det[ s  s ... s ; -o  v_1-o ... v_n-o ] / s
//          (add o times the first row to the others, expand along the first
//          column (s, 0)): an (n+1)-order matrix whose first column, the
//          origin's, never changes along the walk;
//   prism: det[1 ... 1; w_1 ... w_n] = det[ s ... s ; w_1-o ... w_n-o ] / s.
// o is the first vertex of the simplex factorised afresh (so -o is exact) and
// stays until the next fresh factorisation; each v - o is rounded once, an
// error of at most u ||v - o|| in its column, added to that column's
// backward-error bound. A walk that drifts away from o makes the columns
// long again. So the factors are computed afresh (with a new o) when
//   eta > refactor_growth * eta_fresh       (eta = sum_c eps_c / ||a_c||, the
//                                            relative backward error), or
//   ||entering column|| > 4 * max_c ||a_c|| at the last fresh factorisation
//                                           (the walk left the neighbourhood
//                                            of o), or
//   2^20 updates have passed               (bounds stay sums of < 2^30 terms),
// besides after every jump of the walk.
class BoundedSweep {
public:
    BoundedSweep(const ChainView& c, const Topology& t, const ChainOptions& opt)
        : c_(c), t_(t), n_(c.dimension), prism_(opt.formula == SimplexFormula::prism), centroid_(opt.centroid),
          growth_(std::max(1.0, opt.refactor_growth)), big_(prism_ ? n_ : n_ + 1), first_(prism_ ? 0 : 1),
          lu_(big_) {
        const std::size_t m = c.vertex_count();
        pos_of_.assign(m, -1);
        colvert_.assign(big_, kNone);
        colbuf_.resize(static_cast<std::size_t>(big_) * big_);
        cols_.resize(big_);
        norms_.resize(big_);
        extra_.resize(big_);
        o_.resize(n_);
        newcol_.resize(big_);
        if (centroid_) vs_.assign(m, VertexSums{});
    }

    void run_walk(const std::vector<Step>& steps) {
        // The walk jumps around memory: fetch what step i + kAhead will read
        // (its simplex row; then, once that has arrived, its vertices' data).
        constexpr std::size_t kAhead = 8;
        for (std::size_t i = 0; i < steps.size(); ++i) {
            const Step& st = steps[i];
            if (i + kAhead < steps.size())
                __builtin_prefetch(&c_.simplices[std::size_t{steps[i + kAhead].simplex} * n_]);
            if (i + kAhead / 2 < steps.size()) {
                const uint32_t* row = &c_.simplices[std::size_t{steps[i + kAhead / 2].simplex} * n_];
                for (int p = 0; p < n_; ++p) {
                    __builtin_prefetch(&t_.canon[row[p]]);
                    __builtin_prefetch(coords(row[p]));
                    if (centroid_) __builtin_prefetch(&vs_[row[p]], 1);
                }
            }
            if (st.kind == StepKind::fresh) {
                ++stats.jumps;
                factor(st.simplex);
            } else if (!update(st.simplex)) {
                factor(st.simplex);
            }
            if (st.kind == StepKind::pass) {
                ++stats.pass_throughs;
                continue;
            }
            accumulate(st.simplex);
        }
        if (!steps.empty()) --stats.jumps;  // the start is not a jump
    }

    void run_refactor() {
        const std::size_t k = c_.simplex_count();
        constexpr std::size_t kAhead = 4;  // as in run_walk, for the vertices' data
        for (std::size_t s = 0; s < k; ++s) {
            if (s + kAhead < k) {
                const uint32_t* row = &c_.simplices[(s + kAhead) * n_];
                for (int p = 0; p < n_; ++p) {
                    __builtin_prefetch(&t_.canon[row[p]]);
                    __builtin_prefetch(coords(row[p]));
                    if (centroid_) __builtin_prefetch(&vs_[row[p]], 1);
                }
            }
            if (t_.degenerate[s]) continue;
            factor(static_cast<uint32_t>(s));
            accumulate(static_cast<uint32_t>(s));
        }
    }

    void finish(ChainVolume& out) const;

    ChainStats stats;

private:
    const double* coords(uint32_t v) const { return &c_.coordinates[std::size_t{v} * n_]; }
    uint32_t vertex_of(uint32_t s, int p) const { return t_.canon[c_.simplices[std::size_t{s} * n_ + p]]; }
    int dims() const { return prism_ ? n_ - 1 : n_; }  // coordinates in a column after the scale row

    // Column of vertex v in the current local coordinates: (s, v - o); its
    // norm and the bound u ||v - o|| on the rounding of v - o.
    void make_column(uint32_t v, double* out, double& norm, double& extra) const {
        const double* x = coords(v);
        out[0] = scale_;
        for (int i = 0; i < dims(); ++i) out[1 + i] = x[i] - o_[i];
        norm = norm2(out, big_);
        extra = kUnit * norm;
    }

    void factor(uint32_t s) {
        for (int p = 0; p < big_; ++p)
            if (colvert_[p] != kNone) pos_of_[colvert_[p]] = -1;
        // Local origin: the first vertex; scale: a power of two near the
        // largest coordinate difference.
        const double* x0 = coords(vertex_of(s, 0));
        double spread = 0;
        for (int p = 1; p < n_; ++p) {
            const double* x = coords(vertex_of(s, p));
            for (int i = 0; i < dims(); ++i) spread = std::max(spread, std::abs(x[i] - x0[i]));
        }
        for (int i = 0; i < n_; ++i) o_[i] = x0[i];
        // s ~ spread / sqrt(n): a scale row much larger than the coordinate
        // differences makes the columns (s, v - o) nearly parallel, a much
        // smaller one makes the origin's column dominate; Hadamard's product
        // over |det| is smallest in between.
        int e = 0;
        std::frexp(spread / std::sqrt(static_cast<double>(n_)), &e);
        scale_ = spread > 0 && std::isfinite(spread) ? std::ldexp(1.0, e) : 1.0;
        if (!prism_) {  // the origin's column (s, -o), exact
            double* col = &colbuf_[0];
            col[0] = scale_;
            for (int i = 0; i < n_; ++i) col[1 + i] = -o_[i];
            norms_[0] = norm2(col, big_);
            extra_[0] = 0;
            colvert_[0] = kNone;
        }
        for (int p = 0; p < n_; ++p) {
            const uint32_t v = vertex_of(s, p);
            const int q = first_ + p;
            colvert_[q] = v;
            pos_of_[v] = static_cast<int8_t>(q);
            make_column(v, &colbuf_[static_cast<std::size_t>(q) * big_], norms_[q], extra_[q]);
        }
        for (int q = 0; q < big_; ++q) cols_[q] = &colbuf_[static_cast<std::size_t>(q) * big_];
        lu_.factor(cols_.data(), norms_.data(), extra_.data());
        ++stats.factorizations;
        eta_ = lu_.backward_error();
        fresh_eta_ = std::max(eta_, 0x1p-1000);
        updates_since_fresh_ = 0;
        fresh_max_norm_ = 0;
        for (int q = first_; q < big_; ++q) fresh_max_norm_ = std::max(fresh_max_norm_, norms_[q]);
        stats.max_backward_error = std::max(stats.max_backward_error, fresh_eta_);
    }

    // Column replacement towards the adjacent simplex s; false when s is not
    // adjacent to the current one (then the caller factorises).
    bool update(uint32_t s) {
        uint64_t hit = prism_ ? 0 : 1;  // the origin's column never leaves
        uint32_t entering = kNone;
        int entering_count = 0;
        for (int p = 0; p < n_; ++p) {
            const uint32_t v = vertex_of(s, p);
            const int q = pos_of_[v];
            if (q < 0) {
                entering = v;
                ++entering_count;
            } else {
                hit |= uint64_t{1} << q;
            }
        }
        if (entering_count != 1) return false;
        const int j = std::countr_one(hit);
        stats.elimination_steps += static_cast<std::size_t>(big_ - 1 - j);
        double norm = 0, extra = 0;
        make_column(entering, newcol_.data(), norm, extra);
        lu_.replace(j, newcol_.data(), norm, extra);
        pos_of_[colvert_[j]] = -1;
        for (int q = j; q + 1 < big_; ++q) {
            colvert_[q] = colvert_[q + 1];
            pos_of_[colvert_[q]] = static_cast<int8_t>(q);
        }
        colvert_[big_ - 1] = entering;
        pos_of_[entering] = static_cast<int8_t>(big_ - 1);
        ++stats.updates;
        eta_ = lu_.backward_error();
        stats.max_backward_error = std::max(stats.max_backward_error, eta_);
        if (!(eta_ <= growth_ * fresh_eta_) || !(norm <= kDrift * fresh_max_norm_) ||
            ++updates_since_fresh_ >= kMaxUpdates) {
            ++stats.stability_refactors;
            factor(s);
        }
        return true;
    }

    // Sign of the permutation taking s's listed order to position order.
    int listed_sign(uint32_t s) const {
        int8_t perm[kMaxDimension];
        for (int p = 0; p < n_; ++p) perm[p] = static_cast<int8_t>(pos_of_[vertex_of(s, p)] - first_);
        uint64_t seen = 0;
        int sign = 1;
        for (int p = 0; p < n_; ++p) {
            if (seen >> p & 1) continue;
            int len = 0;
            for (int q = p; !(seen >> q & 1); q = perm[q]) {
                seen |= uint64_t{1} << q;
                ++len;
            }
            if (len % 2 == 0) sign = -sign;
        }
        return sign;
    }

    void accumulate(uint32_t s) {
        const int n = n_;
        const double mdet = lu_.det();
        // Dividing by the power of two s is exact (barring underflow, which
        // the bound's absolute 2^-960 term covers).
        const double beta = lu_.det_bound(mdet, eta_) / scale_;
        const double d = listed_sign(s) * (mdet / scale_);
        double term = d, term_bound = beta, hsum = 0;
        if (prism_) {
            // H = sum of the last coordinates (recursive sum, error <= gamma_{n-1} sum |h_j|).
            double habs = 0;
            for (int p = 0; p < n; ++p) {
                const double hj = coords(vertex_of(s, p))[n - 1];
                hsum += hj;
                habs += std::abs(hj);
            }
            const double eh = gamma(n - 1) * habs;
            term = d * hsum;
            term_bound = beta * (std::abs(hsum) + eh) + std::abs(d) * eh + kUnit * std::abs(term);
        }
        vol_.add(term);
        bound_ += term_bound;
        if (centroid_) {
            for (int p = 0; p < n; ++p) {
                VertexSums& x = vs_[vertex_of(s, p)];
                x.w += d;
                x.aw += std::abs(d);
                x.ew += beta;
                x.w2 += term;
                x.aw2 += std::abs(term);
                x.ew2 += term_bound;
                ++x.deg;
            }
        }
    }

    const ChainView& c_;
    const Topology& t_;
    int n_;
    bool prism_, centroid_;
    double growth_;
    int big_;    // order of the matrices: n + 1 (cone), n (prism)
    int first_;  // position of the first vertex column: 1 (cone), 0 (prism)
    ColumnLu lu_;
    std::vector<int8_t> pos_of_;     // position of each (welded) vertex in the factors, -1 if absent
    std::vector<uint32_t> colvert_;  // vertex at each position (kNone: the origin's column)
    std::vector<double> colbuf_, norms_, extra_, o_, newcol_;
    std::vector<const double*> cols_;
    double scale_ = 1;
    double fresh_eta_ = 0, fresh_max_norm_ = 0, eta_ = 0;
    static constexpr double kDrift = 4;
    // A column that never leaves (the cone's origin column) gathers error
    // terms from every update: refactor at least this often, so that every
    // bound is a sum of fewer than 2^30 terms (lu_update.hpp).
    static constexpr std::size_t kMaxUpdates = std::size_t{1} << 20;
    std::size_t updates_since_fresh_ = 0;
    ExactSum vol_;
    double bound_ = 0;
    // Per vertex, over the simplices using it: W = sum D, W2 = sum D H
    // (prism; for the cone the term is D again), their absolute sums and their
    // error bounds; degree. One cache line per vertex.
    struct VertexSums {
        double w = 0, aw = 0, ew = 0, w2 = 0, aw2 = 0, ew2 = 0;
        uint32_t deg = 0;
    };
    std::vector<VertexSums> vs_;
};

// Error accounting of the sums (the terms themselves are added exactly, to
// superaccumulators):
//   volume — each term t_s (cone: D_s; prism: fl(D_s H_s)) is within b_s of
//     its exact value (cone: beta_s from ColumnLu::det_bound; prism:
//     beta_s (|H| + e_H) + |D| e_H + u |t|, e_H = gamma_{n-1} sum_j |h_j|).
//     sum_s b_s is accumulated in double (relative error below k u < 2^-20
//     for k < 2^32 simplices) and inflated by kSlack; V = S / n! rounded adds
//     at most gamma_{n+2} |V| (the roundings of S, of n! beyond 22!, and of
//     the division; round_div rounds once for n <= 12).
//   moments — W_v = sum over the simplices at v of D_s, summed in double:
//     within sum beta_s + gamma_deg sum |D_s| of the exact sum (recursive
//     summation); W2_v alike with the prism's terms. Z_v = h_v W_v + W2_v
//     (prism) adds 3u (|h W| + |W2|) and the products x_v[i] Z_v, summed
//     exactly, u |x Z| each: M_i's bound is sum_v |x_v[i]| err(Z_v) + u |x_v[i] Z_v|,
//     scaled like M_i.
//   centroid — |M/V - M^/V^| <= (|M^| dV + |V^| dM) / (|V^| (|V^| - dV)) when
//     |V^| > dV (otherwise the bound is infinite: the volume may be 0), plus
//     the division's rounding.
void BoundedSweep::finish(ChainVolume& out) const {
    const int n = n_;
    const double sign = prism_ && (n - 1) % 2 == 1 ? -1.0 : 1.0;
    const double nf = factorial(n);
    // V = sign * S / n!, S the exact sum of the terms; |S - exact| <= bound_ (inflated).
    double v = n <= 12 ? vol_.round_div(static_cast<uint32_t>(nf)) : vol_.round() / nf;
    v *= sign;
    double vb = bound_ * kSlack / nf * kSlack + gamma(n + 2) * std::abs(v);
    if (!std::isfinite(v) || !std::isfinite(vb)) vb = kInf;
    out.volume = v;
    out.volume_error_bound = vb;
    out.volume_correctly_rounded = false;
    if (!centroid_) return;
    // First moments: M_i = C sum_v x_v[i] Z_v with Z = W (cone), Z = h W + W2
    // (prism), C = 1/(n+1)! (times sign, and 1/2 for the prism's last coordinate).
    const std::size_t m = c_.vertex_count();
    std::vector<ExactSum> msum(n);
    std::vector<double> mb(n, 0.0);
    for (std::size_t vi = 0; vi < m; ++vi) {
        const VertexSums& x_sums = vs_[vi];
        if (x_sums.deg == 0) continue;
        const double gd = gamma(static_cast<int>(std::min<uint32_t>(x_sums.deg, 1u << 30)));
        const double ew = x_sums.ew + gd * x_sums.aw;
        double z = x_sums.w, ez = ew;
        const double* x = &c_.coordinates[vi * n];
        if (prism_) {
            const double ew2 = x_sums.ew2 + gd * x_sums.aw2;
            const double h = x[n - 1];
            const double hw = h * x_sums.w;
            z = hw + x_sums.w2;
            ez = std::abs(h) * ew + ew2 + 3 * kUnit * (std::abs(hw) + std::abs(x_sums.w2));
        }
        for (int i = 0; i < n; ++i) {
            const double p = x[i] * z;
            msum[i].add(p);
            mb[i] += std::abs(x[i]) * ez + kUnit * std::abs(p);
        }
    }
    const double mf = factorial(n + 1);
    out.centroid.assign(static_cast<std::size_t>(n), kNaN);
    out.centroid_error_bound = 0;
    for (int i = 0; i < n; ++i) {
        const double half = prism_ && i == n - 1 ? 0.5 : 1.0;
        const double mi = msum[i].round() / mf * half * sign;
        const double mbi = mb[i] * kSlack / mf * half * kSlack + gamma(n + 3) * std::abs(mi);
        if (v == 0) {
            out.centroid_error_bound = kInf;
            continue;
        }
        const double ci = mi / v;
        out.centroid[i] = ci;
        double cb = kInf;
        if (std::abs(v) > vb && std::isfinite(mbi)) {
            // |M/V - M^/V^| <= (|M^| dV + |V^| dM) / (|V^| (|V^| - dV)), plus the division's rounding.
            cb = (std::abs(mi) * vb + std::abs(v) * mbi) / (std::abs(v) * (std::abs(v) - vb)) * kSlack +
                 kUnit * std::abs(ci);
        }
        out.centroid_error_bound = std::max(out.centroid_error_bound, cb);
    }
}

}  // namespace

ChainReport validate_chain(const ChainView& chain) { return simplicial::analyze(chain, false).report; }

ChainVolume chain_volume(const ChainView& chain, const ChainOptions& options) {
    const Clock t0;
    const int n = chain.dimension;
    ChainAccuracy acc = options.accuracy;
    if (acc == ChainAccuracy::automatic) acc = n <= 3 ? ChainAccuracy::exact : ChainAccuracy::bounded;
    const bool walk = acc == ChainAccuracy::bounded && options.traversal == Traversal::rank_one;
    simplicial::Topology topo = simplicial::analyze(chain, walk);
    ChainVolume out;
    out.dimension = n;
    out.formula = options.formula;
    out.accuracy = acc;
    out.traversal = options.traversal;
    const RangeCheck range = check_range(chain, topo);
    if (!range.finite) {
        out.topology = std::move(topo.report);
        set_nan(out, n);
        return out;
    }
    ChainStats stats;
    std::vector<simplicial::Step> steps;
    if (walk) steps = simplicial::dual_walk(topo, chain, n >= 14 ? n / 7 - 1 : 0);
    t0.elapsed(stats.seconds_topology, stats.cpu_seconds_topology);
    const Clock t1;
    if (acc == ChainAccuracy::exact) {
        if (n <= 3 && range.safe) {
            small_exact(chain, topo, options, out);
        } else {
            gmp_exact(chain, topo, options, out);
        }
    } else {
        BoundedSweep sweep(chain, topo, options);
        if (walk) {
            sweep.run_walk(steps);
        } else {
            sweep.run_refactor();
        }
        sweep.finish(out);
        const ChainStats& s = sweep.stats;
        stats.factorizations = s.factorizations;
        stats.updates = s.updates;
        stats.jumps = s.jumps;
        stats.stability_refactors = s.stability_refactors;
        stats.pass_throughs = s.pass_throughs;
        stats.elimination_steps = s.elimination_steps;
        stats.max_backward_error = s.max_backward_error;
    }
    t1.elapsed(stats.seconds_sweep, stats.cpu_seconds_sweep);
    out.stats = stats;
    out.topology = std::move(topo.report);
    return out;
}

}  // namespace polyvol

// measure/soup.cpp — polyvol/soup.hpp: volume, first moments, area and a
// closedness fingerprint of float32 triangle records, in constant memory.
//
// The passes: pass 1 (soup_pass1.cpp) forms the volume in double-double,
// the first moments in double-double (correctly rounded ones) or in double
// (bounded ones), the area and the fingerprint in one read; the results
// are decided as a loaded mesh's are (measure/cone_results.hpp). What is
// undecided goes through pass 2, the cone kernels' translated form on each
// block (not for a moment that may be exactly 0), then pass 3, which sums
// it exactly. The error analysis behind each bound used here is in
// docs/numerics.md, "The streamed soup".
#include "polyvol/soup.hpp"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/fingerprint.hpp"
#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "measure/cone.hpp"
#include "measure/cone_results.hpp"
#include "measure/soup_pass1.hpp"
#include "measure/soup_testing.hpp"
#include "core/bit_cast.hpp"

namespace polyvol {
namespace {

using exact::ExactSum;
namespace cone = measure::cone;
using core::fingerprint::kP;
using measure::soup::kB;
using measure::soup::kFpLanes;
using measure::soup::kGroupBlocks;
using measure::soup::Keys;
using measure::soup::Pass1Block;
using measure::soup::Pass1Group;
static_assert(SoupAccumulator::kBlockTriangles == kB);
constexpr double kU = 0x1p-53;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr std::size_t kChunk = 8192;  // triangles per parallel task (a multiple of kB)
static_assert(kChunk % kB == 0);

// ---- per-thread sums ------------------------------------------------------------

struct Partial {
    ExactSum sum[cone::kSxx];     // 6 V and 24 ∫x_i (cone::SumIndex): the current pass's sums
    ExactSum vol_mag, mom_mag;    // pass 1: the bounds' magnitudes
    ExactSum mag[cone::kSxx];     // pass 2: each sum's magnitudes
    ExactSum area2, cross;        // pass 1: 2 A and Σ X
    uint64_t fp[kFpLanes] = {};   // mod p
    uint64_t triangles = 0;
    bool nonfinite = false;

    void merge(const Partial& o) {
        for (int k = 0; k < cone::kSxx; ++k) sum[k].merge(o.sum[k]);
        vol_mag.merge(o.vol_mag);
        for (int k = 0; k < cone::kSxx; ++k) mag[k].merge(o.mag[k]);
        mom_mag.merge(o.mom_mag);
        area2.merge(o.area2);
        cross.merge(o.cross);
        for (int l = 0; l < kFpLanes; ++l) {
            fp[l] += o.fp[l];
            if (fp[l] >= kP) fp[l] -= kP;
        }
        triangles += o.triangles;
        nonfinite = nonfinite || o.nonfinite;
    }
};

double up(double x) { return std::nextafter(x, kInf); }

}  // namespace


namespace {
std::atomic<measure::SoupPass1Sums*> g_pass1_record{nullptr};  // record_soup_pass1
}  // namespace

void measure::record_soup_pass1(SoupPass1Sums* out) { g_pass1_record.store(out, std::memory_order_relaxed); }

struct SoupAccumulator::State {
    Keys keys{};
    SoupWants wants;
    measure::soup::Moments moments;  // what pass 1 forms of them
    int pass = 1;
    bool done = false;
    tbb::enumerable_thread_specific<Partial> tls;
    uint64_t pass1_triangles = 0;
    // The sums as known after the last pass (cone::SumIndex kV, kMx..kMz):
    // the exact sum of the approximations, and a bound on its distance to
    // the exact sum (0: exact).
    ExactSum sum[cone::kSxx];
    double bound[cone::kSxx] = {};
    uint32_t exact_mask = 0;  // passes 2 and 3: the sums they recompute
    bool pass2_moments = false;  // pass 2 recomputes moments too (else the volume alone)
    int reads = 1;            // passes over the input so far (pass 2 may be skipped)
    SoupResult result;

    State(uint64_t seed, SoupWants w)
        : wants(w),
          moments(!w.moments_and_area                       ? measure::soup::kNoMoments
                  : w.moments == Accuracy::correctly_rounded ? measure::soup::kDoubleDouble
                                                             : measure::soup::kPlain) {
        if (!std::isfinite(w.density))
            throw std::invalid_argument("SoupAccumulator: the density is not finite");
        uint64_t s = seed;
        for (auto& k : keys.aes)
            for (auto& x : k) x = core::fingerprint::splitmix(s);
    }

    // Pass 1 over a group: triangles [first, first + n) of t, n <= kGroupBlocks
    // kB, relative index (first is a multiple of kB in the whole input).
    void group(const Float32Triangles& t, std::size_t first, int n, Partial& p) const {
        p.triangles += static_cast<uint64_t>(n);
        Pass1Group g;
        if (!measure::soup::pass1_group(t.data + first * t.stride + t.offset, t.stride, n, keys, wants.closedness,
                                        moments, g)) {
            p.nonfinite = true;  // NaN or infinity: nothing else is meaningful
            return;
        }
        for (int l = 0; l < kFpLanes; ++l) {
            p.fp[l] += g.fp[l];
            if (p.fp[l] >= kP) p.fp[l] -= kP;
        }
        p.sum[cone::kV].add(g.vs);
        p.sum[cone::kV].add(g.ve);
        if (moments == measure::soup::kDoubleDouble)
            for (int k = 0; k < 3; ++k) {
                p.sum[cone::kMx + k].add(g.ms[k]);
                p.sum[cone::kMx + k].add(g.me[k]);
            }
        double volume_magnitude = 0, moments_magnitude = 0;
        for (int b = 0; b * kB < n; ++b) {
            const double M = static_cast<double>(core::bit_cast<float>(g.mx[b]));
            const double nb = static_cast<double>(std::min(kB, n - b * kB));
            volume_magnitude += 6 * (M * M * M) * nb;
            if (moments == measure::soup::kNoMoments) continue;
            const Pass1Block& r = g.block[b];
            p.area2.add(r.area2);
            p.cross.add(r.cross);
            if (moments == measure::soup::kDoubleDouble) {
                moments_magnitude += 18 * ((M * M) * (M * M)) * nb;
            } else {
                for (int k = 0; k < 3; ++k) p.sum[cone::kMx + k].add(r.mom[k]);
                p.mom_mag.add(3 * M * r.abs_d + 0x1p-43 * ((M * M) * (M * M)) * nb);
            }
        }
        p.vol_mag.add(volume_magnitude);
        if (moments == measure::soup::kDoubleDouble) p.mom_mag.add(moments_magnitude);
    }

    // Passes 2 and 3 over one block: triangles [first, first + n) of t, n <= kB.
    void block(const Float32Triangles& t, std::size_t first, int n, Partial& p) const {
        const std::byte* base = t.data + first * t.stride + t.offset;
        cone::TriangleBlock b;
        for (int i = 0; i < n; ++i) {
            float f[9];
            std::memcpy(f, base + static_cast<std::size_t>(i) * t.stride, 36);
            for (int k = 0; k < 9; ++k) b.c[k][i] = static_cast<double>(f[k]);
        }
        for (int k = 0; k < 9; ++k)
            for (int i = n; i < kB; ++i) b.c[k][i] = 0;
        b.n = n;
        p.triangles += static_cast<uint64_t>(n);
        if (pass == 2 && pass2_moments) {
            cone::filtered_first_moments_block(b, p.sum, p.mag);
        } else if (pass == 2) {
            cone::filtered_volume_block(b, p.sum[cone::kV], p.mag[cone::kV]);
        } else {
            cone::exact_block_sums(b, exact_mask, p.sum);
        }
    }

    void range(const Float32Triangles& t, std::size_t begin, std::size_t end) {
        Partial& p = tls.local();
        const std::size_t step = pass == 1 ? kGroupBlocks * kB : kB;
        for (std::size_t i = begin; i < end; i += step) {
            const int n = static_cast<int>(std::min(step, end - i));
            if (pass == 1) group(t, i, n, p);
            else block(t, i, n, p);
        }
    }
};

SoupAccumulator::SoupAccumulator(SoupWants wants) {
    std::random_device rd;
    uint64_t seed = 0;
    for (int i = 0; i < 4; ++i) seed = (seed << 16) ^ (static_cast<uint64_t>(rd()) * 0x9E3779B97F4A7C15ull) ^ (seed >> 7);
    // More entropy than one 64-bit seed for the keys themselves.
    s_ = std::make_unique<State>(seed, wants);
    for (auto& k : s_->keys.aes)
        for (auto& x : k) x ^= core::fingerprint::random_word(rd);
}

SoupAccumulator::SoupAccumulator(uint64_t seed, SoupWants wants) : s_(std::make_unique<State>(seed, wants)) {}

SoupAccumulator::~SoupAccumulator() = default;

int SoupAccumulator::pass() const { return s_->pass; }

void SoupAccumulator::add(const Float32Triangles& t, uint64_t first_triangle) {
    if (first_triangle % kB != 0)
        throw std::invalid_argument("SoupAccumulator::add: first_triangle " + std::to_string(first_triangle) +
                                    " is not a multiple of " + std::to_string(kB));
    if (t.count > 0 && (t.data == nullptr || t.stride < 36))
        throw std::invalid_argument("SoupAccumulator::add: no data, or a stride below 36 bytes");
    if (s_->done) throw std::logic_error("SoupAccumulator::add after the last pass");
    const std::size_t n = t.count;
    if (n <= kChunk) {
        s_->range(t, 0, n);
        return;
    }
    const std::size_t chunks = (n + kChunk - 1) / kChunk;
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, chunks, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t c = r.begin(); c < r.end(); ++c) s_->range(t, c * kChunk, std::min(n, (c + 1) * kChunk));
        },
        tbb::simple_partitioner());
}

namespace {
// Every figure NaN but (unless `volume`) the volume's (a NaN or infinite
// coordinate, or not asked for).
void set_nan(MassProperties& m, bool volume) {
    if (volume) m.volume = m.mass = m.volume_error_bound = kNaN;
    m.first_moments = m.centroid = {kNaN, kNaN, kNaN};
    m.second_moments = m.inertia_origin = m.inertia_centroid = {kNaN, kNaN, kNaN, kNaN, kNaN, kNaN};
    m.area = m.edge_length = kNaN;
    m.moments_relative_error = m.area_relative_error = m.edge_length_relative_error = kNaN;
}

// First moments and centroid within a bound, from the sums Σ d s_i ± B
// (sum[kMx..kMz], bound) and the correctly rounded volume V (m.volume):
//   F_i = ρ round(Σ_i / 24) within E = B/24 + u |F| (+ u |ρ F| for ρ != 1);
//   c_i = F_i / V within (E + 1.01 u (|F| + E)) / |V| + u |c|;
// each relative to its array's largest entry (measure.hpp), rounded up.
void set_bounded_moments(const ExactSum* sum, const double* bound, double density, MassProperties& m) {
    // x rounded up, an exact 0 kept (every nonzero sum here is a multiple of
    // 2^-596 / 24 and far from underflow: docs/numerics.md).
    const auto up0 = [](double x) { return x == 0 ? 0.0 : up(x); };
    const double V = m.volume;
    double e_first = 0, e_centroid = 0, largest_first = 0, largest_centroid = 0;
    for (int k = 0; k < 3; ++k) {
        const double F = sum[cone::kMx + k].round_div(24);
        const double E = up0(up0(bound[cone::kMx + k] / 24) + up0(kU * std::fabs(F)));
        m.first_moments[k] = density * F;
        e_first = std::max(e_first, density == 1 ? E : up0(up0(std::fabs(density) * E) + up0(kU * std::fabs(density * F))));
        largest_first = std::max(largest_first, std::fabs(m.first_moments[k]));
        m.centroid[k] = V == 0 ? kNaN : F / V;
        if (V == 0) continue;
        const double num = up0(E + up0(1.01 * kU * up0(std::fabs(F) + E)));
        e_centroid = std::max(e_centroid, up0(up0(num / std::fabs(V)) + up0(kU * std::fabs(m.centroid[k]))));
        largest_centroid = std::max(largest_centroid, std::fabs(m.centroid[k]));
    }
    m.moments_correctly_rounded = false;
    m.moments_relative_error = V == 0 ? kInf
                                      : std::max(cone::relative_to(e_first, largest_first),
                                                 cone::relative_to(e_centroid, largest_centroid));
    m.accuracy = Accuracy::fast;
}
}  // namespace

bool SoupAccumulator::next_pass() {
    State& s = *s_;
    if (s.done) return false;
    Partial all;
    for (const Partial& p : s.tls) all.merge(p);
    s.tls.clear();
    SoupResult& r = s.result;
    MassProperties& m = r.properties;
    const bool moments = s.wants.moments_and_area;
    const int count = moments ? int{cone::kSxx} : 1;
    if (s.pass == 1) {
        if (measure::SoupPass1Sums* rec = g_pass1_record.load(std::memory_order_relaxed))
            *rec = {all.sum[cone::kV],   all.vol_mag, {all.sum[cone::kMx], all.sum[cone::kMy], all.sum[cone::kMz]},
                    all.mom_mag,         all.area2,   all.cross};
        s.pass1_triangles = all.triangles;
        r.computed = s.wants;
        r.triangles = all.triangles;
        r.nonfinite = all.nonfinite;
        r.fingerprint = {all.fp[0], all.fp[1], all.fp[2], all.fp[3]};
        r.closed = s.wants.closedness && !all.nonfinite && all.fp[0] == 0 && all.fp[1] == 0 && all.fp[2] == 0 &&
                   all.fp[3] == 0;
        set_nan(m, false);  // second moments, inertia, edge length: never; the rest when computed below
        if (all.nonfinite) {
            set_nan(m, true);
            r.passes = s.reads;
            s.done = true;
            return false;
        }
        if (moments) {
            // Area.
            const double a2 = all.area2.round();
            const double cross = all.cross.round();
            m.area = a2 / 2;
            m.area_relative_error =
                a2 > 0 ? up(up(up(up(15 * kU * a2) + up(5 * kU * cross)) / a2) + kU) : (cross > 0 ? kInf : 0.0);
        }
        for (int k = 0; k < count; ++k) s.sum[k] = all.sum[k];
        s.bound[cone::kV] = up(512 * kU * kU * up(all.vol_mag.round() * (1 + 0x1p-10)));
        // Each Σ d s_i: double-double terms (error <= 532 u² Σ 18 M_b^4 n_b), or
        // plain ones (error <= 9.01 u Σ (3 M_b Σ|d| + 2^-43 M_b^4 n_b)).
        const double mom_bound = s.moments == measure::soup::kDoubleDouble
                                     ? up(1024 * kU * kU * up(all.mom_mag.round() * (1 + 0x1p-10)))
                                     : up(16 * kU * up(all.mom_mag.round() * (1 + 0x1p-10)));
        for (int k = cone::kMx; k < count; ++k) s.bound[k] = mom_bound;
    } else {
        if (all.triangles != s.pass1_triangles)
            throw std::logic_error("SoupAccumulator: pass " + std::to_string(s.pass) + " saw " +
                                   std::to_string(all.triangles) + " triangles, pass 1 saw " +
                                   std::to_string(s.pass1_triangles));
        if (s.pass == 2) {
            // The translated double-double sums replace those still undecided.
            for (int k = 0; k < count; ++k)
                if (s.exact_mask & cone::bit(k)) {
                    s.sum[k] = all.sum[k];
                    s.bound[k] = cone::filtered_bound(k, cone::Precision::double_double, all.mag[k].round());
                }
        } else {
            for (int k = 0; k < count; ++k)
                if (s.exact_mask & cone::bit(k)) {
                    s.sum[k] = all.sum[k];
                    s.bound[k] = 0;
                }
        }
    }
    // Decide. Correctly rounded moments (or a mass with a density) as a
    // loaded mesh's results, in rational intervals; the volume alone, and
    // bounded moments, in doubles by the superaccumulator.
    const bool bounded_moments = moments && s.wants.moments == Accuracy::fast;
    const bool rational = (moments && !bounded_moments) || s.wants.density != 1;
    const int decided_count = rational && !bounded_moments ? count : 1;
    std::vector<cone::Result> results;
    std::optional<double> volume;
    uint32_t need = 0;
    if (rational) {
        std::array<cone::Interval, cone::kSumCount> iv;
        for (int k = 0; k < decided_count; ++k) iv[k] = cone::interval(s.sum[k], s.bound[k]);
        results = cone::evaluate(iv, decided_count, exact::Rational(s.wants.density));
        need = cone::undecided_sums(results);
    } else {
        volume = exact::decided_round_div(s.sum[cone::kV], s.bound[cone::kV], 6);
        need = volume ? 0u : cone::bit(cone::kV);
    }
    if (need != 0) {
        // After pass 1, pass 2: the cone kernels' translated form, whose bound
        // shrinks with the triangles' size, not their distance from the origin
        // (for the moments only when each undecided one is away from 0: an
        // exact zero, a centred part's, no filter decides). Else, and after
        // pass 2, pass 3: the exact sums always decide.
        bool translate = s.pass == 1;
        for (int k = cone::kMx; k < count; ++k)
            if ((need & cone::bit(k)) && !(std::fabs(s.sum[k].round()) > 2 * s.bound[k])) translate = false;
        s.pass = translate ? 2 : 3;
        s.pass2_moments = translate && (need & ~cone::bit(cone::kV)) != 0;
        s.exact_mask = need;
        ++s.reads;
        return true;
    }
    m.method = Method::cone;
    m.accuracy = Accuracy::correctly_rounded;
    m.volume = rational ? *cone::decided(results[cone::kVolume]) : *volume;
    m.mass = rational ? *cone::decided(results[cone::kMass]) : m.volume;
    m.volume_correctly_rounded = true;
    m.volume_error_bound = 0;
    if (moments && !bounded_moments) {
        for (int i = 0; i < 3; ++i) {
            m.first_moments[i] = *cone::decided(results[cone::kFirst + i]);
            m.centroid[i] = *cone::decided(results[cone::kCentroid + i]);
        }
        m.moments_correctly_rounded = true;
        m.moments_relative_error = 0x1p-53;
    } else if (moments) {
        set_bounded_moments(s.sum, s.bound, s.wants.density, m);
        // A bound that no entry can carry (every approximation exactly 0, a
        // nonzero volume): the sums that have a bound are summed exactly.
        uint32_t inexact = 0;
        for (int k = cone::kMx; k < count; ++k)
            if (s.bound[k] > 0) inexact |= cone::bit(k);
        if (!std::isfinite(m.moments_relative_error) && m.volume != 0 && inexact != 0) {
            s.pass = 3;
            s.exact_mask = inexact;
            ++s.reads;
            return true;
        }
    }
    r.passes = s.reads;
    s.done = true;
    return false;
}

const SoupResult& SoupAccumulator::result() const {
    if (!s_->done) throw std::logic_error("SoupAccumulator::result before the last pass ended");
    return s_->result;
}

namespace {
SoupResult run_all(SoupAccumulator& acc, const Float32Triangles& t) {
    do {
        acc.add(t, 0);
    } while (acc.next_pass());
    return acc.result();
}
}  // namespace

SoupResult soup_properties(const Float32Triangles& t, SoupWants wants) {
    SoupAccumulator acc(wants);
    return run_all(acc, t);
}

SoupResult soup_properties(const Float32Triangles& t, uint64_t seed, SoupWants wants) {
    SoupAccumulator acc(seed, wants);
    return run_all(acc, t);
}

double soup_volume(const Float32Triangles& t) {
    // No keys are needed without the fingerprint: a fixed seed spares
    // std::random_device.
    SoupAccumulator acc(0, SoupWants{.closedness = false, .moments_and_area = false});
    return run_all(acc, t).properties.volume;
}

}  // namespace polyvol

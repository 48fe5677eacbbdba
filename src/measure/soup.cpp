// measure/soup.cpp — polyvol/soup.hpp: volume, first moments, area and a
// closedness fingerprint of float32 triangle records, in constant memory.
//
// The passes: pass 1 (soup_pass1.cpp) forms the volume, first moments,
// area and fingerprint in one read; when its volume does not decide the
// rounding, pass 2 runs the cone kernels' translated form on each block,
// and pass 3 the exact sum. The error analysis behind each bound used here
// is in docs/numerics.md, "The streamed soup".
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

#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "measure/cone.hpp"
#include "measure/fingerprint.hpp"
#include "measure/soup_pass1.hpp"
#include "measure/soup_testing.hpp"

namespace polyvol {
namespace {

using exact::ExactSum;
namespace cone = measure::cone;
using measure::fingerprint::kP;
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
    ExactSum vol, vol_mag;        // 6 V: the current pass's sum and magnitudes
    ExactSum mom[3], mom_mag;     // pass 1: 24 ∫x_i and the bound's magnitudes
    ExactSum area2, cross;        // pass 1: 2 A and Σ X
    uint64_t fp[kFpLanes] = {};   // mod p
    uint64_t triangles = 0;
    bool nonfinite = false;

    void merge(const Partial& o) {
        vol.merge(o.vol);
        vol_mag.merge(o.vol_mag);
        for (int k = 0; k < 3; ++k) mom[k].merge(o.mom[k]);
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
    int pass = 1;
    bool done = false;
    tbb::enumerable_thread_specific<Partial> tls;
    uint64_t pass1_triangles = 0;
    SoupResult result;

    State(uint64_t seed, SoupWants w) : wants(w) {
        uint64_t s = seed;
        for (auto& k : keys.aes)
            for (auto& x : k) x = measure::fingerprint::splitmix(s);
        for (auto& k : keys.mix)
            for (auto& x : k) x = measure::fingerprint::splitmix(s) | 1;
    }

    // Pass 1 over a group: triangles [first, first + n) of t, n <= kGroupBlocks
    // kB, relative index (first is a multiple of kB in the whole input).
    void group(const Float32Triangles& t, std::size_t first, int n, Partial& p) const {
        p.triangles += static_cast<uint64_t>(n);
        Pass1Group g;
        if (!measure::soup::pass1_group(t.data + first * t.stride + t.offset, t.stride, n, keys, wants.closedness,
                                        wants.moments_and_area, g)) {
            p.nonfinite = true;  // NaN or infinity: nothing else is meaningful
            return;
        }
        for (int l = 0; l < kFpLanes; ++l) {
            p.fp[l] += g.fp[l];
            if (p.fp[l] >= kP) p.fp[l] -= kP;
        }
        p.vol.add(g.vs);
        p.vol.add(g.ve);
        double magnitude = 0;
        for (int b = 0; b * kB < n; ++b) {
            const double M = static_cast<double>(std::bit_cast<float>(g.mx[b]));
            const double nb = static_cast<double>(std::min(kB, n - b * kB));
            magnitude += 6 * (M * M * M) * nb;
            if (!wants.moments_and_area) continue;
            const Pass1Block& r = g.block[b];
            for (int k = 0; k < 3; ++k) p.mom[k].add(r.mom[k]);
            p.mom_mag.add(3 * M * r.abs_d + 0x1p-43 * ((M * M) * (M * M)) * nb);
            p.area2.add(r.area2);
            p.cross.add(r.cross);
        }
        p.vol_mag.add(magnitude);
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
        if (pass == 2) {
            cone::filtered_volume_block(b, p.vol, p.vol_mag);
        } else {
            cone::exact_block_sums(b, 1u << cone::kV, &p.vol);
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
        for (auto& x : k) x ^= measure::fingerprint::random_word(rd);
    for (auto& k : s_->keys.mix)
        for (auto& x : k) x ^= measure::fingerprint::random_word(rd);
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

bool SoupAccumulator::next_pass() {
    State& s = *s_;
    if (s.done) return false;
    Partial all;
    for (const Partial& p : s.tls) all.merge(p);
    s.tls.clear();
    SoupResult& r = s.result;
    if (s.pass == 1) {
        if (measure::SoupPass1Sums* rec = g_pass1_record.load(std::memory_order_relaxed))
            *rec = {all.vol, all.vol_mag, {all.mom[0], all.mom[1], all.mom[2]}, all.mom_mag, all.area2, all.cross};
        s.pass1_triangles = all.triangles;
        r.computed = s.wants;
        r.triangles = all.triangles;
        r.nonfinite = all.nonfinite;
        r.fingerprint = {all.fp[0], all.fp[1], all.fp[2], all.fp[3]};
        r.closed = s.wants.closedness && !all.nonfinite && all.fp[0] == 0 && all.fp[1] == 0 && all.fp[2] == 0 &&
                   all.fp[3] == 0;
        if (all.nonfinite || !s.wants.moments_and_area) {  // NaN unless computed below
            r.area = kNaN;
            r.first_moments = r.centroid = {kNaN, kNaN, kNaN};
            r.first_moments_error_bound = r.centroid_error_bound = r.area_relative_error = kNaN;
        }
        if (all.nonfinite) {
            r.volume = kNaN;
            r.passes = 1;
            s.done = true;
            return false;
        }
        if (s.wants.moments_and_area) {
            // Area.
            const double a2 = all.area2.round();
            const double cross = all.cross.round();
            r.area = a2 / 2;
            r.area_relative_error =
                a2 > 0 ? up(up(up(up(15 * kU * a2) + up(5 * kU * cross)) / a2) + kU) : (cross > 0 ? kInf : 0.0);
            // First moments (the centroid needs the volume: below).
            const double mom_bound = up(up(16 * kU * up(all.mom_mag.round() * (1 + 0x1p-10))) / 24);
            double emax = 0;
            for (int k = 0; k < 3; ++k) {
                r.first_moments[k] = all.mom[k].round_div(24);
                emax = std::max(emax, up(mom_bound + up(kU * std::fabs(r.first_moments[k]))));
            }
            r.first_moments_error_bound = emax;
        }
        const double bound = up(512 * kU * kU * up(all.vol_mag.round() * (1 + 0x1p-10)));
        if (const auto v = exact::decided_round_div(all.vol, bound, 6)) {
            r.volume = *v;
        } else {
            s.pass = 2;
            return true;
        }
    } else {
        if (all.triangles != s.pass1_triangles)
            throw std::logic_error("SoupAccumulator: pass " + std::to_string(s.pass) + " saw " +
                                   std::to_string(all.triangles) + " triangles, pass 1 saw " +
                                   std::to_string(s.pass1_triangles));
        const double bound =
            s.pass == 2 ? cone::filtered_bound(cone::kV, cone::Precision::double_double, all.vol_mag.round()) : 0.0;
        if (const auto v = exact::decided_round_div(all.vol, bound, 6)) {
            r.volume = *v;
        } else {
            s.pass = 3;  // only from pass 2: the exact sum always decides
            return true;
        }
    }
    r.volume_correctly_rounded = true;
    r.passes = s.pass;
    if (!s.wants.moments_and_area) {
        s.done = true;
        return false;
    }
    // Centroid c_i = F_i / V with F_i ± E (first moments) and V correctly
    // rounded (|V - V*| <= u |V|): |c - c*| <= (E + 1.01 u (|F| + E)) / |V| + u |c|.
    const double V = r.volume;
    double cmax = 0;
    for (int k = 0; k < 3; ++k) {
        if (V == 0) {
            r.centroid[k] = kNaN;
            continue;
        }
        const double F = r.first_moments[k], E = r.first_moments_error_bound;
        r.centroid[k] = F / V;
        const double num = up(E + up(1.01 * kU * up(std::fabs(F) + E)));
        cmax = std::max(cmax, up(up(num / std::fabs(V)) + up(kU * std::fabs(r.centroid[k]))));
    }
    r.centroid_error_bound = V == 0 ? kInf : cmax;
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
    return run_all(acc, t).volume;
}

}  // namespace polyvol

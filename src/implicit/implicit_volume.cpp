// The volume of {F <= 0}: one PL surface per lattice, its chain volume
// (simplicial.hpp), and the Richardson estimate from the lattices of spacing
// h and 2h.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "implicit/surface.hpp"
#include "polyvol/implicit.hpp"
#include "polyvol/simplicial.hpp"

namespace polyvol {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

struct Box {
    std::vector<double> lo, hi;
};

Box checked_box(const ImplicitOptions& o) {
    if (o.dimension < 2 || o.dimension > kImplicitMaxDimension)
        throw std::invalid_argument("implicit: dimension must be 2 .. " + std::to_string(kImplicitMaxDimension));
    const auto n = static_cast<std::size_t>(o.dimension);
    auto widen = [&](const std::vector<double>& v, const char* name) {
        if (v.size() == 1) return std::vector<double>(n, v[0]);
        if (v.size() != n)
            throw std::invalid_argument(std::string("implicit: box ") + name + " needs 1 or " + std::to_string(n) +
                                        " entries");
        return v;
    };
    Box b{widen(o.lo, "lo"), widen(o.hi, "hi")};
    for (std::size_t k = 0; k < n; ++k)
        if (!std::isfinite(b.lo[k]) || !std::isfinite(b.hi[k]) || !(b.lo[k] < b.hi[k]))
            throw std::invalid_argument("implicit: the box needs finite lo < hi on every axis");
    if (!(o.h >= 0) || !std::isfinite(o.h)) throw std::invalid_argument("implicit: h must be > 0 (or 0: default)");
    if (o.seeds.size() % n != 0) throw std::invalid_argument("implicit: seeds must hold n coordinates per point");
    return b;
}

double resolved_h(const ImplicitOptions& o, const Box& b) {
    if (o.h > 0) return o.h;
    double widest = 0;
    for (std::size_t k = 0; k < b.lo.size(); ++k) widest = std::max(widest, b.hi[k] - b.lo[k]);
    return widest / default_cells(o.dimension);
}

// One pass on the lattice with the given cells per axis. With `chain` the
// PL surface is built into it (its volume is measure_pass's); without, the
// volume is streamed (ConeSum: the cone formula, no chain, no validation —
// the chain is closed by construction) into pass.volume and
// pass.rounding_error_bound.
// The evaluations options.max_memory_bytes allows (0: no limit); a kept
// chain about doubles the memory per evaluation.
std::size_t max_evaluations(const ImplicitOptions& o) {
    if (o.max_memory_bytes == 0) return 0;
    return std::max<std::size_t>(1, o.max_memory_bytes / (kImplicitBytesPerEvaluation * (o.keep_chain ? 2 : 1)));
}

void run_pass(const ImplicitBatchFunction& f, bool lookahead, const ImplicitOptions& o, const Box& b,
              std::span<const int32_t> cells, ImplicitPass& pass, Chain* chain, ImplicitProgress progress = {}) {
    const auto t0 = Clock::now();
    const implicit::Lattice lattice(o.dimension, b.lo, b.hi, cells);
    implicit::Sampler sampler(lattice, f, o.box_rule, lookahead, max_evaluations(o));
    if (o.progress) {
        o.progress(progress);
        sampler.on_evaluations([&](std::size_t n) {
            progress.evaluations = n;
            o.progress(progress);
        });
    }
    std::optional<implicit::ConeSum> cone;
    if (!chain) cone.emplace(lattice);
    implicit::SurfaceBuilder builder(lattice, sampler, o.max_boundary_simplices, cone ? &*cone : nullptr);
    const int coarse = o.coarse_cells == 0 ? default_coarse_cells(o.dimension) : o.coarse_cells;
    implicit::seed_and_walk(lattice, sampler, builder, coarse, o.seeds);
    pass.components = builder.surface_walks();
    pass.face_walks = builder.face_walks();
    pass.face_simplices = builder.face_simplices();
    pass.spacing.assign(lattice.spacing.begin(), lattice.spacing.begin() + o.dimension);
    pass.cells.assign(cells.begin(), cells.end());
    pass.crossed_simplices = builder.crossed_simplices();
    pass.function_evaluations = sampler.evaluations();
    pass.box_vertices_inside = sampler.box_vertices_inside();
    pass.boundary_simplices = builder.boundary_simplices();
    if (cone) {
        cone->finish();
        pass.volume = cone->volume();
        pass.rounding_error_bound = cone->bound();
    } else {
        *chain = builder.take_chain();
    }
    pass.seconds = seconds_since(t0);
}

void measure_pass(const Chain& chain, const ImplicitOptions& o, ImplicitPass& pass) {
    const auto t0 = Clock::now();
    ChainOptions co;
    co.formula = o.formula;
    co.centroid = false;
    const ChainVolume v = chain_volume(chain.view(), co);
    pass.volume = v.volume;
    pass.rounding_error_bound = v.volume_error_bound;
    pass.seconds += seconds_since(t0);
}

// One pass measured: streamed unless the chain is wanted (kept) or the prism
// formula is asked for (chain_volume only).
void volume_pass(const ImplicitBatchFunction& f, bool lookahead, const ImplicitOptions& o, const Box& b,
                 std::span<const int32_t> cells, ImplicitPass& pass, std::optional<Chain>* kept,
                 const ImplicitProgress& progress) {
    if (!kept && o.formula == SimplexFormula::cone) {
        run_pass(f, lookahead, o, b, cells, pass, nullptr, progress);
        return;
    }
    Chain chain;
    run_pass(f, lookahead, o, b, cells, pass, &chain, progress);
    measure_pass(chain, o, pass);
    if (kept) *kept = std::move(chain);
}

}  // namespace

int default_cells(int dimension) {
    static constexpr int kCells[] = {512, 96, 32, 16, 12, 8, 8};
    return kCells[std::clamp(dimension, 2, kImplicitMaxDimension) - 2];
}

int default_coarse_cells(int dimension) {
    static constexpr int kCells[] = {256, 48, 16, 10, 6, 5, 4};
    return kCells[std::clamp(dimension, 2, kImplicitMaxDimension) - 2];
}

Richardson richardson(double fine, double coarse, double ratio, double order) {
    const double factor = std::pow(ratio, order);
    return {(factor * fine - coarse) / (factor - 1), std::fabs(fine - coarse) / (factor - 1)};
}

namespace {
// A pointwise F as a batch function: one call per point.
ImplicitBatchFunction batch_of(const ImplicitFunction& f, int dimension) {
    const auto n = static_cast<std::size_t>(dimension);
    return [&f, n](std::span<const double> points, std::span<double> values) {
        for (std::size_t i = 0; i < values.size(); ++i) values[i] = f(points.subspan(i * n, n));
    };
}
}  // namespace

Chain implicit_surface(const ImplicitFunction& f, const ImplicitOptions& options, ImplicitPass* pass) {
    const Box b = checked_box(options);
    const std::vector<int32_t> cells = implicit::lattice_cells(b.lo, b.hi, resolved_h(options, b));
    ImplicitPass local;
    Chain chain;
    run_pass(batch_of(f, options.dimension), false, options, b, cells, pass ? *pass : local, &chain);
    return chain;
}

namespace {
ImplicitVolume volume_with(const ImplicitBatchFunction& f, bool lookahead, const ImplicitOptions& options);
}  // namespace

ImplicitVolume implicit_volume(const ImplicitFunction& f, const ImplicitOptions& options) {
    return volume_with(batch_of(f, options.dimension), false, options);
}

ImplicitVolume implicit_volume_batch(const ImplicitBatchFunction& f, const ImplicitOptions& options) {
    return volume_with(f, true, options);
}

namespace {
// |R(h) - R(2h)| + the three passes' rounding bounds, R(h) = (4 V(h) - V(2h)) / 3:
// the extrapolation's error while V(2h) - V(4h) is 3 to 5 times V(h) - V(2h)
// (the h^2 regime; implicit.hpp); NaN otherwise or without the 4h pass.
double extrapolation_error(const ImplicitPass& h, const ImplicitPass& h2, const std::optional<ImplicitPass>& h4) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (!h4) return nan;
    const double d1 = h.volume - h2.volume, d2 = h2.volume - h4->volume;
    if (!(d1 != 0 && d2 / d1 >= 3 && d2 / d1 <= 5)) return nan;
    const double r1 = richardson(h.volume, h2.volume).extrapolated;
    const double r2 = richardson(h2.volume, h4->volume).extrapolated;
    const double rounding = h.rounding_error_bound + h2.rounding_error_bound + h4->rounding_error_bound;
    return std::fabs(r1 - r2) + 2 * rounding;  // 4/3 + 1/3 of each bound, over both extrapolations
}

ImplicitVolume volume_with(const ImplicitBatchFunction& f, bool lookahead, const ImplicitOptions& options) {
    const auto t0 = Clock::now();
    const Box b = checked_box(options);
    ImplicitVolume r;
    r.dimension = options.dimension;
    r.h = resolved_h(options, b);
    const std::vector<int32_t> cells = implicit::lattice_cells(b.lo, b.hi, r.h);
    // The 2h lattice first: its evaluations times 2^(n-1) (the surface's
    // vertices scale as h^-(n-1)) estimate the fine pass's memory before it starts.
    ImplicitPass coarse;
    if (options.error_estimate) {
        std::vector<int32_t> half(cells);
        for (auto& c : half) c /= 2;  // even, so spacing exactly 2 h_k
        volume_pass(f, lookahead, options, b, half, coarse, nullptr, ImplicitProgress{});
        const double estimate = std::ldexp(static_cast<double>(coarse.function_evaluations), options.dimension - 1);
        const std::size_t most = max_evaluations(options);
        if (most != 0 && estimate > static_cast<double>(most))
            throw ImplicitError(ImplicitError::Code::too_large, {},
                                "implicit: the lattice of spacing h would need about " +
                                    std::to_string(static_cast<long long>(
                                        estimate * kImplicitBytesPerEvaluation * (options.keep_chain ? 2 : 1) / 1e6)) +
                                    " MB (estimated from the 2h lattice: " +
                                    std::to_string(coarse.function_evaluations) + " vertices evaluated there, 2^" +
                                    std::to_string(options.dimension - 1) +
                                    " times as many at h), more than the memory limit allows; a larger h, a smaller "
                                    "box, or a higher limit");
    }
    // The 4h lattice, for the extrapolation's own estimate (4^-(n-1) of the work).
    std::optional<ImplicitPass> coarser;
    if (options.error_estimate && std::all_of(cells.begin(), cells.end(), [](int32_t c) { return c % 4 == 0; })) {
        std::vector<int32_t> quarter(cells);
        for (auto& c : quarter) c /= 4;
        ImplicitOptions quiet = options;  // too short to report
        quiet.progress = nullptr;
        coarser.emplace();
        volume_pass(f, lookahead, quiet, b, quarter, *coarser, nullptr, ImplicitProgress{});
    }
    ImplicitProgress fine{.pass = 1};
    if (options.error_estimate) {
        // The seeding scan's (coarse_cells + 1)^n evaluations are the same at
        // h; the surface's vertices scale as h^-(n-1).
        const int scan_cells = options.coarse_cells == 0 ? default_coarse_cells(options.dimension) : options.coarse_cells;
        double scan = 1;
        for (const int32_t c : cells) scan *= std::max(0, std::min(scan_cells, c / 2)) + 1;
        const double coarse_evaluations = static_cast<double>(coarse.function_evaluations);
        scan = scan_cells < 0 ? 0.0 : std::min(scan, coarse_evaluations);
        fine.expected_evaluations = scan + std::ldexp(coarse_evaluations - scan, options.dimension - 1);
        fine.expected_seconds = coarse_evaluations > 0 ? coarse.seconds * fine.expected_evaluations / coarse_evaluations : 0;
    }
    volume_pass(f, lookahead, options, b, cells, r.fine, options.keep_chain ? &r.chain : nullptr, fine);
    r.clipped = r.fine.box_vertices_inside > 0;
    if (options.error_estimate) {
        const Richardson e = richardson(r.fine.volume, coarse.volume);
        r.volume_extrapolated = e.extrapolated;
        r.volume = e.extrapolated;
        r.error_estimate = e.error_of_fine + r.fine.rounding_error_bound + coarse.rounding_error_bound;
        // Not informative where it exceeds V(h)'s (4h too coarse for R's regime).
        r.extrapolated_error_estimate = extrapolation_error(r.fine, coarse, coarser);
        if (!(r.extrapolated_error_estimate < r.error_estimate))
            r.extrapolated_error_estimate = std::numeric_limits<double>::quiet_NaN();
        r.coarse = std::move(coarse);
        r.coarser = std::move(coarser);
    } else {
        r.volume = r.fine.volume;
        r.volume_extrapolated = std::numeric_limits<double>::quiet_NaN();
        r.error_estimate = std::numeric_limits<double>::quiet_NaN();
        r.extrapolated_error_estimate = std::numeric_limits<double>::quiet_NaN();
    }
    r.seconds = seconds_since(t0);
    return r;
}
}  // namespace

}  // namespace polyvol

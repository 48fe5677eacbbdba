// The lattice of one pass and the cached samples of F on it.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "implicit/surface.hpp"

namespace polyvol::implicit {

namespace {

// a * b, or false when it would reach 2^63.
bool checked_mul(uint64_t a, uint64_t b, uint64_t& out) {
    constexpr uint64_t kLimit = uint64_t{1} << 63;
    if (a != 0 && b >= kLimit / a) return false;
    out = a * b;
    return true;
}

std::string point_text(std::span<const double> x) {
    std::ostringstream s;
    s.precision(17);
    s << "(";
    for (std::size_t k = 0; k < x.size(); ++k) s << (k ? ", " : "") << x[k];
    s << ")";
    return s.str();
}

}  // namespace

std::vector<int32_t> lattice_cells(std::span<const double> lo, std::span<const double> hi, double h) {
    std::vector<int32_t> cells(lo.size());
    for (std::size_t k = 0; k < lo.size(); ++k) {
        const double half = std::ceil((hi[k] - lo[k]) / (2 * h));
        if (!(half >= 1)) throw std::invalid_argument("implicit: empty box side");
        if (half > 1 << 29)
            throw ImplicitError(ImplicitError::Code::too_large, {},
                                "implicit: more than 2^30 lattice cells along an axis (h is too small for the box)");
        cells[k] = 2 * static_cast<int32_t>(half);
    }
    return cells;
}

Lattice::Lattice(int dimension, std::span<const double> lo_, std::span<const double> hi_,
                 std::span<const int32_t> cells_)
    : n(dimension) {
    uint64_t vs = 1, cs = 1;
    for (int k = 0; k < n; ++k) {
        lo[k] = lo_[k];
        hi[k] = hi_[k];
        cells[k] = cells_[k];
        spacing[k] = (hi[k] - lo[k]) / cells[k];
        vertex_stride[k] = vs;
        cube_stride[k] = cs;
        if (!checked_mul(vs, static_cast<uint64_t>(cells[k]) + 3, vs) ||
            !checked_mul(cs, static_cast<uint64_t>(cells[k]) + 2, cs))
            throw ImplicitError(ImplicitError::Code::too_large, {},
                                "implicit: the lattice has too many vertices for 64-bit keys");
    }
    uint64_t unused;  // point keys and face keys stay below vertex key * 2^n
    if (!checked_mul(vs, uint64_t{1} << n, unused))
        throw ImplicitError(ImplicitError::Code::too_large, {},
                            "implicit: the lattice has too many vertices for 64-bit keys");
}

Sampler::Sampler(const Lattice& lattice, const ImplicitBatchFunction& f, BoxRule rule, bool lookahead,
                 std::size_t max_evaluations)
    : lattice_(lattice), f_(f), rule_(rule), lookahead_(lookahead), max_evaluations_(max_evaluations),
      values_(1 << 12), prefetched_(1 << 12), x_(static_cast<std::size_t>(lattice.n)) {}

void Sampler::count(std::size_t evaluations) {
    evaluations_ += evaluations;
    if (tick_ && evaluations_ >= next_tick_) {
        tick_(evaluations_);
        next_tick_ = evaluations_ + (std::size_t{1} << 18);
    }
    if (max_evaluations_ != 0 && evaluations_ > max_evaluations_)
        throw ImplicitError(ImplicitError::Code::too_large, {},
                            "implicit: the lattice needs more memory than allowed: over " +
                                std::to_string(evaluations_) + " lattice vertices evaluated (about " +
                                std::to_string(kImplicitBytesPerEvaluation) +
                                " bytes each); a larger h, a smaller box, or a higher memory limit");
}

void Sampler::prefetch(std::span<const Index> vs) {
    keys_.clear();
    points_.clear();
    for (const Index& v : vs) {
        if (lattice_.is_virtual(v)) continue;
        const uint64_t key = lattice_.vertex_key(v);
        if (values_.find(key) || prefetched_.find(key)) continue;
        if (std::find(keys_.begin(), keys_.end(), key) != keys_.end()) continue;
        keys_.push_back(key);
        for (int k = 0; k < lattice_.n; ++k) points_.push_back(lattice_.coordinate(k, v[k]));
    }
    if (keys_.empty()) return;
    batch_.assign(keys_.size(), 0.0);
    f_(points_, batch_);
    count(keys_.size());
    for (std::size_t i = 0; i < keys_.size(); ++i) prefetched_.insert(keys_[i], batch_[i]);
}

double Sampler::value(const Index& v) {
    if (lattice_.is_virtual(v)) return std::numeric_limits<double>::infinity();
    const uint64_t key = lattice_.vertex_key(v);
    if (const double* cached = values_.find(key)) return *cached;
    for (int k = 0; k < lattice_.n; ++k) x_[k] = lattice_.coordinate(k, v[k]);
    // Prefetched, else evaluated alone.
    double fx = 0;
    if (const double* early = prefetched_.find(key)) {
        fx = *early;
    } else {
        f_(x_, std::span<double>(&fx, 1));
        count(1);
    }
    if (std::isnan(fx))
        throw ImplicitError(ImplicitError::Code::not_a_number, x_, "F is NaN at " + point_text(x_));
    if (fx <= 0 && lattice_.on_boundary(v)) {
        if (rule_ == BoxRule::error)
            throw ImplicitError(ImplicitError::Code::touches_box, x_,
                                "the solid reaches the box boundary: F = " + std::to_string(fx) + " <= 0 at " +
                                    point_text(x_) + " (enlarge the box, or clip)");
        ++box_inside_;
        boundary_inside_.push_back(v);
    }
    values_.insert(key, fx);
    return fx;
}

}  // namespace polyvol::implicit

// grid/axis.hpp — private: locating coordinates among the planes of one axis.
//
// An axis has planes c[0] < c[1] < ... < c[n] (n cells). A coordinate v lies
// in slab s when c[s] <= v < c[s+1]; s = -1 below c[0] and s = n at or above
// c[n]. For a part spanning [mn, mx] along the axis, the slabs it meets are
//     first = count_le(mn) - 1,   last = max(first, count_lt(mx) - 1),
// exactly the slabs split_into_slabs (clip.hpp) hands out: the planes strictly
// between mn and mx are c[first+1 .. last].
#pragma once

#include <algorithm>
#include <cmath>
#include <span>

namespace polyvol::grid {

class Axis {
public:
    explicit Axis(std::span<const double> planes)
        : c_(planes.data()), n_(static_cast<int>(planes.size()) - 1) {
        const double step = (planes.back() - planes.front()) / n_;
        inv_step_ = 1.0 / step;
        // Uniform enough for the guess below to be off by at most one or two.
        uniform_ = true;
        for (int i = 1; i <= n_ && uniform_; ++i) {
            const double d = planes[i] - planes[i - 1];
            uniform_ = std::abs(d - step) <= 1e-6 * step;
        }
    }

    const double* planes() const { return c_; }
    int cells() const { return n_; }
    double plane(int i) const { return c_[i]; }

    // The number of planes <= v (0 .. n+1).
    int count_le(double v) const {
        if (!uniform_) return static_cast<int>(std::upper_bound(c_, c_ + n_ + 1, v) - c_);
        int g = guess(v);
        while (g > 0 && c_[g - 1] > v) --g;
        while (g <= n_ && c_[g] <= v) ++g;
        return g;
    }
    // The number of planes < v (0 .. n+1).
    int count_lt(double v) const {
        if (!uniform_) return static_cast<int>(std::lower_bound(c_, c_ + n_ + 1, v) - c_);
        int g = guess(v);
        while (g > 0 && c_[g - 1] >= v) --g;
        while (g <= n_ && c_[g] < v) ++g;
        return g;
    }
    // Slabs met by a part spanning [mn, mx] (see the top of this file).
    void slab_range(double mn, double mx, int& first, int& last) const {
        first = count_le(mn) - 1;
        last = mx > mn ? std::max(first, count_lt(mx) - 1) : first;
    }

private:
    // A first guess at count_le(v) (the walks above correct it): truncation
    // instead of floor (no libm call), off by one at most for v < c[0].
    int guess(double v) const {
        const double g = std::clamp((v - c_[0]) * inv_step_ + 1, 0.0, static_cast<double>(n_ + 1));
        return static_cast<int>(g);
    }

    const double* c_;
    int n_;
    double inv_step_ = 0;
    bool uniform_ = false;
};

}  // namespace polyvol::grid

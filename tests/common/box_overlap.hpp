// The exact volume of the intersection of two axis-aligned boxes, for tests
// whose cells and bodies are boxes (a closed form to compare with).
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <array>

namespace polyvol::test {

// |[lo, hi] ∩ [a, b]|, exactly.
inline mpq_class box_overlap(const double* lo, const double* hi, const std::array<double, 3>& a,
                             const std::array<double, 3>& b) {
    mpq_class v = 1;
    for (int k = 0; k < 3; ++k) {
        const double l = std::max(lo[k], a[k]), h = std::min(hi[k], b[k]);
        if (!(h > l)) return 0;
        v *= mpq_class(h) - mpq_class(l);
    }
    return v;
}

}  // namespace polyvol::test

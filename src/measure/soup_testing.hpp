// Private: test hooks for measure/soup.cpp.
#pragma once

#include "exact/exact_sum.hpp"

namespace polyvol::measure {

// Pass 1's exact sums over all blocks, before any bound or rounding: the
// blocks' volume pairs (6 V) and magnitudes (6 M_b^3 n_b), first moments
// (24 ∫x_i) and their magnitudes, 2 A and Σ X.
struct SoupPass1Sums {
    exact::ExactSum volume, volume_magnitude;
    exact::ExactSum moments[3], moments_magnitude;
    exact::ExactSum area2, cross;
};

// While out is not null, every SoupAccumulator that ends pass 1 (next_pass)
// copies its sums to *out. For tests that compare the kernel levels' sums
// themselves; not for accumulators that end pass 1 concurrently.
void record_soup_pass1(SoupPass1Sums* out);

}  // namespace polyvol::measure

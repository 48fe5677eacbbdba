// implicit/eliminate.hpp — private: batches of kLanes determinants with
// their rounding-error bounds (eliminate.cpp), for the streaming cone
// volume (cone_sum.cpp).
#pragma once

namespace polyvol::implicit {

inline constexpr int kLanes = 4;

// The batch of pieces waiting for a kernel: matrices M in lanes.
template <int N>
struct Batch {
    alignas(32) double a[N][N][kLanes];
    double det[kLanes], bound[kLanes];
    int count = 0;
};

// det and bound of each of the batch's count matrices (lanes past count are
// overwritten with lane 0 and ignored), for n = 2 .. 8.
void eliminate_batch(Batch<2>& b);
void eliminate_batch(Batch<3>& b);
void eliminate_batch(Batch<4>& b);
void eliminate_batch(Batch<5>& b);
void eliminate_batch(Batch<6>& b);
void eliminate_batch(Batch<7>& b);
void eliminate_batch(Batch<8>& b);

}  // namespace polyvol::implicit

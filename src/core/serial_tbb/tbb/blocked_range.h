// core/serial_tbb/tbb/blocked_range.h — one thread's stand-in for oneTBB
// (-DPOLYVOL_TBB=serial: the WebAssembly build, where Debian has no TBB).
// The part of oneTBB's interface polyvol uses, run in the calling thread.
// Ranges split as oneTBB 2021 splits them (divisible while size > grain, cut
// at begin + (end - begin) / 2), so the reductions whose rounding depends on
// the split tree (parallel_deterministic_reduce, simple_partitioner) give
// oneTBB's bits; the others are schedule-independent by their callers' design.
#pragma once

#include <cstddef>

namespace tbb {

struct split {};

template <typename Value>
class blocked_range {
public:
    using const_iterator = Value;
    using size_type = std::size_t;

    blocked_range(Value begin, Value end, size_type grainsize = 1) : begin_(begin), end_(end), grain_(grainsize) {}
    // The upper half of r; r keeps the lower half.
    blocked_range(blocked_range& r, split) : begin_(r.middle()), end_(r.end_), grain_(r.grain_) { r.end_ = begin_; }

    Value begin() const { return begin_; }
    Value end() const { return end_; }
    size_type size() const { return size_type(end_ - begin_); }
    size_type grainsize() const { return grain_; }
    bool empty() const { return !(begin_ < end_); }
    bool is_divisible() const { return grain_ < size(); }

private:
    Value middle() const { return begin_ + (end_ - begin_) / 2u; }

    Value begin_, end_;
    size_type grain_;
};

}  // namespace tbb

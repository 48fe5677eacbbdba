// core/serial_tbb/tbb/parallel_for.h — see blocked_range.h.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/partitioner.h>

namespace tbb {

template <typename Range, typename Body>
void parallel_for(const Range& range, const Body& body) {
    if (!range.empty()) body(range);
}

template <typename Range, typename Body>
void parallel_for(const Range& range, const Body& body, const auto_partitioner&) {
    parallel_for(range, body);
}

template <typename Range, typename Body>
void parallel_for(const Range& range, const Body& body, const simple_partitioner&) {
    if (!range.empty()) serial::for_each_leaf(range, body);
}

template <typename Index, typename Function>
    requires requires(Index i) { ++i; }
void parallel_for(Index first, Index last, const Function& f) {
    for (Index i = first; i < last; ++i) f(i);
}

}  // namespace tbb

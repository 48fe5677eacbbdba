// core/serial_tbb/tbb/parallel_reduce.h — see blocked_range.h. The automatic
// partitioner runs the range as one leaf; the simple partitioner and the
// deterministic reduction replay oneTBB's halving tree and its joins.
#pragma once

#include <tbb/blocked_range.h>
#include <tbb/partitioner.h>

namespace tbb {

template <typename Range, typename Value, typename Body, typename Reduction>
Value parallel_reduce(const Range& range, const Value& identity, const Body& body, const Reduction&) {
    return range.empty() ? identity : body(range, identity);
}

template <typename Range, typename Value, typename Body, typename Reduction>
Value parallel_reduce(const Range& range, const Value& identity, const Body& body, const Reduction& reduction,
                      const auto_partitioner&) {
    return parallel_reduce(range, identity, body, reduction);
}

template <typename Range, typename Value, typename Body, typename Reduction>
Value parallel_reduce(const Range& range, const Value& identity, const Body& body, const Reduction& reduction,
                      const simple_partitioner&) {
    return range.empty() ? identity : serial::reduce_tree(range, identity, body, reduction);
}

template <typename Range, typename Value, typename Body, typename Reduction>
Value parallel_deterministic_reduce(const Range& range, const Value& identity, const Body& body,
                                    const Reduction& reduction, const simple_partitioner& = {}) {
    return range.empty() ? identity : serial::reduce_tree(range, identity, body, reduction);
}

}  // namespace tbb

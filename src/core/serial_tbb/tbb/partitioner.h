// core/serial_tbb/tbb/partitioner.h — see blocked_range.h. A simple partitioner
// cuts ranges down to their grain (its leaves decide some callers' rounding);
// the automatic one runs a range as one leaf.
#pragma once

namespace tbb {

class simple_partitioner {};
class auto_partitioner {};

namespace serial {

// Calls leaf(r) on the leaves of r's halving down to its grain, left to right.
template <typename Range, typename Leaf>
void for_each_leaf(Range r, const Leaf& leaf) {
    if (!r.is_divisible()) {
        leaf(r);
        return;
    }
    Range right(r, split());
    for_each_leaf(r, leaf);
    for_each_leaf(right, leaf);
}

// reduction(left, right) over the halving tree of r, body(leaf, identity) at its leaves.
template <typename Range, typename Value, typename Body, typename Reduction>
Value reduce_tree(Range r, const Value& identity, const Body& body, const Reduction& reduction) {
    if (!r.is_divisible()) return body(r, identity);
    Range right(r, split());
    Value left = reduce_tree(r, identity, body, reduction);
    return reduction(left, reduce_tree(right, identity, body, reduction));
}

}  // namespace serial
}  // namespace tbb

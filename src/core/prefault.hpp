// Private to the library (core and io): faulting in the pages of a large
// array before a reader or a pass fills it.
#pragma once

#include <cstddef>
#include <vector>

namespace polyvol::core {

// Faults in (writable) the whole pages inside [data, data + bytes) of a
// large buffer, in parallel slices on oneTBB; contents are kept (a buffer
// already partly filled is fine). Below 8 MiB it does nothing. Advice only
// (madvise MADV_POPULATE_WRITE, Linux 5.14): where the kernel declines, the
// first writes fault the pages in.
//
// Why, and why not transparent huge pages (which an earlier version asked
// for): a page fault costs the same whether the first write comes from
// std::vector's zero fill on one core or from the filling pass, so faulting
// in on every core divides that time by the number of cores. Huge pages are
// a bad bet in a virtual machine whose host takes back free 2 MiB blocks once
// it idles: a first touch in huge pages is then several times slower than in
// 4 KiB pages (the figures are in git history of docs/benchmarks.md).
// Where the system itself gives huge pages (THP "always") this still faults
// them in, in parallel.
void prefault(void* data, std::size_t bytes);

// v.resize(n) for an array a reader is about to fill: its pages faulted in
// on every core (prefault) between the allocation and std::vector's zero fill.
template <class T>
void resize_for_filling(std::vector<T>& v, std::size_t n) {
    v.reserve(n);
    prefault(v.data(), n * sizeof(T));
    v.resize(n);
}

}  // namespace polyvol::core

// Private to the library (core and io): faulting in the pages of a large
// array before a reader or a pass fills it.
#pragma once

#include <cstddef>
#include <vector>

namespace polyvol::core {

// Faults in (writable) the whole pages inside [data, data + bytes) of a
// large buffer nothing has touched yet, in parallel slices on oneTBB. Below
// 8 MiB it does nothing. Advice only (madvise MADV_POPULATE_WRITE, Linux
// 5.14): where the kernel declines, the first writes fault the pages in.
//
// Why, and why not transparent huge pages (which an earlier version asked
// for): a page fault costs the same whether the first write comes from
// std::vector's zero fill on one core or from the filling pass, so faulting
// in on every core first halves it. Huge pages were measured to be a bad
// bet on the reference machine (a Firecracker VM; docs/benchmarks.md): once
// the machine has idled for a few seconds, the host has taken back the free
// 2 MiB blocks, and a first touch of huge pages runs at 0.4-0.6 GB/s against
// 2-2.8 GB/s for 4 KiB pages (4-5 GB/s on two cores), while later passes over
// the array were no faster with them.
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

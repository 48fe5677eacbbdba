// core/serial_tbb/tbb/parallel_sort.h — see blocked_range.h.
#pragma once

#include <algorithm>

namespace tbb {

template <typename It>
void parallel_sort(It begin, It end) {
    std::sort(begin, end);
}

template <typename It, typename Compare>
void parallel_sort(It begin, It end, const Compare& less) {
    std::sort(begin, end, less);
}

}  // namespace tbb

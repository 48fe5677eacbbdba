// Shared by the peer harnesses: seconds since a point, and the median of
// repeated in-memory volume calls.
#pragma once

#include <algorithm>
#include <chrono>
#include <vector>

namespace peers {

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Median seconds of `runs` calls of f (f returns the volume, kept in *volume).
template <class F>
double median_seconds(int runs, F&& f, double* volume) {
    std::vector<double> t;
    for (int i = 0; i < runs; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        *volume = f();
        t.push_back(seconds_since(t0));
    }
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
}

}  // namespace peers

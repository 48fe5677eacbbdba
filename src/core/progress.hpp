// Private to the library: work counted by any number of threads, reported
// as a fraction done through a caller's callback (grid_volumes, the cells,
// measure_file's streamed files). Progress is for people: the callback runs
// when the count passes a whole percent and at the end, one call at a time,
// never with a smaller fraction than before.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <mutex>

namespace polyvol::core {

class ProgressCounter {
public:
    // report may be empty (then add() costs one test); total > 0.
    ProgressCounter(std::function<void(double)> report, uint64_t total) : report_(std::move(report)), total_(total) {}

    void add(uint64_t n = 1) {
        if (!report_) return;
        const uint64_t done = done_ += n;
        if (done < total_ && done * 100 / total_ <= reported_.load(std::memory_order_relaxed) * 100 / total_) return;
        std::lock_guard<std::mutex> lock(mutex_);
        if (done <= reported_.load(std::memory_order_relaxed)) return;  // a later count was reported already
        reported_.store(done, std::memory_order_relaxed);
        report_(done >= total_ ? 1.0 : static_cast<double>(done) / static_cast<double>(total_));
    }

private:
    std::function<void(double)> report_;
    uint64_t total_;
    std::atomic<uint64_t> done_{0}, reported_{0};
    std::mutex mutex_;
};

}  // namespace polyvol::core

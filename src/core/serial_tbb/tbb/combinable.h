// core/serial_tbb/tbb/combinable.h — see blocked_range.h.
#pragma once

#include <tbb/enumerable_thread_specific.h>

#include <utility>

namespace tbb {

template <typename T>
class combinable {
public:
    combinable() = default;
    template <typename Make>
    explicit combinable(Make make) : ets_(std::move(make)) {}

    T& local() { return ets_.local(); }
    void clear() { ets_.clear(); }
    template <typename Combine>
    void combine_each(const Combine& f) {
        ets_.combine_each(f);
    }
    template <typename Combine>
    T combine(const Combine&) {
        return ets_.empty() ? T() : *ets_.begin();
    }

private:
    enumerable_thread_specific<T> ets_;
};

}  // namespace tbb

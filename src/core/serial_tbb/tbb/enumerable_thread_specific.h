// core/serial_tbb/tbb/enumerable_thread_specific.h — see blocked_range.h. One
// thread, so at most one local, made on first use.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <type_traits>
#include <utility>

namespace tbb {

template <typename T>
class enumerable_thread_specific {
public:
    enumerable_thread_specific() : make_([] { return T(); }) {}
    template <typename Make>
        requires std::is_invocable_r_v<T, Make>
    explicit enumerable_thread_specific(Make make) : make_(std::move(make)) {}
    explicit enumerable_thread_specific(const T& exemplar) : make_([exemplar] { return exemplar; }) {}

    T& local() {
        if (!value_) value_.emplace(make_());
        return *value_;
    }
    T& local(bool& exists) {
        exists = value_.has_value();
        return local();
    }
    std::size_t size() const { return value_ ? 1 : 0; }
    bool empty() const { return !value_; }
    void clear() { value_.reset(); }

    T* begin() { return value_ ? &*value_ : nullptr; }
    T* end() { return value_ ? &*value_ + 1 : nullptr; }
    const T* begin() const { return value_ ? &*value_ : nullptr; }
    const T* end() const { return value_ ? &*value_ + 1 : nullptr; }

    template <typename Combine>
    void combine_each(const Combine& f) {
        if (value_) f(*value_);
    }

private:
    std::function<T()> make_;
    std::optional<T> value_;
};

}  // namespace tbb

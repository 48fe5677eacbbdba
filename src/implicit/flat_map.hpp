// Private to implicit: an open-addressing hash map from 64-bit keys to small
// values (lattice vertex -> F value, edge -> chain vertex, simplex -> visited).
// Linear probing in a power-of-two table kept at most half full; the key
// ~0 marks an empty slot and is never stored (callers' keys are < 2^63).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace polyvol::implicit {

inline uint64_t mix64(uint64_t x) {  // splitmix64's finaliser
    x ^= x >> 30;
    x *= 0xbf58476d1ce4e5b9ULL;
    x ^= x >> 27;
    x *= 0x94d049bb133111ebULL;
    x ^= x >> 31;
    return x;
}

template <class Value>
class FlatMap {
public:
    static constexpr uint64_t kEmpty = ~uint64_t{0};

    explicit FlatMap(std::size_t capacity_hint = 1024) { rehash(capacity_for(capacity_hint)); }

    std::size_t size() const { return size_; }

    // The value for key, or nullptr.
    const Value* find(uint64_t key) const {
        for (std::size_t i = mix64(key) & mask_;; i = (i + 1) & mask_) {
            if (slots_[i].key == key) return &slots_[i].value;
            if (slots_[i].key == kEmpty) return nullptr;
        }
    }
    // Inserts (key, value) unless key is present; returns the stored value and
    // whether it was inserted.
    std::pair<Value*, bool> insert(uint64_t key, const Value& value) {
        if (2 * (size_ + 1) > slots_.size()) rehash(2 * slots_.size());
        std::size_t i = mix64(key) & mask_;
        for (; slots_[i].key != kEmpty; i = (i + 1) & mask_)
            if (slots_[i].key == key) return {&slots_[i].value, false};
        slots_[i] = {key, value};
        ++size_;
        return {&slots_[i].value, true};
    }

private:
    static std::size_t capacity_for(std::size_t n) {
        std::size_t c = 16;
        while (c < 2 * n) c *= 2;
        return c;
    }
    void rehash(std::size_t capacity) {
        std::vector<Slot> slots(capacity, Slot{kEmpty, Value{}});
        const std::size_t mask = capacity - 1;
        for (const Slot& s : slots_) {
            if (s.key == kEmpty) continue;
            std::size_t i = mix64(s.key) & mask;
            while (slots[i].key != kEmpty) i = (i + 1) & mask;
            slots[i] = s;
        }
        slots_ = std::move(slots);
        mask_ = mask;
    }

    // Key and value side by side: one cache line per probe.
    struct Slot {
        uint64_t key;
        Value value;
    };
    std::vector<Slot> slots_;
    std::size_t mask_ = 0;
    std::size_t size_ = 0;
};

}  // namespace polyvol::implicit

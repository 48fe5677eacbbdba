// core/bit_cast.hpp — core::bit_cast, which older standard libraries lack
// (libc++ 13, Emscripten 3.1.6's), from the compiler builtin that implements it
// in GCC 11+ and clang 9+.
#pragma once

#include <type_traits>

namespace polyvol::core {

template <typename To, typename From>
    requires(sizeof(To) == sizeof(From) && std::is_trivially_copyable_v<To> && std::is_trivially_copyable_v<From>)
constexpr To bit_cast(const From& from) noexcept {
    return __builtin_bit_cast(To, from);
}

}  // namespace polyvol::core

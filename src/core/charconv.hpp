// core/charconv.hpp — doubles to and from text, the same bits on every standard
// library. std::to_chars and std::from_chars for doubles are missing from
// older ones (libc++ 13, Emscripten 3.1.6's): there, the text is made from
// printf's correctly rounded digits (tests/core/charconv_test.cpp holds it to
// std::to_chars natively); parsing is fast_float's, correctly rounded as the
// standard's.
#pragma once

#include <charconv>
#include <string>

namespace polyvol::core {

// The shortest digits that read back as x, as std::to_chars(first, last, x)
// writes them: positional or scientific, whichever is shorter (positional on a
// tie). x finite.
std::to_chars_result shortest_chars(char* first, char* last, double x);

// The same digits in a given notation, as std::to_chars(first, last, x, format):
// fixed, or general (scientific below 1e-4 and from 1e6 on, as %g at its
// default precision chooses). x finite.
enum class Notation { fixed, general };
std::to_chars_result shortest_chars(char* first, char* last, double x, Notation format);

// shortest_chars as a string.
std::string shortest_text(double x);

// The printf-based text shortest_chars falls back on, always built so that
// its tests can hold it to std::to_chars where both exist.
std::to_chars_result portable_shortest_chars(char* first, char* last, double x);
std::to_chars_result portable_shortest_chars(char* first, char* last, double x, Notation format);

// std::from_chars for a double (general format: no leading +, no hex;
// out of range when it overflows or underflows to zero).
std::from_chars_result parse_double(const char* first, const char* last, double& value);

}  // namespace polyvol::core

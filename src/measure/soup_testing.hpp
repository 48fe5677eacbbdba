// Private: a test hook for measure/soup.cpp.
#pragma once

namespace polyvol::measure {

// Caps the pass-1 kernels used (when the CPU has more): 0 portable, 1 AVX2 +
// FMA + AES-NI, 2 AVX-512 + VAES; -1 removes the cap. So tests can compare
// every path on one machine. Not for use while a SoupAccumulator is fed.
void cap_soup_kernels(int max_level);

}  // namespace polyvol::measure

// Private: a test hook for measure/soup.cpp.
#pragma once

namespace polyvol::measure {

// Use the portable pass-1 kernels (no AVX2/FMA/AES-NI/VAES) even when the CPU
// has them, so tests can compare both paths on one machine. Not for use
// while a SoupAccumulator is being fed.
void force_portable_soup_kernels(bool on);

}  // namespace polyvol::measure

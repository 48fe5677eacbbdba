// core/prefault.hpp: pages faulted in, contents untouched.
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/prefault.hpp"

namespace {

// Resident pages of [p, p + bytes) (p page-aligned), by mincore(2); a
// failure fails the test (and gives a count no check expects).
std::size_t resident_pages(void* p, std::size_t bytes) {
    const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
    std::vector<unsigned char> v((bytes + page - 1) / page);
    if (::mincore(p, bytes, v.data()) != 0) {
        ADD_FAILURE() << "mincore failed: errno " << errno;
        return std::numeric_limits<std::size_t>::max();
    }
    std::size_t n = 0;
    for (unsigned char c : v) n += c & 1u;
    return n;
}

TEST(Prefault, FaultsInAnUntouchedBuffer) {
    const auto page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
#ifdef MADV_POPULATE_WRITE
    void* probe = ::mmap(nullptr, page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ASSERT_NE(probe, MAP_FAILED);
    // Supported where the call succeeds and the page is then resident (not
    // before Linux 5.14, nor under a sandbox or emulator that refuses or
    // ignores it).
    const bool supported = ::madvise(probe, page, MADV_POPULATE_WRITE) == 0 && resident_pages(probe, page) == 1;
    ::munmap(probe, page);
    if (!supported) GTEST_SKIP() << "madvise(MADV_POPULATE_WRITE) does not fault pages in here";
#else
    GTEST_SKIP() << "no MADV_POPULATE_WRITE in these headers";
#endif
    const std::size_t bytes = std::size_t{24} << 20;
    void* m = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ASSERT_NE(m, MAP_FAILED);
    auto* p = static_cast<unsigned char*>(m);
    (void)::madvise(p, bytes, MADV_NOHUGEPAGE);  // page by page even where THP is "always"
    EXPECT_EQ(resident_pages(p, bytes), 0u);
    // An unaligned start and end: the whole pages inside, all but the first
    // and the last.
    polyvol::core::prefault(p + 100, bytes - 200);
    EXPECT_EQ(resident_pages(p, bytes), bytes / page - 2);
    EXPECT_EQ(resident_pages(p, page), 0u);
    EXPECT_EQ(resident_pages(p + bytes - page, page), 0u);
    ::munmap(m, bytes);
}

TEST(Prefault, LeavesTheContentsAndSmallBuffersAlone) {
    std::vector<uint64_t> v(std::size_t{3} << 20);  // 24 MiB, written
    for (std::size_t i = 0; i < v.size(); ++i) v[i] = i * 0x9E3779B97F4A7C15ull;
    polyvol::core::prefault(v.data(), v.size() * sizeof(uint64_t));
    for (std::size_t i = 0; i < v.size(); ++i) ASSERT_EQ(v[i], i * 0x9E3779B97F4A7C15ull) << i;
    // Below 8 MiB nothing happens (one core's faults are cheaper).
    const std::size_t bytes = std::size_t{4} << 20;
    void* m = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ASSERT_NE(m, MAP_FAILED);
    (void)::madvise(m, bytes, MADV_NOHUGEPAGE);
    polyvol::core::prefault(m, bytes);
    EXPECT_EQ(resident_pages(m, bytes), 0u);
    ::munmap(m, bytes);
}

TEST(Prefault, ResizeForFillingGivesZeros) {
    std::vector<double> v;
    polyvol::core::resize_for_filling(v, std::size_t{2} << 20);  // 16 MiB
    ASSERT_EQ(v.size(), std::size_t{2} << 20);
    for (double x : v) ASSERT_EQ(x, 0.0);
}

}  // namespace

// Streaming binary STL (polyvol/io.hpp): the records of a file too large to
// hold, handed over window by window.
//
// How (default, options.map = false): pread(2) into one buffer per thread,
// which turns a file shrinking under us into a ReadError at the offset
// where the data stopped; posix_fadvise(SEQUENTIAL) asks for read-ahead
// when the file is not cached.
// With options.map: the whole file is mapped once; slabs of ~4 MB go to
// threads (oneTBB), each walks its slab window by window (~200 KB) and then
// drops the slab's pages from the process in whole 2 MiB units (madvise
// DONTNEED: they stay in the page cache, so the resident set stays about
// threads × slab_bytes, plus a few units shared by neighbouring slabs,
// whatever the file size). No copy: with the page cache in large folios a
// fault maps many pages at once. Mapping each window on its own costs more
// than either (a new mapping, faults and an unmap with its TLB shootdown
// per window). A mapping that fails falls back to pread; a file truncated
// while mapped ends the process with SIGBUS, hence not the default.
//
// Detection is read_mesh_file's (detect.cpp), restricted to what decides
// binary STL: gzip, zip and PLY content win over the size rule; then the
// size must be 84 + 50 n, n the count at bytes 80..83.
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>

#include <cerrno>
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "io/readers.hpp"
#include "polyvol/io.hpp"

namespace polyvol {
namespace {

constexpr uint64_t kRecord = 50;
constexpr uint64_t kHugeUnit = uint64_t{2} << 20;  // bytes dropped at once (see for_each_mapped_window)

struct Fd {
    int fd = -1;
    Fd() = default;
    Fd(const Fd&) = delete;
    Fd& operator=(const Fd&) = delete;
    Fd(Fd&& o) noexcept : fd(std::exchange(o.fd, -1)) {}
    ~Fd() {
        if (fd >= 0) ::close(fd);
    }
    int release() { return std::exchange(fd, -1); }
};

// Reads exactly len bytes at offset (fewer only at the end of the file);
// returns the number read. Throws ReadError on an I/O error.
std::size_t read_at(int fd, std::byte* dst, std::size_t len, uint64_t offset, const std::string& name) {
    std::size_t got = 0;
    while (got < len) {
        const ssize_t r = ::pread(fd, dst + got, len - got, static_cast<off_t>(offset + got));
        if (r < 0) {
            if (errno == EINTR) continue;
            throw ReadError::at_byte(name, offset + got, std::string("cannot read: ") + std::strerror(errno));
        }
        if (r == 0) break;
        got += static_cast<std::size_t>(r);
    }
    return got;
}

// The probe on an open descriptor; head receives the first bytes.
BinaryStlProbe probe_fd(int fd, const std::string& name, unsigned char (&head)[84], std::size_t& head_len) {
    BinaryStlProbe p;
    head_len = 0;
    struct stat st {};
    if (::fstat(fd, &st) != 0) throw ReadError::whole_file(name, std::string("cannot stat: ") + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) return p;
    p.file_bytes = static_cast<uint64_t>(st.st_size);
    head_len = read_at(fd, reinterpret_cast<std::byte*>(head), sizeof head, 0, name);
    const io::Bytes bytes(reinterpret_cast<const std::byte*>(head), head_len);
    if (io::is_gzip(bytes) || io::is_zip(bytes) || io::is_ply(bytes)) return p;  // read_mesh_file's order
    if (head_len < 84) return p;
    p.triangles = io::stl_triangle_count(bytes);
    p.header_starts_with_solid = std::memcmp(head, "solid", 5) == 0;
    p.binary_stl = 84 + kRecord * p.triangles == p.file_bytes;
    return p;
}

Fd open_file(const std::string& path) {
    Fd f;
    f.fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (f.fd < 0) throw ReadError::whole_file(path, std::string("cannot open: ") + std::strerror(errno));
    return f;
}

// body(i) for i in [0, count): in order on this thread, or spread over
// threads (oneTBB, one index per task).
template <class Body>
void for_each_index(uint64_t count, bool parallel, Body&& body) {
    if (!parallel || count == 1) {
        for (uint64_t i = 0; i < count; ++i) body(i);
        return;
    }
    tbb::parallel_for(
        tbb::blocked_range<uint64_t>(0, count, 1),
        [&](const tbb::blocked_range<uint64_t>& r) {
            for (uint64_t i = r.begin(); i < r.end(); ++i) body(i);
        },
        tbb::simple_partitioner());
}

// The records [0, n) through fn from a mapping of the whole file, windows of
// per_window records grouped into slabs; false (nothing called) when the
// file cannot be mapped.
bool for_each_mapped_window(int fd, uint64_t file_bytes, uint64_t n, uint64_t per_window, const StlWindowFn& fn,
                            const StlStreamOptions& options) {
    if (file_bytes > std::numeric_limits<std::size_t>::max()) return false;
    const auto size = static_cast<std::size_t>(file_bytes);
    void* m = ::mmap(nullptr, size, PROT_READ, MAP_SHARED, fd, 0);
    if (m == MAP_FAILED) return false;
    struct Unmap {
        void* p;
        std::size_t len;
        ~Unmap() { ::munmap(p, len); }
    } unmap{m, size};
    const auto* base = static_cast<const std::byte*>(m);
    const uint64_t per_slab = per_window * std::max<uint64_t>(1, options.slab_bytes / (per_window * kRecord));
    const uint64_t slabs = (n + per_slab - 1) / per_slab;
    const auto page = static_cast<uint64_t>(::sysconf(_SC_PAGESIZE));
    // Pages are dropped in whole units of `unit` bytes: 2 MiB (a PMD on
    // x86-64) when slabs are at least that long, else a page. A page cache
    // in large folios is mapped a PMD at a time; dropping part of one splits
    // it first, which costs a TLB flush on every core running the process
    // (an IPI, expensive in a VM). A unit shared by two slabs is dropped by
    // whichever finishes second (a counter kept with the first of them).
    // Units are file offsets, so they are PMDs only when the mapping starts
    // on a 2 MiB boundary (the kernel places large file mappings so).
    const bool huge = per_slab * kRecord >= kHugeUnit && kHugeUnit % page == 0 &&
                      reinterpret_cast<std::uintptr_t>(base) % kHugeUnit == 0;
    const uint64_t unit = huge ? kHugeUnit : page;
    // The slab whose bytes hold file offset `byte` (the header is slab 0's).
    auto slab_at = [&](uint64_t byte) { return byte < 84 ? 0 : std::min(slabs - 1, (byte - 84) / kRecord / per_slab); };
    // done[s]: how many users of the shared unit whose first user is slab s
    // have finished (two shared units never have the same first user).
    std::vector<std::atomic<uint8_t>> done(slabs);
    // The number of slabs whose bytes lie in unit u (at most 2 for 2 MiB
    // units; a page-sized unit holds at least 1600 bytes of each but its
    // first and last users: at most 4 with 4 KiB pages, 42 with 64 KiB).
    auto users = [&](uint64_t u) {
        const uint64_t lo = u * unit, hi = std::min<uint64_t>(size, lo + unit) - 1;
        return static_cast<uint8_t>(slab_at(hi) - slab_at(lo) + 1);
    };
    auto drop = [&](uint64_t u0, uint64_t u1) {  // units [u0, u1), within the mapping's pages
        const uint64_t lo = u0 * unit, hi = std::min((size + page - 1) / page * page, u1 * unit);
        if (hi > lo)
            (void)::madvise(const_cast<std::byte*>(base) + lo, static_cast<std::size_t>(hi - lo), MADV_DONTNEED);
    };

    auto slab = [&](uint64_t s) {
        const uint64_t first = s * per_slab, last = std::min(n, first + per_slab);
        for (uint64_t w = first; w < last; w += per_window) {
            const uint64_t count = std::min(per_window, last - w);
            fn(std::span<const std::byte>(base + 84 + w * kRecord, static_cast<std::size_t>(count * kRecord)), w);
        }
        // This slab's bytes (with the header for the first, up to the end
        // for the last) lie in units u0..u1; those between are its own.
        const uint64_t from = s == 0 ? 0 : 84 + first * kRecord, to = s + 1 == slabs ? size : 84 + last * kRecord;
        const uint64_t u0 = from / unit, u1 = (to - 1) / unit;
        auto finished = [&](uint64_t u) {
            const uint8_t k = users(u);
            return k == 1 || done[slab_at(u * unit)].fetch_add(1) + 1 == k;
        };
        const bool drop_first = finished(u0);
        const bool drop_last = u1 == u0 ? drop_first : finished(u1);
        drop(drop_first ? u0 : u0 + 1, drop_last ? u1 + 1 : u1);
    };
    for_each_index(slabs, options.parallel, slab);
    return true;
}

}  // namespace

BinaryStlFile::BinaryStlFile(const std::string& path) : path_(path) {
    if (path == "-") return;  // standard input: never a file to map
    Fd f = open_file(path);   // closed if the probe throws
    probe_ = probe_fd(f.fd, path, head_, head_len_);
    fd_ = f.release();
}

BinaryStlFile::~BinaryStlFile() {
    if (fd_ >= 0) ::close(fd_);
}

// A moved-from file holds nothing: it probes as not binary STL, as "-" does.
BinaryStlFile::BinaryStlFile(BinaryStlFile&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)), probe_(std::exchange(other.probe_, {})),
      head_len_(std::exchange(other.head_len_, 0)) {
    std::memcpy(head_, other.head_, sizeof head_);
}

BinaryStlFile& BinaryStlFile::operator=(BinaryStlFile&& other) noexcept {
    if (this != &other) {
        if (fd_ >= 0) ::close(fd_);
        path_ = std::move(other.path_);
        fd_ = std::exchange(other.fd_, -1);
        probe_ = std::exchange(other.probe_, {});
        head_len_ = std::exchange(other.head_len_, 0);
        std::memcpy(head_, other.head_, sizeof head_);
    }
    return *this;
}

BinaryStlProbe probe_binary_stl(const std::string& path) { return BinaryStlFile(path).probe(); }

void for_each_stl_window(const std::string& path, const StlWindowFn& fn, const StlStreamOptions& options) {
    BinaryStlFile(path).for_each_window(fn, options);
}

void BinaryStlFile::for_each_window(const StlWindowFn& fn, const StlStreamOptions& options) const {
    const BinaryStlProbe& p = probe_;
    const std::string& path = path_;
    const unsigned char* head = head_;
    const std::size_t head_len = head_len_;
    if (!p.binary_stl) {
        const bool regular = p.file_bytes > 0 || head_len > 0;
        const io::Bytes bytes(reinterpret_cast<const std::byte*>(head), head_len);
        const bool other_format = io::is_gzip(bytes) || io::is_zip(bytes) || io::is_ply(bytes);
        if (!regular) throw ReadError::whole_file(path, "not a regular, non-empty file: cannot stream it as binary STL");
        if (other_format) throw ReadError::whole_file(path, "not binary STL (gzip, zip or PLY content)");
        if (p.file_bytes < 84)
            throw ReadError::whole_file(path, "file too short for binary STL (" + std::to_string(p.file_bytes) + " bytes)");
        throw ReadError::at_byte(path, 80,
                                 "binary STL size mismatch: header declares " + std::to_string(p.triangles) +
                                     " triangles (" + std::to_string(84 + kRecord * p.triangles) +
                                     " bytes) but file has " + std::to_string(p.file_bytes) + " bytes");
    }
    const uint64_t n = p.triangles;
    if (n == 0) return;
    (void)::posix_fadvise(fd_, 0, 0, POSIX_FADV_SEQUENTIAL);
    const uint64_t group = std::max<uint64_t>(1, options.alignment);  // records per alignment group
    if (group > (uint64_t{1} << 32)) throw std::invalid_argument("StlStreamOptions::alignment beyond 2^32 records");
    const uint64_t groups = std::max<uint64_t>(1, options.window_bytes / (kRecord * group));
    const uint64_t per_window = groups * group;  // records
    if (options.map && for_each_mapped_window(fd_, p.file_bytes, n, per_window, fn, options)) return;

    const uint64_t windows = (n + per_window - 1) / per_window;
    tbb::enumerable_thread_specific<std::vector<std::byte>> buffers;  // one per thread
    for_each_index(windows, options.parallel, [&](uint64_t w) {
        std::vector<std::byte>& buf = buffers.local();
        const uint64_t first = w * per_window;
        const uint64_t count = std::min(per_window, n - first);
        const std::size_t bytes = static_cast<std::size_t>(count * kRecord);
        if (buf.size() < bytes) buf.resize(static_cast<std::size_t>(per_window * kRecord));
        const uint64_t offset = 84 + first * kRecord;
        const std::size_t got = read_at(fd_, buf.data(), bytes, offset, path);
        if (got < bytes)
            throw ReadError::at_byte(path, offset + got,
                                     "unexpected end of file: expected " + std::to_string(84 + n * kRecord) +
                                         " bytes for " + std::to_string(n) + " triangles (the file shrank while being read)");
        fn(std::span<const std::byte>(buf.data(), bytes), first);
    });
}

}  // namespace polyvol

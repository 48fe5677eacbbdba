// cli/memory.hpp — how much memory a command may take: the machine's
// physical memory, and byte counts as users write and read them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace polyvol::cli {

// For a command that runs once and exits: the allocator keeps memory freed
// during the run for the next allocations instead of handing it back to the
// system, so arrays freed by one stage are reused by the next without a page
// fault per 4 KiB (glibc's mallopt: no trimming, mmap only above 256 MiB;
// nothing elsewhere). docs/benchmarks.md, "The command's allocator".
void keep_freed_memory();

// Physical memory in bytes (sysconf), 0 when unknown.
uint64_t physical_memory();

// The default --max-memory: three quarters of physical memory (16 GiB when unknown).
uint64_t default_memory_limit();

// "512M", "8G", "1.5GiB", "100000" (bytes; K, M, G, T are powers of 1024,
// with or without "iB"); nullopt when malformed or not positive.
std::optional<uint64_t> parse_bytes(std::string_view text);

// "1.5 GiB", "512 MiB", "900 bytes".
std::string bytes_text(double bytes);

}  // namespace polyvol::cli

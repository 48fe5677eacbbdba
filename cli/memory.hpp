// cli/memory.hpp — how much memory a command may take: the machine's
// physical memory, and byte counts as users write and read them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace polyvol::cli {

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

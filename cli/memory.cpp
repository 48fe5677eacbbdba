// cli/memory.cpp — memory.hpp.
#include "memory.hpp"

#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>

namespace polyvol::cli {

void keep_freed_memory() {
#ifdef __GLIBC__
    ::mallopt(M_MMAP_THRESHOLD, 256 << 20);
    ::mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

uint64_t physical_memory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
    return pages > 0 && page > 0 ? static_cast<uint64_t>(pages) * static_cast<uint64_t>(page) : 0;
}

uint64_t default_memory_limit() {
    const uint64_t p = physical_memory();
    return p > 0 ? p / 4 * 3 : uint64_t{16} << 30;
}

std::optional<uint64_t> parse_bytes(std::string_view text) {
    std::string s(text);
    std::size_t used = 0;
    double v = 0;
    try {
        v = std::stod(s, &used);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    std::string unit = s.substr(used);
    for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (unit.size() == 3 && unit.substr(1) == "IB") unit = unit.substr(0, 1);
    if (unit.size() == 2 && unit[1] == 'B') unit = unit.substr(0, 1);
    double scale = 1;
    if (unit == "K") scale = 0x1p10;
    else if (unit == "M") scale = 0x1p20;
    else if (unit == "G") scale = 0x1p30;
    else if (unit == "T") scale = 0x1p40;
    else if (!unit.empty() && unit != "B") return std::nullopt;
    const double bytes = v * scale;
    if (!(bytes >= 1) || !(bytes < 0x1p63)) return std::nullopt;
    return static_cast<uint64_t>(bytes);
}

std::string bytes_text(double bytes) {
    const char* units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
    int u = 0;
    while (bytes >= 1024 && u < 5) {
        bytes /= 1024;
        ++u;
    }
    char buf[64];
    std::snprintf(buf, sizeof buf, u == 0 ? "%.0f %s" : "%.3g %s", bytes, units[u]);
    return buf;
}

}  // namespace polyvol::cli

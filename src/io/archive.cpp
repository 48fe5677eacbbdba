// Tar archives of meshes, plain or compressed (.tar, .tar.gz, .tgz,
// .tar.bz2, .tbz2).
//
// gzip and bzip2 are gunzip's and bunzip2's (readers.hpp; zlib and libbz2
// natively, web/src/io_in_javascript.cpp in the WebAssembly build). A tar is
// read here: POSIX ustar headers of 512 bytes
// (name at 0, size in octal at 124, checksum at 148, type at 156, name
// prefix at 345), with GNU long names (type 'L') and pax headers (type 'x',
// their "path" record); each member's data follows its header, padded to
// 512. (libarchive reads them too, but it loads libxml2, ICU and nettle at
// every start of the command, for every file: docs/benchmarks.md.)
// Every header's checksum is verified and every size is checked against the
// bytes present; decompressed bytes count against the caller's limit.
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/readers.hpp"
#include "polyvol/io.hpp"

namespace polyvol::io {
namespace {

bool starts_with(Bytes data, std::string_view magic) {
    return data.size() >= magic.size() && std::memcmp(data.data(), magic.data(), magic.size()) == 0;
}

std::string_view field(Bytes block, std::size_t at, std::size_t len) {
    const char* p = reinterpret_cast<const char*>(block.data()) + at;
    return {p, static_cast<std::size_t>(std::find(p, p + len, '\0') - p)};
}

// A numeric header field: octal digits (blanks around), or base-256 when the
// first byte has its high bit set (GNU, for sizes of 8 GiB and more).
std::optional<uint64_t> number(Bytes block, std::size_t at, std::size_t len) {
    const auto* b = reinterpret_cast<const unsigned char*>(block.data()) + at;
    uint64_t v = 0;
    if (b[0] & 0x80) {
        for (std::size_t i = 1; i < len; ++i) {
            if (v >> 55) return std::nullopt;
            v = v << 8 | b[i];
        }
        return (b[0] & 0x7F) == 0 ? std::optional(v) : std::nullopt;
    }
    std::size_t i = 0;
    while (i < len && b[i] == ' ') ++i;
    bool digits = false;
    for (; i < len && b[i] >= '0' && b[i] <= '7'; ++i, digits = true) {
        if (v >> 60) return std::nullopt;
        v = v * 8 + (b[i] - '0');
    }
    for (; i < len; ++i)
        if (b[i] != ' ' && b[i] != '\0') return std::nullopt;
    return digits ? std::optional(v) : std::nullopt;
}

// The header's checksum: the sum of its bytes with the checksum field as blanks.
bool checksum_ok(Bytes block) {
    const std::optional<uint64_t> want = number(block, 148, 8);
    uint64_t sum = 0;
    for (std::size_t i = 0; i < 512; ++i)
        sum += i >= 148 && i < 156 ? ' ' : static_cast<unsigned char>(block[i]);
    return want && *want == sum;
}

struct TarEntry {
    std::string path;
    std::size_t offset = 0, size = 0;  // the data
};

// The regular files of a tar, in order. Throws ReadError on a bad header or
// data past the end.
std::vector<TarEntry> tar_entries(Bytes data, const std::string& name) {
    std::vector<TarEntry> entries;
    std::string long_name;  // from a GNU 'L' or a pax 'x' header, for the next entry
    for (std::size_t at = 0; at + 512 <= data.size();) {
        const Bytes h = data.subspan(at, 512);
        if (std::all_of(h.begin(), h.end(), [](std::byte b) { return b == std::byte{0}; })) break;  // the end
        if (!checksum_ok(h)) throw ReadError::at_byte(name, at, "tar: a header's checksum does not match");
        const std::optional<uint64_t> size = number(h, 124, 12);
        if (!size) throw ReadError::at_byte(name, at + 124, "tar: a header's size is not a number");
        if (*size > data.size() - at - 512)
            throw ReadError::at_byte(name, at, "tar: a member of " + std::to_string(*size) + " bytes runs past the end");
        const auto type = static_cast<char>(h[156]);
        const std::size_t begin = at + 512;
        const std::string_view content(reinterpret_cast<const char*>(data.data()) + begin, *size);
        if (type == 'L') {
            long_name.assign(content.substr(0, content.find('\0')));
        } else if (type == 'x') {  // pax: records "LEN key=value\n"
            for (std::size_t p = 0; p < content.size();) {
                const std::size_t space = content.find(' ', p);
                if (space == std::string_view::npos) break;
                const std::size_t len = static_cast<std::size_t>(std::strtoull(std::string(content.substr(p, space - p)).c_str(), nullptr, 10));
                // a record holds at least its length, a blank and a newline, and no more than what is left
                if (len > content.size() - p || len < space - p + 2) break;
                const std::string_view record = content.substr(space + 1, p + len - space - 2);  // without "\n"
                if (record.substr(0, 5) == "path=") long_name.assign(record.substr(5));
                p += len;
            }
        } else {
            if (type == '0' || type == '\0') {
                std::string path = long_name;
                if (path.empty()) {
                    // POSIX ustar ("ustar\0") has the name prefix at 345; GNU's "ustar  " has times there
                    const std::string_view prefix =
                        starts_with(h.subspan(257), std::string_view("ustar\0", 6)) ? field(h, 345, 155) : "";
                    path = (prefix.empty() ? "" : std::string(prefix) + "/") + std::string(field(h, 0, 100));
                }
                entries.push_back({std::move(path), begin, static_cast<std::size_t>(*size)});
            }
            long_name.clear();
        }
        at = begin + (static_cast<std::size_t>(*size) + 511) / 512 * 512;
    }
    return entries;
}

// The data made plain: a tar as it is, or after gunzip or bunzip2.
std::vector<std::byte> plain(Bytes data, const std::string& name, uint64_t limit) {
    if (is_gzip(data)) return gunzip(data, name, limit);
    if (is_bzip2(data)) return bunzip2(data, name, limit);
    return {data.begin(), data.end()};
}

}  // namespace

bool is_bzip2(Bytes head) {
    return starts_with(head, "BZh") && head.size() > 3 && head[3] >= std::byte{'1'} && head[3] <= std::byte{'9'};
}
bool is_tar(Bytes data) { return data.size() >= 512 && starts_with(data.subspan(257), "ustar") && checksum_ok(data.first(512)); }

std::vector<std::string> tar_members(Bytes data, const std::string& name) {
    try {
        const std::vector<std::byte> tar = plain(data, name, decompression_limit(data.size()));
        if (!is_tar(tar)) return {};
        std::vector<std::string> meshes;
        for (const TarEntry& e : tar_entries(tar, name))
            if (format_from_extension(e.path) != Format::unknown) meshes.push_back(e.path);
        return meshes;
    } catch (const ReadError&) {
        return {};  // not a readable tar: read_mesh_file says why
    }
}

std::vector<std::byte> tar_member(Bytes data, const std::string& name, const std::string& member, uint64_t limit) {
    const std::vector<std::byte> tar = plain(data, name, limit);
    if (!is_tar(tar)) throw ReadError::whole_file(name, "not a tar archive");
    for (const TarEntry& e : tar_entries(tar, name))
        if (e.path == member) return {tar.begin() + static_cast<std::ptrdiff_t>(e.offset),
                                      tar.begin() + static_cast<std::ptrdiff_t>(e.offset + e.size)};
    throw ReadError::whole_file(name, "the archive has no member " + member);
}

}  // namespace polyvol::io

// A small read-only wrapper over minizip (zlib's contrib/minizip) for archives
// held in memory (3MF packages, zipped AMF). Every error is a polyvol::ReadError
// naming the file. minizip rather than libzip: it needs only zlib, where libzip
// loads libcrypto, libbz2 and liblzma into every process that links polyvol.
// minizip reads stored and deflate entries only, which is what 3MF and AMF
// writers produce; other compression methods and encrypted entries are errors.
//
// Decompression is bounded: the bytes read from an archive, summed over all
// entries read through one ZipArchive, may not exceed max_total_bytes()
// (by default min(4 GiB, max(64 x the archive size, 16 MiB))). Sizes the
// archive claims are checked against that bound before anything is allocated
// and are never trusted beyond it.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "io/readers.hpp"

namespace polyvol::io {

// An entry's uncompressed and compressed sizes and its local header's offset,
// as its ZIP64 extra field gives them.
struct Zip64Sizes {
    uint64_t size = 0, compressed = 0, offset = 0;
};

// The name an entry is matched by when not exactly (OPC part names are
// case-insensitive): '\\' as '/', ASCII letters in lower case, leading '/'
// dropped.
inline std::string zip_entry_key(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (char c : s) {
        if (c == '\\') c = '/';
        if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
        out += c;
    }
    const auto first = out.find_first_not_of('/');
    return first == std::string::npos ? std::string() : out.substr(first);
}

// The stored name an entry asked for is found under: `entry` itself when the
// archive holds it (held_exactly), else the file entry whose zip_entry_key
// is entry's.
inline std::optional<std::string> match_entry(std::string_view entry, bool held_exactly,
                                              const std::vector<std::string>& file_names) {
    if (held_exactly) return std::string(entry);
    const std::string want = zip_entry_key(entry);
    if (want.empty()) return std::nullopt;
    for (const std::string& n : file_names)
        if (zip_entry_key(n) == want) return n;
    return std::nullopt;
}

class ZipArchive {
public:
    // Opens the archive in data (which must outlive this object). Throws
    // ReadError::whole_file when data is not a readable zip archive.
    // max_total_bytes == 0 selects default_limit(data.size()).
    ZipArchive(Bytes data, std::string name, uint64_t max_total_bytes = 0);
    ~ZipArchive();
    ZipArchive(const ZipArchive&) = delete;
    ZipArchive& operator=(const ZipArchive&) = delete;

    // decompression_limit(archive_bytes) (readers.hpp).
    static uint64_t default_limit(std::size_t archive_bytes);
    uint64_t max_total_bytes() const { return limit_; }

    // Names of the file entries (directory entries left out), in archive order.
    // Names are decoded as libzip did: the Info-ZIP Unicode Path extra field
    // when it matches, else the stored bytes, converted from CP437 to UTF-8 when
    // they are not flagged UTF-8 and do not look like UTF-8.
    std::vector<std::string> file_names() const;

    // The stored name of the entry called `entry`: exact match first, then
    // ignoring ASCII case, a leading '/' and '\\' vs '/' (OPC part names are
    // case-insensitive). nullopt when there is none.
    std::optional<std::string> find(std::string_view entry) const;

    // The whole content of an entry (a stored name, e.g. from find()). Throws
    // ReadError when it is missing, encrypted, compressed with an unsupported
    // method, corrupt (CRC), or would exceed the decompression limit.
    std::vector<std::byte> read(const std::string& entry);

private:
    struct Impl;  // the minizip handle (unzFile), its in-memory stream and the entry index
    std::vector<std::byte> read_zip64_entry(const std::string& entry, const Zip64Sizes& sizes, uint64_t method,
                                            uint64_t crc);
    std::unique_ptr<Impl> impl_;
    std::string name_;
    uint64_t limit_ = 0;
    uint64_t used_ = 0;  // bytes decompressed so far
};

}  // namespace polyvol::io

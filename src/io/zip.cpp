#include "io/zip.hpp"

#include <unzip.h>
#include <zlib.h>

#include <algorithm>
#include <cstring>
#include <optional>
#include <unordered_map>
#include <utility>

namespace polyvol::io {

namespace {

std::string bytes_text(uint64_t bytes) {
    return std::to_string(bytes) + " bytes";
}

// ---- Entry names, decoded as libzip 1.7 decoded them (zip_get_name, flags 0),
// so that find() and the messages see the same names as before.

// CP437 (the zip format's default code page) to Unicode, libzip's table (as
// in Debian's libzip 1.7.3, which maps 0x00 to a space).
constexpr uint16_t kCp437[256] = {
    0x0020, 0x263A, 0x263B, 0x2665, 0x2666, 0x2663, 0x2660, 0x2022, 0x25D8, 0x25CB, 0x25D9, 0x2642, 0x2640,
    0x266A, 0x266B, 0x263C, 0x25BA, 0x25C4, 0x2195, 0x203C, 0x00B6, 0x00A7, 0x25AC, 0x21A8, 0x2191, 0x2193,
    0x2192, 0x2190, 0x221F, 0x2194, 0x25B2, 0x25BC, 0x0020, 0x0021, 0x0022, 0x0023, 0x0024, 0x0025, 0x0026,
    0x0027, 0x0028, 0x0029, 0x002A, 0x002B, 0x002C, 0x002D, 0x002E, 0x002F, 0x0030, 0x0031, 0x0032, 0x0033,
    0x0034, 0x0035, 0x0036, 0x0037, 0x0038, 0x0039, 0x003A, 0x003B, 0x003C, 0x003D, 0x003E, 0x003F, 0x0040,
    0x0041, 0x0042, 0x0043, 0x0044, 0x0045, 0x0046, 0x0047, 0x0048, 0x0049, 0x004A, 0x004B, 0x004C, 0x004D,
    0x004E, 0x004F, 0x0050, 0x0051, 0x0052, 0x0053, 0x0054, 0x0055, 0x0056, 0x0057, 0x0058, 0x0059, 0x005A,
    0x005B, 0x005C, 0x005D, 0x005E, 0x005F, 0x0060, 0x0061, 0x0062, 0x0063, 0x0064, 0x0065, 0x0066, 0x0067,
    0x0068, 0x0069, 0x006A, 0x006B, 0x006C, 0x006D, 0x006E, 0x006F, 0x0070, 0x0071, 0x0072, 0x0073, 0x0074,
    0x0075, 0x0076, 0x0077, 0x0078, 0x0079, 0x007A, 0x007B, 0x007C, 0x007D, 0x007E, 0x2302, 0x00C7, 0x00FC,
    0x00E9, 0x00E2, 0x00E4, 0x00E0, 0x00E5, 0x00E7, 0x00EA, 0x00EB, 0x00E8, 0x00EF, 0x00EE, 0x00EC, 0x00C4,
    0x00C5, 0x00C9, 0x00E6, 0x00C6, 0x00F4, 0x00F6, 0x00F2, 0x00FB, 0x00F9, 0x00FF, 0x00D6, 0x00DC, 0x00A2,
    0x00A3, 0x00A5, 0x20A7, 0x0192, 0x00E1, 0x00ED, 0x00F3, 0x00FA, 0x00F1, 0x00D1, 0x00AA, 0x00BA, 0x00BF,
    0x2310, 0x00AC, 0x00BD, 0x00BC, 0x00A1, 0x00AB, 0x00BB, 0x2591, 0x2592, 0x2593, 0x2502, 0x2524, 0x2561,
    0x2562, 0x2556, 0x2555, 0x2563, 0x2551, 0x2557, 0x255D, 0x255C, 0x255B, 0x2510, 0x2514, 0x2534, 0x252C,
    0x251C, 0x2500, 0x253C, 0x255E, 0x255F, 0x255A, 0x2554, 0x2569, 0x2566, 0x2560, 0x2550, 0x256C, 0x2567,
    0x2568, 0x2564, 0x2565, 0x2559, 0x2558, 0x2552, 0x2553, 0x256B, 0x256A, 0x2518, 0x250C, 0x2588, 0x2584,
    0x258C, 0x2590, 0x2580, 0x03B1, 0x00DF, 0x0393, 0x03C0, 0x03A3, 0x03C3, 0x00B5, 0x03C4, 0x03A6, 0x0398,
    0x03A9, 0x03B4, 0x221E, 0x03C6, 0x03B5, 0x2229, 0x2261, 0x00B1, 0x2265, 0x2264, 0x2320, 0x2321, 0x00F7,
    0x2248, 0x00B0, 0x2219, 0x00B7, 0x221A, 0x207F, 0x00B2, 0x25A0, 0x00A0};

// libzip's guess: plain when every byte is printable ASCII, tab, CR or LF, or
// the other bytes form UTF-8 sequences (lead and continuation bytes); CP437
// otherwise.
bool looks_cp437(std::string_view s) {
    const auto* p = reinterpret_cast<const unsigned char*>(s.data());
    const std::size_t n = s.size();
    for (std::size_t i = 0; i < n; ++i) {
        const unsigned c = p[i];
        if ((c > 31 && c < 128) || c == '\r' || c == '\n' || c == '\t') continue;
        std::size_t follow = 0;
        if ((c & 0xE0) == 0xC0)
            follow = 1;
        else if ((c & 0xF0) == 0xE0)
            follow = 2;
        else if ((c & 0xF8) == 0xF0)
            follow = 3;
        else
            return true;
        if (i + follow >= n) return true;
        for (std::size_t j = 1; j <= follow; ++j)
            if ((p[i + j] & 0xC0) != 0x80) return true;
        i += follow;
    }
    return false;
}

std::string cp437_to_utf8(std::string_view s) {
    std::string out;
    out.reserve(s.size() * 3);
    for (const char ch : s) {
        const unsigned cp = kCp437[static_cast<unsigned char>(ch)];
        if (cp < 0x80) {
            out += static_cast<char>(cp);
        } else if (cp < 0x800) {
            out += static_cast<char>(0xC0 | (cp >> 6));
            out += static_cast<char>(0x80 | (cp & 0x3F));
        } else {
            out += static_cast<char>(0xE0 | (cp >> 12));
            out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
            out += static_cast<char>(0x80 | (cp & 0x3F));
        }
    }
    return out;
}

// The Info-ZIP Unicode Path extra field (0x7075, version 1): a UTF-8 name that
// replaces the stored one when the CRC-32 it carries is that of the stored name.
std::optional<std::string> unicode_path(std::string_view raw, std::string_view extra) {
    const auto* p = reinterpret_cast<const unsigned char*>(extra.data());
    std::size_t i = 0;
    while (i + 4 <= extra.size()) {
        const unsigned id = p[i] | (p[i + 1] << 8);
        const std::size_t len = p[i + 2] | (p[i + 3] << 8);
        if (len > extra.size() - i - 4) break;
        if (id == 0x7075) {
            const unsigned char* d = p + i + 4;
            if (len <= 5 || d[0] != 1) return std::nullopt;
            const uint32_t want = uint32_t{d[1]} | (uint32_t{d[2]} << 8) | (uint32_t{d[3]} << 16) |
                                  (uint32_t{d[4]} << 24);
            const uLong crc =
                crc32(0L, reinterpret_cast<const Bytef*>(raw.data()), static_cast<uInt>(raw.size()));
            if (crc != want) return std::nullopt;
            const std::string_view name(reinterpret_cast<const char*>(d + 5), len - 5);
            if (looks_cp437(name)) return std::nullopt;
            return std::string(name);
        }
        i += 4 + len;
    }
    return std::nullopt;
}

std::string decoded_name(const std::string& raw, uint64_t flags, std::string_view extra) {
    if (auto u = unicode_path(raw, extra)) return std::move(*u);
    constexpr uint64_t utf8_flag = uint64_t{1} << 11;  // general purpose bit 11: UTF-8 name
    if ((flags & utf8_flag) == 0 && looks_cp437(raw)) return cp437_to_utf8(raw);
    return raw;
}

// ---- minizip reads the archive through these callbacks, from memory.

struct MemoryStream {
    Bytes data;
    uint64_t pos = 0;
};

voidpf ZCALLBACK mem_open(voidpf opaque, const void* /*filename*/, int mode) {
    if ((mode & ZLIB_FILEFUNC_MODE_WRITE) != 0) return nullptr;
    auto* s = static_cast<MemoryStream*>(opaque);
    s->pos = 0;
    return s;
}

uLong ZCALLBACK mem_read(voidpf /*opaque*/, voidpf stream, void* buf, uLong size) {
    auto* s = static_cast<MemoryStream*>(stream);
    const uint64_t n = std::min<uint64_t>(size, s->data.size() - s->pos);
    if (n > 0) std::memcpy(buf, s->data.data() + s->pos, static_cast<std::size_t>(n));
    s->pos += n;
    return static_cast<uLong>(n);
}

uLong ZCALLBACK mem_write(voidpf /*opaque*/, voidpf /*stream*/, const void* /*buf*/, uLong /*size*/) {
    return 0;
}

ZPOS64_T ZCALLBACK mem_tell(voidpf /*opaque*/, voidpf stream) {
    return static_cast<MemoryStream*>(stream)->pos;
}

long ZCALLBACK mem_seek(voidpf /*opaque*/, voidpf stream, ZPOS64_T offset, int origin) {
    auto* s = static_cast<MemoryStream*>(stream);
    const uint64_t size = s->data.size();
    uint64_t base = 0;
    switch (origin) {
        case ZLIB_FILEFUNC_SEEK_SET: base = 0; break;
        case ZLIB_FILEFUNC_SEEK_CUR: base = s->pos; break;
        case ZLIB_FILEFUNC_SEEK_END: base = size; break;
        default: return -1;
    }
    // minizip seeks backwards with SEEK_CUR and an offset that wrapped around
    // (lSeek -= size_file_extra): the sum modulo 2^64 is the signed sum.
    const uint64_t target = base + offset;
    if (target > size) return -1;  // nothing lies beyond the buffer
    s->pos = target;
    return 0;
}

int ZCALLBACK mem_close(voidpf /*opaque*/, voidpf /*stream*/) { return 0; }
int ZCALLBACK mem_error(voidpf /*opaque*/, voidpf /*stream*/) { return 0; }

// What a minizip (or zlib) error code returned while opening or reading an
// entry means.
std::string unz_error_text(int rc) {
    switch (rc) {
        case UNZ_ERRNO: return "the entry's data runs past the end of the archive (truncated or corrupt)";
        case UNZ_BADZIPFILE: return "its local header is missing or does not match the central directory";
        case Z_DATA_ERROR: return "corrupt deflate data";
        case Z_BUF_ERROR: return "the deflate data ends early (truncated or corrupt)";
        case Z_MEM_ERROR:
        case UNZ_INTERNALERROR: return "out of memory";
        default: return "minizip error " + std::to_string(rc);
    }
}

std::string method_text(uint64_t method) {
    std::string text = "compression method " + std::to_string(method);
    const char* known = nullptr;
    switch (method) {
        case 1: known = "Shrink"; break;
        case 2: case 3: case 4: case 5: known = "Reduce"; break;
        case 6: known = "Implode"; break;
        case 9: known = "Deflate64"; break;
        case 10: known = "PKWARE DCL Implode"; break;
        case 12: known = "bzip2"; break;
        case 14: known = "LZMA"; break;
        case 93: known = "Zstandard"; break;
        case 95: known = "XZ"; break;
        case 98: known = "PPMd"; break;
        case 99: known = "WinZip AES"; break;
        default: break;
    }
    if (known != nullptr) text += std::string(" (") + known + ")";
    return text;
}

uint64_t little_endian(Bytes data, uint64_t at, int bytes) {
    uint64_t v = 0;
    for (int i = bytes - 1; i >= 0; --i) v = (v << 8) | std::to_integer<uint64_t>(data[at + static_cast<uint64_t>(i)]);
    return v;
}

// The sizes and local header offset of the central directory record at
// `at`, from its ZIP64 extended information (extra field 0x0001) where the
// 32-bit fields hold 0xFFFFFFFF. (Debian's minizip 1.1 does not read it, and
// then takes 0xFFFFFFFF for the sizes.) nullopt when no field is 0xFFFFFFFF,
// or the record is not where it should be.
std::optional<Zip64Sizes> zip64_sizes(Bytes data, uint64_t at) {
    constexpr uint64_t kMax = 0xFFFFFFFF;
    if (at > data.size() || data.size() - at < 46 || little_endian(data, at, 4) != 0x02014b50) return std::nullopt;
    Zip64Sizes z{little_endian(data, at + 24, 4), little_endian(data, at + 20, 4), little_endian(data, at + 42, 4)};
    if (z.size != kMax && z.compressed != kMax && z.offset != kMax) return std::nullopt;
    const uint64_t name_length = little_endian(data, at + 28, 2), extra_length = little_endian(data, at + 30, 2);
    uint64_t p = at + 46 + name_length;
    const uint64_t end = p + extra_length;
    if (end > data.size()) return std::nullopt;
    while (p + 4 <= end) {
        const uint64_t id = little_endian(data, p, 2), length = little_endian(data, p + 2, 2);
        p += 4;
        if (length > end - p) return std::nullopt;
        if (id == 0x0001) {
            uint64_t q = p;
            auto take = [&](uint64_t& field) {
                if (field != kMax) return true;
                if (q + 8 > p + length) return false;
                field = little_endian(data, q, 8);
                q += 8;
                return true;
            };
            if (!take(z.size) || !take(z.compressed) || !take(z.offset)) return std::nullopt;
            return z;
        }
        p += length;
    }
    return std::nullopt;  // 0xFFFFFFFF without the field: minizip's reading stands (and the limits judge it)
}

// Closes the entry minizip has open, also when reading it throws.
class OpenEntry {
public:
    explicit OpenEntry(unzFile f) : f_(f) {}
    ~OpenEntry() {
        if (f_ != nullptr) unzCloseCurrentFile(f_);
    }
    OpenEntry(const OpenEntry&) = delete;
    OpenEntry& operator=(const OpenEntry&) = delete;
    // UNZ_CRCERROR when the whole entry was read and its CRC-32 does not match.
    int close() {
        const int rc = unzCloseCurrentFile(f_);
        f_ = nullptr;
        return rc;
    }

private:
    unzFile f_;
};

}  // namespace

struct ZipArchive::Impl {
    struct Entry {
        std::string name;
        unz64_file_pos pos{};  // where minizip finds it in the central directory
        std::optional<Zip64Sizes> zip64;  // read here, not by minizip
    };

    MemoryStream stream;
    unzFile uf = nullptr;
    std::vector<Entry> entries;                             // archive order
    std::unordered_map<std::string, std::size_t> by_name;  // the first entry of each name

    Impl() = default;
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    ~Impl() {
        if (uf != nullptr) unzClose(uf);
    }
};

uint64_t ZipArchive::default_limit(std::size_t archive_bytes) { return decompression_limit(archive_bytes); }

ZipArchive::ZipArchive(Bytes data, std::string name, uint64_t max_total_bytes)
    : impl_(std::make_unique<Impl>()),
      name_(std::move(name)),
      limit_(max_total_bytes ? max_total_bytes : default_limit(data.size())) {
    Impl& z = *impl_;
    z.stream.data = data;
    zlib_filefunc64_def io{};
    io.zopen64_file = mem_open;
    io.zread_file = mem_read;
    io.zwrite_file = mem_write;
    io.ztell64_file = mem_tell;
    io.zseek64_file = mem_seek;
    io.zclose_file = mem_close;
    io.zerror_file = mem_error;
    io.opaque = &z.stream;
    if (data.empty()) return;  // an empty archive, as libzip read it (minizip finds no directory)
    z.uf = unzOpen2_64(name_.c_str(), &io);
    if (z.uf == nullptr)
        throw ReadError::whole_file(name_, "not a readable zip archive: no end of central directory record, "
                                           "or one that does not match the file");

    const auto corrupt = [&](std::size_t index) {
        return ReadError::whole_file(name_, "not a readable zip archive: its central directory is corrupt "
                                            "(entry " + std::to_string(index + 1) + ")");
    };
    unz_global_info64 global{};
    if (unzGetGlobalInfo64(z.uf, &global) != UNZ_OK) throw corrupt(0);
    if (global.number_entry == 0) return;  // unzGoToFirstFile fails on an empty archive
    int rc = unzGoToFirstFile(z.uf);
    while (rc == UNZ_OK) {
        const std::size_t index = z.entries.size();
        unz_file_info64 info{};
        if (unzGetCurrentFileInfo64(z.uf, &info, nullptr, 0, nullptr, 0, nullptr, 0) != UNZ_OK)
            throw corrupt(index);
        std::string raw(info.size_filename, '\0');
        std::string extra(info.size_file_extra, '\0');
        if (unzGetCurrentFileInfo64(z.uf, &info, raw.data(), raw.size(), extra.data(), extra.size(),
                                    nullptr, 0) != UNZ_OK)
            throw corrupt(index);
        Impl::Entry e;
        e.name = decoded_name(raw, info.flag, extra);
        if (unzGetFilePos64(z.uf, &e.pos) != UNZ_OK) throw corrupt(index);
        e.zip64 = zip64_sizes(data, e.pos.pos_in_zip_directory);
        z.by_name.emplace(e.name, index);
        z.entries.push_back(std::move(e));
        rc = unzGoToNextFile(z.uf);
    }
    // minizip cannot tell the end of the list from a broken record when the
    // count is 0xffff (a zip64 placeholder); the count read decides then.
    if (rc != UNZ_END_OF_LIST_OF_FILE && z.entries.size() != global.number_entry)
        throw corrupt(z.entries.size());
}

ZipArchive::~ZipArchive() = default;

std::vector<std::string> ZipArchive::file_names() const {
    std::vector<std::string> names;
    for (const Impl::Entry& e : impl_->entries) {
        if (e.name.empty() || e.name.back() == '/') continue;  // directory entry
        names.push_back(e.name);
    }
    return names;
}

std::optional<std::string> ZipArchive::find(std::string_view entry) const {
    const bool held = impl_->by_name.count(std::string(entry)) != 0;
    return match_entry(entry, held, held ? std::vector<std::string>{} : file_names());
}

std::vector<std::byte> ZipArchive::read(const std::string& entry) {
    Impl& z = *impl_;
    const auto found = z.by_name.find(entry);
    if (found == z.by_name.end()) throw ReadError::whole_file(name_, "zip entry '" + entry + "' is missing");
    const uint64_t budget = limit_ - std::min(used_, limit_);
    const std::string limit_text = decompression_limit_words(limit_);

    unz_file_info64 info{};
    if (unzGoToFilePos64(z.uf, &z.entries[found->second].pos) != UNZ_OK ||
        unzGetCurrentFileInfo64(z.uf, &info, nullptr, 0, nullptr, 0, nullptr, 0) != UNZ_OK)
        throw ReadError::whole_file(name_, "cannot open zip entry '" + entry +
                                               "': its central directory record is unreadable");
    if ((info.flag & 1) != 0)
        throw ReadError::whole_file(name_, "zip entry '" + entry +
                                               "' is encrypted; encrypted entries are not supported");
    if (info.compression_method != 0 && info.compression_method != Z_DEFLATED)
        throw ReadError::whole_file(name_, "zip entry '" + entry + "' uses " +
                                               method_text(info.compression_method) +
                                               ", which is not supported: only stored (0) and deflate (8) "
                                               "entries can be read (minizip)");
    // minizip never returns more than the claimed size; the claim is checked
    // against the budget before anything is allocated for it.
    const Impl::Entry& e = z.entries[found->second];
    const uint64_t claimed = e.zip64 ? e.zip64->size : info.uncompressed_size;
    if (claimed > budget)
        throw ReadError::whole_file(
            name_, "zip entry '" + entry + "' claims " + bytes_text(claimed) + " uncompressed, more than " +
                       limit_text + "; refusing to decompress it");

    if (e.zip64) {
        std::vector<std::byte> out = read_zip64_entry(entry, *e.zip64, info.compression_method, info.crc);
        used_ += out.size();
        return out;
    }
    if (const int rc = unzOpenCurrentFile(z.uf); rc != UNZ_OK)
        throw ReadError::whole_file(name_, "cannot open zip entry '" + entry + "': " + unz_error_text(rc));
    OpenEntry open(z.uf);
    std::vector<std::byte> out;
    out.reserve(static_cast<std::size_t>(claimed));
    constexpr unsigned chunk = 1u << 16;
    std::vector<std::byte> buf(chunk);
    for (;;) {
        const int got = unzReadCurrentFile(z.uf, buf.data(), chunk);
        if (got < 0)
            throw ReadError::whole_file(name_, "cannot decompress zip entry '" + entry + "': " +
                                                   unz_error_text(got));
        if (got == 0) break;
        const auto n = static_cast<std::size_t>(got);
        if (n > budget - out.size())
            throw ReadError::whole_file(name_, "zip entry '" + entry + "' decompresses to more than " +
                                                   limit_text + "; refusing to read it (zip bomb?)");
        out.insert(out.end(), buf.begin(), buf.begin() + got);
    }
    const int rc = open.close();
    if (rc == UNZ_CRCERROR)
        throw ReadError::whole_file(name_, "cannot decompress zip entry '" + entry +
                                               "': CRC mismatch (the data is corrupt)");
    if (rc != UNZ_OK)
        throw ReadError::whole_file(name_, "cannot decompress zip entry '" + entry + "': " +
                                               unz_error_text(rc));
    // minizip checks the CRC only when it got the claimed size: a shorter
    // stream ends early without one.
    if (out.size() != claimed)
        throw ReadError::whole_file(name_, "cannot decompress zip entry '" + entry + "': it holds " +
                                               bytes_text(out.size()) + " where its header says " +
                                               bytes_text(claimed) + " (the data is corrupt)");
    used_ += out.size();
    return out;
}

// A ZIP64 entry, from the archive in memory: its local header at the
// offset the central directory gives, then `compressed` bytes, stored or raw
// deflate, which must give exactly `size` bytes with the CRC-32 `crc`.
std::vector<std::byte> ZipArchive::read_zip64_entry(const std::string& entry, const Zip64Sizes& z, uint64_t method,
                                                     uint64_t crc) {
    const Bytes data = impl_->stream.data;
    auto corrupt = [&](const std::string& why) {
        return ReadError::whole_file(name_, "cannot read zip entry '" + entry + "': " + why);
    };
    if (z.offset > data.size() || data.size() - z.offset < 30 || little_endian(data, z.offset, 4) != 0x04034b50)
        throw corrupt("no local header at offset " + std::to_string(z.offset));
    const uint64_t start = z.offset + 30 + little_endian(data, z.offset + 26, 2) + little_endian(data, z.offset + 28, 2);
    if (start > data.size() || data.size() - start < z.compressed)
        throw corrupt("its " + bytes_text(z.compressed) + " of data run past the end of the archive");
    const auto* in = reinterpret_cast<const Bytef*>(data.data() + start);
    std::vector<std::byte> out;
    if (method == 0) {
        if (z.compressed != z.size) throw corrupt("a stored entry whose sizes differ");
        out.assign(data.begin() + static_cast<std::ptrdiff_t>(start),
                   data.begin() + static_cast<std::ptrdiff_t>(start + z.size));
    } else {
        // Output grows as it arrives (never more than the claimed size): a
        // claim alone commits no memory.
        z_stream zs{};
        if (inflateInit2(&zs, -MAX_WBITS) != Z_OK) throw corrupt("zlib cannot start");
        constexpr std::size_t kChunk = std::size_t{1} << 16;
        std::vector<std::byte> chunk(kChunk);
        uint64_t read = 0, written = 0;
        int rc = Z_OK;
        while (rc == Z_OK) {
            constexpr uint64_t kStep = uint64_t{1} << 30;
            zs.next_in = const_cast<Bytef*>(in + read);
            zs.avail_in = static_cast<uInt>(std::min(kStep, z.compressed - read));
            zs.next_out = reinterpret_cast<Bytef*>(chunk.data());
            zs.avail_out = static_cast<uInt>(kChunk);
            const uInt in_before = zs.avail_in;
            rc = inflate(&zs, Z_NO_FLUSH);
            read += in_before - zs.avail_in;
            const std::size_t got = kChunk - zs.avail_out;
            if (got > z.size - written) {
                rc = Z_DATA_ERROR;  // more than the header says
                break;
            }
            out.insert(out.end(), chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(got));
            written += got;
            if (rc == Z_OK && in_before == zs.avail_in && got == 0) rc = Z_BUF_ERROR;
        }
        inflateEnd(&zs);
        if (rc != Z_STREAM_END || written != z.size)
            throw corrupt(rc == Z_STREAM_END ? "it holds " + bytes_text(written) + " where its header says " +
                                                   bytes_text(z.size) + " (the data is corrupt)"
                                             : "its deflate data is corrupt or longer than its header says");
    }
    uLong c = crc32(0L, Z_NULL, 0);
    for (uint64_t done = 0; done < out.size();) {
        const auto n = static_cast<uInt>(std::min<uint64_t>(out.size() - done, uint64_t{1} << 30));
        c = crc32(c, reinterpret_cast<const Bytef*>(out.data() + done), n);
        done += n;
    }
    if (c != crc) throw corrupt("CRC mismatch (the data is corrupt)");
    return out;
}

}  // namespace polyvol::io

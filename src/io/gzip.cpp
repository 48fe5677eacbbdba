// gzip decompression with zlib's inflate, in streaming chunks.
//
// The output grows with the data actually produced (never from the size a
// gzip trailer claims). Concatenated gzip members are read one after the
// other, as gunzip does; bytes after the last member that are not another
// member are ignored. The output stops at a limit (a gzip bomb: a few KB
// that expand to gigabytes) with a ReadError, never at the end of memory.
#include <zlib.h>

#include <algorithm>
#include <climits>
#include <string>
#include <vector>

#include "io/readers.hpp"

namespace polyvol::io {

namespace {

struct Inflater {
    z_stream zs{};
    bool ok = false;
    Inflater() { ok = inflateInit2(&zs, 15 + 16) == Z_OK; }  // 15: max window, +16: gzip wrapper
    ~Inflater() {
        if (ok) inflateEnd(&zs);
    }
    Inflater(const Inflater&) = delete;
    Inflater& operator=(const Inflater&) = delete;
};

}  // namespace

std::vector<std::byte> gunzip(Bytes data, const std::string& name, uint64_t max_bytes) {
    Inflater inf;
    if (!inf.ok) throw ReadError::whole_file(name, "cannot initialise zlib");
    z_stream& zs = inf.zs;

    constexpr std::size_t chunk = std::size_t{1} << 16;
    std::vector<std::byte> out;
    std::size_t produced = 0;
    std::size_t in_pos = 0;  // input bytes handed to zlib so far
    const auto* in = reinterpret_cast<const Bytef*>(data.data());

    for (;;) {
        if (zs.avail_in == 0 && in_pos < data.size()) {
            const std::size_t n = std::min<std::size_t>(data.size() - in_pos, UINT_MAX);
            zs.next_in = const_cast<Bytef*>(in + in_pos);  // zlib's API is not const-correct
            zs.avail_in = static_cast<uInt>(n);
            in_pos += n;
        }
        if (out.size() - produced < chunk) {
            if (produced >= max_bytes)
                throw ReadError::whole_file(name, "gzip data expands beyond " + decompression_limit_words(max_bytes) +
                                                      ": refusing to decompress it (a gzip bomb?)");
            const uint64_t room = std::max<uint64_t>(max_bytes - produced, 1);
            out.resize(produced + std::min<uint64_t>(std::max(out.size(), chunk), room));
        }
        zs.next_out = reinterpret_cast<Bytef*>(out.data() + produced);
        zs.avail_out = static_cast<uInt>(std::min<std::size_t>(out.size() - produced, UINT_MAX));
        const uInt before = zs.avail_out;
        const int rc = inflate(&zs, Z_NO_FLUSH);
        produced += before - zs.avail_out;
        const std::size_t consumed = in_pos - zs.avail_in;

        if (rc == Z_STREAM_END) {
            // Another member follows? (magic 1f 8b)
            if (consumed + 2 <= data.size() && in[consumed] == 0x1f && in[consumed + 1] == 0x8b) {
                if (inflateReset(&zs) != Z_OK) throw ReadError::at_byte(name, consumed, "gzip: cannot reset zlib");
                continue;
            }
            break;
        }
        if (rc == Z_OK) continue;
        if (rc == Z_BUF_ERROR) {
            // No progress possible: either output space (handled above by
            // growing) or the input ran out before the stream's end.
            if (zs.avail_in == 0 && in_pos == data.size())
                throw ReadError::at_byte(name, consumed, "truncated gzip data (the compressed stream ends early)");
            continue;
        }
        const char* why = zs.msg != nullptr ? zs.msg : "corrupt data";
        throw ReadError::at_byte(name, consumed, std::string("corrupt gzip data: ") + why);
    }
    out.resize(produced);
    return out;
}

}  // namespace polyvol::io

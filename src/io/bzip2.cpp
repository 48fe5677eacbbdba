// bzip2 streams (a mesh.stl.bz2, a .tar.bz2) with libbz2, in chunks: the
// output grows with the data produced, every stream of a pbzip2 file in
// turn, and stops at the caller's limit (a bomb) with a ReadError.
#include <bzlib.h>

#include <algorithm>
#include <string>
#include <vector>

#include "io/readers.hpp"

namespace polyvol::io {

std::vector<std::byte> bunzip2(Bytes data, const std::string& name, uint64_t limit) {
    const auto too_big = [&] {
        return ReadError::whole_file(name, "bzip2 data expands beyond " + decompression_limit_words(limit) +
                                               ": refusing to decompress it (a bomb?)");
    };
    struct Stream {
        bz_stream bz{};
        bool ok = false;
        Stream() { ok = BZ2_bzDecompressInit(&bz, 0, 0) == BZ_OK; }
        ~Stream() {
            if (ok) BZ2_bzDecompressEnd(&bz);
        }
    };
    std::vector<std::byte> out;
    std::size_t produced = 0, consumed = 0;
    while (consumed < data.size()) {  // one stream after another (pbzip2 writes several)
        Stream s;
        if (!s.ok) throw ReadError::whole_file(name, "cannot initialise libbz2");
        for (;;) {
            if (produced == out.size()) {  // grow, up to one byte past the limit (to see it passed)
                const uint64_t room = limit + 1 - std::min<uint64_t>(limit + 1, produced);
                if (room == 0) throw too_big();
                out.resize(produced + static_cast<std::size_t>(
                                          std::min<uint64_t>(room, std::clamp<std::size_t>(produced, 1 << 16, 64 << 20))));
            }
            const std::size_t in_now = std::min<std::size_t>(data.size() - consumed, 1u << 30);
            const std::size_t out_now = std::min<std::size_t>(out.size() - produced, 1u << 30);
            s.bz.next_in = const_cast<char*>(reinterpret_cast<const char*>(data.data() + consumed));
            s.bz.avail_in = static_cast<unsigned>(in_now);
            s.bz.next_out = reinterpret_cast<char*>(out.data() + produced);
            s.bz.avail_out = static_cast<unsigned>(out_now);
            const int status = BZ2_bzDecompress(&s.bz);
            consumed += in_now - s.bz.avail_in;
            produced += out_now - s.bz.avail_out;
            if (produced > limit) throw too_big();
            if (status == BZ_STREAM_END) break;
            if (status != BZ_OK)
                throw ReadError::at_byte(name, consumed, "corrupt bzip2 data (libbz2 error " + std::to_string(status) + ")");
            if (consumed == data.size() && s.bz.avail_out != 0)
                throw ReadError::at_byte(name, consumed, "truncated bzip2 data (the compressed stream ends early)");
        }
        if (consumed < data.size() && !is_bzip2(data.subspan(consumed))) break;  // trailing bytes are ignored, as gzip's
    }
    out.resize(produced);
    return out;
}

}  // namespace polyvol::io

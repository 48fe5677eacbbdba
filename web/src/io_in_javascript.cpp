// web/src/io_in_javascript.cpp — the WebAssembly build's stand-ins for the
// readers that need zlib, minizip or bzip2 (src/io/gzip.cpp, zip.cpp,
// archive.cpp), which Debian builds for no wasm target. gzip streams and zip
// archives are unpacked in JavaScript by fflate (npm), handed to the module as
// Module.fflate (web/js/node.mjs, browser.mjs), under the native build's
// decompression limits; tar archives are archive.cpp's, as natively. bzip2
// is refused with a ReadError that says so: no bzip2 decoder on npm checks
// its input's bounds and stops at a limit. (pugixml's stand-in, for 3MF and
// AMF: xml_in_javascript.cpp.)
#include <emscripten.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <boost/crc.hpp>
#include <nlohmann/json.hpp>

#include "io/readers.hpp"
#include "io/zip.hpp"

namespace polyvol::io {
namespace {

[[noreturn]] void not_in_this_build(const std::string& name, const std::string& what) {
    throw ReadError::whole_file(name, what + ": not read by polyvol's WebAssembly build");
}

// One call into JavaScript: `what` (0: gunzip, 1: the zip's entry names as a
// JSON array, 2: one zip entry) of data[0, size), at most `limit` bytes out.
// The result is malloc'ed (its size in *out_size), or null with a malloc'ed
// message in *error. A zip entry's CRC-32 and size as its central directory
// record states them go to expected[0..1] (fflate checks neither).
EM_JS(void*, polyvol_js_unpack,
      (int what, const void* data, size_t size, const char* entry, double limit, size_t* out_size, char** error,
       double* expected), {
    // Pointers past 2 GiB arrive negative: read them unsigned.
    data >>>= 0; size >>>= 0; entry >>>= 0; out_size >>>= 0; error >>>= 0; expected >>>= 0;
    const fail = (text) => {
        const n = lengthBytesUTF8(text) + 1;
        const p = _malloc(n) >>> 0;
        if (p) stringToUTF8(text, p, n);
        HEAPU32[error >>> 2] = p;  // 0 when even the message found no memory: "out of memory"
        return 0;
    };
    let out;
    try {
        const fflate = Module['fflate'];
        if (!fflate) return fail('gzip and zip need fflate (web/js/core.mjs passes it to the module)');
        const bytes = HEAPU8.subarray(data, data + size);
        if (what === 0) {
            const parts = [];
            let total = 0;
            const g = new fflate.Gunzip((chunk) => {
                total += chunk.length;
                if (total > limit) throw new Error('limit');
                parts.push(chunk);
            });
            try {
                // In slices: fflate inflates what it is given at once, so the
                // limit is checked every 64 KiB of input, not after a bomb has
                // gone off.
                const slice = 1 << 16;
                for (let at = 0; at < bytes.length || at === 0; at += slice)
                    g.push(bytes.subarray(at, Math.min(bytes.length, at + slice)), at + slice >= bytes.length);
            } catch (e) {
                if (e.message === 'limit') return fail('limit');
                return fail('corrupt gzip data (' + e.message + ')');
            }
            out = new Uint8Array(total);
            let at = 0;
            for (const p of parts) { out.set(p, at); at += p.length; }
        } else if (what === 1) {
            const names = [];
            fflate.unzipSync(bytes, { filter: (f) => { names.push(f.name); return false; } });
            out = new TextEncoder().encode(JSON.stringify(names));
        } else {
            const want = UTF8ToString(entry);
            let claimed = -1, index = -1, seen = 0;
            const files = fflate.unzipSync(bytes, { filter: (f) => {
                if (f.name !== want) return ++seen, false;
                claimed = f.originalSize;
                index = seen++;
                return f.originalSize <= limit;
            } });
            if (claimed > limit) return fail('claims ' + claimed);  // words: ZipArchive::read
            if (!(want in files)) return fail('is missing');
            out = files[want];
            // The record of entry `index`, found as fflate finds the records
            // (the end record, its zip64 locator, then record after record).
            const u16 = (at) => bytes[at] | bytes[at + 1] << 8;
            const u32 = (at) => (u16(at) | u16(at + 2) << 16) >>> 0;
            let e = bytes.length - 22;
            while (u32(e) !== 0x06054b50) --e;
            let at = u32(e + 16);
            if (e >= 20 && u32(e - 20) === 0x07064b50 && u32(u32(e - 12)) === 0x06064b50) at = u32(u32(e - 12) + 48);
            for (let k = 0; k < index; ++k) at += 46 + u16(at + 28) + u16(at + 30) + u16(at + 32);
            HEAPF64[expected >>> 3] = u32(at + 16);
            HEAPF64[(expected >>> 3) + 1] = claimed;
        }
    } catch (e) {
        return fail(String(e && e.message ? e.message : e));
    }
    const p = _malloc(Math.max(out.length, 1)) >>> 0;
    if (!p) return fail('out of memory for ' + out.length + ' bytes');
    HEAPU8.set(out, p);
    HEAPU32[out_size >>> 2] = out.length;
    return p;
});

struct Unpacked {
    std::vector<std::byte> bytes;
    std::string error;  // empty: bytes are the result
    double crc = -1, size = -1;  // a zip entry's, as its record states them
};

Unpacked unpack(int what, Bytes data, const std::string& entry, uint64_t limit) {
    std::size_t size = 0;
    char* error = nullptr;
    double expected[2] = {-1, -1};
    void* p = polyvol_js_unpack(what, data.data(), data.size(), entry.c_str(), static_cast<double>(limit), &size, &error,
                                expected);
    Unpacked u;
    u.crc = expected[0];
    u.size = expected[1];
    if (p == nullptr) {
        u.error = error ? error : "out of memory";
        std::free(error);
        return u;
    }
    const auto* b = static_cast<const std::byte*>(p);
    u.bytes.assign(b, b + size);
    std::free(p);
    return u;
}

}  // namespace

std::vector<std::byte> gunzip(Bytes data, const std::string& name, uint64_t max_bytes) {
    Unpacked u = unpack(0, data, "", max_bytes);
    if (u.error == "limit")
        throw ReadError::whole_file(name, "gzip data expands beyond " + decompression_limit_words(max_bytes) +
                                              ": refusing to decompress it (a gzip bomb?)");
    if (!u.error.empty()) throw ReadError::whole_file(name, u.error);
    return std::move(u.bytes);
}

std::vector<std::byte> bunzip2(Bytes, const std::string& name, uint64_t) { not_in_this_build(name, "bzip2-compressed"); }


// The archive's entry names, listed by fflate; entries read on demand.
struct ZipArchive::Impl {
    Bytes data;
    std::vector<std::string> names;  // archive order, directories too
};

uint64_t ZipArchive::default_limit(std::size_t archive_bytes) { return decompression_limit(archive_bytes); }

ZipArchive::ZipArchive(Bytes data, std::string name, uint64_t max_total_bytes)
    : impl_(std::make_unique<Impl>()),
      name_(std::move(name)),
      limit_(max_total_bytes ? max_total_bytes : default_limit(data.size())) {
    impl_->data = data;
    if (data.empty()) return;
    const Unpacked u = unpack(1, data, "", limit_);
    if (!u.error.empty()) throw ReadError::whole_file(name_, "not a readable zip archive: " + u.error);
    const auto list = nlohmann::json::parse(std::string(reinterpret_cast<const char*>(u.bytes.data()), u.bytes.size()));
    for (const auto& n : list) impl_->names.push_back(n.get<std::string>());
}

ZipArchive::~ZipArchive() = default;

std::vector<std::string> ZipArchive::file_names() const {
    std::vector<std::string> names;
    for (const std::string& n : impl_->names)
        if (!n.empty() && n.back() != '/') names.push_back(n);
    return names;
}

std::optional<std::string> ZipArchive::find(std::string_view entry) const {
    const bool held = std::find(impl_->names.begin(), impl_->names.end(), entry) != impl_->names.end();
    return match_entry(entry, held, held ? std::vector<std::string>{} : file_names());
}

std::vector<std::byte> ZipArchive::read(const std::string& entry) {
    const uint64_t budget = limit_ - std::min(used_, limit_);
    Unpacked u = unpack(2, impl_->data, entry, budget);
    if (u.error.rfind("claims ", 0) == 0)
        throw ReadError::whole_file(name_, "zip entry '" + entry + "' " + u.error + " bytes uncompressed, more than " +
                                               decompression_limit_words(limit_) + "; refusing to decompress it");
    if (!u.error.empty()) throw ReadError::whole_file(name_, "zip entry '" + entry + "' " + u.error);
    // What minizip checks natively (zip.cpp, in its words): the CRC-32 where
    // the size is right, else the size. Here the size first, then the CRC-32.
    if (static_cast<double>(u.bytes.size()) != u.size)
        throw ReadError::whole_file(name_, "cannot decompress zip entry '" + entry + "': it holds " +
                                               std::to_string(u.bytes.size()) + " bytes where its header says " +
                                               std::to_string(static_cast<uint64_t>(u.size)) +
                                               " bytes (the data is corrupt)");
    boost::crc_32_type crc;
    crc.process_bytes(u.bytes.data(), u.bytes.size());
    if (static_cast<double>(crc.checksum()) != u.crc)
        throw ReadError::whole_file(name_, "cannot decompress zip entry '" + entry +
                                               "': CRC mismatch (the data is corrupt)");
    used_ += u.bytes.size();
    return std::move(u.bytes);
}

std::vector<std::byte> ZipArchive::read_zip64_entry(const std::string& entry, const Zip64Sizes&, uint64_t, uint64_t) {
    return read(entry);
}

}  // namespace polyvol::io

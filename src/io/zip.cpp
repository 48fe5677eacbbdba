#include "io/zip.hpp"

#include <zip.h>

#include <algorithm>

namespace polyvol::io {

namespace {

std::string normalized(std::string_view s) {
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

std::string bytes_text(uint64_t bytes) {
    return std::to_string(bytes) + " bytes";
}

}  // namespace

uint64_t ZipArchive::default_limit(std::size_t archive_bytes) {
    constexpr uint64_t floor = uint64_t{16} << 20;
    constexpr uint64_t ceiling = uint64_t{4} << 30;
    const uint64_t n = archive_bytes;
    const uint64_t scaled = n > ceiling / 64 ? ceiling : 64 * n;
    return std::min(ceiling, std::max(scaled, floor));
}

ZipArchive::ZipArchive(Bytes data, std::string name, uint64_t max_total_bytes)
    : name_(std::move(name)),
      limit_(max_total_bytes ? max_total_bytes : default_limit(data.size())) {
    zip_error_t err;
    zip_error_init(&err);
    zip_source_t* src = zip_source_buffer_create(data.data(), data.size(), 0, &err);
    if (src == nullptr) {
        std::string msg = std::string("cannot read the zip archive: ") + zip_error_strerror(&err);
        zip_error_fini(&err);
        throw ReadError::whole_file(name_, msg);
    }
    archive_ = zip_open_from_source(src, ZIP_RDONLY, &err);
    if (archive_ == nullptr) {
        zip_source_free(src);
        std::string msg = std::string("not a readable zip archive: ") + zip_error_strerror(&err);
        zip_error_fini(&err);
        throw ReadError::whole_file(name_, msg);
    }
    zip_error_fini(&err);
}

ZipArchive::~ZipArchive() {
    if (archive_ != nullptr) zip_discard(archive_);
}

std::vector<std::string> ZipArchive::file_names() const {
    std::vector<std::string> names;
    const zip_int64_t n = zip_get_num_entries(archive_, 0);
    for (zip_int64_t i = 0; i < n; ++i) {
        const char* s = zip_get_name(archive_, static_cast<zip_uint64_t>(i), 0);
        if (s == nullptr) continue;
        const std::string_view v(s);
        if (v.empty() || v.back() == '/') continue;  // directory entry
        names.emplace_back(v);
    }
    return names;
}

std::optional<std::string> ZipArchive::find(std::string_view entry) const {
    const std::string exact(entry);
    if (zip_name_locate(archive_, exact.c_str(), 0) >= 0) return exact;
    const std::string want = normalized(entry);
    if (want.empty()) return std::nullopt;
    for (const std::string& n : file_names())
        if (normalized(n) == want) return n;
    return std::nullopt;
}

std::vector<std::byte> ZipArchive::read(const std::string& entry) {
    const zip_int64_t idx = zip_name_locate(archive_, entry.c_str(), 0);
    if (idx < 0) throw ReadError::whole_file(name_, "zip entry '" + entry + "' is missing");
    const auto index = static_cast<zip_uint64_t>(idx);
    const uint64_t budget = limit_ - std::min(used_, limit_);
    const std::string limit_text = "the decompression limit of " + bytes_text(limit_) +
                                   " for this archive (64 x its size, at least 16 MiB, at most 4 GiB)";

    zip_stat_t st;
    zip_stat_init(&st);
    uint64_t claimed = 0;
    if (zip_stat_index(archive_, index, 0, &st) == 0 && (st.valid & ZIP_STAT_SIZE) != 0) {
        claimed = st.size;
        if (claimed > budget)
            throw ReadError::whole_file(
                name_, "zip entry '" + entry + "' claims " + bytes_text(claimed) +
                           " uncompressed, more than " + limit_text + "; refusing to decompress it");
    }

    zip_file_t* f = zip_fopen_index(archive_, index, 0);
    if (f == nullptr)
        throw ReadError::whole_file(name_, "cannot open zip entry '" + entry + "': " +
                                               zip_strerror(archive_));
    std::vector<std::byte> out;
    // The claimed size is only a hint, bounded by the budget checked above.
    out.reserve(static_cast<std::size_t>(claimed) + (std::size_t{1} << 16));
    constexpr std::size_t chunk = std::size_t{1} << 16;
    for (;;) {
        const std::size_t old = out.size();
        if (old > budget) {
            zip_fclose(f);
            throw ReadError::whole_file(name_, "zip entry '" + entry + "' decompresses to more than " +
                                                   limit_text + "; refusing to read it (zip bomb?)");
        }
        out.resize(old + chunk);
        const zip_int64_t got = zip_fread(f, out.data() + old, chunk);
        if (got < 0) {
            std::string msg = "cannot decompress zip entry '" + entry + "': " + zip_file_strerror(f);
            zip_fclose(f);
            throw ReadError::whole_file(name_, msg);
        }
        out.resize(old + static_cast<std::size_t>(got));
        if (got == 0) break;
    }
    zip_fclose(f);
    if (out.size() > budget)
        throw ReadError::whole_file(name_, "zip entry '" + entry + "' decompresses to more than " +
                                               limit_text + "; refusing to read it (zip bomb?)");
    used_ += out.size();
    return out;
}

}  // namespace polyvol::io

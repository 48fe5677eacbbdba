// Format detection and the public entry points read_mesh_file and
// read_mesh_memory. Detection is by content, in this order (io.hpp):
//   empty                   -> an empty OBJ when the hint says OBJ, else an error
//   gzip magic 1f 8b        -> gunzip, detect again ("gzip-compressed")
//   bzip2 magic "BZh"       -> bunzip2, detect again ("bzip2-compressed")
//   tar ("ustar" at 257)    -> an error naming its meshes (each is measured as ARCHIVE:MEMBER)
//   zip magic PK 3 4        -> 3MF when the archive names 3D/3dmodel.model, else AMF
//   UTF-16 byte-order mark  -> converted to UTF-8, detect again ("utf16-be-bom")
//   "ply" line              -> PLY
//   XML                     -> AMF (root <amf>) or 3MF (root <model>)
//   size == 84 + 50 n       -> binary STL
//   "solid"                 -> ASCII STL
//   [ST][C][N][4][n]OFF     -> OFF
//   OBJ statements          -> OBJ
//   otherwise               -> the reader the hint names (it reports what is
//                              wrong: an OFF file without its header, a binary
//                              STL of the wrong size, ...), or an error.
// The binary STL size rule is tried before the byte-order marks: a binary
// header may start with any bytes, while UTF-16 text never satisfies it.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <new>
#include <span>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "io/readers.hpp"
#include "io/zip.hpp"
#include "io/text.hpp"

namespace polyvol {

// Said where a file is not one polyvol reads.
constexpr const char* kFormatsRead =
    "polyvol reads STL, OBJ, OFF, PLY, 3MF, AMF and glTF (.gltf, .glb), each also gzip- or "
    "bzip2-compressed, alone or in zip and tar archives";

std::string unit_short_name(std::string_view declared) {
    static constexpr std::pair<std::string_view, std::string_view> kNames[] = {
        {"micron", "micron"}, {"micrometer", "micron"}, {"millimeter", "mm"}, {"centimeter", "cm"},
        {"meter", "m"},       {"inch", "in"},           {"foot", "ft"},       {"feet", "ft"}};
    for (const auto& [name, short_name] : kNames)
        if (declared == name) return std::string(short_name);
    return "";
}

std::string_view format_name(Format f) {
    switch (f) {
        case Format::stl: return "stl";
        case Format::obj: return "obj";
        case Format::off: return "off";
        case Format::ply: return "ply";
        case Format::threemf: return "3mf";
        case Format::amf: return "amf";
        case Format::gltf: return "gltf";
        case Format::unknown: break;
    }
    return "unknown";
}

Format format_from_extension(std::string_view path) {
    const std::size_t slash = path.find_last_of("/\\");
    std::string_view file = slash == std::string_view::npos ? path : path.substr(slash + 1);
    for (;;) {
        const std::size_t dot = file.rfind('.');
        if (dot == std::string_view::npos || dot == 0) return Format::unknown;
        const std::string_view ext = file.substr(dot + 1);
        using io::text::iequals;
        if (iequals(ext, "gz") || iequals(ext, "bz2")) {
            file = file.substr(0, dot);
            continue;
        }
        if (iequals(ext, "stl")) return Format::stl;
        if (iequals(ext, "obj")) return Format::obj;
        if (iequals(ext, "off")) return Format::off;
        if (iequals(ext, "ply")) return Format::ply;
        if (iequals(ext, "3mf")) return Format::threemf;
        if (iequals(ext, "amf")) return Format::amf;
        if (iequals(ext, "gltf") || iequals(ext, "glb")) return Format::gltf;
        return Format::unknown;
    }
}

namespace {

using io::Bytes;
namespace text = io::text;

bool starts_with(Bytes data, std::string_view magic) {
    return data.size() >= magic.size() && std::memcmp(data.data(), magic.data(), magic.size()) == 0;
}

bool contains(Bytes data, std::string_view needle) {
    return text::as_text(data).find(needle) != std::string_view::npos;
}

// The first line of s that is neither blank nor a '#' comment, trimmed.
std::string_view first_statement(std::string_view s) {
    std::size_t pos = 0;
    while (pos < s.size()) {
        std::size_t eol = pos;
        while (eol < s.size() && !text::is_eol(s[eol])) ++eol;
        const std::string_view line = text::trim(s.substr(pos, eol - pos));
        if (!line.empty() && line.front() != '#') return line;
        pos = eol + 1;
    }
    return {};
}

std::string_view first_word(std::string_view line) {
    std::size_t i = 0;
    while (i < line.size() && !text::is_space(line[i]) && line[i] != '#') ++i;
    return line.substr(0, i);
}

bool is_ascii_stl(std::string_view s) {
    std::size_t i = 0;
    while (i < s.size() && text::is_space(s[i])) ++i;
    return s.size() - i >= 5 && text::iequals(s.substr(i, 5), "solid") &&
           (s.size() - i == 5 || text::is_space(s[i + 5]));
}

bool is_binary_stl(Bytes data) { return data.size() >= 84 && 84 + 50 * io::stl_triangle_count(data) == data.size(); }

bool is_off(std::string_view s) {
    return text::parse_off_keyword(first_word(first_statement(s))).valid;
}

// Plain text whose first statement is an OBJ one.
bool looks_like_obj(std::string_view s) {
    const std::string_view head = s.substr(0, 4096);
    for (char c : head) {
        const auto u = static_cast<unsigned char>(c);
        if (u < 0x20 && !text::is_space(c)) return false;
    }
    static constexpr std::string_view keywords[] = {
        "v", "vt", "vn", "vp", "f", "l", "p", "o", "g", "s", "usemtl", "mtllib", "usemap", "maplib",
        "cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv", "sp", "end",
        "con", "mg", "bevel", "c_interp", "d_interp", "lod", "shadow_obj", "trace_obj", "ctech", "stech", "fo"};
    const std::string_view kw = first_word(first_statement(s));
    for (std::string_view k : keywords)
        if (kw == k) return true;
    return false;
}

// The name of the root element of an XML document (namespace prefix
// removed), or empty when s does not start like XML.
std::string_view xml_root(std::string_view s) {
    std::size_t i = 0;
    for (;;) {
        while (i < s.size() && text::is_space(s[i])) ++i;
        if (i >= s.size() || s[i] != '<') return {};
        const std::string_view rest = s.substr(i);
        std::string_view close;
        if (rest.starts_with("<?")) close = "?>";
        else if (rest.starts_with("<!--")) close = "-->";
        else if (rest.starts_with("<!")) close = ">";
        if (!close.empty()) {
            const std::size_t e = s.find(close, i + 2);
            if (e == std::string_view::npos) return {};
            i = e + close.size();
            continue;
        }
        std::size_t j = i + 1;
        while (j < s.size() && !text::is_space(s[j]) && s[j] != '>' && s[j] != '/') ++j;
        std::string_view name = s.substr(i + 1, j - i - 1);
        const std::size_t colon = name.rfind(':');
        if (colon != std::string_view::npos) name.remove_prefix(colon + 1);
        return name.empty() ? std::string_view("?") : name;
    }
}

// UTF-16 (either byte order) to UTF-8; unpaired surrogates become '?'.
std::vector<std::byte> utf16_to_utf8(Bytes data, bool big_endian) {
    std::vector<std::byte> out;
    out.reserve(data.size() / 2);
    auto put = [&](uint32_t c) { out.push_back(static_cast<std::byte>(c)); };
    const auto* b = reinterpret_cast<const unsigned char*>(data.data());
    const std::size_t n = data.size() / 2;
    auto unit = [&](std::size_t k) -> uint32_t {
        return big_endian ? (uint32_t{b[2 * k]} << 8 | b[2 * k + 1]) : (uint32_t{b[2 * k + 1]} << 8 | b[2 * k]);
    };
    for (std::size_t k = 1; k < n; ++k) {  // unit 0 is the byte-order mark
        uint32_t c = unit(k);
        if (c >= 0xD800 && c < 0xDC00 && k + 1 < n && unit(k + 1) >= 0xDC00 && unit(k + 1) < 0xE000) {
            c = 0x10000 + ((c - 0xD800) << 10) + (unit(k + 1) - 0xDC00);
            ++k;
        } else if (c >= 0xD800 && c < 0xE000) {
            c = '?';
        }
        if (c < 0x80) {
            put(c);
        } else if (c < 0x800) {
            put(0xC0 | c >> 6);
            put(0x80 | (c & 0x3F));
        } else if (c < 0x10000) {
            put(0xE0 | c >> 12);
            put(0x80 | ((c >> 6) & 0x3F));
            put(0x80 | (c & 0x3F));
        } else {
            put(0xF0 | c >> 18);
            put(0x80 | ((c >> 12) & 0x3F));
            put(0x80 | ((c >> 6) & 0x3F));
            put(0x80 | (c & 0x3F));
        }
    }
    return out;
}

// The members of a zip that hold meshes by their extension (format_from_extension,
// which looks through ".gz"), when the zip is not an AMF package (no *.amf):
// a zip of plain meshes. Empty otherwise.
std::vector<std::string> mesh_members(Bytes data, const std::string& name) {
    io::ZipArchive zip(data, name);
    std::vector<std::string> meshes;
    for (const std::string& n : zip.file_names()) {
        const Format f = format_from_extension(n);
        if (f == Format::amf) return {};
        if (f != Format::unknown) meshes.push_back(n);
    }
    return meshes;
}

// glTF JSON: an object (after blanks) naming its "asset" near the start.
bool looks_like_gltf(std::string_view s) {
    std::size_t i = 0;
    while (i < s.size() && text::is_space(s[i])) ++i;
    return i < s.size() && s[i] == '{' && s.substr(i, 1 << 16).find("\"asset\"") != std::string_view::npos;
}

LoadedMesh with_note_first(LoadedMesh m, std::string note) {
    m.notes.insert(m.notes.begin(), std::move(note));
    return m;
}

// limit: what gzip may still expand to, from the size of the file as read
// (nested gzip shares it).
LoadedMesh detect(Bytes data, const std::string& name, Format hint, int depth, uint64_t limit) {
    if (data.empty()) {
        if (hint == Format::obj) {
            LoadedMesh m;
            m.format = Format::obj;
            m.encoding = "ascii";
            return m;
        }
        throw ReadError::whole_file(name, "empty file");
    }
    if (io::is_gzip(data)) {
        if (depth >= 3) throw ReadError::whole_file(name, "gzip nested too deeply");
        const std::vector<std::byte> inner = io::gunzip(data, name, limit);
        LoadedMesh m = detect(inner, name, hint, depth + 1, limit - std::min<uint64_t>(limit, inner.size()));
        m.gzip = true;
        return with_note_first(std::move(m), "gzip-compressed");
    }
    if (io::is_bzip2(data)) {
        if (depth >= 3) throw ReadError::whole_file(name, "compressed data nested too deeply");
        const std::vector<std::byte> inner = io::bunzip2(data, name, limit);
        LoadedMesh m = detect(inner, name, hint, depth + 1, limit - std::min<uint64_t>(limit, inner.size()));
        return with_note_first(std::move(m), "bzip2-compressed");
    }
    if (io::is_tar(data)) {  // a tar of meshes is not one mesh: say what it holds
        const std::vector<std::string> meshes = io::tar_members(data, name);
        std::string list;
        for (std::size_t i = 0; i < meshes.size() && i < 3; ++i) list += (i ? ", " : "") + meshes[i];
        if (meshes.size() > 3) list += ", ...";
        throw ReadError::whole_file(name, "a tar archive of " + std::to_string(meshes.size()) + " mesh file" +
                                              (meshes.size() == 1 ? "" : "s") + (list.empty() ? "" : " (" + list + ")") +
                                              ": each is a mesh of its own (`polyvol volume` measures each as "
                                              "ARCHIVE:MEMBER)");
    }
    if (io::is_zip(data)) {
        if (contains(data, "3D/3dmodel.model")) return io::read_3mf_zip(data, name);
        if (hint == Format::threemf) return io::read_3mf_zip(data, name);
        // A zip of plain meshes is not one mesh: say what it holds.
        if (const std::vector<std::string> meshes = mesh_members(data, name); !meshes.empty()) {
            std::string list;
            for (std::size_t i = 0; i < meshes.size() && i < 3; ++i) list += (i ? ", " : "") + meshes[i];
            if (meshes.size() > 3) list += ", ...";
            throw ReadError::whole_file(name, "a zip archive of " + std::to_string(meshes.size()) + " mesh file" +
                                                  (meshes.size() == 1 ? "" : "s") + " (" + list +
                                                  "), not a 3MF or AMF package: each is a mesh of its own "
                                                  "(`polyvol volume` measures each as ARCHIVE:MEMBER)");
        }
        return io::read_amf_zip(data, name);
    }
    if (io::is_glb(data)) return io::read_gltf(data, name);
    const bool binary_stl = is_binary_stl(data);
    if (!binary_stl && depth < 3) {
        if (starts_with(data, "\xfe\xff") || starts_with(data, "\xff\xfe")) {
            const bool be = starts_with(data, "\xfe\xff");
            const std::vector<std::byte> utf8 = utf16_to_utf8(data, be);
            return with_note_first(detect(utf8, name, hint, depth + 1, limit), be ? "utf16-be-bom" : "utf16-le-bom");
        }
        if (starts_with(data, "\xef\xbb\xbf"))
            return with_note_first(detect(data.subspan(3), name, hint, depth + 1, limit), "utf8-bom");
    }
    const std::string_view s = text::as_text(data);
    if (io::is_ply(data)) return io::read_ply(data, name);
    if (!binary_stl) {
        const std::string_view root = xml_root(s.substr(0, 1 << 16));
        if (!root.empty()) {
            if (root == "amf") return io::read_amf_xml(data, name);
            if (root == "model") return io::read_3mf_xml(data, name);
            throw ReadError::whole_file(name, "XML document with root <" + std::string(root) +
                                                  "> is neither AMF (<amf>) nor 3MF (<model>)");
        }
    }
    if (!binary_stl && looks_like_gltf(s)) return io::read_gltf(data, name);
    if (binary_stl || is_ascii_stl(s)) return io::read_stl(data, name);
    if (is_off(s)) return io::read_off(data, name);
    if (looks_like_obj(s)) return io::read_obj(data, name);
    switch (hint) {
        case Format::stl: return io::read_stl(data, name);
        case Format::obj: return io::read_obj(data, name);
        case Format::off: return io::read_off(data, name);
        case Format::ply: return io::read_ply(data, name);
        case Format::threemf: return io::read_3mf_zip(data, name);
        case Format::amf: return io::read_amf_xml(data, name);
        case Format::gltf: return io::read_gltf(data, name);
        case Format::unknown: break;
    }
    throw ReadError::whole_file(
        name,
        "unrecognised content (tried gzip, zip (3MF/AMF), PLY, XML (AMF/3MF), binary STL (size 84 + 50 n), "
        "ASCII STL ('solid'), OFF and OBJ; the file name's extension gives no hint). " +
            std::string(kFormatsRead));
}

}  // namespace

LoadedMesh read_mesh_memory(std::span<const std::byte> data, const std::string& name, Format hint) {
    if (hint == Format::unknown) hint = format_from_extension(name);
    LoadedMesh m = detect(data, name, hint, 0, io::decompression_limit(data.size()));
    if (m.format != Format::stl) m.vertices_in_file = m.mesh.vertex_count();  // the STL reader counts its own
    return m;
}

namespace io {

uint64_t decompression_limit(std::size_t compressed_bytes) {
    constexpr uint64_t floor = uint64_t{16} << 20;
    constexpr uint64_t ceiling = uint64_t{4} << 30;
    const uint64_t n = compressed_bytes;
    const uint64_t scaled = n > ceiling / 64 ? ceiling : 64 * n;
    return std::min(ceiling, std::max(scaled, floor));
}

std::string decompression_limit_words(uint64_t limit) {
    return "the decompression limit of " + std::to_string(limit) +
           " bytes (all an input's compressed data may expand to: 64 x its size, at least 16 MiB, at most 4 GiB)";
}

bool is_gzip(Bytes head) { return starts_with(head, "\x1f\x8b"); }
bool is_zip(Bytes head) { return starts_with(head, "PK\x03\x04"); }
bool is_ply(Bytes head) {
    return starts_with(head, "ply") && (head.size() == 3 || text::is_space(static_cast<char>(head[3])));
}
uint64_t stl_triangle_count(Bytes head) {
    const auto* b = reinterpret_cast<const unsigned char*>(head.data()) + 80;
    return uint64_t{b[0]} | uint64_t{b[1]} << 8 | uint64_t{b[2]} << 16 | uint64_t{b[3]} << 24;
}

std::vector<std::byte> read_whole_input(const std::string& path, std::string& name) {
    const bool from_stdin = path == "-";
    name = from_stdin ? std::string("<stdin>") : path;
    std::FILE* f = from_stdin ? stdin : std::fopen(path.c_str(), "rb");
    if (f == nullptr) throw ReadError::whole_file(name, std::string("cannot open: ") + std::strerror(errno));
    // Sized from the real file size when there is one (plus a byte, so the
    // end of the file is seen without growing), doubled as data arrives.
    std::size_t cap = std::size_t{1} << 16;
    if (!from_stdin) {
        std::error_code ec;
        const auto size = std::filesystem::file_size(path, ec);
        if (!ec) cap = static_cast<std::size_t>(size) + 1;
    }
    std::vector<std::byte> buf(cap);
    std::size_t used = 0;
    for (;;) {
        if (used == buf.size()) buf.resize(2 * buf.size());
        const std::size_t got = std::fread(buf.data() + used, 1, buf.size() - used, f);
        used += got;
        if (got == 0) break;
    }
    const bool failed = std::ferror(f) != 0;
    const int err = errno;
    if (!from_stdin) std::fclose(f);
    if (failed) throw ReadError::whole_file(name, std::string("cannot read: ") + std::strerror(err));
    buf.resize(used);
    return buf;
}

}  // namespace io

namespace {

// A regular file's bytes, read with pread(2) into memory of our own. A
// mapping of the file would save the copy, but another process truncating
// the file while it is parsed would end this one with SIGBUS; a read simply
// stops at the new end, and the readers report what they got like any
// short file (with the line or byte offset). The copy's cost is kept small:
// the buffer is anonymous memory in transparent huge pages where the kernel
// allows (one fault per 2 MiB instead of 512), filled by several threads at
// once. Empty or special files: nothing read (read_whole_input reads them).
class FileBytes {
public:
    explicit FileBytes(const std::string& path) {
        const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) return;
        struct Close {
            int fd;
            ~Close() { ::close(fd); }
        } close{fd};
        struct stat st {};
        if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size <= 0) return;
        const auto size = static_cast<std::size_t>(st.st_size);
        constexpr std::size_t kHuge = std::size_t{2} << 20, kChunk = std::size_t{8} << 20;
        capacity_ = (size + kHuge - 1) / kHuge * kHuge;
        void* p = ::mmap(nullptr, capacity_, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
        if (p == MAP_FAILED) throw std::bad_alloc();
        data_ = static_cast<std::byte*>(p);
        (void)::madvise(p, capacity_, MADV_HUGEPAGE);
        (void)::posix_fadvise(fd, 0, 0, POSIX_FADV_SEQUENTIAL);
        // Chunk c holds [c kChunk, (c + 1) kChunk); got[c] bytes of it arrived.
        const std::size_t chunks = (size + kChunk - 1) / kChunk;
        std::vector<std::size_t> got(chunks, 0);
        std::vector<int> error(chunks, 0);
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& r) {
            for (std::size_t c = r.begin(); c != r.end(); ++c) {
                const std::size_t from = c * kChunk, len = std::min(kChunk, size - from);
                while (got[c] < len) {
                    const ssize_t n = ::pread(fd, data_ + from + got[c], len - got[c], static_cast<off_t>(from + got[c]));
                    if (n < 0 && errno == EINTR) continue;
                    if (n < 0) error[c] = errno;
                    if (n <= 0) break;  // an error, or the end: the file shrank meanwhile
                    got[c] += static_cast<std::size_t>(n);
                }
            }
        });
        // The data is what arrived before the first gap: the file as it is now.
        for (std::size_t c = 0; c < chunks; ++c) {
            if (error[c] != 0)
                throw ReadError::at_byte(path, c * kChunk + got[c], std::string("cannot read: ") + std::strerror(error[c]));
            size_ += got[c];
            if (got[c] < std::min(kChunk, size - c * kChunk)) break;
        }
        read_ = true;
    }
    ~FileBytes() {
        if (data_ != nullptr) ::munmap(data_, capacity_);
    }
    FileBytes(const FileBytes&) = delete;
    FileBytes& operator=(const FileBytes&) = delete;
    bool read() const { return read_; }
    std::span<const std::byte> bytes() const { return {data_, size_}; }

private:
    std::byte* data_ = nullptr;
    std::size_t capacity_ = 0, size_ = 0;
    bool read_ = false;
};

}  // namespace

namespace {

// Whether the first bytes of the file at path may start an archive of
// meshes: zip, or a tar (plain, or compressed by gzip or bzip2).
bool may_be_archive(const std::string& path) {
    std::byte head[512] = {};
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;
    const ssize_t n = ::pread(fd, head, sizeof head, 0);
    ::close(fd);
    if (n < 6) return false;
    const Bytes h(head, static_cast<std::size_t>(n));
    return io::is_zip(h) || io::is_gzip(h) || io::is_bzip2(h) || io::is_tar(h);
}

}  // namespace

std::vector<std::string> mesh_archive_members(const std::string& path) {
    if (!may_be_archive(path)) return {};  // other files are not read
    const FileBytes file(path);
    if (!file.read()) return {};
    if (io::is_zip(file.bytes()))
        return contains(file.bytes(), "3D/3dmodel.model") ? std::vector<std::string>{} : mesh_members(file.bytes(), path);
    return io::tar_members(file.bytes(), path);
}

LoadedMesh read_archive_member(const std::string& path, const std::string& member) {
    const FileBytes file(path);
    if (!file.read()) throw ReadError::whole_file(path, "cannot read the archive");
    if (!io::is_zip(file.bytes())) {
        const std::vector<std::byte> bytes =
            io::tar_member(file.bytes(), path, member, io::decompression_limit(file.bytes().size()));
        return read_mesh_memory(bytes, path + ":" + member, Format::unknown);
    }
    io::ZipArchive zip(file.bytes(), path);
    const std::vector<std::byte> bytes = zip.read(member);
    return read_mesh_memory(bytes, path + ":" + member, Format::unknown);
}

LoadedMesh read_mesh_file(const std::string& path) {
    std::error_code ec;
    if (path != "-" && std::filesystem::is_directory(path, ec))
        throw ReadError::whole_file(path, "a directory, not a mesh file. " + std::string(kFormatsRead));
    if (path != "-") {
        const FileBytes file(path);
        if (file.read()) return read_mesh_memory(file.bytes(), path, Format::unknown);
    }
    std::string name;
    const std::vector<std::byte> buf = io::read_whole_input(path, name);
    return read_mesh_memory(buf, name, Format::unknown);
}

}  // namespace polyvol

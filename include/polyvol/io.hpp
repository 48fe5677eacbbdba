// polyvol/io.hpp — reading mesh files.
//
// Readers turn bytes into a Mesh (see mesh.hpp) and never measure or
// validate geometry. Format is chosen by content, with the file extension as
// a hint for the few cases content cannot decide (an empty file, an OFF file
// without its header line):
//   gzip magic 1f 8b        -> decompressed (zlib), then detected again
//   bzip2 magic "BZh"       -> decompressed (libbz2), then detected again
//   zip magic "PK\3\4"      -> 3MF (has 3D/3dmodel.model) or zipped AMF
//   "ply" line              -> PLY (ascii, binary_little_endian, binary_big_endian)
//   XML with root <amf>     -> AMF; root <model> -> 3MF model part as bare XML
//   "glTF" magic, or JSON with "asset" -> glTF 2.0 (.glb, or .gltf with its buffers
//                              beside it: read only from the file's directory)
//   size == 84 + 50 * n     -> binary STL (n from bytes 80..83), even when the
//                              header starts with "solid"
//   "solid"                 -> ASCII STL (several solid blocks allowed)
//   [ST][C][N][4][n]OFF     -> OFF
//   otherwise               -> OBJ if the extension says so or the lines look like OBJ
// A UTF-16 byte-order mark converts the text to 8-bit first.
//
// Errors: every reader throws ReadError naming the file, the 1-based line (text
// formats) or the byte offset (binary formats), and what was expected. No reader
// allocates from a count the file claims before checking it against the bytes
// that are actually there.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "polyvol/mesh.hpp"

namespace polyvol {

enum class Format { unknown, stl, obj, off, ply, threemf, amf, gltf };

// "stl", "obj", "off", "ply", "3mf", "amf", "gltf", "unknown".
std::string_view format_name(Format f);
// Format suggested by a path's extension (".gz" is looked through), or unknown.
Format format_from_extension(std::string_view path);

// Where in the input a problem is. line is 1-based for text formats (0 = not
// applicable); byte_offset is from the start of the (decompressed) data.
struct ReadError : std::runtime_error {
    std::string file;
    uint64_t line = 0;
    uint64_t byte_offset = 0;
    bool has_byte_offset = false;
    std::string message;  // what was wrong / what was expected

    ReadError(std::string file, uint64_t line, std::string message);
    static ReadError at_byte(std::string file, uint64_t offset, std::string message);
    static ReadError whole_file(std::string file, std::string message);
};

// STL lists three vertices for every facet and shares none, so the STL
// reader welds them (weld_vertices, mesh.hpp: bit-identical coordinates,
// -0.0 equal to +0.0): `mesh` is the indexed mesh CGAL's and VTK's readers
// give too, its facets as faces in file order, its vertices numbered in the
// order of their first corner (exactly welded(soup) of the facets' corners).
// Welding only merges equal values, so every exact and correctly rounded
// result is that of the soup. The other formats' vertices are kept as listed.
// A named part of a file: a run of consecutive faces (3MF build items and
// glTF mesh instances).
struct MeshPart {
    std::string name;
    std::size_t first_face = 0, faces = 0;
    double coordinate_error = 0;  // LoadedMesh::coordinate_error for this part's vertices
};

struct LoadedMesh {
    Mesh mesh;
    std::size_t vertices_in_file = 0;  // as the file lists them (STL: per facet corner; else mesh.vertex_count())
    Format format = Format::unknown;
    std::string encoding;             // "ascii", "binary_le", "binary_be", "zip", "xml"
    bool gzip = false;                // the bytes were gzip-compressed
    std::vector<std::string> notes;   // quirks met while reading, e.g. "stl-multiple-solids(2)"
    // A bound on |coordinate - the value the file defines| for every vertex:
    // 0 when the coordinates are the file's numbers; above 0 where the reader
    // computed them (3MF transforms, applied in floating point).
    double coordinate_error = 0;
    // STL: the triangle facets whose stated normal points against the winding
    // of their corners (n · ((b − a) × (c − a)) < 0 in double; zero normals
    // never count). Other formats: 0.
    std::size_t facet_normals_against_winding = 0;
    // The length unit the file declares: "micron", "mm", "cm", "m", "in" or
    // "ft" (3MF and AMF: their unit attribute, millimetre when absent); ""
    // when the format has none (STL, OBJ, OFF, PLY) or the value is not one
    // of those. Coordinates are never scaled by it.
    std::string unit;
    // The file's parts, in order: 3MF build items (the object's name
    // attribute, else "object ID"), glTF mesh instances (the node's name,
    // else the mesh's, else "node N"). Empty for formats without parts.
    std::vector<MeshPart> parts;
};

// The short name ("mm", ...) of a unit as 3MF or AMF spell it ("millimeter",
// "micron", "micrometer", "centimeter", "meter", "inch", "foot", "feet"), or
// "" for anything else.
std::string unit_short_name(std::string_view declared);

// What a reader's note (LoadedMesh::notes: "stl-multiple-solids(2)") means,
// in words for people ("2 solids in one file, measured together"); an
// unknown note as it is.
std::string note_words(std::string_view note);

// Reads a file; "-" reads standard input. Throws ReadError (a zip archive
// of several meshes, not a 3MF or AMF package, included: see below).
LoadedMesh read_mesh_file(const std::string& path);

// An archive of plain meshes — a zip (not a 3MF package, no *.amf member)
// or a tar (plain, .tar.gz/.tgz, .tar.bz2/.tbz2): the members that are
// meshes by their extension (stl, obj, off, ply, 3mf, amf, each also .gz or
// .bz2), in archive order; empty for any other file.
std::vector<std::string> mesh_archive_members(const std::string& path);
// One member of such an archive, read as a file of its own named
// "PATH:MEMBER" (the archive's decompression limits apply). Throws ReadError.
LoadedMesh read_archive_member(const std::string& path, const std::string& member);

// Reads from memory. name is used in messages and, through its extension, as a
// format hint; hint overrides the extension when not unknown. Throws ReadError.
LoadedMesh read_mesh_memory(std::span<const std::byte> data, const std::string& name,
                            Format hint = Format::unknown);

// ---- Streaming binary STL (src/io/stl_stream.cpp) --------------------------
// For files too large to hold: the 50-byte triangle records are handed to the
// caller window by window, read with pread into a fixed buffer per thread
// (or, with StlStreamOptions::map, from a mapping of the file whose finished
// slabs are dropped), so memory stays constant whatever the file size.

struct BinaryStlProbe {
    bool binary_stl = false;      // what read_mesh_file would read as binary STL
    uint64_t triangles = 0;       // n from bytes 80..83 (== (size - 84) / 50)
    uint64_t file_bytes = 0;
    bool header_starts_with_solid = false;
};

// Decides as read_mesh_file's detection does (docs at the top of this file):
// not gzip, not zip, not PLY, and size == 84 + 50 n. Reads 84 bytes. A path
// that is not a regular file ("-", a pipe) is never binary STL here. Throws
// ReadError when the file cannot be opened. (BinaryStlFile(path).probe().)
BinaryStlProbe probe_binary_stl(const std::string& path);

struct StlStreamOptions {
    // Bytes per window; rounded down to a whole number of `alignment` records,
    // at least one such group. Windows start at triangle indices that are
    // multiples of `alignment`: the caller's block size, e.g.
    // SoupAccumulator::kBlockTriangles (soup.hpp) for the accumulator.
    std::size_t window_bytes = 50 * 4096;
    // Read and call back on several threads at once (oneTBB). The callback
    // must then be thread-safe; windows arrive in no particular order.
    bool parallel = true;
    // false (the default): read with pread(2) into one buffer per thread,
    // so that a file truncated by another process meanwhile is a ReadError
    // at the offset where the data stopped. true: map the file and hand out
    // windows of the mapping (no copy), dropping each finished slab of
    // slab_bytes from the process (in whole 2 MiB units when slabs are at
    // least that long, so that a page cache in large folios is never split),
    // so the resident set stays about threads x slab_bytes; but a file
    // truncated while mapped ends the process with SIGBUS.
    bool map = false;
    std::size_t slab_bytes = std::size_t{4} << 20;
    // Windows start at multiples of this many records (see window_bytes).
    std::size_t alignment = 1;
};

// records: whole 50-byte records; first_triangle: index of the first one.
using StlWindowFn = std::function<void(std::span<const std::byte> records, uint64_t first_triangle)>;

// A file opened and probed once, then streamed any number of times from the
// same open descriptor (kept open for the object's lifetime):
//   * the constructor opens and probes as probe_binary_stl does, and throws
//     ReadError when the file cannot be opened, stat'ed or read; "-" (standard
//     input) is never opened and probes as not binary STL;
//   * for_each_window is one pass, with for_each_stl_window's rules (it
//     throws ReadError for a file that is not binary STL, "-" included); it
//     may run concurrently with itself (pread and mmap of a shared
//     descriptor).
// The records streamed are those of the file probed even if its path is
// replaced meanwhile (a rename over it), and a pass costs no new open or
// probe; a file truncated or rewritten in place is not protected (see
// StlStreamOptions::map).
class BinaryStlFile {
public:
    explicit BinaryStlFile(const std::string& path);
    ~BinaryStlFile();
    BinaryStlFile(const BinaryStlFile&) = delete;
    BinaryStlFile& operator=(const BinaryStlFile&) = delete;
    BinaryStlFile(BinaryStlFile&& other) noexcept;
    BinaryStlFile& operator=(BinaryStlFile&& other) noexcept;

    const BinaryStlProbe& probe() const { return probe_; }
    void for_each_window(const StlWindowFn& fn, const StlStreamOptions& options = {}) const;

private:
    std::string path_;
    int fd_ = -1;
    BinaryStlProbe probe_;
    unsigned char head_[84] = {};
    std::size_t head_len_ = 0;
};

// Streams every record of a binary STL file through fn. Throws ReadError
// (file, byte offset, message) when the file is not binary STL by the size
// rule (byte offset 80, as read_mesh_file), is "-" or not a regular file,
// cannot be read, or ends early while being read (the offset where the data
// stopped). Exceptions thrown by fn propagate (other windows may still have
// been called). (BinaryStlFile(path).for_each_window(fn, options).)
void for_each_stl_window(const std::string& path, const StlWindowFn& fn, const StlStreamOptions& options = {});

// The triangles of a binary STL file as float32, nine per triangle (a, b, c)
// and packed (36 bytes each): the file's own numbers, nothing welded or
// widened, in the layout of polyvol::packed_triangles (soup.hpp) and of a
// numpy (n, 3, 3) float32 array, and what soup_volume reads fastest (no
// welding: about a fifth of read_mesh_file's time on the same file, which
// welds). Copies the mapped records in parallel. Throws ReadError as
// for_each_stl_window does, and at the byte offset of the first NaN or
// infinite coordinate (as read_mesh_file).
std::vector<float> read_binary_stl_triangles(const std::string& path);

}  // namespace polyvol

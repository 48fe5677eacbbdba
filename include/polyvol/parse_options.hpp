// polyvol/parse_options.hpp — how the readers parse (serially or in chunks
// on several threads, STL welded or kept as a soup) and what the last read
// on this thread did. The readers of polyvol/io.hpp take these options from
// the calling thread; tests, benchmarks and fuzz targets set them with
// ScopedParseOptions. Every choice gives the same mesh, bit for bit, and the
// same errors (src/io/chunks.hpp says how); only the time differs.
#pragma once

#include <cstddef>

namespace polyvol::io {

struct ParseOptions {
    // Parse large inputs in chunks on several threads (oneTBB): ASCII STL,
    // OBJ, OFF, PLY (ascii and binary bodies), binary STL (blocks of 16384
    // records: chunk_bytes does not apply). false selects the serial
    // readers (welding's own passes may still use other threads).
    bool parallel = true;
    // Bytes per chunk: a chunk ends at the first suitable line start at
    // least this far from its beginning (at least 1), or an eighth of the
    // input when that is less, so every parallel read has several chunks.
    std::size_t chunk_bytes = std::size_t{2} << 20;
    // Inputs smaller than this (for OFF and PLY: what follows the header;
    // binary PLY: what is left at an element's start) are read serially,
    // where splitting would cost more than it saves.
    std::size_t min_parallel_bytes = std::size_t{1} << 20;
    // STL: weld the facets' corners into an indexed mesh (LoadedMesh, io.hpp).
    // false keeps the soup, every corner its own vertex (for tests).
    bool weld_stl = true;
};

// The options of the calling thread, used by the readers when they are
// called without options (read_mesh_memory, read_mesh_file). Tests and
// benchmarks change them with ScopedParseOptions.
ParseOptions& thread_parse_options();

class ScopedParseOptions {
public:
    explicit ScopedParseOptions(const ParseOptions& o) : saved_(thread_parse_options()) {
        thread_parse_options() = o;
    }
    ~ScopedParseOptions() { thread_parse_options() = saved_; }
    ScopedParseOptions(const ScopedParseOptions&) = delete;
    ScopedParseOptions& operator=(const ScopedParseOptions&) = delete;

private:
    ParseOptions saved_;
};

// What the last text reader called on this thread did, for tests and
// benchmarks (reset by every call of read_stl/obj/off/ply).
struct ParseReport {
    std::size_t chunks = 0;        // chunks (binary STL: blocks of records) read in parallel (0: read serially)
    bool serial_fallback = false;  // the chunks could not decide alone; then read serially
};
ParseReport& thread_parse_report();

}  // namespace polyvol::io

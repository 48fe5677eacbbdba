// Private interface between the format dispatcher (detect.cpp) and the
// per-format readers. Each reader takes the whole (decompressed) content and
// the name to use in messages, and throws polyvol::ReadError.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "polyvol/io.hpp"

namespace polyvol::io {

using Bytes = std::span<const std::byte>;

LoadedMesh read_stl(Bytes data, const std::string& name);   // ASCII or binary by the size rule
LoadedMesh read_obj(Bytes data, const std::string& name);
LoadedMesh read_off(Bytes data, const std::string& name);
LoadedMesh read_ply(Bytes data, const std::string& name);
LoadedMesh read_3mf_zip(Bytes data, const std::string& name);
LoadedMesh read_3mf_xml(Bytes data, const std::string& name);  // the model part as bare XML
LoadedMesh read_amf_xml(Bytes data, const std::string& name);
LoadedMesh read_amf_zip(Bytes data, const std::string& name);

// The whole content of a file, or of standard input for "-"; name is set to
// the name for messages ("<stdin>" or the path). Throws ReadError.
std::vector<std::byte> read_whole_input(const std::string& path, std::string& name);

// Content tests on the first bytes, shared by read_mesh_file's detection
// (detect.cpp) and the binary STL stream's probe (stl_stream.cpp), so the
// two decide alike: gzip magic 1f 8b, zip magic "PK\3\4", a "ply" line.
bool is_gzip(Bytes head);
bool is_zip(Bytes head);
bool is_ply(Bytes head);
// A binary STL header's triangle count: bytes 80..83, little-endian
// (head.size() >= 84).
uint64_t stl_triangle_count(Bytes head);

// How many bytes a compressed input of `compressed_bytes` may expand to, in
// all (gzip members, nested gzip, zip entries): min(4 GiB, max(64 ×
// compressed_bytes, 16 MiB)). Meshes compress 2–20×; a bomb expands 1000×
// per level.
uint64_t decompression_limit(std::size_t compressed_bytes);
// "the decompression limit of N bytes (...)": the words of every refusal at
// the limit (gzip, bzip2, zip entries), the same in every build; N is what
// was left of the input's limit (decompression_limit, or the caller's).
std::string decompression_limit_words(uint64_t limit);

// zlib: the decompressed bytes of a gzip stream (every member). Throws
// ReadError on corrupt data, and before producing more than max_bytes.
std::vector<std::byte> gunzip(Bytes data, const std::string& name, uint64_t max_bytes);

// gltf.cpp: glTF 2.0, JSON (.gltf, its buffers beside it) or binary (.glb,
// magic "glTF"); external buffers are read relative to name's directory.
bool is_glb(Bytes head);
LoadedMesh read_gltf(Bytes data, const std::string& name);

// archive.cpp: bzip2 streams ("BZh1".."BZh9") and tar archives ("ustar"
// at byte 257, with a valid header checksum).
bool is_bzip2(Bytes head);
bool is_tar(Bytes data);
// bzip2.cpp (libbz2): the decompressed bytes of a bzip2 stream
// (concatenated streams too), at most `limit`. Throws ReadError on corrupt
// or truncated data.
std::vector<std::byte> bunzip2(Bytes data, const std::string& name, uint64_t limit);
// A tar archive's regular files that are meshes by their extension, in
// archive order (the tar plain, or gzip or bzip2 compressed); empty when it
// is not a tar.
std::vector<std::string> tar_members(Bytes data, const std::string& name);
// One member's bytes (the archive's decompression at most `limit`). Throws ReadError.
std::vector<std::byte> tar_member(Bytes data, const std::string& name, const std::string& member, uint64_t limit);

}  // namespace polyvol::io

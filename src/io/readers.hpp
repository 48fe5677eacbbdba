// Private interface between the format dispatcher (detect.cpp) and the
// per-format readers. Each reader takes the whole (decompressed) content and
// the name to use in messages, and throws polyvol::ReadError.
#pragma once

#include <cstddef>
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

// zlib: the decompressed bytes of a gzip stream (throws ReadError on corrupt data).
std::vector<std::byte> gunzip(Bytes data, const std::string& name);

}  // namespace polyvol::io

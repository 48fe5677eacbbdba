// 3MF reader — stub until written.
#include "io/readers.hpp"

namespace polyvol::io {
LoadedMesh read_3mf_zip(Bytes, const std::string& name) { throw ReadError::whole_file(name, "3MF is not supported yet"); }
LoadedMesh read_3mf_xml(Bytes, const std::string& name) { throw ReadError::whole_file(name, "3MF is not supported yet"); }
}  // namespace polyvol::io

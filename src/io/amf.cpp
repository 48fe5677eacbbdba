// AMF reader — stub until written.
#include "io/readers.hpp"

namespace polyvol::io {
LoadedMesh read_amf_zip(Bytes, const std::string& name) { throw ReadError::whole_file(name, "AMF is not supported yet"); }
LoadedMesh read_amf_xml(Bytes, const std::string& name) { throw ReadError::whole_file(name, "AMF is not supported yet"); }
}  // namespace polyvol::io

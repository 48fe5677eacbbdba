// Element names in the XML-based readers (3MF, AMF): files may qualify a name
// with a namespace prefix ("m:vertex"); the readers compare local names only.
#pragma once

#include <string_view>

#include <pugixml.hpp>

namespace polyvol::io::xmlname {

// The name without its namespace prefix: what follows the last ':'.
inline std::string_view local_name(const char* name) {
    const std::string_view s(name);
    const auto colon = s.rfind(':');
    return colon == std::string_view::npos ? s : s.substr(colon + 1);
}

// Whether n is an element whose local name is `local`.
inline bool is_element(pugi::xml_node n, std::string_view local) {
    return n.type() == pugi::node_element && local_name(n.name()) == local;
}

}  // namespace polyvol::io::xmlname

// AMF reader (ISO/ASTM 52915), as XML or as a zip holding one .amf entry.
//
// What is read: every <object>, each <mesh> with
//   <vertices><vertex><coordinates><x/><y/><z/></coordinates></vertex>...</vertices>
// and any number of <volume>s of <triangle><v1/><v2/><v3/></triangle>.
// Triangle indices refer to the vertices of their own mesh; all objects and
// volumes are kept, untransformed, in document order. Ignored: <constellation>
// (note "amf-constellation-ignored"), <metadata>, <color>, <material>,
// <texture>, <edge> (curved triangles are read as flat ones). Element names are
// matched by local name (any namespace prefix).
//
// Units: the unit attribute of <amf> is read into LoadedMesh::unit
// (millimeter when absent) and reported as a note ("amf-unit(<unit>)") when
// it is given and is not millimeter; coordinates are never scaled.
//
// Notes: "amf-zip-compressed", "amf-multiple-volumes" (a mesh with more than
// one volume), "amf-multiple-objects(n)" (n > 1 objects), "amf-constellation-ignored".
#include <pugixml.hpp>

#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "io/readers.hpp"
#include "io/xml_names.hpp"
#include "io/xml_numbers.hpp"
#include "io/zip.hpp"

namespace polyvol::io {

namespace {

using xmlname::is_element;

pugi::xml_node amf_child(pugi::xml_node n, std::string_view local) {
    for (pugi::xml_node c : n.children())
        if (is_element(c, local)) return c;
    return {};
}

class AmfReader {
public:
    AmfReader(const std::string& name, std::string entry, Bytes text)
        : name_(name), entry_(std::move(entry)), text_(text) {}

    void read(LoadedMesh& out) {
        const pugi::xml_parse_result r =
            doc_.load_buffer(text_.data(), text_.size(), pugi::parse_default, pugi::encoding_auto);
        if (!r) {
            std::string msg = std::string("XML parse error: ") + r.description();
            if (!entry_.empty()) msg += " (zip entry '" + entry_ + "')";
            throw ReadError::at_byte(name_, static_cast<uint64_t>(r.offset), msg);
        }
        offsets_valid_ = r.encoding == pugi::encoding_utf8;
        const pugi::xml_node root = doc_.document_element();
        if (!is_element(root, "amf"))
            fail(root, std::string("the root element is <") + root.name() + ">, expected <amf>");

        const std::string unit = root.attribute("unit").value();
        std::size_t objects = 0;
        bool multiple_volumes = false;
        bool constellation = false;
        Mesh& mesh = out.mesh;
        for (pugi::xml_node obj : root.children()) {
            if (is_element(obj, "constellation")) constellation = true;
            if (!is_element(obj, "object")) continue;
            ++objects;
            for (pugi::xml_node m : obj.children()) {
                if (!is_element(m, "mesh")) continue;
                const std::size_t base = mesh.vertex_count();
                std::size_t nv = 0;
                for (pugi::xml_node vs : m.children()) {
                    if (!is_element(vs, "vertices")) continue;
                    for (pugi::xml_node v : vs.children()) {
                        if (!is_element(v, "vertex")) continue;
                        if (base + nv >= std::numeric_limits<uint32_t>::max())
                            fail(v, "more than 4294967295 vertices");
                        const pugi::xml_node c = amf_child(v, "coordinates");
                        if (!c) fail(v, "<vertex> without <coordinates>");
                        const double x = number(c, "x");
                        const double y = number(c, "y");
                        const double z = number(c, "z");
                        mesh.add_vertex(x, y, z);
                        ++nv;
                    }
                }
                std::size_t volumes = 0;
                for (pugi::xml_node vol : m.children()) {
                    if (!is_element(vol, "volume")) continue;
                    ++volumes;
                    for (pugi::xml_node t : vol.children()) {
                        if (!is_element(t, "triangle")) continue;
                        const uint32_t a = index(t, "v1", nv, base);
                        const uint32_t b = index(t, "v2", nv, base);
                        const uint32_t c = index(t, "v3", nv, base);
                        mesh.add_triangle(a, b, c);
                    }
                }
                if (volumes > 1) multiple_volumes = true;
            }
        }
        out.format = Format::amf;
        if (multiple_volumes) out.notes.emplace_back("amf-multiple-volumes");
        if (objects > 1) out.notes.push_back("amf-multiple-objects(" + std::to_string(objects) + ")");
        if (constellation) out.notes.emplace_back("amf-constellation-ignored");
        if (!unit.empty() && unit != "millimeter") out.notes.push_back("amf-unit(" + unit + ")");
        out.unit = unit_short_name(unit.empty() ? "millimeter" : unit);
    }

private:
    [[noreturn]] void fail(pugi::xml_node n, std::string msg) const {
        if (!entry_.empty()) msg += " (zip entry '" + entry_ + "')";
        const std::ptrdiff_t off = n ? n.offset_debug() : -1;
        if (off >= 0 && offsets_valid_)
            throw ReadError(name_, xmlnum::line_at(text_, static_cast<std::size_t>(off)), msg);
        throw ReadError::whole_file(name_, msg);
    }

    double number(pugi::xml_node coords, const char* axis) {
        const pugi::xml_node n = amf_child(coords, axis);
        if (!n) fail(coords, std::string("<coordinates> without <") + axis + ">, expected a decimal number");
        const char* text = n.child_value();
        const auto v = xmlnum::parse_double(text);
        if (!v)
            fail(n, "bad number " + xmlnum::quote(xmlnum::trim(text)) + " in <" + axis +
                        ">, expected a finite decimal number");
        return *v;
    }

    uint32_t index(pugi::xml_node tri, const char* which, std::size_t nv, std::size_t base) {
        const pugi::xml_node n = amf_child(tri, which);
        if (!n) fail(tri, std::string("<triangle> without <") + which + ">, expected a vertex index");
        const char* text = n.child_value();
        const auto v = xmlnum::parse_index(text);
        if (!v)
            fail(n, "bad vertex index " + xmlnum::quote(xmlnum::trim(text)) + " in <" + which +
                        ">, expected a non-negative integer");
        if (*v >= nv)
            fail(n, "vertex index " + std::to_string(*v) + " in <" + which +
                        "> out of range: the mesh has " + std::to_string(nv) +
                        (nv ? " vertices (indices 0.." + std::to_string(nv - 1) + ")" : " vertices"));
        return static_cast<uint32_t>(base + *v);
    }

    const std::string& name_;
    std::string entry_;
    Bytes text_;
    pugi::xml_document doc_;
    bool offsets_valid_ = false;
};

bool ends_with_amf(std::string_view s) {
    if (s.size() < 4) return false;
    const std::string_view ext = s.substr(s.size() - 4);
    return ext[0] == '.' && (ext[1] | 0x20) == 'a' && (ext[2] | 0x20) == 'm' && (ext[3] | 0x20) == 'f';
}

}  // namespace

LoadedMesh read_amf_xml(Bytes data, const std::string& name) {
    LoadedMesh out;
    AmfReader(name, std::string(), data).read(out);
    out.encoding = "xml";
    return out;
}

LoadedMesh read_amf_zip(Bytes data, const std::string& name) {
    ZipArchive zip(data, name);
    const std::vector<std::string> names = zip.file_names();
    std::string entry;
    for (const std::string& n : names)
        if (ends_with_amf(n)) {
            entry = n;
            break;
        }
    if (entry.empty()) {
        if (names.size() != 1)
            throw ReadError::whole_file(name, "the zip archive holds " + std::to_string(names.size()) +
                                                  " files and none is named *.amf, expected one AMF file");
        entry = names.front();
    }
    const std::vector<std::byte> xml = zip.read(entry);
    LoadedMesh out;
    out.notes.emplace_back("amf-zip-compressed");
    AmfReader(name, entry, xml).read(out);
    out.encoding = "zip";
    return out;
}

}  // namespace polyvol::io

// 3MF reader: the model part of a 3MF package (zip), or that part as bare XML.
//
// What is read (3MF core specification):
//   <model unit=...><resources><object id=...> with either
//     <mesh><vertices><vertex x= y= z=/>...</vertices>
//           <triangles><triangle v1= v2= v3=/>...</triangles></mesh>
//   or <components><component objectid= [transform=] [p:path=]/>...</components>
//   and <build><item objectid= [transform=] [p:path=]/>...</build>.
// The mesh is every build item instantiated (components recursively), or, when
// there is no build item, every object's own mesh untransformed.
// Element names are matched by local name (any namespace prefix).
//
// Transforms: "m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32" is the 4x3
// matrix of the 3MF core spec applied to row vectors:
//   x' = x*m00 + y*m10 + z*m20 + m30
//   y' = x*m01 + y*m11 + z*m21 + m31
//   z' = x*m02 + y*m12 + z*m22 + m32
// A component's transform maps the referenced object into its parent; the
// item's maps the object into the build. Transforms are applied one after the
// other (innermost component first), each with a compensated dot product
// (error-free products via fma, Dot2 of Ogita, Rump & Oishi): the result is as
// accurate as if computed in twice double precision and then rounded, so it is
// almost always the correctly rounded value the corpus manifest uses (exact
// rational arithmetic), but it can differ in the last bit, and nested
// transforms round once per level: LoadedMesh::coordinate_error bounds the
// difference (each level's Dot2 bound, and the earlier levels' through |M|).
// Identity transforms leave coordinates untouched.
//
// Units: the model's unit attribute is read into LoadedMesh::unit (millimeter
// when absent) and reported as a note ("3mf-unit(<unit>)") when it is not the
// default millimeter; coordinates are never scaled.
//
// Notes: "3mf-transform" when an instantiated item or component carries a
// transform attribute, "3mf-components" when an instantiated object has
// components, "3mf-bare-xml-not-zip" for read_3mf_xml.
//
// Production extension: a component or item with a p:path attribute refers to
// an object in another model part of the package; that part is loaded from
// the zip (its own components refer to objects of that part).
#include <pugixml.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "io/readers.hpp"
#include "io/xml_names.hpp"
#include "io/xml_numbers.hpp"
#include "io/zip.hpp"

namespace polyvol::io {

namespace {

using Affine = std::array<double, 12>;  // m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32

constexpr Affine kIdentity = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
constexpr int kMaxComponentDepth = 64;

using xmlname::is_element;
using xmlname::local_name;

pugi::xml_attribute attribute_local(pugi::xml_node n, std::string_view local) {
    for (pugi::xml_attribute a : n.attributes())
        if (local_name(a.name()) == local) return a;
    return {};
}

// Error-free transformations.
inline void two_sum(double a, double b, double& s, double& e) {
    s = a + b;
    const double bb = s - a;
    e = (a - (s - bb)) + (b - bb);
}

// a0*b0 + a1*b1 + a2*b2 + c, compensated (Dot2).
inline double dot3_plus(double a0, double b0, double a1, double b1, double a2, double b2, double c) {
    const double p0 = a0 * b0, e0 = std::fma(a0, b0, -p0);
    const double p1 = a1 * b1, e1 = std::fma(a1, b1, -p1);
    const double p2 = a2 * b2, e2 = std::fma(a2, b2, -p2);
    double s1, q1, s2, q2, s3, q3;
    two_sum(p0, p1, s1, q1);
    two_sum(s1, p2, s2, q2);
    two_sum(s2, c, s3, q3);
    return s3 + (((e0 + e1) + e2) + ((q1 + q2) + q3));
}

// A bound on |dot3_plus(...) - the exact value|: Dot2 of n = 4 terms (c as
// c · 1) is within u |s| + γ_4² Σ|a_i b_i| of the exact s (Ogita, Rump, Oishi
// 2005, Prop. 5.3; γ_k = k u / (1 - k u), γ_4² < 17 u²), so within
// (u |r| + γ_4² Σ)/(1 - u) of the result r; rounded up generously, plus what
// underflow in the products may lose.
inline double dot3_plus_error(double r, double a0, double b0, double a1, double b1, double a2, double b2, double c) {
    constexpr double u = 0x1p-53;
    const double sum = std::fabs(a0 * b0) + std::fabs(a1 * b1) + std::fabs(a2 * b2) + std::fabs(c);
    return (1 + 8 * u) * (u * std::fabs(r) + 20 * u * u * sum) + 0x1p-1020 * 0x1p-50;
}

struct MeshData {
    std::vector<double> positions;
    std::vector<uint32_t> triangles;
};

struct Component {
    pugi::xml_node node;
    uint64_t objectid = 0;
    std::string path;  // normalized part name; empty = the part holding the component
    bool has_transform = false;
    Affine transform = kIdentity;
};

struct Object {
    pugi::xml_node node;
    bool has_mesh = false;
    MeshData mesh;
    bool has_components = false;
    std::vector<Component> components;
};

struct Part {
    std::string entry;  // zip entry name; empty for bare XML
    std::vector<std::byte> owned;
    Bytes text;
    pugi::xml_document doc;
    bool offsets_valid = false;  // node offsets index `text` (no encoding conversion)
    std::string unit;
    std::vector<uint64_t> order;  // object ids in document order
    std::unordered_map<uint64_t, Object> objects;
};

std::string normalize_part_name(std::string_view target) {
    // Percent-decoding of OPC part names (e.g. %20); a leading '/' dropped.
    std::string out;
    for (std::size_t i = 0; i < target.size(); ++i) {
        const char c = target[i];
        auto hex = [](char h) -> int {
            if (h >= '0' && h <= '9') return h - '0';
            if (h >= 'a' && h <= 'f') return h - 'a' + 10;
            if (h >= 'A' && h <= 'F') return h - 'A' + 10;
            return -1;
        };
        if (c == '%' && i + 2 < target.size() && hex(target[i + 1]) >= 0 && hex(target[i + 2]) >= 0) {
            out += static_cast<char>(hex(target[i + 1]) * 16 + hex(target[i + 2]));
            i += 2;
        } else {
            out += c;
        }
    }
    const auto first = out.find_first_not_of('/');
    return first == std::string::npos ? std::string() : out.substr(first);
}

class Reader {
public:
    Reader(const std::string& name, ZipArchive* zip) : name_(name), zip_(zip) {}

    LoadedMesh read(std::unique_ptr<Part> root_part) {
        Part& root = *root_part;
        parts_.emplace(root.entry, std::move(root_part));
        parse_part(root);
        out_.format = Format::threemf;
        out_.encoding = zip_ ? "zip" : "xml";
        if (!zip_) out_.notes.emplace_back("3mf-bare-xml-not-zip");
        if (!root.unit.empty() && root.unit != "millimeter")
            out_.notes.push_back("3mf-unit(" + root.unit + ")");
        out_.unit = unit_short_name(root.unit.empty() ? "millimeter" : root.unit);

        const pugi::xml_node model = root.doc.document_element();
        std::vector<pugi::xml_node> items;
        for (pugi::xml_node build : model.children())
            if (is_element(build, "build"))
                for (pugi::xml_node item : build.children())
                    if (is_element(item, "item")) items.push_back(item);

        if (items.empty()) {
            for (uint64_t id : root.order) {
                const Object& o = root.objects.at(id);
                const std::size_t first = out_.mesh.face_count();
                if (o.has_mesh) emit(root, o, o.node);
                add_part(o.node, id, first);
            }
        } else {
            for (pugi::xml_node item : items) {
                const Component ref = parse_reference(root, item);
                Part& target = ref.path.empty() ? root : part(ref.path, root, item);
                if (ref.has_transform) {
                    transform_seen_ = true;
                    if (ref.transform != kIdentity) chain_.push_back(ref.transform);
                }
                const std::size_t first = out_.mesh.face_count();
                instantiate(target, ref.objectid, root, item, 0);
                const auto object = target.objects.find(ref.objectid);
                add_part(object != target.objects.end() ? object->second.node : pugi::xml_node(), ref.objectid, first);
                if (ref.has_transform && ref.transform != kIdentity) chain_.pop_back();
            }
        }
        if (components_seen_) out_.notes.emplace_back("3mf-components");
        if (transform_seen_) out_.notes.emplace_back("3mf-transform");
        return std::move(out_);
    }

private:
    // The faces since `first` as a part named by the object's name attribute.
    void add_part(pugi::xml_node object, uint64_t id, std::size_t first) {
        const std::size_t faces = out_.mesh.face_count() - first;
        if (faces == 0) return;
        const std::string name = object ? object.attribute("name").value() : "";
        out_.parts.push_back({name.empty() ? "object " + std::to_string(id) : name, first, faces, part_error_});
        part_error_ = 0;
    }

    [[noreturn]] void fail(const Part& p, pugi::xml_node n, std::string msg) const {
        if (!p.entry.empty()) msg += " (zip entry '" + p.entry + "')";
        const std::ptrdiff_t off = n ? n.offset_debug() : -1;
        if (off >= 0 && p.offsets_valid)
            throw ReadError(name_, xmlnum::line_at(p.text, static_cast<std::size_t>(off)), msg);
        throw ReadError::whole_file(name_, msg);
    }

    Part& part(const std::string& path, const Part& from, pugi::xml_node ref) {
        if (!zip_)
            fail(from, ref, "reference to the model part '" + path +
                                "', which cannot exist: the model is bare XML, not a 3MF package");
        const auto stored = zip_->find(path);
        if (!stored) fail(from, ref, "reference to the model part '" + path + "', which is not in the package");
        if (auto it = parts_.find(*stored); it != parts_.end()) return *it->second;
        auto p = std::make_unique<Part>();
        p->entry = *stored;
        p->owned = zip_->read(*stored);
        p->text = p->owned;
        Part& loaded = *p;
        parts_.emplace(*stored, std::move(p));
        parse_part(loaded);
        return loaded;
    }

    void parse_part(Part& p) {
        const pugi::xml_parse_result r =
            p.doc.load_buffer(p.text.data(), p.text.size(), pugi::parse_default, pugi::encoding_auto);
        if (!r) {
            std::string msg = std::string("XML parse error: ") + r.description();
            if (!p.entry.empty()) msg += " (zip entry '" + p.entry + "')";
            throw ReadError::at_byte(name_, static_cast<uint64_t>(r.offset), msg);
        }
        p.offsets_valid = r.encoding == pugi::encoding_utf8;
        const pugi::xml_node model = p.doc.document_element();
        if (!is_element(model, "model"))
            fail(p, model, std::string("the root element is <") + model.name() +
                               ">, expected <model> (a 3MF model part)");
        p.unit = model.attribute("unit").value();
        for (pugi::xml_node res : model.children()) {
            if (!is_element(res, "resources")) continue;
            for (pugi::xml_node obj : res.children())
                if (is_element(obj, "object")) parse_object(p, obj);
        }
    }

    uint64_t index_attr(const Part& p, pugi::xml_node n, const char* attr, const char* what) {
        const pugi::xml_attribute a = n.attribute(attr);
        if (!a)
            fail(p, n, "<" + std::string(local_name(n.name())) + "> without attribute " + attr +
                           ", expected " + what);
        const auto v = xmlnum::parse_index(a.value());
        if (!v)
            fail(p, n, "bad " + std::string(attr) + " " + xmlnum::quote(a.value()) + " in <" +
                           std::string(local_name(n.name())) + ">, expected " + what);
        return *v;
    }

    double number_attr(const Part& p, pugi::xml_node n, const char* attr) {
        const pugi::xml_attribute a = n.attribute(attr);
        if (!a)
            fail(p, n, "<" + std::string(local_name(n.name())) + "> without attribute " + attr +
                           ", expected a decimal number");
        const auto v = xmlnum::parse_double(a.value());
        if (!v)
            fail(p, n, "bad number " + xmlnum::quote(xmlnum::trim(a.value())) + " in attribute " + attr +
                           " of <" + std::string(local_name(n.name())) +
                           ">, expected a finite decimal number");
        return *v;
    }

    Affine parse_transform(const Part& p, pugi::xml_node n, const char* text) {
        Affine m{};
        std::string_view s(text);
        std::size_t k = 0;
        for (;;) {
            while (!s.empty() && xmlnum::is_xml_space(s.front())) s.remove_prefix(1);
            if (s.empty()) break;
            std::size_t len = 0;
            while (len < s.size() && !xmlnum::is_xml_space(s[len])) ++len;
            const std::string_view tok = s.substr(0, len);
            s.remove_prefix(len);
            if (k == 12)
                fail(p, n, "transform " + xmlnum::quote(text) + " has more than 12 numbers, expected 12");
            const auto v = xmlnum::parse_double(tok);
            if (!v)
                fail(p, n, "bad number " + xmlnum::quote(tok) + " in transform of <" +
                               std::string(local_name(n.name())) + ">, expected a finite decimal number");
            m[k++] = *v;
        }
        if (k != 12)
            fail(p, n, "transform " + xmlnum::quote(text) + " has " + std::to_string(k) +
                           " numbers, expected 12 (m00 m01 m02 m10 m11 m12 m20 m21 m22 m30 m31 m32)");
        return m;
    }

    // objectid, transform and p:path of an <item> or <component>.
    Component parse_reference(const Part& p, pugi::xml_node n) {
        Component c;
        c.node = n;
        c.objectid = index_attr(p, n, "objectid", "an object id (a non-negative integer)");
        if (const pugi::xml_attribute t = n.attribute("transform")) {
            c.has_transform = true;
            c.transform = parse_transform(p, n, t.value());
        }
        if (const pugi::xml_attribute path = attribute_local(n, "path"); path && *path.value())
            c.path = normalize_part_name(path.value());
        return c;
    }

    void parse_object(Part& p, pugi::xml_node obj) {
        const uint64_t id = index_attr(p, obj, "id", "an object id (a non-negative integer)");
        if (p.objects.count(id)) fail(p, obj, "duplicate object id " + std::to_string(id));
        Object o;
        o.node = obj;
        for (pugi::xml_node c : obj.children()) {
            if (is_element(c, "mesh")) {
                if (o.has_mesh) fail(p, c, "object " + std::to_string(id) + " has more than one <mesh>");
                o.has_mesh = true;
                parse_mesh(p, c, o.mesh);
            } else if (is_element(c, "components")) {
                o.has_components = true;
                for (pugi::xml_node comp : c.children())
                    if (is_element(comp, "component")) o.components.push_back(parse_reference(p, comp));
            }
        }
        p.order.push_back(id);
        p.objects.emplace(id, std::move(o));
    }

    void parse_mesh(const Part& p, pugi::xml_node mesh, MeshData& m) {
        std::size_t nv = 0;
        for (pugi::xml_node vs : mesh.children()) {
            if (!is_element(vs, "vertices")) continue;
            for (pugi::xml_node v : vs.children()) {
                if (!is_element(v, "vertex")) continue;
                if (nv == std::numeric_limits<uint32_t>::max())
                    fail(p, v, "more than 4294967295 vertices in one mesh");
                m.positions.push_back(number_attr(p, v, "x"));
                m.positions.push_back(number_attr(p, v, "y"));
                m.positions.push_back(number_attr(p, v, "z"));
                ++nv;
            }
        }
        for (pugi::xml_node ts : mesh.children()) {
            if (!is_element(ts, "triangles")) continue;
            for (pugi::xml_node t : ts.children()) {
                if (!is_element(t, "triangle")) continue;
                for (const char* attr : {"v1", "v2", "v3"}) {
                    const uint64_t i = index_attr(p, t, attr, "a vertex index (a non-negative integer)");
                    if (i >= nv)
                        fail(p, t, "vertex index " + std::string(attr) + "=" + std::to_string(i) +
                                       " out of range: the mesh has " + std::to_string(nv) +
                                       (nv ? " vertices (indices 0.." + std::to_string(nv - 1) + ")"
                                           : " vertices"));
                    m.triangles.push_back(static_cast<uint32_t>(i));
                }
            }
        }
        parsed_elements_ += nv + m.triangles.size() / 3;
    }

    void instantiate(Part& p, uint64_t id, const Part& from, pugi::xml_node ref, int depth) {
        const auto it = p.objects.find(id);
        if (it == p.objects.end())
            fail(from, ref, "reference to object " + std::to_string(id) + ", which is not defined" +
                                (&p != &from ? " in model part '" + p.entry + "'" : std::string()));
        if (depth >= kMaxComponentDepth)
            fail(from, ref, "components nested deeper than " + std::to_string(kMaxComponentDepth) +
                                " levels (a cycle?)");
        const auto key = std::make_pair(&p, id);
        if (!active_.insert(key).second)
            fail(from, ref, "object " + std::to_string(id) + " contains itself through its components");
        const Object& o = it->second;
        if (o.has_mesh) emit(from, o, ref);
        if (o.has_components) {
            components_seen_ = true;
            for (const Component& c : o.components) {
                Part& target = c.path.empty() ? p : part(c.path, p, c.node);
                if (c.has_transform) {
                    transform_seen_ = true;
                    if (c.transform != kIdentity) chain_.push_back(c.transform);
                }
                instantiate(target, c.objectid, p, c.node, depth + 1);
                if (c.has_transform && c.transform != kIdentity) chain_.pop_back();
            }
        }
        active_.erase(key);
    }

    // Appends an object's own mesh under the current transform chain.
    // (ref, in part p, is the item or component that led here: errors point at it.)
    void emit(const Part& p, const Object& o, pugi::xml_node ref) {
        const MeshData& m = o.mesh;
        const std::size_t nv = m.positions.size() / 3;
        const std::size_t nt = m.triangles.size() / 3;
        const std::size_t base = out_.mesh.positions.size() / 3;
        if (base + nv > std::numeric_limits<uint32_t>::max())
            fail(p, ref, "the build has more than 4294967295 vertices");
        emitted_elements_ += nv + nt;
        const uint64_t limit = std::max<uint64_t>(uint64_t{1} << 24, 1024 * parsed_elements_);
        if (emitted_elements_ > limit)
            fail(p, ref, "build items and components instantiate " + std::to_string(emitted_elements_) +
                             " vertices and triangles, more than 1024 times the " +
                             std::to_string(parsed_elements_) + " in the file; refusing to expand further");

        std::vector<double>& pos = out_.mesh.positions;
        if (chain_.empty()) {
            pos.insert(pos.end(), m.positions.begin(), m.positions.end());
        } else {
            pos.reserve(pos.size() + m.positions.size());
            for (std::size_t v = 0; v < nv; ++v) {
                double x = m.positions[3 * v], y = m.positions[3 * v + 1], z = m.positions[3 * v + 2];
                double ex = 0, ey = 0, ez = 0;  // bounds on each coordinate's error so far
                for (auto t = chain_.rbegin(); t != chain_.rend(); ++t) {  // innermost first
                    const Affine& a = *t;
                    const double nx = dot3_plus(x, a[0], y, a[3], z, a[6], a[9]);
                    const double ny = dot3_plus(x, a[1], y, a[4], z, a[7], a[10]);
                    const double nz = dot3_plus(x, a[2], y, a[5], z, a[8], a[11]);
                    // This level's rounding, plus the earlier errors through |M|.
                    auto carried = [&](double m0, double m1, double m2) {
                        return (1 + 0x1p-50) * (std::fabs(m0) * ex + std::fabs(m1) * ey + std::fabs(m2) * ez);
                    };
                    const double fx = dot3_plus_error(nx, x, a[0], y, a[3], z, a[6], a[9]) + carried(a[0], a[3], a[6]);
                    const double fy = dot3_plus_error(ny, x, a[1], y, a[4], z, a[7], a[10]) + carried(a[1], a[4], a[7]);
                    const double fz = dot3_plus_error(nz, x, a[2], y, a[5], z, a[8], a[11]) + carried(a[2], a[5], a[8]);
                    x = nx;
                    y = ny;
                    z = nz;
                    ex = fx;
                    ey = fy;
                    ez = fz;
                }
                out_.coordinate_error = std::max({out_.coordinate_error, ex, ey, ez});
                part_error_ = std::max({part_error_, ex, ey, ez});
                if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z))
                    fail(p, ref, "a transformed vertex overflows the double range");
                pos.push_back(x);
                pos.push_back(y);
                pos.push_back(z);
            }
        }
        std::vector<uint32_t>& idx = out_.mesh.indices;
        idx.reserve(idx.size() + m.triangles.size());
        const auto shift = static_cast<uint32_t>(base);
        for (uint32_t i : m.triangles) idx.push_back(i + shift);
    }

    const std::string& name_;
    ZipArchive* zip_;
    std::map<std::string, std::unique_ptr<Part>> parts_;
    std::vector<Affine> chain_;  // outermost first
    std::set<std::pair<const Part*, uint64_t>> active_;
    uint64_t parsed_elements_ = 0;
    uint64_t emitted_elements_ = 0;
    bool transform_seen_ = false;
    bool components_seen_ = false;
    double part_error_ = 0;  // the coordinate error of the part being read (LoadedMesh::parts)
    LoadedMesh out_;
};

// The model part named by _rels/.rels (relationship type .../3dmodel), else 3D/3dmodel.model.
std::string find_model_part(ZipArchive& zip, const std::string& name) {
    std::string why;
    if (const auto rels = zip.find("_rels/.rels")) {
        const std::vector<std::byte> bytes = zip.read(*rels);
        pugi::xml_document doc;
        if (doc.load_buffer(bytes.data(), bytes.size(), pugi::parse_default, pugi::encoding_auto)) {
            for (pugi::xml_node rel : doc.document_element().children()) {
                if (!is_element(rel, "Relationship")) continue;
                const std::string_view type = rel.attribute("Type").value();
                constexpr std::string_view suffix = "/3dmodel";
                if (type.size() < suffix.size() || type.substr(type.size() - suffix.size()) != suffix)
                    continue;
                const std::string target = normalize_part_name(rel.attribute("Target").value());
                if (const auto found = zip.find(target)) return *found;
                if (why.empty()) why = "_rels/.rels names the model part '" + target + "', which is missing";
            }
            if (why.empty()) why = "_rels/.rels names no 3D model part";
        } else {
            why = "_rels/.rels is not well-formed XML";
        }
    } else {
        why = "there is no _rels/.rels";
    }
    if (const auto found = zip.find("3D/3dmodel.model")) return *found;
    throw ReadError::whole_file(name, "not a 3MF package: " + why + " and there is no 3D/3dmodel.model");
}

}  // namespace

LoadedMesh read_3mf_zip(Bytes data, const std::string& name) {
    ZipArchive zip(data, name);
    auto root = std::make_unique<Part>();
    root->entry = find_model_part(zip, name);
    root->owned = zip.read(root->entry);
    root->text = root->owned;
    Reader reader(name, &zip);
    return reader.read(std::move(root));
}

LoadedMesh read_3mf_xml(Bytes data, const std::string& name) {
    auto root = std::make_unique<Part>();
    root->text = data;
    Reader reader(name, nullptr);
    return reader.read(std::move(root));
}

}  // namespace polyvol::io

// glTF 2.0: a .gltf (JSON, its buffers in .bin files beside it or in data:
// URIs) or a .glb (binary container). tinygltf parses the document; this
// file turns the default scene into one Mesh:
//   * every node with a mesh, its world transform the product of its
//     ancestors' (matrix, or translation · rotation · scale);
//   * every primitive of mode TRIANGLES (4), TRIANGLE_STRIP (5, every other
//     triangle reversed so that all keep the strip's orientation) or
//     TRIANGLE_FAN (6); points and lines are skipped, with a note;
//   * positions of any component type the spec allows (FLOAT, and with
//     KHR_mesh_quantization (UNSIGNED_)BYTE and (UNSIGNED_)SHORT, normalized
//     or not), sparse accessors included; indices UNSIGNED_BYTE, _SHORT, _INT.
// glTF lengths are metres (LoadedMesh::unit "m"). A buffer the document
// names is read only from the file's own directory or below it.
// Draco (KHR_draco_mesh_compression) and meshopt (EXT_meshopt_compression)
// buffers are refused by name: neither decoder is linked.
//
// Exactness. FLOAT positions are exact doubles; a normalized integer is
// c / (2^(b-1) - 1) or c / (2^b - 1), rounded once. An identity world
// transform leaves the coordinates untouched; any other is applied in
// double, and LoadedMesh::coordinate_error bounds the difference from the
// exact transform of the file's numbers (docs/numerics.md, "glTF transforms").
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "io/readers.hpp"
#include "polyvol/io.hpp"

namespace polyvol::io {
namespace {

constexpr double kU = 0x1p-53;

// An affine map x -> A x + t (A row-major, rows (a_i0 a_i1 a_i2 t_i)), with
// entrywise bounds: abs >= the magnitudes of the exact entries and of the
// computed ones, err >= |computed - exact| from the inputs' own errors (a
// quaternion's rotation). The roundings of the products are the γ term of
// the point bound (`levels` of them), apart from err.
struct Affine {
    std::array<double, 12> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    std::array<double, 12> abs{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    std::array<double, 12> err{};
    int levels = 0;  // products rounded into m
    // Exactly the identity, nothing rounded on the way.
    bool exact_identity() const { return m == Affine{}.m && levels == 0; }
};

// p ∘ l: entries Σ_k p_ik l_kj (+ p_i3 for the translation); its err is the
// first-order propagation |p| err_l + err_p |l| + err_p err_l.
Affine compose(const Affine& p, const Affine& l) {
    Affine r;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 4; ++j) {
            const bool t = j == 3;
            double v = t ? p.m[4 * i + 3] : 0, a = t ? p.abs[4 * i + 3] : 0, e = t ? p.err[4 * i + 3] : 0;
            for (int k = 0; k < 3; ++k) {
                v += p.m[4 * i + k] * l.m[4 * k + j];
                a += p.abs[4 * i + k] * l.abs[4 * k + j];
                e += p.abs[4 * i + k] * l.err[4 * k + j] + p.err[4 * i + k] * (l.abs[4 * k + j] + l.err[4 * k + j]);
            }
            r.m[4 * i + j] = v;
            r.abs[4 * i + j] = a;
            r.err[4 * i + j] = e * (1 + 8 * kU);
        }
    r.levels = p.levels + l.levels + 1;
    return r;
}

// A node's own transform. A matrix is the file's numbers (column-major);
// T · R · S computes R from the quaternion (x, y, z, w): each entry within
// 12 u max(1, |q|²) of the formula's value, then times the scale.
Affine local(const tinygltf::Node& n) {
    Affine a;
    if (n.matrix.size() == 16) {
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 4; ++j) a.m[4 * i + j] = n.matrix[4 * j + i];
        for (int k = 0; k < 12; ++k) a.abs[k] = std::fabs(a.m[k]);
        if (n.matrix[3] != 0 || n.matrix[7] != 0 || n.matrix[11] != 0 || n.matrix[15] != 1)
            throw std::invalid_argument("a node's matrix is not affine (its last row is not 0 0 0 1)");
        return a;
    }
    double R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1}, rerr = 0;
    if (n.rotation.size() == 4) {
        const double x = n.rotation[0], y = n.rotation[1], z = n.rotation[2], w = n.rotation[3];
        const double R2[9] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),
                              2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
                              2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y)};
        std::copy(R2, R2 + 9, R);
        rerr = 12 * kU * std::max(1.0, x * x + y * y + z * z + w * w);
    }
    const double S[3] = {n.scale.size() == 3 ? n.scale[0] : 1, n.scale.size() == 3 ? n.scale[1] : 1,
                         n.scale.size() == 3 ? n.scale[2] : 1};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            a.m[4 * i + j] = R[3 * i + j] * S[j];
            a.abs[4 * i + j] = (std::fabs(R[3 * i + j]) + rerr) * std::fabs(S[j]) * (1 + kU);
            a.err[4 * i + j] = rerr * std::fabs(S[j]) * (1 + kU);
        }
        a.m[4 * i + 3] = n.translation.size() == 3 ? n.translation[i] : 0;
        a.abs[4 * i + 3] = std::fabs(a.m[4 * i + 3]);
    }
    a.levels = n.rotation.size() == 4 || n.scale.size() == 3 ? 1 : 0;
    return a;
}

// Reads files for tinygltf: only below the glTF file's own directory.
struct Files {
    std::filesystem::path base;
};
bool file_exists(const std::string& path, void*) {
    std::error_code ec;  // a name too long, a loop of links: not there
    return std::filesystem::is_regular_file(path, ec);
}
std::string expand_path(const std::string& path, void*) { return path; }
bool read_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
    const auto* files = static_cast<const Files*>(user);
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(fs::path(path), ec);
    const fs::path base = fs::weakly_canonical(files->base, ec);
    const auto rel = p.lexically_relative(base);
    if (ec || files->base.empty() || rel.empty() || *rel.begin() == "..") {
        if (err) *err += "a buffer outside the glTF file's directory is not read: " + path + "\n";
        return false;
    }
    std::ifstream in(p, std::ios::binary);
    if (!in) {
        if (err) *err += "cannot open the buffer " + path + "\n";
        return false;
    }
    out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    return true;
}
bool no_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
    if (err) *err += "writing is not allowed\n";
    return false;
}
bool ignore_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

class Reader {
public:
    // budget: the most vertices (and triangles) the whole scene may have.
    Reader(const tinygltf::Model& model, const std::string& name, std::size_t budget)
        : model_(model), name_(name), budget_(budget) {}
    std::size_t budget() const { return budget_; }

    // The bytes of element i of an accessor: its buffer view's, checked
    // against the buffer, or nullptr for an accessor without a view (zeros).
    const unsigned char* element(const tinygltf::Accessor& a, std::size_t i, std::size_t size) const {
        if (a.bufferView < 0) return nullptr;
        const tinygltf::BufferView& v = view(a.bufferView);  // checked against its buffer (check_views)
        const std::size_t stride = v.byteStride ? v.byteStride : size;
        // a.byteOffset + i * stride + size <= v.byteLength, without overflow
        if (a.byteOffset > v.byteLength || size > v.byteLength - a.byteOffset ||
            i > (v.byteLength - a.byteOffset - size) / std::max<std::size_t>(stride, 1))
            fail("an accessor reads past the end of its buffer view");
        return buffer(v.buffer).data.data() + v.byteOffset + a.byteOffset + i * stride;
    }

    // Every buffer view within its buffer, with a stride the spec allows.
    void check_views() const {
        for (const tinygltf::BufferView& v : model_.bufferViews) {
            const tinygltf::Buffer& b = buffer(v.buffer);
            if (v.byteOffset > b.data.size() || v.byteLength > b.data.size() - v.byteOffset)
                fail("a buffer view runs past the end of its buffer");
            if (v.byteStride != 0 && (v.byteStride < 4 || v.byteStride > 252)) fail("a buffer view's byteStride is not 4 .. 252");
        }
    }

    // Component c of element i as a double (normalized integers mapped as the spec says).
    static double component(const unsigned char* p, int type, bool normalized, int c) {
        switch (type) {
            case TINYGLTF_COMPONENT_TYPE_FLOAT: {
                float f;
                std::memcpy(&f, p + 4 * c, 4);
                return f;
            }
            case TINYGLTF_COMPONENT_TYPE_BYTE: {
                const auto v = static_cast<signed char>(p[c]);
                return normalized ? std::max(v / 127.0, -1.0) : v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[c] / 255.0 : p[c];
            case TINYGLTF_COMPONENT_TYPE_SHORT: {
                int16_t v;
                std::memcpy(&v, p + 2 * c, 2);
                return normalized ? std::max(v / 32767.0, -1.0) : v;
            }
            case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                uint16_t v;
                std::memcpy(&v, p + 2 * c, 2);
                return normalized ? v / 65535.0 : v;
            }
            default: return 0;
        }
    }

    // Positions: count × 3 doubles, sparse substitutions applied. `rounded`
    // is set when a normalized integer was divided (each within u of its value).
    std::vector<double> positions(int index, bool& rounded) const {
        const tinygltf::Accessor& a = accessor(index);
        if (a.type != TINYGLTF_TYPE_VEC3) fail("POSITION is not a VEC3 accessor");
        const int ct = a.componentType;
        const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(ct));
        if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT || ct == TINYGLTF_COMPONENT_TYPE_INT ||
            ct == TINYGLTF_COMPONENT_TYPE_DOUBLE || size <= 0)
            fail("POSITION has a component type the spec does not allow (" + std::to_string(ct) + ")");
        rounded = a.normalized && ct != TINYGLTF_COMPONENT_TYPE_FLOAT;
        if (a.bufferView < 0 && !a.sparse.isSparse) fail("a POSITION accessor without data (no buffer view, not sparse)");
        if (a.count > budget_) fail("a POSITION accessor of " + std::to_string(a.count) + " vertices, more than this file can hold");
        std::vector<double> out(3 * a.count, 0.0);
        if (a.bufferView >= 0) check_count(a, 3 * static_cast<std::size_t>(size));
        for (std::size_t i = 0; i < a.count; ++i)
            if (const unsigned char* p = element(a, i, 3 * static_cast<std::size_t>(size)))
                for (int c = 0; c < 3; ++c) out[3 * i + c] = component(p, ct, a.normalized, c);
        if (a.sparse.isSparse) {
            if (a.sparse.count < 0 || static_cast<std::size_t>(a.sparse.count) > a.count) fail("a sparse count exceeds the accessor's");
            tinygltf::Accessor idx, val;
            idx.bufferView = a.sparse.indices.bufferView;
            idx.byteOffset = static_cast<std::size_t>(std::max(0, a.sparse.indices.byteOffset));
            idx.componentType = a.sparse.indices.componentType;
            val.bufferView = a.sparse.values.bufferView;
            val.byteOffset = static_cast<std::size_t>(std::max(0, a.sparse.values.byteOffset));
            const int isize = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(idx.componentType));
            if (idx.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                idx.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                idx.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
                fail("sparse indices are not unsigned bytes, shorts or ints");
            if (isize <= 0 || idx.bufferView < 0 || val.bufferView < 0) fail("a sparse accessor without its indices or values");
            for (int s = 0; s < a.sparse.count; ++s) {
                const std::size_t i = index_at(element(idx, static_cast<std::size_t>(s), static_cast<std::size_t>(isize)), idx.componentType);
                if (i >= a.count) fail("a sparse index past the accessor's count");
                const unsigned char* p = element(val, static_cast<std::size_t>(s), 3 * static_cast<std::size_t>(size));
                for (int c = 0; c < 3; ++c) out[3 * i + c] = component(p, ct, a.normalized, c);
            }
        }
        return out;
    }

    // Indices of a primitive (its accessor), or 0 .. vertices - 1.
    std::vector<uint32_t> indices(int index, std::size_t vertices) const {
        std::vector<uint32_t> out;
        if (index < 0) {
            out.resize(vertices);
            for (std::size_t i = 0; i < vertices; ++i) out[i] = static_cast<uint32_t>(i);
            return out;
        }
        const tinygltf::Accessor& a = accessor(index);
        const int size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
        if (a.type != TINYGLTF_TYPE_SCALAR ||
            (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
             a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
             a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
            fail("indices are not an unsigned byte, short or int scalar accessor");
        if (a.bufferView < 0) fail("an indices accessor without a buffer view");
        check_count(a, static_cast<std::size_t>(size));
        out.resize(a.count);
        for (std::size_t i = 0; i < a.count; ++i) {
            const std::size_t v = index_at(element(a, i, static_cast<std::size_t>(size)), a.componentType);
            if (v >= vertices) fail("an index " + std::to_string(v) + " past the " + std::to_string(vertices) + " vertices");
            out[i] = static_cast<uint32_t>(v);
        }
        return out;
    }

    [[noreturn]] void fail(const std::string& what) const { throw ReadError::whole_file(name_, "glTF: " + what); }

private:
    static std::size_t index_at(const unsigned char* p, int type) {
        if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) return p[0];
        if (type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            uint16_t v;
            std::memcpy(&v, p, 2);
            return v;
        }
        uint32_t v;
        std::memcpy(&v, p, 4);
        return v;
    }
    // An accessor's count against its view before anything is allocated from it.
    void check_count(const tinygltf::Accessor& a, std::size_t element_size) const {
        const tinygltf::BufferView& v = view(a.bufferView);
        const std::size_t stride = std::max<std::size_t>(v.byteStride ? v.byteStride : element_size, 1);
        if (a.count > 0 && (a.count - 1) > v.byteLength / stride) fail("an accessor's count exceeds its buffer view");
    }
    const tinygltf::Accessor& accessor(int i) const {
        if (i < 0 || static_cast<std::size_t>(i) >= model_.accessors.size()) fail("an accessor index out of range");
        return model_.accessors[static_cast<std::size_t>(i)];
    }
    const tinygltf::BufferView& view(int i) const {
        if (i < 0 || static_cast<std::size_t>(i) >= model_.bufferViews.size()) fail("a buffer view index out of range");
        return model_.bufferViews[static_cast<std::size_t>(i)];
    }
    const tinygltf::Buffer& buffer(int i) const {
        if (i < 0 || static_cast<std::size_t>(i) >= model_.buffers.size()) fail("a buffer index out of range");
        return model_.buffers[static_cast<std::size_t>(i)];
    }

    const tinygltf::Model& model_;
    const std::string& name_;
    std::size_t budget_;
};

bool compressed_by(const tinygltf::Model& m, const std::string& ext) {
    const auto& req = m.extensionsRequired;
    const auto& used = m.extensionsUsed;
    return std::find(req.begin(), req.end(), ext) != req.end() || std::find(used.begin(), used.end(), ext) != used.end();
}

}  // namespace

bool is_glb(Bytes head) { return head.size() >= 4 && std::memcmp(head.data(), "glTF", 4) == 0; }

// The deepest nesting of arrays and objects in JSON text (outside strings):
// tinygltf parses it recursively, so a document nested thousands deep would
// overflow the stack.
std::size_t json_depth(std::string_view text) {
    std::size_t depth = 0, deepest = 0;
    bool in_string = false;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (in_string) {
            if (c == '\\') ++i;
            else if (c == '"') in_string = false;
        } else if (c == '"') {
            in_string = true;
        } else if (c == '[' || c == '{') {
            deepest = std::max(deepest, ++depth);
        } else if ((c == ']' || c == '}') && depth > 0) {
            --depth;
        }
    }
    return deepest;
}

LoadedMesh read_gltf_checked(Bytes data, const std::string& name);

LoadedMesh read_gltf(Bytes data, const std::string& name) {
    try {
        return read_gltf_checked(data, name);
    } catch (const ReadError&) {
        throw;
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {  // tinygltf's and the file system's own
        throw ReadError::whole_file(name, std::string("glTF: ") + e.what());
    }
}

LoadedMesh read_gltf_checked(Bytes data, const std::string& name) {
    tinygltf::TinyGLTF loader;
    Files files;
    const std::filesystem::path p(name);
    files.base = p.has_parent_path() ? p.parent_path() : std::filesystem::path(".");
    if (name == "<stdin>") files.base.clear();
    loader.SetFsCallbacks({&file_exists, &expand_path, &read_file, &no_write, &files});
    loader.SetImageLoader(&ignore_image, nullptr);
    tinygltf::Model model;
    std::string err, warn;
    const bool glb = is_glb(data);
    if (data.size() > UINT32_MAX) throw ReadError::whole_file(name, "glTF: larger than 4 GiB");
    const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
    {
        // The JSON: all of a .gltf, a .glb's first chunk (its length at byte 12).
        std::string_view json(reinterpret_cast<const char*>(bytes), data.size());
        if (glb && data.size() >= 20) {
            uint32_t length = 0;
            std::memcpy(&length, bytes + 12, 4);
            json = json.substr(20, std::min<std::size_t>(length, data.size() - 20));
        }
        if (json_depth(json) > 200) throw ReadError::whole_file(name, "glTF: JSON nested more than 200 levels deep");
    }
    const bool ok = glb ? loader.LoadBinaryFromMemory(&model, &err, &warn, bytes, static_cast<unsigned>(data.size()),
                                                      files.base.string())
                        : loader.LoadASCIIFromString(&model, &err, &warn, reinterpret_cast<const char*>(bytes),
                                                     static_cast<unsigned>(data.size()), files.base.string());
    if (!ok) {
        while (!err.empty() && err.back() == '\n') err.pop_back();
        throw ReadError::whole_file(name, "glTF: " + (err.empty() ? std::string("not a valid glTF document") : err));
    }
    for (const char* ext : {"KHR_draco_mesh_compression", "EXT_meshopt_compression", "KHR_meshopt_compression"})
        if (compressed_by(model, ext))
            throw ReadError::whole_file(name, std::string("glTF: its meshes are compressed with ") + ext +
                                                  ", which polyvol does not decode: export it without that compression");

    LoadedMesh out;
    out.format = Format::gltf;
    out.encoding = glb ? "glb" : "json";
    out.unit = "m";
    // The whole scene's vertices and triangles, instances included: at most
    // 2^22 plus 64 per byte of the file (a mesh instanced many times is
    // legitimate; a kilobyte that instances itself into billions is not).
    const Reader reader(model, name, (std::size_t{1} << 22) + 64 * data.size());
    reader.check_views();
    std::size_t skipped = 0;
    bool transformed = false;
    Mesh& mesh = out.mesh;

    // One mesh instance under its world transform.
    const auto add_mesh = [&](int index, const Affine& world) {
        if (index < 0 || static_cast<std::size_t>(index) >= model.meshes.size()) reader.fail("a mesh index out of range");
        for (const tinygltf::Primitive& prim : model.meshes[static_cast<std::size_t>(index)].primitives) {
            const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
            if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
                ++skipped;
                continue;
            }
            const auto pos = prim.attributes.find("POSITION");
            if (pos == prim.attributes.end()) reader.fail("a triangle primitive without POSITION");
            bool rounded = false;
            const std::vector<double> xyz = reader.positions(pos->second, rounded);
            const std::size_t n = xyz.size() / 3;
            if (mesh.vertex_count() + n > std::min<std::size_t>(reader.budget(), UINT32_MAX - 1))
                reader.fail("the scene's instances add up to more vertices than this file can hold");
            const auto base = static_cast<uint32_t>(mesh.vertex_count());
            const bool identity = world.exact_identity();
            transformed = transformed || !identity;
            const double scale = (4 * (world.levels + 1 + (rounded ? 1 : 0))) * kU * 1.01;
            for (std::size_t v = 0; v < n; ++v) {
                const double* q = &xyz[3 * v];
                if (identity) {
                    mesh.add_vertex(q[0], q[1], q[2]);
                    if (rounded)
                        out.coordinate_error = std::max({out.coordinate_error, kU * std::fabs(q[0]), kU * std::fabs(q[1]),
                                                         kU * std::fabs(q[2])});
                    continue;
                }
                double r[3];
                for (int i = 0; i < 3; ++i) {
                    const double* m = &world.m[4 * i];
                    const double* a = &world.abs[4 * i];
                    const double* e = &world.err[4 * i];
                    r[i] = m[0] * q[0] + m[1] * q[1] + m[2] * q[2] + m[3];
                    const double size = a[0] * std::fabs(q[0]) + a[1] * std::fabs(q[1]) + a[2] * std::fabs(q[2]) + a[3];
                    const double entries = e[0] * std::fabs(q[0]) + e[1] * std::fabs(q[1]) + e[2] * std::fabs(q[2]) + e[3];
                    out.coordinate_error = std::max(out.coordinate_error, (scale * size + entries) * (1 + 8 * kU));
                }
                mesh.add_vertex(r[0], r[1], r[2]);
            }
            const std::vector<uint32_t> idx = reader.indices(prim.indices, n);
            if (mesh.indices.size() / 3 + idx.size() > reader.budget())
                reader.fail("the scene's instances add up to more triangles than this file can hold");
            if (mode == TINYGLTF_MODE_TRIANGLES) {
                for (std::size_t t = 0; t + 2 < idx.size(); t += 3) mesh.add_triangle(base + idx[t], base + idx[t + 1], base + idx[t + 2]);
            } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                for (std::size_t t = 0; t + 2 < idx.size(); ++t) {
                    const uint32_t a = idx[t], b = idx[t + 1], c = idx[t + 2];
                    if (t % 2 == 0) mesh.add_triangle(base + a, base + b, base + c);
                    else mesh.add_triangle(base + b, base + a, base + c);
                }
            } else {
                for (std::size_t t = 1; t + 1 < idx.size(); ++t) mesh.add_triangle(base + idx[0], base + idx[t], base + idx[t + 1]);
            }
        }
    };

    // The default scene's nodes, depth first; a node met twice on one path is a cycle.
    const int scene = model.defaultScene >= 0 ? model.defaultScene : model.scenes.empty() ? -1 : 0;
    if (scene < 0) {
        for (std::size_t m = 0; m < model.meshes.size(); ++m) add_mesh(static_cast<int>(m), Affine{});
        out.notes.emplace_back("gltf-no-scene-all-meshes");
    } else {
        if (static_cast<std::size_t>(scene) >= model.scenes.size()) reader.fail("the default scene does not exist");
        std::vector<char> on_path(model.nodes.size(), 0);
        std::size_t visits = 0;
        const auto visit = [&](const auto& self, int node, const Affine& parent, int depth) -> void {
            if (node < 0 || static_cast<std::size_t>(node) >= model.nodes.size()) reader.fail("a node index out of range");
            if (depth > 1000) reader.fail("the node hierarchy is more than 1000 levels deep");
            if (on_path[static_cast<std::size_t>(node)]) reader.fail("the node hierarchy has a cycle");
            if (++visits > (std::size_t{1} << 24)) reader.fail("more than 2^24 node instances");
            const tinygltf::Node& n = model.nodes[static_cast<std::size_t>(node)];
            Affine world;
            try {
                const Affine own = local(n);
                world = own.exact_identity() ? parent : parent.exact_identity() ? own : compose(parent, own);
            } catch (const std::invalid_argument& e) {
                reader.fail(e.what());
            }
            on_path[static_cast<std::size_t>(node)] = 1;
            if (n.mesh >= 0) {
                const std::size_t first = mesh.face_count();
                const double before = out.coordinate_error;
                out.coordinate_error = 0;
                add_mesh(n.mesh, world);
                const double own = out.coordinate_error;
                out.coordinate_error = std::max(before, own);
                const std::string& mesh_name = model.meshes[static_cast<std::size_t>(n.mesh)].name;
                if (mesh.face_count() > first)
                    out.parts.push_back({!n.name.empty() ? n.name : !mesh_name.empty() ? mesh_name : "node " + std::to_string(node),
                                         first, mesh.face_count() - first, own});
            }
            for (int child : n.children) self(self, child, world, depth + 1);
            on_path[static_cast<std::size_t>(node)] = 0;
        };
        for (int root : model.scenes[static_cast<std::size_t>(scene)].nodes) visit(visit, root, Affine{}, 0);
    }
    if (transformed) out.notes.emplace_back("gltf-transform");
    if (skipped) out.notes.push_back("gltf-non-triangle-primitives-skipped(" + std::to_string(skipped) + ")");
    out.vertices_in_file = mesh.vertex_count();
    return out;
}

}  // namespace polyvol::io

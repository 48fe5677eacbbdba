// Helpers for the reader tests: bytes from strings, writers for every text
// and binary format (so identities can be checked), a hand-made gzip encoder
// (stored blocks, so the tests need no zlib), and error expectations.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "polyvol/io.hpp"

namespace iotest {

using polyvol::Format;
using polyvol::LoadedMesh;
using polyvol::Mesh;
using polyvol::ReadError;

inline std::span<const std::byte> as_bytes(const std::string& s) {
    return {reinterpret_cast<const std::byte*>(s.data()), s.size()};
}

inline LoadedMesh read(const std::string& content, const std::string& name, Format hint = Format::unknown) {
    return polyvol::read_mesh_memory(as_bytes(content), name, hint);
}

// Runs f, which must throw ReadError; returns it.
inline ReadError expect_error(const std::function<void()>& f) {
    try {
        f();
    } catch (const ReadError& e) {
        return e;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "expected ReadError, got another exception: " << e.what();
        return ReadError::whole_file("?", "?");
    }
    ADD_FAILURE() << "expected ReadError, nothing was thrown";
    return ReadError::whole_file("?", "?");
}

inline ReadError read_error(const std::string& content, const std::string& name, Format hint = Format::unknown) {
    return expect_error([&] { (void)read(content, name, hint); });
}

// Shortest decimal that reads back to exactly v.
inline std::string num(double v) {
    char buf[40];
    for (int prec = 1; prec <= 17; ++prec) {
        std::snprintf(buf, sizeof buf, "%.*g", prec, v);
        if (std::strtod(buf, nullptr) == v) break;
    }
    return buf;
}

inline void put_u16(std::string& s, uint16_t v, bool be = false) {
    if (be) {
        s += static_cast<char>(v >> 8);
        s += static_cast<char>(v & 0xff);
    } else {
        s += static_cast<char>(v & 0xff);
        s += static_cast<char>(v >> 8);
    }
}
inline void put_u32(std::string& s, uint32_t v, bool be = false) {
    for (int i = 0; i < 4; ++i) {
        const int shift = be ? 8 * (3 - i) : 8 * i;
        s += static_cast<char>((v >> shift) & 0xff);
    }
}
inline void put_f32(std::string& s, float f, bool be = false) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    put_u32(s, u, be);
}
inline void put_f64(std::string& s, double d, bool be = false) {
    uint64_t u;
    std::memcpy(&u, &d, 8);
    for (int i = 0; i < 8; ++i) {
        const int shift = be ? 8 * (7 - i) : 8 * i;
        s += static_cast<char>((u >> shift) & 0xff);
    }
}

inline std::vector<uint32_t> face_of(const Mesh& m, std::size_t f) {
    const auto v = m.view().face(f);
    return {v.begin(), v.end()};
}

// ---- writers -------------------------------------------------------------
// (Strings are built by appending: GCC 12 warns falsely on "literal" + string.)

// "x y z" of vertex i, each the shortest decimal that reads back exactly.
inline std::string xyz(const Mesh& m, std::size_t i) {
    std::string s = num(m.positions[3 * i]);
    s += ' ';
    s += num(m.positions[3 * i + 1]);
    s += ' ';
    s += num(m.positions[3 * i + 2]);
    return s;
}

inline std::string write_ascii_stl(const Mesh& m, const std::string& solid = "test") {
    std::string s = "solid ";
    s += solid;
    s += '\n';
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        s += "  facet normal 0 0 1\n    outer loop\n";
        for (uint32_t i : face_of(m, f)) {
            s += "      vertex ";
            s += xyz(m, i);
            s += '\n';
        }
        s += "    endloop\n  endfacet\n";
    }
    s += "endsolid ";
    s += solid;
    s += '\n';
    return s;
}

// Triangles only; coordinates must be float32 values.
inline std::string write_binary_stl(const Mesh& m, const std::string& header = "binary") {
    std::string s = header;
    s.resize(80, ' ');
    put_u32(s, static_cast<uint32_t>(m.face_count()));
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        for (int k = 0; k < 3; ++k) put_f32(s, 0.0f);
        for (uint32_t i : face_of(m, f))
            for (int k = 0; k < 3; ++k) put_f32(s, static_cast<float>(m.positions[3 * i + k]));
        put_u16(s, 0);
    }
    return s;
}

inline std::string write_obj(const Mesh& m) {
    std::string s = "# test\no test\n";
    for (std::size_t i = 0; i < m.vertex_count(); ++i) {
        s += "v ";
        s += xyz(m, i);
        s += '\n';
    }
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        s += "f";
        for (uint32_t i : face_of(m, f)) {
            s += ' ';
            s += std::to_string(i + 1);
        }
        s += '\n';
    }
    return s;
}

inline std::string write_off(const Mesh& m) {
    std::string s = "OFF\n";
    s += std::to_string(m.vertex_count());
    s += ' ';
    s += std::to_string(m.face_count());
    s += " 0\n";
    for (std::size_t i = 0; i < m.vertex_count(); ++i) {
        s += xyz(m, i);
        s += '\n';
    }
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const auto face = face_of(m, f);
        s += std::to_string(face.size());
        for (uint32_t i : face) {
            s += ' ';
            s += std::to_string(i);
        }
        s += '\n';
    }
    return s;
}

enum class PlyEnc { ascii, le, be };

// Vertex x y z as float (coordinates must be float32 values), an extra
// uchar property, faces as "list uchar int vertex_indices".
inline std::string write_ply(const Mesh& m, PlyEnc enc) {
    const char* fmt = enc == PlyEnc::ascii ? "ascii" : enc == PlyEnc::le ? "binary_little_endian" : "binary_big_endian";
    std::string s = "ply\nformat ";
    s += fmt;
    s += " 1.0\ncomment test\nelement vertex ";
    s += std::to_string(m.vertex_count());
    s += "\nproperty float x\nproperty float y\nproperty float z\nproperty uchar red\nelement face ";
    s += std::to_string(m.face_count());
    s += "\nproperty list uchar int vertex_indices\nend_header\n";
    const bool be = enc == PlyEnc::be;
    for (std::size_t i = 0; i < m.vertex_count(); ++i) {
        if (enc == PlyEnc::ascii) {
            s += xyz(m, i);
            s += " 7\n";
        } else {
            for (int k = 0; k < 3; ++k) put_f32(s, static_cast<float>(m.positions[3 * i + k]), be);
            s += '\x07';
        }
    }
    for (std::size_t f = 0; f < m.face_count(); ++f) {
        const auto face = face_of(m, f);
        if (enc == PlyEnc::ascii) {
            s += std::to_string(face.size());
            for (uint32_t i : face) {
                s += ' ';
                s += std::to_string(i);
            }
            s += '\n';
        } else {
            s += static_cast<char>(face.size());
            for (uint32_t i : face) put_u32(s, i, be);
        }
    }
    return s;
}

// ---- gzip (stored blocks) ------------------------------------------------

inline uint32_t crc32(const std::string& s) {
    uint32_t c = 0xffffffffu;
    for (unsigned char b : s) {
        c ^= b;
        for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xedb88320u & (0u - (c & 1u)));
    }
    return c ^ 0xffffffffu;
}

inline std::string gzip_stored(const std::string& data) {
    std::string s("\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\xff", 10);
    std::size_t pos = 0;
    do {
        const std::size_t n = std::min<std::size_t>(data.size() - pos, 65535);
        const bool last = pos + n == data.size();
        s += static_cast<char>(last ? 1 : 0);
        put_u16(s, static_cast<uint16_t>(n));
        put_u16(s, static_cast<uint16_t>(~n & 0xffff));
        s.append(data, pos, n);
        pos += n;
    } while (pos < data.size());
    put_u32(s, crc32(data));
    put_u32(s, static_cast<uint32_t>(data.size()));
    return s;
}

// ---- a test mesh ---------------------------------------------------------

// An octahedron with float32-exact, non-trivial coordinates, outward faces.
inline Mesh octahedron() {
    Mesh m;
    const double a = 1.25, b = -0.375, c = 3.0517578125e-05, d = 1e3 + 0.5;
    m.add_vertex(a, c, 0.5);
    m.add_vertex(-a, c, 0.5);
    m.add_vertex(0, a + 1, 0.5);
    m.add_vertex(0, b, 0.5);
    m.add_vertex(0, c, d);
    m.add_vertex(-0.0, c, -d);
    const uint32_t f[8][3] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
    for (const auto& t : f) m.add_triangle(t[0], t[1], t[2]);
    return m;
}

// A cube with quad faces (and so compressed rows), float32-exact.
inline Mesh quad_cube() {
    Mesh m;
    for (int i = 0; i < 8; ++i) m.add_vertex((i & 1) ? 1.5 : -0.25, (i & 2) ? 2.0 : 0.0, (i & 4) ? 0.125 : -1.0);
    const uint32_t f[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : f) m.add_face(q);
    return m;
}

}  // namespace iotest

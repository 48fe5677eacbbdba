// The glTF reader on hostile documents (a review of src/io/gltf.cpp): every
// one is a ReadError naming what is wrong, never a crash, a read outside the
// buffers, a blown stack or an allocation sized by the file; and a transform
// that rounds to the identity is not taken as exact.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "polyvol/io.hpp"

namespace {

using polyvol::Format;
using polyvol::ReadError;

std::vector<std::byte> bytes(const std::string& s) {
    const auto* p = reinterpret_cast<const std::byte*>(s.data());
    return {p, p + s.size()};
}

std::string error_of(const std::string& json) {
    try {
        (void)polyvol::read_mesh_memory(bytes(json), "<stdin>", Format::gltf);
    } catch (const ReadError& e) {
        return e.what();
    }
    return "";
}

// A tetrahedron's 4 float positions and 12 unsigned-byte indices, base64 (48 + 12 bytes).
const std::string kTetData =
    "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAIBAAEDAAMCAQID";

std::string doc(const std::string& views, const std::string& accessors, const std::string& nodes,
                const std::string& extra = "") {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"buffers":[{"byteLength":60,"uri":")" +
           kTetData + R"("}],"bufferViews":)" + views + R"(,"accessors":)" + accessors +
           R"(,"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],"nodes":)" + nodes + extra + "}";
}

const std::string kViews = R"([{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}])";
const std::string kAccessors =
    R"([{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},{"bufferView":1,"componentType":5121,"count":12,"type":"SCALAR"}])";

TEST(Gltf, TheTetrahedronReads) {
    const polyvol::LoadedMesh m =
        polyvol::read_mesh_memory(bytes(doc(kViews, kAccessors, R"([{"mesh":0}])")), "<stdin>", Format::gltf);
    EXPECT_EQ(m.mesh.face_count(), 4u);
    EXPECT_EQ(m.coordinate_error, 0.0);
}

TEST(Gltf, ViewsAndAccessorsOutsideTheirBuffersAreRefused) {
    const std::string far_view =
        R"([{"buffer":0,"byteOffset":18446744073709551608,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}])";
    EXPECT_NE(error_of(doc(far_view, kAccessors, R"([{"mesh":0}])")).find("glTF"), std::string::npos);
    const std::string long_view = R"([{"buffer":0,"byteOffset":40,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}])";
    EXPECT_NE(error_of(doc(long_view, kAccessors, R"([{"mesh":0}])")).find("past the end of its buffer"), std::string::npos);
    const std::string sparse_bytes =
        R"([{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","sparse":{"count":1,"indices":{"bufferView":1,"byteOffset":11,"componentType":5120},"values":{"bufferView":0}}},)"
        R"({"bufferView":1,"componentType":5121,"count":12,"type":"SCALAR"}])";
    EXPECT_NE(error_of(doc(kViews, sparse_bytes, R"([{"mesh":0}])")).find("sparse indices"), std::string::npos);
    const std::string no_data =
        R"([{"componentType":5126,"count":4294967296,"type":"VEC3"},{"bufferView":1,"componentType":5121,"count":12,"type":"SCALAR"}])";
    EXPECT_NE(error_of(doc(kViews, no_data, R"([{"mesh":0}])")).find("without data"), std::string::npos);
}

TEST(Gltf, DeepOrExplodingHierarchiesAreRefused) {
    std::string chain = "[";
    for (int i = 0; i < 20000; ++i) chain += R"({"children":[)" + std::to_string(i + 1) + "]},";
    chain += R"({"mesh":0}])";
    EXPECT_NE(error_of(doc(kViews, kAccessors, chain)).find("1000 levels"), std::string::npos);
    // 25 levels, each node's child listed twice: 2^25 instances of the mesh from a few hundred bytes
    std::string twice = "[";
    for (int i = 0; i < 25; ++i) twice += R"({"children":[)" + std::to_string(i + 1) + "," + std::to_string(i + 1) + "]},";
    twice += R"({"mesh":0}])";
    EXPECT_NE(error_of(doc(kViews, kAccessors, twice)).find("more"), std::string::npos);
    const std::string nested = doc(kViews, kAccessors, R"([{"mesh":0}])", R"(,"extras":)" + std::string(5000, '[') +
                                                                              std::string(5000, ']'));
    EXPECT_NE(error_of(nested).find("nested"), std::string::npos);
}

TEST(Gltf, ATransformRoundedToTheIdentityIsNotExact) {
    // scale 3 then 0.3333333333333333: the product rounds to 1, the exact one is 1 - 2^-54
    const polyvol::LoadedMesh m = polyvol::read_mesh_memory(
        bytes(doc(kViews, kAccessors,
                  R"([{"scale":[3,3,3],"children":[1]},{"mesh":0,"scale":[0.3333333333333333,0.3333333333333333,0.3333333333333333]}])")),
        "<stdin>", Format::gltf);
    EXPECT_GT(m.coordinate_error, 0.0);
}

}  // namespace

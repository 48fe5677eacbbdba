// 3MF and AMF readers: the corpus (manifest.json) and in-memory fixtures.
#include <gtest/gtest.h>
#include <minizip/zip.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iterator>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/files.hpp"
#include "common/manifest.hpp"
#include "common/naive_volume.hpp"
#include "io/readers.hpp"
#include "io/xml_numbers.hpp"
#include "io/zip.hpp"
#include "polyvol/io.hpp"

namespace {

using polyvol::LoadedMesh;
using polyvol::ReadError;
using Bytes = std::vector<std::byte>;

Bytes to_bytes(std::string_view s) {
    Bytes b(s.size());
    if (!s.empty()) std::memcpy(b.data(), s.data(), s.size());
    return b;
}

// A zip archive built in memory with minizip (deflate).
struct ZipBuffer {
    Bytes bytes;
    uint64_t pos = 0;
};
voidpf ZCALLBACK zb_open(voidpf opaque, const void*, int) { return opaque; }
uLong ZCALLBACK zb_read(voidpf, voidpf s, void* buf, uLong size) {
    auto* z = static_cast<ZipBuffer*>(s);
    const uint64_t n = std::min<uint64_t>(size, z->bytes.size() - std::min<uint64_t>(z->pos, z->bytes.size()));
    if (n) std::memcpy(buf, z->bytes.data() + z->pos, n);
    z->pos += n;
    return static_cast<uLong>(n);
}
uLong ZCALLBACK zb_write(voidpf, voidpf s, const void* buf, uLong size) {
    auto* z = static_cast<ZipBuffer*>(s);
    if (z->pos + size > z->bytes.size()) z->bytes.resize(z->pos + size);
    if (size) std::memcpy(z->bytes.data() + z->pos, buf, size);
    z->pos += size;
    return size;
}
ZPOS64_T ZCALLBACK zb_tell(voidpf, voidpf s) { return static_cast<ZipBuffer*>(s)->pos; }
long ZCALLBACK zb_seek(voidpf, voidpf s, ZPOS64_T offset, int origin) {
    auto* z = static_cast<ZipBuffer*>(s);
    const uint64_t base = origin == ZLIB_FILEFUNC_SEEK_CUR ? z->pos
                          : origin == ZLIB_FILEFUNC_SEEK_END ? z->bytes.size() : 0;
    z->pos = base + offset;
    return 0;
}
int ZCALLBACK zb_close(voidpf, voidpf) { return 0; }
int ZCALLBACK zb_error(voidpf, voidpf) { return 0; }

Bytes make_zip(const std::vector<std::pair<std::string, std::string>>& entries) {
    ZipBuffer buffer;
    zlib_filefunc64_def io{zb_open, zb_read, zb_write, zb_tell, zb_seek, zb_close, zb_error, &buffer};
    zipFile zf = zipOpen2_64("memory", APPEND_STATUS_CREATE, nullptr, &io);
    if (!zf) throw std::runtime_error("zipOpen2_64");
    for (const auto& [name, data] : entries) {
        zip_fileinfo info{};
        if (zipOpenNewFileInZip64(zf, name.c_str(), &info, nullptr, 0, nullptr, 0, nullptr, Z_DEFLATED,
                                  Z_DEFAULT_COMPRESSION, 0) != ZIP_OK ||
            zipWriteInFileInZip(zf, data.data(), static_cast<unsigned>(data.size())) != ZIP_OK ||
            zipCloseFileInZip(zf) != ZIP_OK)
            throw std::runtime_error("zip entry " + name);
    }
    if (zipClose(zf, nullptr) != ZIP_OK) throw std::runtime_error("zipClose");
    return std::move(buffer.bytes);
}

const std::string kRels =
    R"(<?xml version="1.0" encoding="UTF-8"?>
<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">)"
    R"(<Relationship Target="/3D/3dmodel.model" Id="rel0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>)"
    R"(</Relationships>)";

bool has_note(const LoadedMesh& m, const std::string& note) {
    return std::find(m.notes.begin(), m.notes.end(), note) != m.notes.end();
}

template <class F>
ReadError expect_read_error(F&& f) {
    try {
        f();
    } catch (const ReadError& e) {
        return e;
    }
    ADD_FAILURE() << "no ReadError thrown";
    return ReadError::whole_file("", "");
}

// ---------------------------------------------------------------- corpus

LoadedMesh read_direct(const std::string& format, const std::string& encoding, const Bytes& data,
                       const std::string& name) {
    const bool zip = encoding.empty() ? (data.size() >= 2 && data[0] == std::byte{'P'} &&
                                         data[1] == std::byte{'K'})
                                      : encoding == "zip";
    if (format == "3mf") return zip ? polyvol::io::read_3mf_zip(data, name) : polyvol::io::read_3mf_xml(data, name);
    return zip ? polyvol::io::read_amf_zip(data, name) : polyvol::io::read_amf_xml(data, name);
}

TEST(ThreeMfAmfCorpus, EveryEntryMatchesTheManifest) {
    const nlohmann::json& manifest = polyvol::test::corpus_manifest();
    ASSERT_FALSE(manifest.empty()) << "no manifest in " << polyvol::test::corpus_dir();
    int checked = 0, invalid = 0;
    for (const auto& e : manifest) {
        const std::string format = e.at("format").get<std::string>();
        if (format != "3mf" && format != "amf") continue;
        const std::string path = e.at("path").get<std::string>();
        SCOPED_TRACE(path);
        const std::string name = polyvol::test::corpus_file(path);
        const Bytes data = polyvol::test::read_bytes(name);
        const std::string encoding = e.value("encoding", std::string());

        if (e.at("category") == "invalid") {
            ++invalid;
            const ReadError err = expect_read_error([&] { read_direct(format, encoding, data, name); });
            EXPECT_EQ(err.file, name);
            EXPECT_FALSE(err.message.empty());
            EXPECT_NE(std::string(err.what()).find(name), std::string::npos);
            const ReadError err2 = expect_read_error([&] { polyvol::read_mesh_memory(data, name); });
            EXPECT_EQ(err2.file, name);
            continue;
        }
        ++checked;
        LoadedMesh m;
        ASSERT_NO_THROW(m = read_direct(format, encoding, data, name));
        EXPECT_EQ(m.format, format == "3mf" ? polyvol::Format::threemf : polyvol::Format::amf);
        EXPECT_EQ(m.encoding, encoding);
        const auto& counts = e.at("counts");
        EXPECT_EQ(m.mesh.vertex_count(), counts.at("vertices_in_file").get<std::size_t>());
        EXPECT_EQ(m.mesh.face_count(), counts.at("faces").get<std::size_t>());
        EXPECT_EQ(m.mesh.view().triangle_count(), counts.at("triangles").get<std::size_t>());

        // Notes are the manifest's quirks (unit notes are ours only).
        std::set<std::string> notes, quirks;
        for (const auto& n : m.notes)
            if (n.find("-unit(") == std::string::npos) notes.insert(n);
        for (const auto& q : e.at("quirks")) {
            const std::string s = q.get<std::string>();
            if (s.rfind("signed-zero-coordinates-merged", 0) == 0) continue;  // a welding remark
            quirks.insert(s);
        }
        EXPECT_EQ(notes, quirks);
        const std::string unit = e.at("info").value("unit", std::string("millimeter"));
        EXPECT_EQ(has_note(m, format + "-unit(" + unit + ")"), unit != "millimeter");

        // Bounding box: exact, or to 1e-12 relative where transforms were applied.
        const bool transformed = quirks.count("3mf-transform") != 0;
        ASSERT_GT(m.mesh.vertex_count(), 0u);
        for (int k = 0; k < 3; ++k) {
            double lo = INFINITY, hi = -INFINITY;
            for (std::size_t v = 0; v < m.mesh.vertex_count(); ++v) {
                lo = std::min(lo, m.mesh.positions[3 * v + k]);
                hi = std::max(hi, m.mesh.positions[3 * v + k]);
            }
            const double want_lo = e.at("bbox").at("min").at(k).get<double>();
            const double want_hi = e.at("bbox").at("max").at(k).get<double>();
            if (transformed) {
                EXPECT_NEAR(lo, want_lo, 1e-12 * std::max(1.0, std::fabs(want_lo))) << "axis " << k;
                EXPECT_NEAR(hi, want_hi, 1e-12 * std::max(1.0, std::fabs(want_hi))) << "axis " << k;
            } else {
                EXPECT_EQ(lo, want_lo) << "axis " << k;
                EXPECT_EQ(hi, want_hi) << "axis " << k;
            }
        }
        // A naive double volume confirms the orientation and the transforms.
        if (e.value("exact", false) && e.at("topology").at("closed_2_cycle").get<bool>()) {
            const double want = e.at("volume").at("double").get<double>();
            EXPECT_NEAR(polyvol::test::naive_volume(m.mesh.view()), want, 1e-9 * std::fabs(want));
        }

        // Through the dispatcher: the same mesh.
        LoadedMesh d;
        ASSERT_NO_THROW(d = polyvol::read_mesh_memory(data, name));
        EXPECT_EQ(d.format, m.format);
        EXPECT_EQ(d.encoding, m.encoding);
        EXPECT_EQ(d.mesh.positions, m.mesh.positions);
        EXPECT_EQ(d.mesh.indices, m.mesh.indices);
    }
    EXPECT_GE(checked, 15);
    EXPECT_GE(invalid, 1);
}

TEST(ThreeMfAmfCorpus, BrokenAmfNamesTheLineAndTheNumber) {
    const std::string name = std::string(POLYVOL_CORPUS_DIR) + "/meshes/openscad-testing-data/amf_broken.amf";
    const Bytes data = polyvol::test::read_bytes(name);
    const ReadError e = expect_read_error([&] { polyvol::io::read_amf_xml(data, name); });
    EXPECT_EQ(e.file, name);
    EXPECT_EQ(e.line, 9u);
    EXPECT_NE(e.message.find("bad number 'a' in <y>"), std::string::npos) << e.message;
    EXPECT_NE(e.message.find("expected"), std::string::npos) << e.message;
}

// ---------------------------------------------------------------- AMF fixtures

const std::string kTwoObjectsAmf = R"(<?xml version="1.0" encoding="utf-8"?>
<amf unit="inch">
 <metadata type="name">two</metadata>
 <object id="0"><mesh><vertices>
  <vertex><coordinates><x>0</x><y>0</y><z>0</z></coordinates></vertex>
  <vertex><coordinates><x>1</x><y>0</y><z>0</z></coordinates></vertex>
  <vertex><coordinates><x>0</x><y>1</y><z>0</z></coordinates></vertex>
 </vertices><volume><triangle><v1>0</v1><v2>1</v2><v3>2</v3></triangle></volume></mesh></object>
 <object id="1"><color><r>1</r><g>0</g><b>0</b></color><mesh><vertices>
  <vertex><coordinates><z> 3 </z><y>2</y><x>0.1</x></coordinates></vertex>
  <vertex><coordinates><x>-1e-3</x><y>+5</y><z>6.25E2</z></coordinates></vertex>
  <vertex><coordinates><x>7</x><y>8</y><z>9</z></coordinates></vertex>
  <vertex><coordinates><x>10</x><y>11</y><z>12</z></coordinates><edge><v1>0</v1><v2>1</v2></edge></vertex>
 </vertices>
 <volume materialid="1"><triangle><v1>0</v1><v2>1</v2><v3>2</v3></triangle></volume>
 <volume><metadata type="name">b</metadata><triangle><v1>
   3
 </v1><v2>2</v2><v3>1</v3></triangle></volume></mesh></object>
 <constellation id="2"><instance objectid="0"><deltax>5</deltax></instance></constellation>
 <material id="1"><color><r>1</r><g>0</g><b>0</b></color></material>
</amf>
)";

void check_two_objects(const LoadedMesh& m) {
    EXPECT_EQ(m.format, polyvol::Format::amf);
    ASSERT_EQ(m.mesh.vertex_count(), 7u);
    ASSERT_EQ(m.mesh.face_count(), 3u);
    EXPECT_TRUE(m.mesh.face_offsets.empty());
    EXPECT_EQ(m.mesh.indices, (std::vector<uint32_t>{0, 1, 2, 3, 4, 5, 6, 5, 4}));
    EXPECT_EQ(m.mesh.positions[9], 0.1);
    EXPECT_EQ(m.mesh.positions[10], 2.0);
    EXPECT_EQ(m.mesh.positions[11], 3.0);
    EXPECT_EQ(m.mesh.positions[12], -1e-3);
    EXPECT_EQ(m.mesh.positions[13], 5.0);
    EXPECT_EQ(m.mesh.positions[14], 625.0);
    EXPECT_EQ(m.mesh.positions[20], 12.0);
    EXPECT_TRUE(has_note(m, "amf-multiple-volumes"));
    EXPECT_TRUE(has_note(m, "amf-multiple-objects(2)"));
    EXPECT_TRUE(has_note(m, "amf-constellation-ignored"));
    EXPECT_TRUE(has_note(m, "amf-unit(inch)"));
}

TEST(AmfReader, TwoObjectsAndVolumesWithPerObjectIndices) {
    const Bytes data = to_bytes(kTwoObjectsAmf);
    const LoadedMesh m = polyvol::io::read_amf_xml(data, "two.amf");
    EXPECT_EQ(m.encoding, "xml");
    check_two_objects(m);
    EXPECT_FALSE(has_note(m, "amf-zip-compressed"));
}

TEST(AmfReader, ZippedAmf) {
    const Bytes zip = make_zip({{"two.amf", kTwoObjectsAmf}});
    const LoadedMesh m = polyvol::io::read_amf_zip(zip, "two.amf");
    EXPECT_EQ(m.encoding, "zip");
    check_two_objects(m);
    EXPECT_TRUE(has_note(m, "amf-zip-compressed"));

    const Bytes none = make_zip({{"a.txt", "x"}, {"b.txt", "y"}});
    const ReadError e = expect_read_error([&] { polyvol::io::read_amf_zip(none, "n.amf"); });
    EXPECT_NE(e.message.find("*.amf"), std::string::npos) << e.message;
}

TEST(AmfReader, IndexOutOfRangeIsPerObject) {
    // Object 2 has 1 vertex: index 1 is out of range although object 1 has 3.
    const std::string amf = R"(<amf>
<object id="1"><mesh><vertices>
<vertex><coordinates><x>0</x><y>0</y><z>0</z></coordinates></vertex>
<vertex><coordinates><x>1</x><y>0</y><z>0</z></coordinates></vertex>
<vertex><coordinates><x>0</x><y>1</y><z>0</z></coordinates></vertex>
</vertices><volume><triangle><v1>0</v1><v2>1</v2><v3>2</v3></triangle></volume></mesh></object>
<object id="2"><mesh><vertices>
<vertex><coordinates><x>0</x><y>0</y><z>0</z></coordinates></vertex>
</vertices><volume><triangle><v1>0</v1>
<v2>1</v2><v3>0</v3></triangle></volume></mesh></object>
</amf>)";
    const Bytes data = to_bytes(amf);
    const ReadError e = expect_read_error([&] { polyvol::io::read_amf_xml(data, "r.amf"); });
    EXPECT_EQ(e.file, "r.amf");
    EXPECT_EQ(e.line, 10u);
    EXPECT_NE(e.message.find("vertex index 1 in <v2> out of range: the mesh has 1 vertices"),
              std::string::npos)
        << e.message;
}

TEST(AmfReader, ErrorsNameWhatWasExpected) {
    auto error_of = [](const std::string& text) {
        const Bytes data = to_bytes(text);
        return expect_read_error([&] { polyvol::io::read_amf_xml(data, "e.amf"); });
    };
    const std::string head = "<amf>\n<object id=\"1\"><mesh><vertices>\n";
    ReadError e = error_of(head + "<vertex><coordinates><x>1</x><y>nan</y><z>0</z></coordinates></vertex>\n"
                                  "</vertices></mesh></object></amf>");
    EXPECT_EQ(e.line, 3u);
    EXPECT_NE(e.message.find("bad number 'nan' in <y>"), std::string::npos) << e.message;
    e = error_of(head + "<vertex><coordinates><x>1</x><z>0</z></coordinates></vertex>\n</vertices></mesh></object></amf>");
    EXPECT_NE(e.message.find("without <y>"), std::string::npos) << e.message;
    e = error_of(head + "<vertex><coordinates><x>1</x><y>1</y><z>0</z></coordinates></vertex>\n</vertices>"
                        "<volume><triangle><v1>0</v1><v2>-1</v2><v3>0</v3></triangle></volume></mesh></object></amf>");
    EXPECT_NE(e.message.find("bad vertex index '-1' in <v2>"), std::string::npos) << e.message;
    e = error_of("<model/>");
    EXPECT_NE(e.message.find("expected <amf>"), std::string::npos) << e.message;
    e = error_of("<amf><object></amf>");
    EXPECT_TRUE(e.has_byte_offset);
    EXPECT_NE(e.message.find("XML parse error"), std::string::npos) << e.message;
}

// ---------------------------------------------------------------- 3MF fixtures

// Object 1: a tetrahedron. Object 2: components -- object 1 turned by 90
// degrees about z and moved, and object 3 from another model part.
// Build: object 2 scaled by 2 and moved by 0.5 in x; object 1 as it is.
const std::string kMainModel = R"(<?xml version="1.0" encoding="UTF-8"?>
<model unit="millimeter" xml:lang="en-US" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02"
       xmlns:p="http://schemas.microsoft.com/3dmanufacturing/production/2015/06">
 <resources>
  <object id="1" type="model"><mesh>
   <vertices><vertex x="0" y="0" z="0"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/><vertex x="0" y="0" z="1"/></vertices>
   <triangles><triangle v1="0" v2="2" v3="1"/><triangle v1="0" v2="1" v3="3"/><triangle v1="0" v2="3" v3="2"/><triangle v1="1" v2="2" v3="3"/></triangles>
  </mesh></object>
  <object id="2" type="model"><components>
   <component objectid="1" transform="0 1 0 -1 0 0 0 0 1 10 20 30"/>
   <component objectid="3" p:path="/3D/other.model"/>
  </components></object>
 </resources>
 <build>
  <item objectid="2" transform="2 0 0 0 2 0 0 0 2 0.5 0 0"/>
  <item objectid="1"/>
 </build>
</model>
)";

const std::string kOtherModel = R"(<?xml version="1.0" encoding="UTF-8"?>
<c:model unit="millimeter" xmlns:c="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
 <c:resources><c:object id="3"><c:mesh>
  <c:vertices><c:vertex x="7" y="8" z="9"/><c:vertex x="1" y="2" z="3"/><c:vertex x="4" y="5" z="6"/></c:vertices>
  <c:triangles><c:triangle v1="0" v2="1" v3="2"/></c:triangles>
 </c:mesh></c:object></c:resources>
</c:model>
)";

TEST(ThreeMfReader, ComponentsTransformsAndExternalParts) {
    const Bytes zip = make_zip({{"[Content_Types].xml", "<Types/>"},
                                {"_rels/.rels", kRels},
                                {"3D/3dmodel.model", kMainModel},
                                {"3D/other.model", kOtherModel}});
    const LoadedMesh m = polyvol::io::read_3mf_zip(zip, "fixture.3mf");
    EXPECT_EQ(m.format, polyvol::Format::threemf);
    EXPECT_EQ(m.encoding, "zip");
    EXPECT_TRUE(has_note(m, "3mf-components"));
    EXPECT_TRUE(has_note(m, "3mf-transform"));
    ASSERT_EQ(m.mesh.vertex_count(), 11u);
    ASSERT_EQ(m.mesh.face_count(), 9u);
    // Row vectors: p' = p * R + t with R = [[0 1 0] [-1 0 0] [0 0 1]], t = (10 20 30):
    // (x, y, z) -> (10 - y, x + 20, z + 30); then the item: *2 + (0.5, 0, 0).
    const std::vector<double> want = {
        20.5, 40, 60,   20.5, 42, 60,   18.5, 40, 60,   20.5, 40, 62,  // object 1 in object 2
        14.5, 16, 18,   2.5, 4, 6,      8.5, 10, 12,                   // object 3 (other part)
        0, 0, 0,        1, 0, 0,        0, 1, 0,        0, 0, 1,       // object 1, second item
    };
    EXPECT_EQ(m.mesh.positions, want);
    EXPECT_EQ(m.mesh.indices, (std::vector<uint32_t>{0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3,  //
                                                     4, 5, 6,                             //
                                                     7, 9, 8, 7, 8, 10, 7, 10, 9, 8, 9, 10}));
    // Transforms keep orientation: the two tetrahedra have volume 8/6 and 1/6.
    EXPECT_NEAR(polyvol::test::naive_volume(m.mesh.view()), 9.0 / 6.0, 1e-12);
}

TEST(ThreeMfReader, ModelPartFoundThroughRelationships) {
    const std::string rels =
        R"(<Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships">)"
        R"(<Relationship Target="/Metadata/thumbnail.png" Id="r1" Type="http://schemas.openxmlformats.org/package/2006/relationships/metadata/thumbnail"/>)"
        R"(<Relationship Target="/3D/My%20Model.model" Id="r0" Type="http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel"/>)"
        R"(</Relationships>)";
    const std::string model = R"(<model unit="inch" xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
<resources><object id="5"><mesh><vertices><vertex x="1" y="2" z="3"/><vertex x="4" y="5" z="6"/><vertex x="7" y="8" z="9.5"/></vertices>
<triangles><triangle v1="0" v2="1" v3="2"/></triangles></mesh></object>
<object id="6"><mesh><vertices><vertex x="0" y="0" z="0"/></vertices></mesh></object></resources>
<build/></model>)";
    const Bytes zip = make_zip({{"_rels/.rels", rels}, {"3D/My Model.model", model}});
    const LoadedMesh m = polyvol::io::read_3mf_zip(zip, "rels.3mf");
    // No build item: every mesh object, untransformed.
    EXPECT_EQ(m.mesh.positions, (std::vector<double>{1, 2, 3, 4, 5, 6, 7, 8, 9.5, 0, 0, 0}));
    EXPECT_EQ(m.mesh.indices, (std::vector<uint32_t>{0, 1, 2}));
    EXPECT_TRUE(has_note(m, "3mf-unit(inch)"));
    EXPECT_FALSE(has_note(m, "3mf-transform"));
    EXPECT_FALSE(has_note(m, "3mf-components"));
}

TEST(ThreeMfReader, BareXmlModelPart) {
    const std::string model = R"(<model xmlns="http://schemas.microsoft.com/3dmanufacturing/core/2015/02">
<resources><object id="1"><mesh><vertices><vertex x="0.1" y="0.2" z="0.3"/><vertex x="1" y="0" z="0"/><vertex x="0" y="1" z="0"/></vertices>
<triangles><triangle v1="0" v2="1" v3="2"/></triangles></mesh></object></resources>
<build><item objectid="1" transform="1 0 0 0 1 0 0 0 1 0 0 0"/></build></model>)";
    const Bytes data = to_bytes(model);
    const LoadedMesh m = polyvol::io::read_3mf_xml(data, "bare.3mf");
    EXPECT_EQ(m.encoding, "xml");
    EXPECT_TRUE(has_note(m, "3mf-bare-xml-not-zip"));
    EXPECT_TRUE(has_note(m, "3mf-transform"));  // the attribute is there, even if it is the identity
    EXPECT_EQ(m.mesh.positions, (std::vector<double>{0.1, 0.2, 0.3, 1, 0, 0, 0, 1, 0}));
}

TEST(ThreeMfReader, TransformIsAccurate) {
    // x' = 1e16*1 + 1*1 + 3*0 - 1e16 = 1 exactly; naive left-to-right double
    // evaluation gives 0 (1e16 + 1 rounds to 1e16).
    // y' = 1e16*(1 + 2^-52) - 1e16 = 5^16 * 2^-36 exactly (a double); naive gives 2.
    const std::string model = R"(<model><resources><object id="1"><mesh><vertices>
<vertex x="1e16" y="1" z="3"/></vertices></mesh></object></resources>
<build><item objectid="1" transform="1 1.0000000000000002 0 1 0 0 0 0 1 -1e16 -1e16 -3"/></build></model>)";
    const Bytes data = to_bytes(model);
    const LoadedMesh m = polyvol::io::read_3mf_xml(data, "acc.3mf");
    ASSERT_EQ(m.mesh.vertex_count(), 1u);
    EXPECT_EQ(m.mesh.positions[0], 1.0);
    EXPECT_EQ(m.mesh.positions[1], 152587890625.0 * 0x1p-36);
    EXPECT_EQ(m.mesh.positions[2], 0.0);
}

ReadError model_error(const std::string& model) {
    const Bytes data = to_bytes(model);
    return expect_read_error([&] { polyvol::io::read_3mf_xml(data, "bad.3mf"); });
}

TEST(ThreeMfReader, BrokenXmlReportsTheByteOffset) {
    const std::string text = "<model>\n<resources><object id=\"1\"></resources></model>";
    const ReadError e = model_error(text);
    EXPECT_EQ(e.file, "bad.3mf");
    EXPECT_TRUE(e.has_byte_offset);
    EXPECT_GT(e.byte_offset, 0u);
    EXPECT_LE(e.byte_offset, text.size());
    EXPECT_NE(e.message.find("XML parse error"), std::string::npos) << e.message;
    EXPECT_NE(std::string(e.what()).find("byte " + std::to_string(e.byte_offset)), std::string::npos);
}

TEST(ThreeMfReader, BadNumbersAndIndicesNameTheLine) {
    const std::string head =
        "<model>\n<resources>\n<object id=\"1\"><mesh><vertices>\n"
        "<vertex x=\"0\" y=\"0\" z=\"0\"/><vertex x=\"1\" y=\"0\" z=\"0\"/>\n";
    ReadError e = model_error(head + "<vertex x=\"1.5x\" y=\"0\" z=\"0\"/>\n</vertices></mesh></object></resources></model>");
    EXPECT_EQ(e.line, 5u);
    EXPECT_FALSE(e.has_byte_offset);
    EXPECT_NE(e.message.find("bad number '1.5x' in attribute x of <vertex>, expected"), std::string::npos)
        << e.message;
    EXPECT_NE(std::string(e.what()).find("bad.3mf:5:"), std::string::npos) << e.what();

    e = model_error(head + "<vertex x=\"0\" y=\"1\" z=\"0\"/>\n</vertices><triangles>\n"
                           "<triangle v1=\"0\" v2=\"1\" v3=\"2\"/>\n<triangle v1=\"0\" v2=\"3\" v3=\"2\"/>\n"
                           "</triangles></mesh></object></resources></model>");
    EXPECT_EQ(e.line, 8u);
    EXPECT_NE(e.message.find("vertex index v2=3 out of range: the mesh has 3 vertices (indices 0..2)"),
              std::string::npos)
        << e.message;

    e = model_error(head + "<vertex x=\"0\" y=\"inf\" z=\"0\"/>\n</vertices></mesh></object></resources></model>");
    EXPECT_NE(e.message.find("bad number 'inf'"), std::string::npos) << e.message;
    e = model_error(head + "<vertex x=\"0\" z=\"0\"/>\n</vertices></mesh></object></resources></model>");
    EXPECT_NE(e.message.find("without attribute y"), std::string::npos) << e.message;
    e = model_error(head + "</vertices><triangles><triangle v1=\"0\" v2=\"x\" v3=\"1\"/></triangles></mesh></object></resources></model>");
    EXPECT_NE(e.message.find("bad v2 'x' in <triangle>"), std::string::npos) << e.message;
}

TEST(ThreeMfReader, BadReferencesAndTransforms) {
    const std::string mesh =
        "<object id=\"1\"><mesh><vertices><vertex x=\"0\" y=\"0\" z=\"0\"/></vertices></mesh></object>\n";
    ReadError e = model_error("<model><resources>" + mesh +
                              "</resources><build><item objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 0 0\"/></build></model>");
    EXPECT_NE(e.message.find("has 11 numbers, expected 12"), std::string::npos) << e.message;
    e = model_error("<model><resources>" + mesh +
                    "</resources><build><item objectid=\"1\" transform=\"1 0 0 0 1 0 0 0 1 0 0 zz\"/></build></model>");
    EXPECT_NE(e.message.find("bad number 'zz' in transform"), std::string::npos) << e.message;
    e = model_error("<model><resources>" + mesh +
                    "</resources>\n<build><item objectid=\"4\"/></build></model>");
    EXPECT_EQ(e.line, 3u);  // the mesh line ends with a newline
    EXPECT_NE(e.message.find("object 4, which is not defined"), std::string::npos) << e.message;
    e = model_error("<model><resources>" + mesh + mesh + "</resources></model>");
    EXPECT_NE(e.message.find("duplicate object id 1"), std::string::npos) << e.message;
    e = model_error(R"(<model><resources>
<object id="1"><components><component objectid="2"/></components></object>
<object id="2"><components><component objectid="1"/></components></object>
</resources><build><item objectid="1"/></build></model>)");
    EXPECT_NE(e.message.find("contains itself"), std::string::npos) << e.message;
    e = model_error(R"(<model xmlns:p="http://schemas.microsoft.com/3dmanufacturing/production/2015/06"><resources>
<object id="1"><components><component objectid="2" p:path="/3D/x.model"/></components></object>
</resources><build><item objectid="1"/></build></model>)");
    EXPECT_NE(e.message.find("bare XML"), std::string::npos) << e.message;
    e = model_error("<amf/>");
    EXPECT_NE(e.message.find("expected <model>"), std::string::npos) << e.message;
}

// A zip whose records all use ZIP64 (as lib3mf writes them): 0xFFFFFFFF in
// every 32-bit size and offset, the values in the extra field 0x0001 of the
// local and central headers, a ZIP64 end of central directory. `stored`:
// method 0 instead of deflate; `bad_crc`: the CRC of the last entry is off by one.
Bytes make_zip64(const std::vector<std::pair<std::string, std::string>>& entries, bool stored = false,
                 bool bad_crc = false) {
    Bytes out, central;
    auto put = [](Bytes& b, uint64_t v, int n) {
        for (int i = 0; i < n; ++i) b.push_back(static_cast<std::byte>((v >> (8 * i)) & 0xFF));
    };
    auto put_text = [](Bytes& b, const std::string& t) {
        for (char c : t) b.push_back(static_cast<std::byte>(c));
    };
    for (std::size_t k = 0; k < entries.size(); ++k) {
        const auto& [name, text] = entries[k];
        std::string data = text;
        if (!stored) {
            z_stream zs{};
            deflateInit2(&zs, Z_DEFAULT_COMPRESSION, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY);
            data.resize(deflateBound(&zs, static_cast<uLong>(text.size())));
            zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
            zs.avail_in = static_cast<uInt>(text.size());
            zs.next_out = reinterpret_cast<Bytef*>(data.data());
            zs.avail_out = static_cast<uInt>(data.size());
            deflate(&zs, Z_FINISH);
            data.resize(zs.total_out);
            deflateEnd(&zs);
        }
        uint32_t crc = static_cast<uint32_t>(crc32(0, reinterpret_cast<const Bytef*>(text.data()), static_cast<uInt>(text.size())));
        if (bad_crc && k + 1 == entries.size()) ++crc;
        const uint64_t offset = out.size();
        put(out, 0x04034b50, 4); put(out, 45, 2); put(out, 0, 2); put(out, stored ? 0 : 8, 2); put(out, 0, 4);
        put(out, crc, 4); put(out, 0xFFFFFFFF, 4); put(out, 0xFFFFFFFF, 4); put(out, name.size(), 2); put(out, 20, 2);
        put_text(out, name);
        put(out, 1, 2); put(out, 16, 2); put(out, text.size(), 8); put(out, data.size(), 8);
        put_text(out, data);
        put(central, 0x02014b50, 4); put(central, 45, 2); put(central, 45, 2); put(central, 0, 2);
        put(central, stored ? 0 : 8, 2); put(central, 0, 4); put(central, crc, 4); put(central, 0xFFFFFFFF, 4);
        put(central, 0xFFFFFFFF, 4); put(central, name.size(), 2); put(central, 28, 2); put(central, 0, 2);
        put(central, 0, 2); put(central, 0, 2); put(central, 0, 4); put(central, 0xFFFFFFFF, 4);
        put_text(central, name);
        put(central, 1, 2); put(central, 24, 2); put(central, text.size(), 8); put(central, data.size(), 8);
        put(central, offset, 8);
    }
    const uint64_t cd = out.size();
    out.insert(out.end(), central.begin(), central.end());
    const uint64_t end64 = out.size();
    put(out, 0x06064b50, 4); put(out, 44, 8); put(out, 45, 2); put(out, 45, 2); put(out, 0, 4); put(out, 0, 4);
    put(out, entries.size(), 8); put(out, entries.size(), 8); put(out, central.size(), 8); put(out, cd, 8);
    put(out, 0x07064b50, 4); put(out, 0, 4); put(out, end64, 8); put(out, 1, 4);
    put(out, 0x06054b50, 4); put(out, 0, 2); put(out, 0, 2); put(out, 0xFFFF, 2); put(out, 0xFFFF, 2);
    put(out, 0xFFFFFFFF, 4); put(out, 0xFFFFFFFF, 4); put(out, 0, 2);
    return out;
}

// ZIP64 entries (sizes 0xFFFFFFFF in the headers, the real ones in the extra
// field) read as the same package written without ZIP64; corrupt ones are errors.
TEST(ThreeMfReader, Zip64Entries) {
    const std::vector<std::pair<std::string, std::string>> parts = {{"[Content_Types].xml", "<Types/>"},
                                                                    {"_rels/.rels", kRels},
                                                                    {"3D/3dmodel.model", kMainModel},
                                                                    {"3D/other.model", kOtherModel}};
    const LoadedMesh plain = polyvol::io::read_3mf_zip(make_zip(parts), "plain.3mf");
    for (const bool stored : {false, true}) {
        const LoadedMesh m = polyvol::io::read_3mf_zip(make_zip64(parts, stored), "zip64.3mf");
        EXPECT_EQ(m.mesh.positions, plain.mesh.positions);
        EXPECT_EQ(m.mesh.indices, plain.mesh.indices);
    }
    // An empty deflated entry is empty (zlib needs an output buffer even then).
    {
        const Bytes with_empty = make_zip64({{"empty.txt", ""}, {"a.txt", "abc"}});
        polyvol::io::ZipArchive zip(with_empty, "empty.zip");
        EXPECT_TRUE(zip.read("empty.txt").empty());
        EXPECT_EQ(zip.read("a.txt").size(), 3u);
    }
    ReadError e = expect_read_error([&] { polyvol::io::read_3mf_zip(make_zip64(parts, false, true), "crc.3mf"); });
    EXPECT_NE(e.message.find("CRC mismatch"), std::string::npos) << e.message;
    Bytes stored = make_zip64(parts, true);
    // The main model's text corrupted in place: the CRC says so.
    const std::string probe = "<vertices>";
    auto at = std::search(stored.begin(), stored.end(), probe.begin(), probe.end(),
                          [](std::byte b, char c) { return b == static_cast<std::byte>(c); });
    ASSERT_NE(at, stored.end());
    *at = static_cast<std::byte>('[');
    e = expect_read_error([&] { polyvol::io::read_3mf_zip(stored, "flipped.3mf"); });
    EXPECT_NE(e.message.find("CRC mismatch"), std::string::npos) << e.message;
}

// A zip of plain meshes is not read as AMF XML: the error says what it holds,
// and each member reads as a file of its own.
TEST(ZipOfMeshes, IsNotOneMeshButItsMembers) {
    const std::string path = std::string(POLYVOL_TEST_DATA) + "/archives/two_meshes.zip";
    const ReadError e = expect_read_error([&] { polyvol::read_mesh_file(path); });
    EXPECT_NE(e.message.find("a zip archive of 2 mesh files (cube.obj, sub/tet.off), not a 3MF or AMF package"),
              std::string::npos)
        << e.message;
    EXPECT_EQ(polyvol::mesh_archive_members(path), (std::vector<std::string>{"cube.obj", "sub/tet.off"}));
    const LoadedMesh tet = polyvol::read_archive_member(path, "sub/tet.off");
    EXPECT_EQ(tet.format, polyvol::Format::off);
    EXPECT_EQ(tet.mesh.face_count(), 4u);
    expect_read_error([&] { polyvol::read_archive_member(path, "gone.stl"); });
    // Not archives: nothing listed.
    EXPECT_TRUE(polyvol::mesh_archive_members(std::string(POLYVOL_TEST_DATA) + "/self_crossing/one.obj").empty());
    EXPECT_TRUE(polyvol::mesh_archive_members("/nonexistent/file.zip").empty());
}

TEST(ThreeMfReader, ZipProblems) {
    const Bytes junk = to_bytes("PK\x03\x04 this is not really a zip archive");
    ReadError e = expect_read_error([&] { polyvol::io::read_3mf_zip(junk, "junk.3mf"); });
    EXPECT_EQ(e.file, "junk.3mf");
    EXPECT_NE(e.message.find("zip"), std::string::npos) << e.message;

    const Bytes empty_package = make_zip({{"_rels/.rels", kRels}, {"readme.txt", "hello"}});
    e = expect_read_error([&] { polyvol::io::read_3mf_zip(empty_package, "empty.3mf"); });
    EXPECT_NE(e.message.find("'3D/3dmodel.model', which is missing"), std::string::npos) << e.message;

    const Bytes missing_part = make_zip(
        {{"_rels/.rels", kRels},
         {"3D/3dmodel.model", R"(<model xmlns:p="p"><resources><object id="1"><components>
<component objectid="2" p:path="/3D/gone.model"/></components></object></resources>
<build><item objectid="1"/></build></model>)"}});
    e = expect_read_error([&] { polyvol::io::read_3mf_zip(missing_part, "gone.3mf"); });
    EXPECT_EQ(e.line, 2u);
    EXPECT_NE(e.message.find("'3D/gone.model', which is not in the package"), std::string::npos) << e.message;
    EXPECT_NE(e.message.find("(zip entry '3D/3dmodel.model')"), std::string::npos) << e.message;

    // Broken XML inside the zip: byte offset into the entry, entry named.
    const Bytes broken = make_zip({{"3D/3dmodel.model", "<model><resources>"}});
    e = expect_read_error([&] { polyvol::io::read_3mf_zip(broken, "broken.3mf"); });
    EXPECT_TRUE(e.has_byte_offset);
    EXPECT_NE(e.message.find("XML parse error"), std::string::npos) << e.message;
    EXPECT_NE(e.message.find("3D/3dmodel.model"), std::string::npos) << e.message;
}

TEST(ThreeMfReader, DecompressionIsBounded) {
    // 24 MiB of white space compresses to a few KiB: more than 64 x the
    // archive and more than the 16 MiB floor.
    std::string model = "<model><resources>";
    model.append(std::size_t{24} << 20, ' ');
    model += "</resources></model>";
    const Bytes zip = make_zip({{"3D/3dmodel.model", model}});
    ASSERT_LT(zip.size() * 64, std::size_t{16} << 20);
    const ReadError e = expect_read_error([&] { polyvol::io::read_3mf_zip(zip, "bomb.3mf"); });
    EXPECT_NE(e.message.find("decompression limit"), std::string::npos) << e.message;
}

TEST(ZipArchive, LimitAndLookup) {
    const Bytes zip = make_zip({{"3D/3dmodel.model", std::string(100000, 'a')}, {"Dir\\Name.TXT", "x"}});
    EXPECT_EQ(polyvol::io::ZipArchive::default_limit(1000), std::uint64_t{16} << 20);
    EXPECT_EQ(polyvol::io::ZipArchive::default_limit(std::size_t{1} << 30), std::uint64_t{4} << 30);
    EXPECT_EQ(polyvol::io::ZipArchive::default_limit(std::size_t{1} << 20), std::uint64_t{64} << 20);
    {
        polyvol::io::ZipArchive za(zip, "z.zip", 50000);
        EXPECT_EQ(za.find("/3d/3DMODEL.model"), std::optional<std::string>("3D/3dmodel.model"));
        EXPECT_EQ(za.find("dir/name.txt"), std::optional<std::string>("Dir\\Name.TXT"));
        EXPECT_EQ(za.find("nothing"), std::nullopt);
        const ReadError e = expect_read_error([&] { za.read("3D/3dmodel.model"); });
        EXPECT_NE(e.message.find("decompression limit"), std::string::npos) << e.message;
    }
    {
        polyvol::io::ZipArchive za(zip, "z.zip", 100001);
        EXPECT_EQ(za.read("3D/3dmodel.model").size(), 100000u);
        // The budget is shared by all entries.
        const ReadError e = expect_read_error([&] { za.read("3D/3dmodel.model"); });
        EXPECT_NE(e.message.find("decompression limit"), std::string::npos) << e.message;
    }
}

// One stored little-endian field of the local and of the central header of the
// only entry of a one-entry archive (offsets from each header's signature).
void patch_both(Bytes& z, std::size_t local_off, std::size_t central_off, uint32_t value, int width) {
    const auto put = [&](std::size_t at) {
        for (int i = 0; i < width; ++i) z[at + i] = static_cast<std::byte>((value >> (8 * i)) & 0xFF);
    };
    put(local_off);
    const std::string_view text(reinterpret_cast<const char*>(z.data()), z.size());
    const std::size_t central = text.find("PK\x01\x02");
    ASSERT_NE(central, std::string_view::npos);
    put(central + central_off);
}

TEST(ZipArchive, DamagedAndUnsupportedEntries) {
    const std::string text = "hello hello hello hello";
    const auto error_of = [](const Bytes& z) {
        polyvol::io::ZipArchive za(z, "d.zip");
        const ReadError e = expect_read_error([&] { za.read("a.txt"); });
        EXPECT_EQ(e.file, "d.zip");
        return e.message;
    };
    {
        const Bytes z = make_zip({{"a.txt", text}});
        polyvol::io::ZipArchive za(z, "d.zip");
        const std::vector<std::byte> got = za.read("a.txt");
        EXPECT_EQ(std::string(reinterpret_cast<const char*>(got.data()), got.size()), text);
    }
    Bytes z = make_zip({{"a.txt", text}});
    patch_both(z, 6, 8, 1, 2);  // flag bit 0
    EXPECT_NE(error_of(z).find("encrypted"), std::string::npos) << error_of(z);

    z = make_zip({{"a.txt", text}});
    patch_both(z, 8, 10, 12, 2);  // bzip2
    EXPECT_NE(error_of(z).find("compression method 12 (bzip2), which is not supported"), std::string::npos)
        << error_of(z);

    z = make_zip({{"a.txt", text}});
    patch_both(z, 14, 16, 0x12345678, 4);  // CRC
    EXPECT_NE(error_of(z).find("CRC mismatch"), std::string::npos) << error_of(z);

    z = make_zip({{"a.txt", text}});
    patch_both(z, 22, 24, 1000, 4);  // claims more than it holds
    EXPECT_NE(error_of(z).find("corrupt"), std::string::npos) << error_of(z);

    z = make_zip({{"a.txt", text}});
    z[30 + 5] = std::byte{0xFF};  // the deflate data (after the 30-byte local header and the name)
    z[30 + 6] = std::byte{0xFF};
    EXPECT_NE(error_of(z).find("cannot decompress zip entry 'a.txt'"), std::string::npos) << error_of(z);

    z = make_zip({{"a.txt", text}});
    const ReadError e = expect_read_error([&] { polyvol::io::ZipArchive za(Bytes(z.begin(), z.end() - 5), "t.zip"); });
    EXPECT_NE(e.message.find("not a readable zip archive"), std::string::npos) << e.message;
    const Bytes one = make_zip({{"a.txt", text}});
    polyvol::io::ZipArchive missing(one, "m.zip");
    EXPECT_NE(expect_read_error([&] { missing.read("b.txt"); }).message.find("'b.txt' is missing"),
              std::string::npos);
}

TEST(ZipArchive, Cp437NamesAreDecodedToUtf8) {
    // No UTF-8 flag and not UTF-8: CP437, as libzip read it (0x81 is u-umlaut).
    const Bytes z = make_zip({{"3D/m\x81" "de.model", "x"}, {"dir/", ""}, {"plain.txt", "y"}});
    polyvol::io::ZipArchive za(z, "n.zip");
    EXPECT_EQ(za.file_names(), (std::vector<std::string>{"3D/m\xC3\xBC" "de.model", "plain.txt"}));
    EXPECT_EQ(za.find("3d/M\xC3\xBC" "DE.MODEL"), std::optional<std::string>("3D/m\xC3\xBC" "de.model"));
    EXPECT_EQ(za.read("3D/m\xC3\xBC" "de.model").size(), 1u);
}

// ---------------------------------------------------------------- numbers

TEST(XmlNumbers, CorrectlyRoundedAndStrict) {
    using polyvol::io::xmlnum::parse_double;
    using polyvol::io::xmlnum::parse_index;
    EXPECT_EQ(parse_double("0.1"), 0.1);
    EXPECT_EQ(parse_double(" \n+1.5\t"), 1.5);
    EXPECT_EQ(parse_double("-2.5e-3"), -2.5e-3);
    EXPECT_EQ(parse_double("1E2"), 100.0);
    EXPECT_EQ(parse_double(".5"), 0.5);
    EXPECT_EQ(parse_double("9007199254740993"), 9007199254740992.0);  // tie to even
    EXPECT_EQ(parse_double("1.00000000000000011102230246251565404236316680908203125"), 1.0);
    EXPECT_EQ(parse_double("1.00000000000000011102230246251565404236316680908203126"), 1.0 + 0x1p-52);
    EXPECT_EQ(parse_double("2.2250738585072011e-308"), 2.2250738585072011e-308);
    EXPECT_EQ(parse_double("1e-400"), 0.0);
    EXPECT_TRUE(std::signbit(*parse_double("-0")));
    for (const char* bad : {"", " ", "nan", "NaN", "inf", "-infinity", "1e400", "0x10", "1.5x", "1,5",
                            "--1", "+-1", "+", "1e", ".", "1 2"})
        EXPECT_EQ(parse_double(bad), std::nullopt) << bad;
    EXPECT_EQ(parse_index(" 12 "), 12u);
    EXPECT_EQ(parse_index("+3"), 3u);
    EXPECT_EQ(parse_index("18446744073709551615"), 18446744073709551615u);
    for (const char* bad : {"", "-1", "18446744073709551616", "1.0", "0x1", "1e3", "+", "++1"})
        EXPECT_EQ(parse_index(bad), std::nullopt) << bad;
}

}  // namespace

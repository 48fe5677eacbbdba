// bzip2 streams and tar archives (src/io/archive.cpp): a bzip2 bomb is
// refused at the decompression limit, concatenated streams are one, a tar
// header with a wrong checksum or a member past the end is an error.
#include <gtest/gtest.h>

#include <bzlib.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "io/readers.hpp"
#include "polyvol/io.hpp"

namespace {

using polyvol::ReadError;

std::vector<std::byte> bzip2(const std::string& text) {
    std::vector<char> out(text.size() + text.size() / 100 + 600);
    auto n = static_cast<unsigned>(out.size());
    EXPECT_EQ(BZ2_bzBuffToBuffCompress(out.data(), &n, const_cast<char*>(text.data()),
                                       static_cast<unsigned>(text.size()), 9, 0, 0),
              BZ_OK);
    const auto* p = reinterpret_cast<const std::byte*>(out.data());
    return {p, p + n};
}

std::string message_of(const std::vector<std::byte>& data, const std::string& name) {
    try {
        (void)polyvol::read_mesh_memory(data, name, polyvol::Format::unknown);
    } catch (const ReadError& e) {
        return e.what();
    }
    return "";
}

TEST(Bzip2, ABombIsRefusedAtTheLimit) {
    const std::vector<std::byte> bomb = bzip2(std::string(std::size_t{64} << 20, ' '));
    ASSERT_LT(bomb.size(), 4096u);
    EXPECT_NE(message_of(bomb, "bomb.obj.bz2").find("beyond the decompression limit"), std::string::npos);
}

TEST(Bzip2, ConcatenatedStreamsAreOneFile) {
    std::vector<std::byte> two = bzip2("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    const std::vector<std::byte> faces = bzip2("v 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
    two.insert(two.end(), faces.begin(), faces.end());
    const polyvol::LoadedMesh m = polyvol::read_mesh_memory(two, "tet.obj.bz2", polyvol::Format::unknown);
    EXPECT_EQ(m.mesh.face_count(), 4u);
    EXPECT_EQ(m.notes.front(), "bzip2-compressed");
}

// A one-member ustar archive, its header checksum computed.
std::vector<std::byte> tar_of(const std::string& name, const std::string& data) {
    std::vector<char> t(512 + (data.size() + 511) / 512 * 512 + 1024, '\0');
    std::memcpy(t.data(), name.data(), name.size());
    std::snprintf(t.data() + 124, 12, "%011o", static_cast<unsigned>(data.size()));
    t[156] = '0';
    std::memcpy(t.data() + 257, "ustar\0" "00", 8);
    std::memset(t.data() + 148, ' ', 8);
    unsigned sum = 0;
    for (int i = 0; i < 512; ++i) sum += static_cast<unsigned char>(t[i]);
    std::snprintf(t.data() + 148, 8, "%06o", sum);
    std::memcpy(t.data() + 512, data.data(), data.size());
    const auto* p = reinterpret_cast<const std::byte*>(t.data());
    return {p, p + t.size()};
}

TEST(Tar, MembersAndBadHeaders) {
    const std::string tet = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
    std::vector<std::byte> tar = tar_of("a/tet.obj", tet);
    ASSERT_TRUE(polyvol::io::is_tar(tar));
    EXPECT_EQ(polyvol::io::tar_members(tar, "t.tar"), std::vector<std::string>{"a/tet.obj"});
    const std::vector<std::byte> member = polyvol::io::tar_member(tar, "t.tar", "a/tet.obj", 1 << 20);
    EXPECT_EQ(std::string(reinterpret_cast<const char*>(member.data()), member.size()), tet);
    EXPECT_NE(message_of(tar, "t.tar").find("a tar archive of 1 mesh file (a/tet.obj)"), std::string::npos);
    // a size past the end
    std::vector<std::byte> long_size = tar_of("a/tet.obj", tet);
    long_size.resize(540);  // the header and 28 of its 71 bytes
    EXPECT_THROW(polyvol::io::tar_member(long_size, "t.tar", "a/tet.obj", 1 << 20), ReadError);
    // a wrong checksum: not a tar at all
    tar[0] = std::byte{'b'};
    EXPECT_FALSE(polyvol::io::is_tar(tar));
    EXPECT_TRUE(polyvol::io::tar_members(tar, "t.tar").empty());
}

// A pax record whose length would wrap the reader's position around (a
// review found it looping forever): the header is skipped, promptly.
TEST(Tar, APaxRecordLongerThanItsHeaderIsNotFollowed) {
    const std::string records = "6 a=b\n18446744073709551610 x\n";
    std::vector<std::byte> tar = tar_of("PaxHeader", records);
    tar[156] = std::byte{'x'};
    // recompute the checksum for the new type
    std::memset(reinterpret_cast<char*>(tar.data()) + 148, ' ', 8);
    unsigned sum = 0;
    for (int i = 0; i < 512; ++i) sum += static_cast<unsigned char>(tar[static_cast<std::size_t>(i)]);
    std::snprintf(reinterpret_cast<char*>(tar.data()) + 148, 8, "%06o", sum);
    EXPECT_TRUE(polyvol::io::tar_members(tar, "t.tar").empty());
}

}  // namespace

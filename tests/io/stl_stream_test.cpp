// Streaming binary STL (polyvol/io.hpp: BinaryStlFile, probe_binary_stl, for_each_stl_window):
// detection as read_mesh_file decides it, windows that cover every record
// once at multiples of the alignment asked for, and errors with the byte offset.
#include <gtest/gtest.h>

#include <unistd.h>

#include <tbb/task_arena.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/files.hpp"
#include "common/manifest.hpp"
#include "io_helpers.hpp"
#include "polyvol/io.hpp"

namespace {

namespace fs = std::filesystem;
using namespace polyvol;

const fs::path& kCorpus = polyvol::test::corpus_dir();

// A temporary file removed at the end of the test.
struct TempFile {
    fs::path path;
    explicit TempFile(const std::string& name)
        : path(fs::temp_directory_path() / ("polyvol_stream_" + std::to_string(::getpid()) + "_" + name)) {}
    ~TempFile() { fs::remove(path); }
    void write(const std::vector<std::byte>& bytes) const {
        std::ofstream out(path, std::ios::binary);
        out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    }
};

// A binary STL of n records whose bytes encode their index (so order and
// coverage can be checked).
std::vector<std::byte> numbered_stl(uint32_t n) {
    std::vector<std::byte> b(84 + 50 * std::size_t{n});
    std::memcpy(b.data(), "numbered", 8);
    std::memcpy(&b[80], &n, 4);
    for (uint32_t t = 0; t < n; ++t)
        for (int k = 0; k < 50; ++k) b[84 + 50 * std::size_t{t} + k] = static_cast<std::byte>((t * 7 + k) & 0xFF);
    return b;
}

// Streams path and returns the records put back in order (checks the windows).
std::vector<std::byte> collect(const std::string& path, const StlStreamOptions& options) {
    const BinaryStlProbe p = probe_binary_stl(path);
    std::vector<std::byte> out(50 * p.triangles);
    std::vector<int> seen(p.triangles, 0);
    std::mutex m;
    for_each_stl_window(
        path,
        [&](std::span<const std::byte> records, uint64_t first) {
            EXPECT_EQ(first % std::max<std::size_t>(1, options.alignment), 0u);
            EXPECT_EQ(records.size() % 50, 0u);
            std::lock_guard<std::mutex> lock(m);
            std::memcpy(out.data() + 50 * first, records.data(), records.size());
            for (uint64_t t = first; t < first + records.size() / 50; ++t) ++seen[t];
        },
        options);
    EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
    return out;
}

TEST(StlStream, ProbeAgreesWithTheManifestOnEveryStl) {
    const nlohmann::json& manifest = polyvol::test::corpus_manifest();
    ASSERT_FALSE(manifest.empty()) << "corpus missing at " << kCorpus;
    int binary = 0;
    for (const auto& e : manifest) {
        const std::string rel = e["path"].get<std::string>();
        const fs::path path = kCorpus / rel;
        SCOPED_TRACE(rel);
        const BinaryStlProbe p = probe_binary_stl(path.string());
        const bool expect = e.value("format", "") == "stl" && e.value("encoding", "") == "binary_le";
        EXPECT_EQ(p.binary_stl, expect);
        if (!expect) continue;
        ++binary;
        EXPECT_EQ(p.triangles, e["counts"]["triangles"].get<uint64_t>());
        EXPECT_EQ(p.file_bytes, e["bytes"].get<uint64_t>());
        // Every record, in windows of several sizes, serial and parallel.
        const auto bytes = polyvol::test::read_bytes(path);
        const std::vector<std::byte> want(bytes.begin() + 84, bytes.end());
        for (std::size_t w : {std::size_t{1}, std::size_t{1600}, std::size_t{50 * 4096}, std::size_t{1} << 24})
            for (bool parallel : {false, true})
                for (bool map : {false, true}) EXPECT_EQ(collect(path.string(), {w, parallel, map}), want);
    }
    EXPECT_GE(binary, 15);
}

TEST(StlStream, WindowsCoverALargerFileExactlyOnce) {
    TempFile f("numbered.stl");
    const auto b = numbered_stl(100003);
    f.write(b);
    const std::vector<std::byte> want(b.begin() + 84, b.end());
    for (std::size_t w : {std::size_t{0}, std::size_t{3200}, std::size_t{50 * 4096 + 17}})
        for (bool parallel : {false, true})
            for (bool map : {false, true})
                // Slabs of one window, of a few windows (not a whole number
                // of pages, so neighbours share pages), and the default.
                for (std::size_t slab : {std::size_t{0}, std::size_t{3 * 4096 + 100}, std::size_t{4} << 20})
                    for (std::size_t align : {std::size_t{1}, std::size_t{32}, std::size_t{1000}})  // 32: the soup's blocks
                        EXPECT_EQ(collect(f.path.string(), {w, parallel, map, slab, align}), want);
}

// Resident file pages of this process, in bytes: RssFile + RssShmem in
// /proc/self/status (a file on tmpfs counts as shared memory).
uint64_t resident_file_bytes() {
    std::ifstream in("/proc/self/status");
    std::string key;
    uint64_t total = 0;
    while (in >> key) {
        if (key == "RssFile:" || key == "RssShmem:") {
            uint64_t kb = 0;
            in >> kb;
            total += kb * 1024;
        }
        in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
    }
    return total;
}

TEST(StlStream, MappedSlabsLeaveTheProcessAsTheyFinish) {
    // 80 MB of records in 4 MiB slabs, on one thread and on two: the
    // mapping's resident part stays within a few slabs (the current ones, and
    // the 2 MiB units they share with slabs not yet finished), whatever the
    // file size.
    TempFile f("resident.stl");
    f.write(numbered_stl(1600000));
    tbb::task_arena two(2);
    for (bool parallel : {false, true}) {
        SCOPED_TRACE(parallel);
        const uint64_t before = resident_file_bytes();
        uint64_t most = 0;
        std::mutex m;
        uint64_t records = 0, touched = 0;
        two.execute([&] {
            for_each_stl_window(
                f.path.string(),
                [&](std::span<const std::byte> r, uint64_t) {
                    uint64_t sum = 0;  // touches every page
                    for (std::size_t i = 0; i < r.size(); i += 512) sum += std::to_integer<uint64_t>(r[i]);
                    std::lock_guard<std::mutex> lock(m);
                    records += r.size() / 50;
                    touched += sum;
                    most = std::max(most, resident_file_bytes());
                },
                {50 * 4096, parallel, true, std::size_t{4} << 20});
        });
        EXPECT_EQ(records, 1600000u);
        EXPECT_GT(touched, 0u);
        ASSERT_GT(most, before);
        EXPECT_LT(most - before, uint64_t{24} << 20);
    }
}

TEST(StlStream, NotBinaryStl) {
    EXPECT_FALSE(probe_binary_stl("-").binary_stl);
    EXPECT_FALSE(probe_binary_stl((kCorpus / "meshes/stl-models/unitCube.ascii.stl").string()).binary_stl);
    const ReadError missing = iotest::expect_error([] { (void)probe_binary_stl("/nonexistent/x.stl"); });
    EXPECT_NE(std::string(missing.what()).find("cannot open"), std::string::npos);

    // Truncated: the size rule fails; the error names byte 80 as read_mesh_file does.
    TempFile f("truncated.stl");
    auto b = numbered_stl(1000);
    b.resize(b.size() - 7);
    f.write(b);
    EXPECT_FALSE(probe_binary_stl(f.path.string()).binary_stl);
    const ReadError e = iotest::expect_error([&] { for_each_stl_window(f.path.string(), [](auto, uint64_t) {}); });
    EXPECT_TRUE(e.has_byte_offset);
    EXPECT_EQ(e.byte_offset, 80u);
    EXPECT_NE(e.message.find("declares 1000 triangles"), std::string::npos) << e.message;
    const ReadError full = iotest::expect_error([&] { (void)read_mesh_file(f.path.string()); });
    EXPECT_EQ(full.byte_offset, e.byte_offset);

    TempFile s("short.stl");
    s.write(std::vector<std::byte>(40, std::byte{0}));
    const ReadError short_error = iotest::expect_error([&] { for_each_stl_window(s.path.string(), [](auto, uint64_t) {}); });
    EXPECT_NE(short_error.message.find("too short"), std::string::npos);

    // gzip magic wins over the size rule, as in read_mesh_file.
    TempFile g("gz.stl");
    auto gz = numbered_stl(10);
    gz[0] = std::byte{0x1f};
    gz[1] = std::byte{0x8b};
    g.write(gz);
    EXPECT_FALSE(probe_binary_stl(g.path.string()).binary_stl);
}

TEST(StlStream, AFileThatShrinksWhileReadErrorsWithTheOffset) {
    TempFile f("shrinking.stl");
    f.write(numbered_stl(10000));
    bool first = true;
    const ReadError e = iotest::expect_error([&] {
        for_each_stl_window(
            f.path.string(),
            [&](std::span<const std::byte>, uint64_t) {
                if (first) fs::resize_file(f.path, 84 + 50 * 5000 + 20);
                first = false;
            },
            {50 * 1024, false, /*map=*/false});
    });
    EXPECT_TRUE(e.has_byte_offset);
    EXPECT_EQ(e.byte_offset, 84u + 50 * 5000 + 20);
    EXPECT_NE(e.message.find("unexpected end of file"), std::string::npos) << e.message;
}

TEST(StlStream, CallbackExceptionsPropagate) {
    TempFile f("throws.stl");
    f.write(numbered_stl(5000));
    for (bool parallel : {false, true})
        EXPECT_THROW(for_each_stl_window(
                         f.path.string(), [](std::span<const std::byte>, uint64_t) { throw std::runtime_error("stop"); },
                         {1600, parallel}),
                     std::runtime_error);
}

}  // namespace

namespace {

TEST(StlStream, BinaryStlTrianglesArePackedFromTheRecords) {
    // The numbered file's bytes 12..47 of each record, packed; at sizes that
    // make several windows and a partial last group of 32.
    for (uint32_t n : {0u, 1u, 33u, 100003u}) {
        SCOPED_TRACE(n);
        TempFile f("packed.stl");
        auto b = numbered_stl(n);
        // Finite coordinates: clear each float's top exponent bit.
        for (uint32_t t = 0; t < n; ++t)
            for (int k = 0; k < 9; ++k) b[84 + 50 * std::size_t{t} + 12 + 4 * k + 3] &= std::byte{0x3F};
        f.write(b);
        const std::vector<float> tri = read_binary_stl_triangles(f.path.string());
        ASSERT_EQ(tri.size(), 9 * std::size_t{n});
        for (uint32_t t = 0; t < n; ++t)
            ASSERT_EQ(std::memcmp(&tri[9 * std::size_t{t}], &b[84 + 50 * std::size_t{t} + 12], 36), 0) << t;
    }
}

TEST(StlStream, BinaryStlTrianglesErrors) {
    // Not binary STL: the streaming reader's error (where, and why).
    const ReadError ascii = iotest::expect_error(
        [] { (void)read_binary_stl_triangles((kCorpus / "meshes/stl-models/unitCube.ascii.stl").string()); });
    EXPECT_TRUE(ascii.has_byte_offset);
    EXPECT_EQ(ascii.byte_offset, 80u);
    const ReadError missing = iotest::expect_error([] { (void)read_binary_stl_triangles("/nonexistent/x.stl"); });
    EXPECT_NE(std::string(missing.what()).find("cannot open"), std::string::npos);
    // NaN or infinity: the byte offset of the first one in the file, however
    // the windows ran (read_mesh_file names the same byte).
    TempFile f("nonfinite.stl");
    auto b = numbered_stl(70000);
    for (uint32_t t = 0; t < 70000; ++t)
        for (int k = 0; k < 9; ++k) b[84 + 50 * std::size_t{t} + 12 + 4 * k + 3] &= std::byte{0x3F};
    const float inf = std::numeric_limits<float>::infinity(), nan = std::numeric_limits<float>::quiet_NaN();
    // In another window, in the same window after it (a later triangle, a
    // later coordinate of the same triangle), and the first.
    std::memcpy(&b[84 + 50 * 69000 + 12 + 4 * 2], &nan, 4);
    std::memcpy(&b[84 + 50 * 41002 + 12 + 4 * 0], &nan, 4);
    std::memcpy(&b[84 + 50 * 41000 + 12 + 4 * 7], &inf, 4);
    std::memcpy(&b[84 + 50 * 41000 + 12 + 4 * 5], &inf, 4);
    f.write(b);
    const ReadError e = iotest::expect_error([&] { (void)read_binary_stl_triangles(f.path.string()); });
    EXPECT_TRUE(e.has_byte_offset);
    EXPECT_EQ(e.byte_offset, 84u + 50 * 41000 + 12 + 4 * 5);
    EXPECT_NE(e.message.find("non-finite coordinate in triangle 41000"), std::string::npos) << e.message;
    EXPECT_EQ(iotest::expect_error([&] { (void)read_mesh_file(f.path.string()); }).byte_offset, e.byte_offset);
}

}  // namespace

namespace {

// BinaryStlFile streams the file it opened and probed, pass after pass, even
// when its path is replaced between the passes (two opens, one to probe and
// one to stream, would read the other file).
TEST(StlStream, AnOpenFileStreamsWhatItProbed) {
    const TempFile f("replaced.stl"), g("other.stl");
    const std::vector<std::byte> first = numbered_stl(1000);
    f.write(first);
    std::vector<std::byte> other = numbered_stl(2000);
    other[84] = std::byte{0x55};  // differs from first in record 0 as well as in length
    g.write(other);
    BinaryStlFile opened(f.path.string());
    const BinaryStlFile file = std::move(opened);  // the descriptor moves with it
    EXPECT_FALSE(opened.probe().binary_stl);         // NOLINT(bugprone-use-after-move): moved-from holds nothing
    EXPECT_THROW(opened.for_each_window([](auto, uint64_t) {}), ReadError);
    ASSERT_TRUE(file.probe().binary_stl);
    EXPECT_EQ(file.probe().triangles, 1000u);
    fs::rename(g.path, f.path);  // the path now names the other file
    for (bool map : {true, false}) {
        for (int pass = 0; pass < 2; ++pass) {
            std::vector<std::byte> got(50 * 1000);
            std::vector<int> seen(1000, 0);
            std::mutex m;
            file.for_each_window(
                [&](std::span<const std::byte> records, uint64_t at) {
                    std::lock_guard<std::mutex> lock(m);
                    ASSERT_LE(at + records.size() / 50, 1000u);
                    std::memcpy(got.data() + 50 * at, records.data(), records.size());
                    for (uint64_t t = at; t < at + records.size() / 50; ++t) ++seen[t];
                },
                {1600, true, map});
            EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int s) { return s == 1; }));
            EXPECT_TRUE(std::equal(got.begin(), got.end(), first.begin() + 84)) << "map " << map << " pass " << pass;
        }
    }
    // The path itself now streams the other file.
    EXPECT_EQ(probe_binary_stl(f.path.string()).triangles, 2000u);
}

}  // namespace

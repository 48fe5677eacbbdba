// Files truncated by another writer while polyvol reads them: read_mesh_file
// and the streamed binary STL (default options) either read the whole file,
// or throw ReadError — never a signal (a mapping of the file would end this
// process with SIGBUS). Many rounds, truncation at random offsets and random
// moments, in binary STL and OBJ, and through the command.
#include <gtest/gtest.h>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "polyvol/io.hpp"

namespace {

namespace fs = std::filesystem;
using namespace polyvol;

fs::path temp_path(const std::string& name) {
    return fs::temp_directory_path() / ("polyvol_trunc_" + std::to_string(::getpid()) + "_" + name);
}

void write(const fs::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

// A binary STL of n triangles (a fan of distinct points; the geometry does not matter here).
std::string binary_stl(uint32_t n) {
    std::string b(84 + 50 * std::size_t{n}, '\0');
    std::memcpy(&b[80], &n, 4);
    for (uint32_t t = 0; t < n; ++t) {
        float v[12] = {0, 0, 1, 0, 0, 0, static_cast<float>(t), 1, 0, static_cast<float>(t) + 1, 0, 1};
        std::memcpy(&b[84 + 50 * std::size_t{t}], v, sizeof v);
    }
    return b;
}

std::string obj(uint32_t n) {
    std::string s;
    for (uint32_t v = 0; v < n + 2; ++v) s += "v " + std::to_string(v) + " " + std::to_string(v % 7) + " 0.5\n";
    for (uint32_t f = 1; f <= n; ++f) s += "f " + std::to_string(f) + " " + std::to_string(f + 1) + " " + std::to_string(f + 2) + "\n";
    return s;
}

// Runs `read` while another thread truncates the file at a random offset
// after a random delay; returns whether read succeeded (it must otherwise
// throw ReadError).
// The delay is drawn up to half the time the fastest of three whole reads
// takes (the first is cold, and a loaded machine slows some), so that most
// cuts land while the file is being read.
template <class Read>
int rounds(const fs::path& path, const std::string& bytes, int n, std::mt19937_64& rng, Read&& read) {
    write(path, bytes);
    auto span = std::chrono::microseconds::max();
    for (int k = 0; k < 3; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        read();
        span = std::min(span, std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - t0) / 2);
    }
    int whole = 0;
    for (int r = 0; r < n; ++r) {
        write(path, bytes);
        const auto offset = std::uniform_int_distribution<std::size_t>(0, bytes.size() - 1)(rng);
        const auto delay = std::chrono::microseconds(
            std::uniform_int_distribution<int64_t>(0, std::max<int64_t>(1, span.count()))(rng));
        std::thread cut([&] {
            std::this_thread::sleep_for(delay);
            fs::resize_file(path, offset);
        });
        try {
            read();
            ++whole;
        } catch (const ReadError& e) {
            EXPECT_FALSE(e.message.empty());
        }
        cut.join();
    }
    return whole;
}

TEST(Truncation, ReadingWhileAnotherWriterTruncatesIsAReadErrorNotASignal) {
    std::mt19937_64 rng(20261127);
    const fs::path stl = temp_path("t.stl"), text = temp_path("t.obj");
    const std::string big = binary_stl(400000), words = obj(60000);
    int read_whole = 0, streamed_whole = 0, text_whole = 0;
    read_whole = rounds(stl, big, 40, rng, [&] {
        const LoadedMesh m = read_mesh_file(stl.string());
        EXPECT_EQ(m.mesh.face_count(), 400000u);  // a success is the whole file
    });
    streamed_whole = rounds(stl, big, 40, rng, [&] {
        std::atomic<uint64_t> records{0};
        for_each_stl_window(stl.string(), [&](std::span<const std::byte> r, uint64_t) { records += r.size() / 50; });
        EXPECT_EQ(records.load(), 400000u);
    });
    text_whole = rounds(text, words, 40, rng, [&] {
        const LoadedMesh m = read_mesh_file(text.string());
        EXPECT_LE(m.mesh.face_count(), 60000u);  // text may end at a line: a prefix is a valid OBJ
    });
    fs::remove(stl);
    fs::remove(text);
    // Both outcomes happened (truncation met the reads, not only came after them).
    EXPECT_LT(read_whole + streamed_whole + text_whole, 120);
    std::printf("whole reads: loaded %d/40, streamed %d/40, text %d/40\n", read_whole, streamed_whole, text_whole);
}

// The command, as a separate process: exit 0 or 2, never a signal.
TEST(Truncation, TheCommandExitsWithAnErrorNotASignal) {
    std::mt19937_64 rng(7);
    const fs::path stl = temp_path("cli.stl");
    const std::string big = binary_stl(200000);
    for (int r = 0; r < 12; ++r) {
        write(stl, big);
        const pid_t pid = ::fork();
        ASSERT_GE(pid, 0);
        if (pid == 0) {
            ::execl(POLYVOL_CLI, POLYVOL_CLI, r % 2 ? "volume" : "measure", stl.c_str(), static_cast<char*>(nullptr));
            ::_exit(127);
        }
        std::this_thread::sleep_for(std::chrono::microseconds(std::uniform_int_distribution<int>(0, 4000)(rng)));
        fs::resize_file(stl, std::uniform_int_distribution<std::size_t>(0, big.size() - 1)(rng));
        int status = 0;
        ASSERT_EQ(::waitpid(pid, &status, 0), pid);
        ASSERT_FALSE(WIFSIGNALED(status)) << "signal " << WTERMSIG(status);
        const int code = WEXITSTATUS(status);
        EXPECT_TRUE(code == 0 || code == 2 || code == 3) << code;
    }
    fs::remove(stl);
}

}  // namespace

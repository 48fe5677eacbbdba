// Running the polyvol binary (POLYVOL_CLI) from the CLI tests: exit code,
// standard output and standard error of one command line.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

namespace cli_test {

struct CliRun {
    int code = -1;  // exit code, -1 when the command did not exit normally
    std::string out, err;
};

// Runs `ENV polyvol ARGS` through the shell (so ARGS may quote and redirect;
// ENV: variable assignments for the command, or empty).
inline CliRun run_polyvol_env(const std::string& env, const std::string& args) {
    static std::atomic<int> counter{0};
    const std::filesystem::path err = std::filesystem::temp_directory_path() /
                                      ("polyvol_cli_test_" + std::to_string(::getpid()) + "_" +
                                       std::to_string(counter++) + ".err");
    const std::string cmd = env + (env.empty() ? "" : " ") + "'" + POLYVOL_CLI + "' " + args + " 2>'" + err.string() + "'";
    CliRun r;
    FILE* p = ::popen(cmd.c_str(), "r");
    if (!p) return r;
    std::array<char, 4096> buf;
    std::size_t n;
    while ((n = std::fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
    const int status = ::pclose(p);
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream in(err, std::ios::binary);
    r.err.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    std::error_code ec;
    std::filesystem::remove(err, ec);
    return r;
}

// Runs `polyvol ARGS` through the shell.
inline CliRun run_polyvol(const std::string& args) { return run_polyvol_env("", args); }

// Writes an OBJ of axis-aligned boxes {xlo, ylo, zlo, xhi, yhi, zhi}, quads
// outward; `drop_last` leaves the last face out (an open surface).
inline void write_boxes_obj(const std::filesystem::path& p, std::initializer_list<std::array<double, 6>> boxes,
                            bool drop_last = false) {
    std::ofstream out(p);
    int base = 1;
    std::string faces;
    for (const auto& b : boxes) {
        for (int i = 0; i < 8; ++i)
            out << "v " << (i & 1 ? b[3] : b[0]) << " " << (i >> 1 & 1 ? b[4] : b[1]) << " "
                << (i >> 2 & 1 ? b[5] : b[2]) << "\n";
        const int q[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
        for (const auto& f : q)
            faces += "f " + std::to_string(base + f[0]) + " " + std::to_string(base + f[1]) + " " +
                     std::to_string(base + f[2]) + " " + std::to_string(base + f[3]) + "\n";
        base += 8;
    }
    if (drop_last) faces.erase(faces.rfind("f "));
    out << faces;
}

}  // namespace cli_test

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
#include <string>

namespace cli_test {

struct CliRun {
    int code = -1;  // exit code, -1 when the command did not exit normally
    std::string out, err;
};

// Runs `polyvol ARGS` through the shell (so ARGS may quote and redirect).
inline CliRun run_polyvol(const std::string& args) {
    static std::atomic<int> counter{0};
    const std::filesystem::path err = std::filesystem::temp_directory_path() /
                                      ("polyvol_cli_test_" + std::to_string(::getpid()) + "_" +
                                       std::to_string(counter++) + ".err");
    const std::string cmd = std::string("'") + POLYVOL_CLI + "' " + args + " 2>'" + err.string() + "'";
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

}  // namespace cli_test

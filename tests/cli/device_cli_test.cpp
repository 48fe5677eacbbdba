// `--device` and `polyvol devices` as users run them: the OpenCL device
// (pocl here) writes the same bytes as the CPU; no runtime or no platform
// runs the CPU with a note and exit 0; a device that cannot be had exits 5;
// `cells --device opencl` says it computes on the CPU.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

#include "cli/run_cli.hpp"
#include "common/opencl_device.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using cli_test::CliRun;

const fs::path kCorpus = POLYVOL_CORPUS_DIR;
const fs::path kData = POLYVOL_TEST_DATA;

CliRun polyvol(const std::string& args) { return cli_test::run_polyvol(args); }

std::string corpus(const std::string& rel) { return "'" + (kCorpus / "meshes" / rel).string() + "'"; }

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("polyvol_device_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir / name;
}

std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}


const std::string kMesh = corpus("stl-models/gearwheel.ascii.stl");

// Removes the scratch files when the test program ends.
struct ScratchCleanup {
    ~ScratchCleanup() {
        std::error_code ec;
        fs::remove_all(scratch("").parent_path(), ec);
    }
} scratch_cleanup;

TEST(DevicesCli, ListsTheCpuAndEachOpenclDevice) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const CliRun text = polyvol("devices");
    EXPECT_EQ(text.code, 0);
    EXPECT_NE(text.out.find("cpu: oneTBB"), std::string::npos) << text.out;
    EXPECT_NE(text.out.find("opencl:0: "), std::string::npos) << text.out;
    const CliRun j = polyvol("devices --json");
    ASSERT_EQ(j.code, 0);
    const json list = json::parse(j.out);
    EXPECT_TRUE(list["opencl_runtime"].get<bool>());
    ASSERT_FALSE(list["devices"].empty());
    for (const char* key : {"index", "name", "platform", "vendor", "type", "version", "global_memory", "compute_units",
                            "fp64", "usable", "reason"})
        EXPECT_TRUE(list["devices"][0].contains(key)) << key;
}

TEST(DevicesCli, WithoutARuntimeTheListIsEmptyAndSaysWhy) {
    const CliRun r = cli_test::run_polyvol_env("POLYVOL_OPENCL_LIBRARY=/nonexistent/libOpenCL.so.1", "devices --json");
    ASSERT_EQ(r.code, 0) << r.err;
    const json list = json::parse(r.out);
    EXPECT_FALSE(list["opencl_runtime"].get<bool>());
    EXPECT_TRUE(list["devices"].empty());
    EXPECT_EQ(list["note"], "no OpenCL runtime (/nonexistent/libOpenCL.so.1 not found)");
}

TEST(GridDeviceCli, OpenclWritesTheCpusBytes) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    std::string files[2];
    for (const std::string device : {"cpu", "opencl"}) {
        const fs::path npy = scratch(device + ".npy"), surface = scratch(device + "_surface.npy"),
                       centroids = scratch(device + "_centroids.npy");
        const CliRun r = polyvol("grid " + kMesh + " --cells 40 --device " + device + " --json -o '" + npy.string() +
                                 "' --surface '" + surface.string() + "' --centroids '" + centroids.string() + "'");
        ASSERT_EQ(r.code, 0) << r.err;
        const json j = json::parse(r.out);
        if (device == "cpu")
            EXPECT_EQ(j["device"], "cpu");
        else
            EXPECT_TRUE(j["device"].get<std::string>().starts_with("opencl: ")) << j["device"];
        files[device == "cpu" ? 0 : 1] = slurp(npy) + slurp(surface) + slurp(centroids);
    }
    EXPECT_GT(files[0].size(), 40u * 40 * 8);
    EXPECT_TRUE(files[0] == files[1]) << "the .npy files differ";
}

TEST(GridDeviceCli, NoRuntimeOrNoPlatformRunsTheCpuWithANote) {
    const std::string vendors = scratch("no_vendors").string();
    fs::create_directories(vendors);
    const CliRun cpu = polyvol("grid " + kMesh + " --cells 12 --json");
    ASSERT_EQ(cpu.code, 0) << cpu.err;
    for (const auto& [env, why] : {std::pair<std::string, std::string>{"POLYVOL_OPENCL_LIBRARY=/nonexistent/libOpenCL.so.1",
                                                                       "no OpenCL runtime"},
                                   {"POLYVOL_OPENCL_LIBRARY= OCL_ICD_VENDORS='" + vendors + "'", "no OpenCL platform"}}) {
        const CliRun r = cli_test::run_polyvol_env(env, "grid " + kMesh + " --cells 12 --json --device opencl");
        ASSERT_EQ(r.code, 0) << env << ": " << r.err;
        const json j = json::parse(r.out);
        EXPECT_TRUE(j["device"].get<std::string>().starts_with("cpu (" + why)) << env << ": " << j["device"];
        EXPECT_NE(r.err.find("note: computed on the CPU, not OpenCL"), std::string::npos) << r.err;
        EXPECT_EQ(j["body_volumes"], json::parse(cpu.out)["body_volumes"]);
    }
}

TEST(GridDeviceCli, ADeviceThatCannotBeHadExits5AndABadNameExits1) {
    POLYVOL_REQUIRE_OPENCL_DEVICE();
    const CliRun beyond = polyvol("grid " + kMesh + " --cells 8 --device opencl:99");
    EXPECT_EQ(beyond.code, 5) << beyond.err;
    EXPECT_NE(beyond.err.find("no OpenCL device 99"), std::string::npos) << beyond.err;
    const CliRun bad = polyvol("grid " + kMesh + " --cells 8 --device gpu");
    EXPECT_EQ(bad.code, 1);
    EXPECT_NE(bad.err.find("--device must be auto, cpu, opencl or opencl:N"), std::string::npos) << bad.err;
}

TEST(CellsDeviceCli, OpenclIsAcceptedAndTheCellsSayTheyRanOnTheCpu) {
    const std::string mesh = "'" + (kData / "openfoam" / "graded_box").string() + "'";
    const CliRun r = polyvol("cells " + mesh + " --json --device opencl");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_TRUE(json::parse(r.out)["device"].get<std::string>().starts_with("cpu (cells are exact booleans"));
    EXPECT_NE(r.err.find("computed on the CPU"), std::string::npos) << r.err;
    EXPECT_EQ(polyvol("cells " + mesh + " --device cuda").code, 1);
}

}  // namespace

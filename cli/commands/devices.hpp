// `polyvol devices [--json]`: the OpenCL devices `--device opencl:N` can name
// (polyvol/device.hpp), with whether each can run the grid and why not.
#pragma once

#include <CLI/CLI.hpp>

namespace polyvol::cli {

struct DevicesArgs {
    bool json = false;
};

CLI::App* add_devices_command(CLI::App& app, DevicesArgs& args);

// Exit code 0, also without OpenCL (the list is then empty and says why).
int run_devices_command(const DevicesArgs& args);

}  // namespace polyvol::cli

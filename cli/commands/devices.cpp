// polyvol devices — the OpenCL devices of this machine, as --device names them.
#include "commands/devices.hpp"

#include <iostream>

#include <nlohmann/json.hpp>

#include "polyvol/device.hpp"

namespace polyvol::cli {

CLI::App* add_devices_command(CLI::App& app, DevicesArgs& a) {
    auto* cmd = app.add_subcommand("devices", "The OpenCL devices --device opencl:N can name (grid, cells)");
    cmd->add_flag("--json", a.json, "Print the list as JSON on stdout");
    return cmd;
}

int run_devices_command(const DevicesArgs& a) {
    const DeviceList list = list_devices();
    if (a.json) {
        nlohmann::json j;
        j["opencl_runtime"] = list.runtime;
        if (!list.note.empty()) j["note"] = list.note;
        j["devices"] = nlohmann::json::array();
        for (const DeviceInfo& d : list.devices)
            j["devices"].push_back({{"index", d.index},
                                    {"name", d.name},
                                    {"platform", d.platform},
                                    {"vendor", d.vendor},
                                    {"type", d.type},
                                    {"version", d.version},
                                    {"global_memory", d.global_memory},
                                    {"compute_units", d.compute_units},
                                    {"fp64", d.fp64},
                                    {"usable", d.usable},
                                    {"reason", d.reason}});
        std::cout << j.dump(2) << "\n";
        return 0;
    }
    std::cout << "cpu: oneTBB on this machine's cores (--device cpu; what --device auto chooses)\n";
    if (list.devices.empty()) std::cout << "opencl: none (" << list.note << ")\n";
    for (const DeviceInfo& d : list.devices) {
        std::cout << "opencl:" << d.index << ": " << d.name << " (" << d.type << ", " << d.platform << ", "
                  << d.compute_units << " compute units, " << d.global_memory / (1u << 20) << " MiB) — ";
        if (!d.usable)
            std::cout << "not usable: " << d.reason << "\n";
        else if (d.type == "cpu")
            std::cout << "usable, the same bits as the CPU path (a CPU OpenCL device: never chosen by auto)\n";
        else
            std::cout << "usable, the same bits as the CPU path\n";
    }
    return 0;
}

}  // namespace polyvol::cli

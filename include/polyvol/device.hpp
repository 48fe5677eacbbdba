// polyvol/device.hpp — where the grid's per-cell work runs: the CPU (oneTBB)
// or an OpenCL device, with the same bits either way (docs/grid.md, "Devices").
//
// OpenCL is loaded at run time (libOpenCL.so.1, the ICD loader; the variable
// POLYVOL_OPENCL_LIBRARY names another file): a machine without it runs the
// CPU path and nothing else changes. A device is usable when it has IEEE
// double precision (cl_khr_fp64 with round-to-nearest, infinities, NaNs and
// denormals) and its compiler keeps every product rounded on its own (checked
// once per device by a small kernel whose bits are known).
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace polyvol {

enum class DeviceKind : uint8_t {
    automatic,  // the CPU until a GPU threshold is measured; never a CPU OpenCL device
    cpu,        // oneTBB on this machine's cores
    opencl,     // an OpenCL device: `index` in list_devices() order, or the first usable (GPUs first)
};

struct DeviceRequest {
    DeviceKind kind = DeviceKind::automatic;
    int index = -1;  // opencl only; -1: the first usable device
};

// "auto", "cpu", "opencl" or "opencl:N"; std::invalid_argument otherwise.
DeviceRequest parse_device(std::string_view text);

struct DeviceInfo {
    int index = 0;  // what opencl:N names
    std::string platform, name, vendor;
    std::string type;     // "gpu", "cpu", "accelerator" or "other"
    std::string version;  // CL_DEVICE_VERSION, e.g. "OpenCL 3.0 PoCL ..."
    std::uint64_t global_memory = 0;
    unsigned compute_units = 0;
    bool fp64 = false;
    bool usable = false;
    std::string reason;  // why not usable (empty when usable)
};

struct DeviceList {
    bool runtime = false;  // the OpenCL loader was found and answered
    std::string note;      // "" or why there are no devices ("no OpenCL runtime: ...", "no OpenCL platform")
    std::vector<DeviceInfo> devices;
};

// The OpenCL devices of this machine (each probed once per process).
DeviceList list_devices();

// An OpenCL request that cannot be met: the device named is absent or has
// no fp64, no device is usable, its canary or its kernel build failed, an
// OpenCL call failed, or it runs out of memory even for one row of columns.
// The message names the device and the cause, with the compiler's log for a
// build error. The outputs are then incomplete. (No OpenCL runtime or
// driver at all is not an error: the CPU computes.)
class DeviceError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace polyvol

// device/opencl.cpp — the OpenCL loader opened at run time, the devices probed
// once, their contexts and built programs kept for the process.
#include "device/opencl.hpp"

#include <dlfcn.h>

#include <charconv>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <memory>
#include <string>

namespace polyvol::device {
namespace {

struct Loaded {
    Api api{};
    bool ok = false;
    std::string why;
};

template <class F>
bool bind(void* lib, const char* name, F& slot) {
    void* p = dlsym(lib, name);
    slot = reinterpret_cast<F>(p);
    return p != nullptr;
}

Loaded load() {
    Loaded l;
    const char* env = std::getenv("POLYVOL_OPENCL_LIBRARY");
    const std::string file = env && *env ? env : "libOpenCL.so.1";
    void* lib = dlopen(file.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        l.why = "no OpenCL runtime (" + file + " not found)";
        return l;
    }
    Api& a = l.api;
    const bool all = bind(lib, "clGetPlatformIDs", a.GetPlatformIDs) && bind(lib, "clGetPlatformInfo", a.GetPlatformInfo) &&
                     bind(lib, "clGetDeviceIDs", a.GetDeviceIDs) && bind(lib, "clGetDeviceInfo", a.GetDeviceInfo) &&
                     bind(lib, "clCreateContext", a.CreateContext) &&
                     bind(lib, "clCreateCommandQueue", a.CreateCommandQueue) &&
                     bind(lib, "clCreateProgramWithSource", a.CreateProgramWithSource) &&
                     bind(lib, "clBuildProgram", a.BuildProgram) &&
                     bind(lib, "clGetProgramBuildInfo", a.GetProgramBuildInfo) &&
                     bind(lib, "clCreateKernel", a.CreateKernel) && bind(lib, "clSetKernelArg", a.SetKernelArg) &&
                     bind(lib, "clCreateBuffer", a.CreateBuffer) &&
                     bind(lib, "clEnqueueWriteBuffer", a.EnqueueWriteBuffer) &&
                     bind(lib, "clEnqueueReadBuffer", a.EnqueueReadBuffer) &&
                     bind(lib, "clEnqueueFillBuffer", a.EnqueueFillBuffer) &&
                     bind(lib, "clEnqueueNDRangeKernel", a.EnqueueNDRangeKernel) && bind(lib, "clFinish", a.Finish) &&
                     bind(lib, "clReleaseMemObject", a.ReleaseMemObject) && bind(lib, "clReleaseKernel", a.ReleaseKernel) &&
                     bind(lib, "clReleaseProgram", a.ReleaseProgram) && bind(lib, "clReleaseContext", a.ReleaseContext) &&
                     bind(lib, "clGetKernelWorkGroupInfo", a.GetKernelWorkGroupInfo);
    if (!all) {
        l.why = "no OpenCL runtime (" + file + " lacks OpenCL 1.2 entry points)";
        return l;
    }
    l.ok = true;
    return l;
}

const Loaded& loaded() {
    static const Loaded l = load();
    return l;
}

std::string info_string(cl_device_id d, cl_device_info what) {
    std::size_t n = 0;
    if (api()->GetDeviceInfo(d, what, 0, nullptr, &n) != CL_SUCCESS || n == 0) return {};
    std::string s(n, '\0');
    api()->GetDeviceInfo(d, what, n, s.data(), nullptr);
    while (!s.empty() && (s.back() == '\0' || s.back() == ' ')) s.pop_back();
    return s;
}

template <class T>
T info_value(cl_device_id d, cl_device_info what) {
    T v{};
    api()->GetDeviceInfo(d, what, sizeof v, &v, nullptr);
    return v;
}

struct Probe {
    std::string note;                           // why there are no devices
    std::deque<Device> devices;                 // stable addresses
};

// fp64 as polyvol needs it: the extension and IEEE double's rounding, infinities, NaNs, denormals.
bool has_fp64(cl_device_id d) {
    const std::string ext = info_string(d, CL_DEVICE_EXTENSIONS);
    const auto config = info_value<cl_device_fp_config>(d, CL_DEVICE_DOUBLE_FP_CONFIG);
    const cl_device_fp_config need = CL_FP_ROUND_TO_NEAREST | CL_FP_INF_NAN | CL_FP_DENORM;
    return ext.find("cl_khr_fp64") != std::string::npos && (config & need) == need;
}

Probe probe() {
    Probe p;
    std::string why;
    const Api* a = api(&why);
    if (!a) {
        p.note = why;
        return p;
    }
    cl_uint np = 0;
    if (a->GetPlatformIDs(0, nullptr, &np) != CL_SUCCESS || np == 0) {
        p.note = "no OpenCL platform (the loader found no driver)";
        return p;
    }
    std::vector<cl_platform_id> platforms(np);
    a->GetPlatformIDs(np, platforms.data(), nullptr);
    for (cl_platform_id pl : platforms) {
        std::size_t n = 0;
        std::string pname;
        if (a->GetPlatformInfo(pl, CL_PLATFORM_NAME, 0, nullptr, &n) == CL_SUCCESS && n > 0) {
            pname.resize(n);
            a->GetPlatformInfo(pl, CL_PLATFORM_NAME, n, pname.data(), nullptr);
            while (!pname.empty() && pname.back() == '\0') pname.pop_back();
        }
        cl_uint nd = 0;
        if (a->GetDeviceIDs(pl, CL_DEVICE_TYPE_ALL, 0, nullptr, &nd) != CL_SUCCESS || nd == 0) continue;
        std::vector<cl_device_id> ids(nd);
        a->GetDeviceIDs(pl, CL_DEVICE_TYPE_ALL, nd, ids.data(), nullptr);
        for (cl_device_id id : ids) {
            Device& d = p.devices.emplace_back();
            d.id = id;
            DeviceInfo& i = d.info;
            i.index = static_cast<int>(p.devices.size()) - 1;
            i.platform = pname;
            i.name = info_string(id, CL_DEVICE_NAME);
            i.vendor = info_string(id, CL_DEVICE_VENDOR);
            i.version = info_string(id, CL_DEVICE_VERSION);
            const auto type = info_value<cl_device_type>(id, CL_DEVICE_TYPE);
            i.type = (type & CL_DEVICE_TYPE_GPU)           ? "gpu"
                     : (type & CL_DEVICE_TYPE_CPU)         ? "cpu"
                     : (type & CL_DEVICE_TYPE_ACCELERATOR) ? "accelerator"
                                                           : "other";
            i.global_memory = info_value<cl_ulong>(id, CL_DEVICE_GLOBAL_MEM_SIZE);
            i.compute_units = info_value<cl_uint>(id, CL_DEVICE_MAX_COMPUTE_UNITS);
            d.fp64 = has_fp64(id);
        }
    }
    if (p.devices.empty()) p.note = "no OpenCL device (the platforms list none)";
    return p;
}

Probe& probed() {
    static Probe p = probe();
    return p;
}

// The device's description now (the fail points apply at each call).
DeviceInfo info_now(const Device& d) {
    DeviceInfo i = d.info;
    i.fp64 = d.fp64 && !fail_points().no_fp64;
    i.usable = i.fp64;
    i.reason = i.usable ? "" : "no cl_khr_fp64 with IEEE rounding, infinities and denormals (polyvol needs IEEE double)";
    return i;
}

std::string label(const DeviceInfo& i) { return "device " + std::to_string(i.index) + " \"" + i.name + "\""; }

}  // namespace

const Api* api(std::string* why) {
    const Loaded& l = loaded();
    if (why) *why = l.why;
    return l.ok ? &l.api : nullptr;
}

FailPoints& fail_points() {
    static FailPoints f;
    return f;
}

const char* error_name(cl_int code) {
    switch (code) {
        case CL_DEVICE_NOT_FOUND: return "CL_DEVICE_NOT_FOUND";
        case CL_DEVICE_NOT_AVAILABLE: return "CL_DEVICE_NOT_AVAILABLE";
        case CL_COMPILER_NOT_AVAILABLE: return "CL_COMPILER_NOT_AVAILABLE";
        case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
        case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
        case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
        case CL_BUILD_PROGRAM_FAILURE: return "CL_BUILD_PROGRAM_FAILURE";
        case CL_INVALID_VALUE: return "CL_INVALID_VALUE";
        case CL_INVALID_BUFFER_SIZE: return "CL_INVALID_BUFFER_SIZE";
        case CL_INVALID_KERNEL_ARGS: return "CL_INVALID_KERNEL_ARGS";
        case CL_INVALID_WORK_GROUP_SIZE: return "CL_INVALID_WORK_GROUP_SIZE";
        case CL_INVALID_ARG_SIZE: return "CL_INVALID_ARG_SIZE";
        case CL_INVALID_KERNEL_NAME: return "CL_INVALID_KERNEL_NAME";
        default: return "an OpenCL error";
    }
}

void check(const Device& d, cl_int code, const char* what) {
    if (code == CL_SUCCESS) return;
    const std::string message =
        label(d.info) + ": " + what + ": " + error_name(code) + " (" + std::to_string(code) + ")";
    if (code == CL_MEM_OBJECT_ALLOCATION_FAILURE || code == CL_OUT_OF_RESOURCES) throw OutOfDeviceMemory(message);
    throw DeviceError(message);
}

Device* resolve(const DeviceRequest& request, std::string& note) {
    Probe& p = probed();
    if (p.devices.empty()) {
        note = p.note;
        return nullptr;
    }
    Device* d = nullptr;
    if (request.index >= 0) {
        if (request.index >= static_cast<int>(p.devices.size()))
            throw DeviceError("no OpenCL device " + std::to_string(request.index) + ": this machine has " +
                              std::to_string(p.devices.size()) + " (polyvol devices lists them)");
        d = &p.devices[static_cast<std::size_t>(request.index)];
        const DeviceInfo now = info_now(*d);
        if (!now.usable) throw DeviceError(label(now) + ": " + now.reason);
    } else {
        for (const char* type : {"gpu", "accelerator", "cpu", "other"}) {
            for (Device& c : p.devices)
                if (!d && info_now(c).usable && c.info.type == type) d = &c;
        }
        if (!d) {
            const DeviceInfo first = info_now(p.devices.front());
            throw DeviceError("no usable OpenCL device: " + label(first) + ": " + first.reason);
        }
    }
    std::lock_guard<std::mutex> lock(d->mutex);
    if (!d->context) {
        cl_int err = CL_SUCCESS;
        cl_context context = api()->CreateContext(nullptr, 1, &d->id, nullptr, nullptr, &err);
        check(*d, err, "creating a context");
        cl_command_queue queue = api()->CreateCommandQueue(context, d->id, 0, &err);
        if (err != CL_SUCCESS) api()->ReleaseContext(context);
        check(*d, err, "creating a queue");
        d->context = context;  // both made, or neither kept
        d->queue = queue;
    }
    return d;
}

cl_program build(Device& d, const std::string& source) {
    const auto found = d.programs.find(source);
    if (found != d.programs.end()) return found->second;
    cl_int err = CL_SUCCESS;
    const char* text = source.c_str();
    const std::size_t length = source.size();
    cl_program p = api()->CreateProgramWithSource(d.context, 1, &text, &length, &err);
    check(d, err, "creating a program");
    // No option that relaxes IEEE arithmetic: the kernels replay the CPU's bits.
    err = api()->BuildProgram(p, 1, &d.id, "-cl-std=CL1.2", nullptr, nullptr);
    if (err != CL_SUCCESS) {
        std::size_t n = 0;
        api()->GetProgramBuildInfo(p, d.id, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n);
        std::string log(n, '\0');
        if (n > 0) api()->GetProgramBuildInfo(p, d.id, CL_PROGRAM_BUILD_LOG, n, log.data(), nullptr);
        while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
        api()->ReleaseProgram(p);
        throw DeviceError(label(d.info) + ": the kernels do not build (" + error_name(err) + "):\n" + log);
    }
    d.programs.emplace(source, p);
    return p;
}

Kernel::Kernel(Device& d, cl_program p, const char* name) {
    cl_int err = CL_SUCCESS;
    k = api()->CreateKernel(p, name, &err);
    check(d, err, "creating a kernel");
}

Buffer make_buffer(Device& d, std::size_t bytes, const void* data) {
    cl_int err = CL_SUCCESS;
    Buffer b;
    if (fail_points().max_buffer > 0 && bytes > fail_points().max_buffer)
        check(d, CL_MEM_OBJECT_ALLOCATION_FAILURE, "allocating device memory");
    const cl_mem_flags flags = CL_MEM_READ_WRITE | (data ? CL_MEM_COPY_HOST_PTR : 0);
    b.mem = api()->CreateBuffer(d.context, flags, bytes == 0 ? 1 : bytes, bytes == 0 ? nullptr : const_cast<void*>(data),
                                &err);
    check(d, err, "allocating device memory");
    b.bytes = bytes;
    return b;
}

}  // namespace polyvol

namespace polyvol {

DeviceRequest parse_device(std::string_view text) {
    if (text == "auto") return {DeviceKind::automatic, -1};
    if (text == "cpu") return {DeviceKind::cpu, -1};
    if (text == "opencl") return {DeviceKind::opencl, -1};
    if (text.starts_with("opencl:")) {
        const std::string_view n = text.substr(7);
        int index = -1;
        const auto [end, ec] = std::from_chars(n.data(), n.data() + n.size(), index);
        if (ec == std::errc{} && end == n.data() + n.size() && index >= 0) return {DeviceKind::opencl, index};
    }
    throw std::invalid_argument("device must be auto, cpu, opencl or opencl:N (N from polyvol devices), not '" +
                                std::string(text) + "'");
}

DeviceList list_devices() {
    DeviceList list;
    auto& p = device::probed();
    list.runtime = device::api() != nullptr;
    list.note = p.note;
    for (const device::Device& d : p.devices) list.devices.push_back(device::info_now(d));
    return list;
}

}  // namespace polyvol

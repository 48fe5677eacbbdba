// device/opencl.hpp — internal interface (for grid): the OpenCL entry points,
// loaded at run time, and one context, queue and program cache per device.
//
// Conventions: every call goes through api(), which is null when no loader
// is present; a device is resolved once per process and kept (contexts are
// never released: they live as long as the process, like the loader). Calls
// on one device's queue are serialised by its mutex; kernels are created per
// call (a cl_kernel's arguments are not thread-safe).
#pragma once

#define CL_TARGET_OPENCL_VERSION 120
#include <CL/cl.h>

#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "polyvol/device.hpp"

namespace polyvol::device {

struct Api {
    cl_int (*GetPlatformIDs)(cl_uint, cl_platform_id*, cl_uint*);
    cl_int (*GetPlatformInfo)(cl_platform_id, cl_platform_info, size_t, void*, size_t*);
    cl_int (*GetDeviceIDs)(cl_platform_id, cl_device_type, cl_uint, cl_device_id*, cl_uint*);
    cl_int (*GetDeviceInfo)(cl_device_id, cl_device_info, size_t, void*, size_t*);
    cl_context (*CreateContext)(const cl_context_properties*, cl_uint, const cl_device_id*,
                                void (*)(const char*, const void*, size_t, void*), void*, cl_int*);
    cl_command_queue (*CreateCommandQueue)(cl_context, cl_device_id, cl_command_queue_properties, cl_int*);
    cl_program (*CreateProgramWithSource)(cl_context, cl_uint, const char**, const size_t*, cl_int*);
    cl_int (*BuildProgram)(cl_program, cl_uint, const cl_device_id*, const char*, void (*)(cl_program, void*), void*);
    cl_int (*GetProgramBuildInfo)(cl_program, cl_device_id, cl_program_build_info, size_t, void*, size_t*);
    cl_kernel (*CreateKernel)(cl_program, const char*, cl_int*);
    cl_int (*SetKernelArg)(cl_kernel, cl_uint, size_t, const void*);
    cl_mem (*CreateBuffer)(cl_context, cl_mem_flags, size_t, void*, cl_int*);
    cl_int (*EnqueueWriteBuffer)(cl_command_queue, cl_mem, cl_bool, size_t, size_t, const void*, cl_uint,
                                 const cl_event*, cl_event*);
    cl_int (*EnqueueReadBuffer)(cl_command_queue, cl_mem, cl_bool, size_t, size_t, void*, cl_uint, const cl_event*,
                                cl_event*);
    cl_int (*EnqueueFillBuffer)(cl_command_queue, cl_mem, const void*, size_t, size_t, size_t, cl_uint,
                                const cl_event*, cl_event*);
    cl_int (*EnqueueNDRangeKernel)(cl_command_queue, cl_kernel, cl_uint, const size_t*, const size_t*, const size_t*,
                                   cl_uint, const cl_event*, cl_event*);
    cl_int (*Finish)(cl_command_queue);
    cl_int (*ReleaseMemObject)(cl_mem);
    cl_int (*ReleaseKernel)(cl_kernel);
    cl_int (*ReleaseProgram)(cl_program);
    cl_int (*ReleaseContext)(cl_context);
    cl_int (*GetKernelWorkGroupInfo)(cl_kernel, cl_device_id, cl_kernel_work_group_info, size_t, void*, size_t*);
};

// The loader's entry points, or null with `why` set (once per process).
const Api* api(std::string* why = nullptr);

// The name of an OpenCL error code ("CL_OUT_OF_RESOURCES"), for messages.
const char* error_name(cl_int code);

struct Device {
    DeviceInfo info;  // as probed; `usable` is decided per call
    bool fp64 = false;
    bool canary_passed = false;  // the grid's canary kernel gave the host's bits (device_grid.cpp)
    cl_device_id id = nullptr;
    cl_context context = nullptr;
    cl_command_queue queue = nullptr;
    std::mutex mutex;                           // one caller at a time on the queue
    std::map<std::string, cl_program> programs;  // built sources, by source text
};

// The device an explicit request names: nullptr when there is no OpenCL
// runtime or no platform (the caller runs the CPU path and says so in
// `note`); DeviceError when the named device is absent or unusable.
Device* resolve(const DeviceRequest& request, std::string& note);

// The program of `source` built for `d` (cached), or DeviceError with the
// build log. Call with d.mutex held.
cl_program build(Device& d, const std::string& source);

// Throws DeviceError "device N "name": what: CL_..." unless code is CL_SUCCESS;
// OutOfDeviceMemory for CL_MEM_OBJECT_ALLOCATION_FAILURE and CL_OUT_OF_RESOURCES
// (drivers allocate lazily: at enqueue or finish as well), which a caller can
// answer with smaller batches.
void check(const Device& d, cl_int code, const char* what);
class OutOfDeviceMemory : public DeviceError {
public:
    using DeviceError::DeviceError;
};

// Owns a cl_mem (of `bytes` as asked for; 0 is allocated as 1) or a cl_kernel.
struct Buffer {
    cl_mem mem = nullptr;
    std::size_t bytes = 0;
    Buffer() = default;
    Buffer(const Buffer&) = delete;
    Buffer& operator=(const Buffer&) = delete;
    Buffer(Buffer&& o) noexcept : mem(o.mem), bytes(o.bytes) { o.mem = nullptr; }
    Buffer& operator=(Buffer&& o) noexcept {
        std::swap(mem, o.mem);
        std::swap(bytes, o.bytes);
        return *this;
    }
    ~Buffer() {
        if (mem) api()->ReleaseMemObject(mem);
    }
};
struct Kernel {
    cl_kernel k = nullptr;
    Kernel(Device& d, cl_program p, const char* name);
    Kernel(const Kernel&) = delete;
    Kernel& operator=(const Kernel&) = delete;
    ~Kernel() {
        if (k) api()->ReleaseKernel(k);
    }
};

// A buffer of `bytes` on d (at least 1), filled from `data` when not null.
Buffer make_buffer(Device& d, std::size_t bytes, const void* data = nullptr);

// Fail points for the tests (process-global; never set outside tests).
struct FailPoints {
    bool no_fp64 = false;     // every device reports no cl_khr_fp64
    bool bad_kernel = false;  // the grid's source gets a line that does not compile
    int capacity = 0;         // > 0: the grid kernel's polygon capacity (forces its CPU fallback)
    std::size_t max_buffer = 0;  // > 0: buffers larger than this fail as out of device memory
};
FailPoints& fail_points();

}  // namespace polyvol::device

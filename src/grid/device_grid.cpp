// grid/device_grid.cpp — the host side of grid_kernels.cl: upload a body and
// the grid, run one work-item per column over batches of rows of columns,
// read the outputs straight into the caller's arrays.
//
// Memory: per batch, each column's sums (its layers × 4 or 14 doubles and a
// flag byte) and the batch's outputs; the batch's rows are chosen so that the
// sums take at most a quarter of the device's memory and 256 MiB.
#include "grid/device_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

namespace polyvol::grid {

extern const char kGridKernels[];  // grid_kernels.cl, embedded by CMake

namespace {

constexpr int kWhatMoments = 1, kWhatArea = 2, kWhatNormal = 4, kWhatUnionArea = 8, kWhatUnionNormal = 16;

std::string kernel_source() {
    std::string s = kGridKernels;
    if (device::fail_points().bad_kernel) s += "\n#error polyvol test: a kernel that does not build\n";
    return s;
}

// The canary's inputs and the host's results of the same operations
// (grid_kernels.cl polyvol_canary), compared bit for bit.
void check_canary(device::Device& d, cl_program program) {
    const double in[11] = {1 + 0x1p-30, 1 - 0x1p-30, -1, 0x1p-1060, 0x1p-10, 1, 3, 2, -0.0, 0.0, -2.5};
    const double round_m25 = -3;  // column_scan.cpp round_integer: halves away from zero
    const double expect[7] = {in[0] * in[1] + in[2], in[3] * in[4], in[5] / in[6], std::sqrt(in[7]),
                              in[9] < in[8] ? in[9] : in[8], in[9] < in[8] ? in[8] : in[9], round_m25};
    const char* what[7] = {"contracts a*b+c into a fused multiply-add despite FP_CONTRACT OFF",
                           "flushes denormal doubles to zero", "does not round double division correctly",
                           "does not round double sqrt correctly", "differs from the host on min of signed zeros",
                           "differs from the host on max of signed zeros", "differs from the host on rounding"};
    device::Buffer bin = device::make_buffer(d, sizeof in, in);
    device::Buffer bout = device::make_buffer(d, sizeof expect);
    device::Kernel k(d, program, "polyvol_canary");
    const device::Api* a = device::api();
    device::check(d, a->SetKernelArg(k.k, 0, sizeof(cl_mem), &bin.mem), "canary argument");
    device::check(d, a->SetKernelArg(k.k, 1, sizeof(cl_mem), &bout.mem), "canary argument");
    const std::size_t one = 1;
    device::check(d, a->EnqueueNDRangeKernel(d.queue, k.k, 1, nullptr, &one, nullptr, 0, nullptr, nullptr),
                  "running the canary");
    double got[7];
    device::check(d, a->EnqueueReadBuffer(d.queue, bout.mem, CL_TRUE, 0, sizeof got, got, 0, nullptr, nullptr),
                  "reading the canary");
    for (int i = 0; i < 7; ++i)
        if (std::memcmp(&got[i], &expect[i], sizeof(double)) != 0)
            throw DeviceError("device " + std::to_string(d.info.index) + " \"" + d.info.name + "\" " + what[i] +
                              ": its results would not be the CPU's bits");
    d.canary_passed = true;
}

// Sets the kernel's arguments in order.
struct Args {
    const device::Api* a;
    device::Device& d;
    cl_kernel k;
    cl_uint next = 0;
    void mem(const device::Buffer& b) { device::check(d, a->SetKernelArg(k, next++, sizeof(cl_mem), &b.mem), "an argument"); }
    void i32(int v) {
        const cl_int x = v;
        device::check(d, a->SetKernelArg(k, next++, sizeof x, &x), "an argument");
    }
};

template <class T>
device::Buffer upload(device::Device& d, std::span<const T> v) {
    return device::make_buffer(d, v.size_bytes(), v.empty() ? nullptr : v.data());
}

}  // namespace

bool device_columns(device::Device& d, const GridAxes& g, const DeviceLayout& l, std::span<const DeviceBody> bodies,
                    const GridOutput& out, std::vector<DeviceCounts>& counts) {
    static_assert(sizeof(std::size_t) == sizeof(cl_ulong), "bin offsets go to the device as ulong");
    std::lock_guard<std::mutex> lock(d.mutex);
    const device::Api* a = device::api();
    const cl_program program = device::build(d, kernel_source());
    if (!d.canary_passed) check_canary(d, program);

    const bool moments = !out.first_moments.empty();
    const bool one = bodies.size() == 1;
    const int what = (moments ? kWhatMoments : 0) | (!out.wetted_area.empty() ? kWhatArea : 0) |
                     (!out.surface_normal.empty() ? kWhatNormal : 0) |
                     (one && !out.union_wetted_area.empty() ? kWhatUnionArea : 0) |
                     (one && !out.union_surface_normal.empty() ? kWhatUnionNormal : 0);
    const int gnz = static_cast<int>(g.nz());
    const std::size_t layers = static_cast<std::size_t>(gnz - l.k0 + 1);
    const std::size_t per_column = layers * ((moments ? 14 : 4) * sizeof(double) + 1);
    const std::size_t budget = std::min<std::size_t>(std::size_t{256} << 20, d.info.global_memory / 4);
    const std::size_t row_bytes = per_column * static_cast<std::size_t>(l.ny);
    const int rows = static_cast<int>(std::clamp<std::size_t>(budget / std::max<std::size_t>(row_bytes, 1), 1,
                                                               static_cast<std::size_t>(l.nx)));
    const std::size_t max_columns = static_cast<std::size_t>(rows) * l.ny;
    const std::size_t bnz = static_cast<std::size_t>(l.bnz);
    const std::size_t cells = static_cast<std::size_t>(l.nx) * l.ny * bnz;

    const device::Buffer xs = upload(d, std::span<const double>(g.x)), ys = upload(d, std::span<const double>(g.y)),
                         zs = upload(d, std::span<const double>(g.z));
    const device::Buffer sums = device::make_buffer(d, max_columns * layers * (moments ? 14 : 4) * sizeof(double));
    const device::Buffer flags = device::make_buffer(d, max_columns * layers);
    const std::size_t out_bytes = max_columns * bnz * sizeof(double);
    const device::Buffer vol = device::make_buffer(d, out_bytes);
    const device::Buffer mom = device::make_buffer(d, moments ? 3 * out_bytes : 0);
    const device::Buffer area = device::make_buffer(d, what & kWhatArea ? out_bytes : 0);
    const device::Buffer normal = device::make_buffer(d, what & kWhatNormal ? 3 * out_bytes : 0);
    const device::Buffer uarea = device::make_buffer(d, what & kWhatUnionArea ? out_bytes : 0);
    const device::Buffer unormal = device::make_buffer(d, what & kWhatUnionNormal ? 3 * out_bytes : 0);
    const device::Buffer column_counts = device::make_buffer(d, max_columns * 4 * sizeof(cl_uint));
    const cl_int zero = 0;
    const device::Buffer error = device::make_buffer(d, sizeof zero, &zero);
    std::vector<cl_uint> host_counts(max_columns * 4);
    counts.assign(bodies.size(), DeviceCounts{});

    auto read = [&](const device::Buffer& b, double* dst, std::size_t values) {
        device::check(d, a->EnqueueReadBuffer(d.queue, b.mem, CL_TRUE, 0, values * sizeof(double), dst, 0, nullptr,
                                              nullptr),
                      "reading the results");
    };
    auto clear = [&](const device::Buffer& b, std::size_t bytes) {
        const double z = 0;
        device::check(d, a->EnqueueFillBuffer(d.queue, b.mem, &z, sizeof z, 0, bytes, 0, nullptr, nullptr),
                      "clearing a buffer");
    };
    for (std::size_t b = 0; b < bodies.size(); ++b) {
        const DeviceBody& body = bodies[b];
        const device::Buffer pos = upload(d, body.positions), tri = upload(d, body.triangles),
                             offsets = upload(d, body.offsets), entries = upload(d, body.entries);
        for (int row0 = 0; row0 < l.nx; row0 += rows) {
            const int nrows = std::min(rows, l.nx - row0);
            const std::size_t columns = static_cast<std::size_t>(nrows) * l.ny;
            if (what & kWhatArea) clear(area, columns * bnz * sizeof(double));
            if (what & kWhatNormal) clear(normal, 3 * columns * bnz * sizeof(double));
            if (what & kWhatUnionArea) clear(uarea, columns * bnz * sizeof(double));
            if (what & kWhatUnionNormal) clear(unormal, 3 * columns * bnz * sizeof(double));
            device::Kernel k(d, program, "polyvol_grid_body");
            Args args{a, d, k.k};
            args.mem(xs), args.mem(ys), args.mem(zs);
            args.i32(static_cast<int>(g.nx())), args.i32(static_cast<int>(g.ny())), args.i32(gnz);
            args.i32(l.i0), args.i32(l.j0), args.i32(l.k0), args.i32(l.ny), args.i32(l.bnz), args.i32(row0);
            args.i32(static_cast<int>(columns)), args.i32(l.tile), args.i32(l.nty);
            args.mem(pos), args.mem(tri), args.mem(offsets), args.mem(entries);
            args.mem(sums), args.mem(flags), args.i32(what), args.i32(device::fail_points().capacity > 0
                                                                           ? device::fail_points().capacity
                                                                           : 1 << 30);
            args.mem(vol), args.mem(mom), args.mem(area), args.mem(normal), args.mem(uarea), args.mem(unormal);
            args.mem(column_counts), args.mem(error);
            // A column's polygons live in private memory: one work-item per
            // group on a CPU device (pocl keeps a group's private arrays on one
            // thread's stack), 64 on the others.
            const std::size_t local = d.info.type == "cpu" ? 1 : 64;
            const std::size_t global = (columns + local - 1) / local * local;
            device::check(d, a->EnqueueNDRangeKernel(d.queue, k.k, 1, nullptr, &global, &local, 0, nullptr, nullptr),
                          "running the grid kernel");
            cl_int failed = 0;
            device::check(d, a->EnqueueReadBuffer(d.queue, error.mem, CL_TRUE, 0, sizeof failed, &failed, 0, nullptr,
                                                  nullptr),
                          "reading the kernel's status");
            if (failed) return false;
            const std::size_t first = b * cells + static_cast<std::size_t>(row0) * l.ny * bnz;
            const std::size_t n = columns * bnz;
            read(vol, &out.volumes[first], n);
            if (moments) read(mom, &out.first_moments[3 * first], 3 * n);
            if (what & kWhatArea) read(area, &out.wetted_area[first], n);
            if (what & kWhatNormal) read(normal, &out.surface_normal[3 * first], 3 * n);
            const std::size_t ufirst = static_cast<std::size_t>(row0) * l.ny * bnz;
            if (what & kWhatUnionArea) read(uarea, &out.union_wetted_area[ufirst], n);
            if (what & kWhatUnionNormal) read(unormal, &out.union_surface_normal[3 * ufirst], 3 * n);
            device::check(d, a->EnqueueReadBuffer(d.queue, column_counts.mem, CL_TRUE, 0,
                                                  columns * 4 * sizeof(cl_uint), host_counts.data(), 0, nullptr,
                                                  nullptr),
                          "reading the counts");
            DeviceCounts& c = counts[b];
            for (std::size_t col = 0; col < columns; ++col) {
                c.empty += host_counts[4 * col];
                c.full += host_counts[4 * col + 1];
                c.cut += host_counts[4 * col + 2];
                c.pieces += host_counts[4 * col + 3];
            }
        }
    }
    return true;
}

}  // namespace polyvol::grid

// grid/device_grid.cpp — the host side of grid_kernels.cl: upload a body and
// the grid, run one work-item per column over batches of rows of columns,
// read the outputs straight into the caller's arrays.
//
// Memory: per batch, each column's sums (its layers × 4 or 14 doubles and a
// flag byte) and the batch's outputs; the batch's rows are chosen so that the
// sums take at most a quarter of the device's memory and 256 MiB.
#include "grid/device_grid.hpp"

#include <algorithm>
#include <chrono>
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
    void u64(std::size_t v) {
        const cl_ulong x = v;
        device::check(d, a->SetKernelArg(k, next++, sizeof x, &x), "an argument");
    }
};

template <class T>
device::Buffer upload(device::Device& d, std::span<const T> v) {
    return device::make_buffer(d, v.size_bytes(), v.empty() ? nullptr : v.data());
}

// Device bytes per column of a batch: its sums (the body's, the levels'),
// each body's outputs (volume, moments, surfaces, state, counts) and the
// union's (union, intersection, class, surface, counts).
std::size_t bytes_per_column(const GridAxes& g, const DeviceLayout& l, std::size_t bodies, const GridOutput& out,
                             int nlevels, bool union_cells) {
    const std::size_t layers = g.nz() - static_cast<std::size_t>(l.k0) + 1, bnz = static_cast<std::size_t>(l.bnz);
    const bool moments = !out.first_moments.empty();
    const std::size_t body_doubles = 1 + (moments ? 3 : 0) + (out.wetted_area.empty() ? 0 : 1) +
                                     (out.surface_normal.empty() ? 0 : 3);
    const std::size_t union_doubles = (union_cells ? 2 : 0) + (out.union_wetted_area.empty() ? 0 : 1) +
                                      (out.union_surface_normal.empty() ? 0 : 3);
    return layers * ((moments ? 14 : 4) * sizeof(double) + 1) +
           static_cast<std::size_t>(nlevels) * layers * (4 * sizeof(double) + 1) +
           bodies * (bnz * (body_doubles * sizeof(double) + 1) + 4 * sizeof(cl_uint)) +
           bnz * (union_doubles * sizeof(double) + 1) + 4 * sizeof(cl_uint);
}

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// Every batch of `rows` rows of columns: the bodies' kernels, then the union's.
bool run_batches(device::Device& d, cl_program program, const GridAxes& g, const DeviceLayout& l,
                 std::span<const DeviceBody> bodies, const DeviceLevels* levels, const GridOutput& out,
                 DeviceResult& result, int rows) {
    const device::Api* a = device::api();
    result = DeviceResult{};
    const std::size_t nb = bodies.size();
    const bool moments = !out.first_moments.empty();
    const bool union_cells = levels != nullptr;
    const bool union_surface = nb == 1 || union_cells;  // one body's surface is the union's
    const int what = (moments ? kWhatMoments : 0) | (!out.wetted_area.empty() ? kWhatArea : 0) |
                     (!out.surface_normal.empty() ? kWhatNormal : 0) |
                     (union_surface && !out.union_wetted_area.empty() ? kWhatUnionArea : 0) |
                     (union_surface && !out.union_surface_normal.empty() ? kWhatUnionNormal : 0);
    const int nlevels = union_cells ? static_cast<int>(levels->count) : 0;
    const int gnz = static_cast<int>(g.nz());
    const std::size_t layers = static_cast<std::size_t>(gnz - l.k0 + 1);
    const std::size_t bnz = static_cast<std::size_t>(l.bnz);
    const std::size_t max_columns = static_cast<std::size_t>(rows) * l.ny;
    const std::size_t cells = static_cast<std::size_t>(l.nx) * l.ny * bnz;
    const std::size_t batch_cells = max_columns * bnz;

    auto t = Clock::now();
    const device::Buffer xs = upload(d, std::span<const double>(g.x)), ys = upload(d, std::span<const double>(g.y)),
                         zs = upload(d, std::span<const double>(g.z));
    std::vector<device::Buffer> pos, tri, offsets, entries, on_level;
    for (const DeviceBody& body : bodies) {
        pos.push_back(upload(d, body.positions));
        tri.push_back(upload(d, body.triangles));
        offsets.push_back(upload(d, body.offsets));
        entries.push_back(upload(d, body.entries));
        on_level.push_back(upload(d, body.level_bits));
    }
    const device::Buffer sums = device::make_buffer(d, max_columns * layers * (moments ? 14 : 4) * sizeof(double));
    const device::Buffer flags = device::make_buffer(d, max_columns * layers);
    const std::size_t level_cells = max_columns * layers;
    const device::Buffer level_sums = device::make_buffer(d, nlevels * level_cells * 4 * sizeof(double));
    const device::Buffer level_flags = device::make_buffer(d, nlevels * level_cells);
    const device::Buffer vol = device::make_buffer(d, nb * batch_cells * sizeof(double));
    const device::Buffer mom = device::make_buffer(d, moments ? 3 * nb * batch_cells * sizeof(double) : 0);
    const device::Buffer states = device::make_buffer(d, nb * batch_cells);
    const device::Buffer area = device::make_buffer(d, what & kWhatArea ? nb * batch_cells * sizeof(double) : 0);
    const device::Buffer normal = device::make_buffer(d, what & kWhatNormal ? 3 * nb * batch_cells * sizeof(double) : 0);
    const device::Buffer uarea = device::make_buffer(d, what & kWhatUnionArea ? batch_cells * sizeof(double) : 0);
    const device::Buffer unormal = device::make_buffer(d, what & kWhatUnionNormal ? 3 * batch_cells * sizeof(double) : 0);
    const device::Buffer column_counts = device::make_buffer(d, nb * max_columns * 4 * sizeof(cl_uint));
    // the union's cells
    const device::Buffer fan_pos = upload(d, std::span<const double>(union_cells ? levels->positions : std::vector<double>{}));
    const device::Buffer fan_tri = upload(d, std::span<const uint32_t>(union_cells ? levels->triangles : std::vector<uint32_t>{}));
    const device::Buffer fan_normal = upload(d, std::span<const double>(union_cells ? levels->normals : std::vector<double>{}));
    const device::Buffer fan_offsets = upload(d, std::span<const std::size_t>(union_cells ? levels->offsets : std::vector<std::size_t>{}));
    const device::Buffer fan_entries = upload(d, std::span<const uint32_t>(union_cells ? levels->entries : std::vector<uint32_t>{}));
    const device::Buffer uvol = device::make_buffer(d, union_cells ? batch_cells * sizeof(double) : 0);
    const bool intersection = union_cells && !out.intersection_volumes.empty();
    const device::Buffer xvol = device::make_buffer(d, intersection ? batch_cells * sizeof(double) : 0);
    const device::Buffer cls = device::make_buffer(d, union_cells ? batch_cells : 0);
    const device::Buffer union_counts = device::make_buffer(d, union_cells ? max_columns * 4 * sizeof(cl_uint) : 0);
    const cl_int zero = 0;
    const device::Buffer error = device::make_buffer(d, sizeof zero, &zero);
    std::vector<cl_uint> host_counts(nb * max_columns * 4);
    std::vector<double> host_values(union_cells ? batch_cells : 0);
    std::vector<uint8_t> host_classes(union_cells ? batch_cells : 0);
    result.bodies.assign(nb, DeviceCounts{});
    result.transfer_seconds += since(t);
    const int cap = device::fail_points().capacity > 0 ? device::fail_points().capacity : 1 << 30;

    auto read = [&](const device::Buffer& b, std::size_t from, void* dst, std::size_t bytes) {
        const auto t0 = Clock::now();
        device::check(d, a->EnqueueReadBuffer(d.queue, b.mem, CL_TRUE, from, bytes, dst, 0, nullptr, nullptr),
                      "reading the results");
        result.transfer_seconds += since(t0);
    };
    // Zero bytes: the sums and surfaces the kernels add into (unused buffers hold none).
    auto clear = [&](const device::Buffer& b) {
        if (b.bytes == 0) return;
        const cl_uchar z = 0;
        device::check(d, a->EnqueueFillBuffer(d.queue, b.mem, &z, sizeof z, 0, b.bytes, 0, nullptr, nullptr),
                      "clearing a buffer");
    };
    auto run = [&](const device::Kernel& k, std::size_t columns) {
        // A column's polygons live in private memory: one work-item per
        // group on a CPU device (pocl keeps a group's private arrays on one
        // thread's stack), 64 on the others.
        std::size_t most = 64;
        device::check(d, a->GetKernelWorkGroupInfo(k.k, d.id, CL_KERNEL_WORK_GROUP_SIZE, sizeof most, &most, nullptr),
                      "asking the kernel's work-group size");
        const std::size_t local = d.info.type == "cpu" ? 1 : std::clamp<std::size_t>(most, 1, 64);
        const std::size_t global = (columns + local - 1) / local * local;
        const auto t0 = Clock::now();
        device::check(d, a->EnqueueNDRangeKernel(d.queue, k.k, 1, nullptr, &global, &local, 0, nullptr, nullptr),
                      "running the grid kernel");
        device::check(d, a->Finish(d.queue), "running the grid kernel");
        result.kernel_seconds += since(t0);
        cl_int failed = 0;
        read(error, 0, &failed, sizeof failed);
        return failed == 0;
    };
    auto column_args = [&](Args& args, int row0, std::size_t columns) {
        args.mem(xs), args.mem(ys), args.mem(zs);
        args.i32(static_cast<int>(g.nx())), args.i32(static_cast<int>(g.ny())), args.i32(gnz);
        args.i32(l.i0), args.i32(l.j0), args.i32(l.k0), args.i32(l.ny), args.i32(l.bnz), args.i32(row0);
        args.i32(static_cast<int>(columns)), args.i32(l.tile), args.i32(l.nty);
    };
    for (int row0 = 0; row0 < l.nx; row0 += rows) {
        const int nrows = std::min(rows, l.nx - row0);
        const std::size_t columns = static_cast<std::size_t>(nrows) * l.ny;
        const std::size_t n = columns * bnz;
        for (const device::Buffer* b : {&area, &normal, &uarea, &unormal, &level_sums, &level_flags}) clear(*b);
        for (std::size_t b = 0; b < nb; ++b) {
            device::Kernel k(d, program, "polyvol_grid_body");
            Args args{a, d, k.k};
            column_args(args, row0, columns);
            args.mem(pos[b]), args.mem(tri[b]), args.mem(offsets[b]), args.mem(entries[b]);
            args.mem(on_level[b]), args.i32(bodies[b].level_bits.empty() ? 0 : nlevels), args.mem(sums), args.mem(flags);
            args.mem(level_sums), args.mem(level_flags), args.u64(level_cells), args.i32(what), args.i32(cap);
            args.u64(b * max_columns), args.mem(vol), args.mem(mom), args.mem(states);
            args.mem(area), args.mem(normal), args.mem(uarea), args.mem(unormal), args.mem(column_counts),
                args.mem(error);
            if (!run(k, columns)) return false;
            const std::size_t first = b * cells + static_cast<std::size_t>(row0) * l.ny * bnz;
            read(vol, b * batch_cells * sizeof(double), &out.volumes[first], n * sizeof(double));
            if (moments)
                read(mom, 3 * b * batch_cells * sizeof(double), &out.first_moments[3 * first], 3 * n * sizeof(double));
            if (what & kWhatArea) read(area, b * batch_cells * sizeof(double), &out.wetted_area[first], n * sizeof(double));
            if (what & kWhatNormal)
                read(normal, 3 * b * batch_cells * sizeof(double), &out.surface_normal[3 * first], 3 * n * sizeof(double));
            read(column_counts, b * max_columns * 4 * sizeof(cl_uint), host_counts.data(), columns * 4 * sizeof(cl_uint));
            DeviceCounts& c = result.bodies[b];
            for (std::size_t col = 0; col < columns; ++col) {
                c.empty += host_counts[4 * col];
                c.full += host_counts[4 * col + 1];
                c.cut += host_counts[4 * col + 2];
                c.pieces += host_counts[4 * col + 3];
            }
        }
        const std::size_t ufirst = static_cast<std::size_t>(row0) * l.ny * bnz;
        if (union_cells) {
            device::Kernel k(d, program, "polyvol_grid_union");
            Args args{a, d, k.k};
            column_args(args, row0, columns);
            args.i32(what), args.i32(cap), args.i32(static_cast<int>(nb)), args.i32(nlevels), args.i32(intersection);
            args.mem(fan_pos), args.mem(fan_tri), args.mem(fan_normal), args.mem(fan_offsets), args.mem(fan_entries);
            args.u64(static_cast<std::size_t>(l.nty) * ((l.nx + l.tile - 1) / l.tile));
            args.mem(level_sums), args.mem(level_flags), args.u64(level_cells);
            args.mem(vol), args.mem(states), args.u64(batch_cells);
            args.mem(uvol), args.mem(xvol), args.mem(cls), args.mem(uarea), args.mem(unormal), args.mem(union_counts),
                args.mem(error);
            if (!run(k, columns)) return false;
            // Each cell of the union (and the intersection) into its exact sum, and where asked for.
            auto values = [&](const device::Buffer& b, std::span<double> dst, exact::ExactSum& sum) {
                read(b, 0, host_values.data(), n * sizeof(double));
                for (std::size_t c = 0; c < n; ++c)
                    if (host_values[c] != 0) sum.add(host_values[c]);
                if (!dst.empty()) std::copy_n(host_values.data(), n, dst.begin() + static_cast<std::ptrdiff_t>(ufirst));
            };
            values(uvol, out.union_volumes, result.union_volume);
            if (intersection) values(xvol, out.intersection_volumes, result.intersection_volume);
            if (!out.cell_class.empty()) read(cls, 0, &out.cell_class[ufirst], n);
            read(union_counts, 0, host_counts.data(), columns * 4 * sizeof(cl_uint));
            for (std::size_t col = 0; col < columns; ++col) {
                result.full += host_counts[4 * col];
                result.empty += host_counts[4 * col + 1];
                result.cut += host_counts[4 * col + 2];
                result.contact += host_counts[4 * col + 3];
            }
        }
        if (what & kWhatUnionArea) read(uarea, 0, &out.union_wetted_area[ufirst], n * sizeof(double));
        if (what & kWhatUnionNormal) read(unormal, 0, &out.union_surface_normal[3 * ufirst], 3 * n * sizeof(double));
    }
    return true;
}

}  // namespace

bool device_columns(device::Device& d, const GridAxes& g, const DeviceLayout& l, std::span<const DeviceBody> bodies,
                    const DeviceLevels* levels, const GridOutput& out, DeviceResult& result) {
    static_assert(sizeof(std::size_t) == sizeof(cl_ulong), "bin offsets go to the device as ulong");
    std::lock_guard<std::mutex> lock(d.mutex);
    const auto t = Clock::now();
    const cl_program program = device::build(d, kernel_source());
    if (!d.canary_passed) check_canary(d, program);
    const double build_seconds = since(t);
    // Batches of at most 256 MiB or a quarter of the device's memory; halved
    // while the device runs out of memory, down to one row of columns.
    const std::size_t row_bytes =
        bytes_per_column(g, l, bodies.size(), out, levels ? static_cast<int>(levels->count) : 0, levels != nullptr) *
        static_cast<std::size_t>(l.ny);
    const std::size_t budget = std::min<std::size_t>(std::size_t{256} << 20, d.info.global_memory / 4);
    int rows = static_cast<int>(std::clamp<std::size_t>(budget / std::max<std::size_t>(row_bytes, 1), 1,
                                                        static_cast<std::size_t>(l.nx)));
    for (;;) {
        try {
            const bool done = run_batches(d, program, g, l, bodies, levels, out, result, rows);
            result.build_seconds = build_seconds;
            return done;
        } catch (const device::OutOfDeviceMemory& e) {
            if (rows == 1)
                throw DeviceError(std::string(e.what()) + ": one row of " + std::to_string(l.ny) +
                                  " columns needs about " + std::to_string((row_bytes + 1023) >> 10) +
                                  " KiB of device memory beside the bodies (fewer cells along z, or the CPU); "
                                  "the outputs are not complete");
            rows = (rows + 1) / 2;
        }
    }
}

}  // namespace polyvol::grid

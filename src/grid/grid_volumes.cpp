// grid/grid_volumes.cpp — polyvol/grid.hpp: the volume of each body in every
// cell of a grid, by clipping and a column scan (docs/grid.md).
//
// The work is cut into tiles of T × T columns. Each triangle is listed for
// the tiles its bounding box meets (a parallel counting sort that keeps the
// triangle order), then each tile — in parallel, one task per tile —
//   1. clips its triangles into pieces in its columns (clip.hpp), the same
//      pieces whichever tile computes them, and scatters each piece's (P, Q)
//      into tile-local double-double sums (tile_sums.hpp);
//   2. scans each of its columns from the top down (column_scan.cpp),
//      writing the cells straight into the caller's arrays;
//   3. with several bodies, scatters the union's (and the intersection's)
//      own pieces too — the bodies' whole triangles that lie on its boundary,
//      scattered with the pieces above, and the crossed triangles' parts
//      (boolean/level_pieces.hpp) — scans them, and takes each cell from the
//      bodies' values where those decide it, else from that scan.
// Tiles own disjoint cells, so there are no atomics and no second copy of the
// grid; every cell's sums run in triangle order, so the results do not depend
// on the number of threads. Memory: the caller's outputs, the triangle lists
// (about one entry per triangle) and one tile of sums per thread.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include "core/fan_triangles.hpp"
#include "core/progress.hpp"
#include "exact/eft.hpp"
#include "exact/exact_sum.hpp"
#include "grid/axis.hpp"
#include "grid/clip.hpp"
#include "grid/column_scan.hpp"
#include "grid/device_grid.hpp"
#include "grid/piece.hpp"
#include "grid/tile_sums.hpp"
#include "boolean/level_pieces.hpp"
#include "polyvol/grid.hpp"

namespace polyvol {
namespace {

using grid::Axis;

void check_axis(const std::vector<double>& c, const char* name) {
    if (c.size() < 2) throw std::invalid_argument(std::string("grid: the ") + name + " axis needs at least 2 planes");
    if (c.size() - 1 > (std::size_t{1} << 24))
        throw std::invalid_argument(std::string("grid: too many planes along ") + name);
    for (std::size_t i = 0; i < c.size(); ++i) {
        if (!std::isfinite(c[i])) throw std::invalid_argument(std::string("grid: a non-finite ") + name + " plane");
        if (i > 0 && !(c[i] > c[i - 1]))
            throw std::invalid_argument(std::string("grid: the ") + name + " planes must be strictly increasing");
    }
}

// The fan triangles (v0, vi, vi+1) of a mesh's faces, 3 indices each.
struct Triangles {
    std::span<const uint32_t> index;
    std::vector<uint32_t> storage;
    std::size_t count() const { return index.size() / 3; }
};

Triangles fan_triangles(const MeshView& m) {
    Triangles t;
    if (m.all_triangles()) {
        t.index = m.indices.first(m.indices.size() / 3 * 3);
        return t;
    }
    core::append_fan_triangles(m, t.storage);
    t.index = t.storage;
    return t;
}

// The block's columns are cut into tiles; each tile scans its columns from
// the grid's top down to the block's floor k0 (the cells above the block
// count through their sums, as in the whole grid) and outputs the block's
// layers k0 .. k0 + bnz - 1.
struct Layout {
    int nx, ny;   // the block's columns
    int nz;       // layers scanned: the grid's nz - k0
    int bnz;      // layers output (the block's)
    int i0, j0, k0;  // the block's first cell
    int tile;     // columns per tile side
    int ntx, nty;
    std::size_t tiles() const { return static_cast<std::size_t>(ntx) * nty; }
    std::size_t out_cells() const { return static_cast<std::size_t>(nx) * ny * bnz; }
    // Index into the outputs of global column (i, j), output layer kb.
    std::size_t out_cell(int i, int j, int kb) const {
        return (static_cast<std::size_t>(i - i0) * ny + (j - j0)) * bnz + kb;
    }
    bool direct() const { return bnz == nz; }  // the scan writes straight into the outputs
};

// Tile size from the block's shape only (never from the thread count): tile
// sums of at most ~8 MB, and at least ~64 tiles to share out when possible.
Layout choose_layout(const GridAxes& g, const GridBlock& b, bool moments) {
    const int nx = static_cast<int>(b.hi[0] - b.lo[0]), ny = static_cast<int>(b.hi[1] - b.lo[1]);
    const int nz = static_cast<int>(g.nz() - b.lo[2]);
    const double bytes_per_cell = (moments ? 7 : 2) * 16.0 + 1;
    int t = 16;
    while (t > 1 && static_cast<double>(t) * t * (nz + 1) * bytes_per_cell > 8e6) t /= 2;
    auto count = [&](int s) { return static_cast<double>((nx + s - 1) / s) * ((ny + s - 1) / s); };
    while (t > 4 && count(t) < 64) t /= 2;
    Layout l{nx, ny, nz, static_cast<int>(b.hi[2] - b.lo[2]), static_cast<int>(b.lo[0]), static_cast<int>(b.lo[1]),
             static_cast<int>(b.lo[2]), t, (nx + t - 1) / t, (ny + t - 1) / t};
    return l;
}

// Triangles of one body listed per tile, in triangle order:
// entries[offsets[tile] .. offsets[tile + 1]).
struct Bins {
    std::vector<std::size_t> offsets;
    std::vector<uint32_t> entries;
};

struct TileRange {
    int32_t tx0 = 1, tx1 = 0, ty0 = 0, ty1 = 0;  // empty when tx0 > tx1
};

enum BinError : int { kNone = 0, kIndex = 1, kNonFinite = 2 };

// The tiles a triangle's bounding box meets (only those its pieces can be in).
TileRange tile_range(const MeshView& m, const uint32_t* v, const Axis& ax, const Axis& ay, const Axis& az,
                     const Layout& l, int& error) {
    TileRange r;
    const std::size_t nv = m.vertex_count();
    if (v[0] >= nv || v[1] >= nv || v[2] >= nv) {
        error = kIndex;
        return r;
    }
    double lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
        const double p = m.positions[3 * std::size_t{v[0]} + a], q = m.positions[3 * std::size_t{v[1]} + a],
                     s = m.positions[3 * std::size_t{v[2]} + a];
        if (!std::isfinite(p) || !std::isfinite(q) || !std::isfinite(s)) {
            error = kNonFinite;
            return r;
        }
        lo[a] = std::min({p, q, s});
        hi[a] = std::max({p, q, s});
    }
    if (hi[2] < az.plane(l.k0)) return r;  // wholly below the block: contributes nothing
    int x0, x1, y0, y1;
    ax.slab_range(lo[0], hi[0], x0, x1);
    ay.slab_range(lo[1], hi[1], y0, y1);
    x0 = std::max(x0, l.i0) - l.i0;
    x1 = std::min(x1, l.i0 + l.nx - 1) - l.i0;
    y0 = std::max(y0, l.j0) - l.j0;
    y1 = std::min(y1, l.j0 + l.ny - 1) - l.j0;
    if (x0 > x1 || y0 > y1) return r;
    r.tx0 = x0 / l.tile;
    r.tx1 = x1 / l.tile;
    r.ty0 = y0 / l.tile;
    r.ty1 = y1 / l.tile;
    return r;
}

Bins bin_triangles(const MeshView& m, const Triangles& tris, const Axis& ax, const Axis& ay, const Axis& az,
                   const Layout& l) {
    const std::size_t n = tris.count();
    const std::size_t ntiles = l.tiles();
    std::vector<TileRange> range(n);
    // chunks × tiles counters, bounded to ~16M
    std::size_t chunks = std::clamp<std::size_t>(n / 8192, 1, std::max<std::size_t>(1, (std::size_t{1} << 24) / ntiles));
    const std::size_t chunk = (n + chunks - 1) / std::max<std::size_t>(chunks, 1);
    chunks = chunk == 0 ? 1 : (n + chunk - 1) / chunk;
    std::vector<std::size_t> counts(chunks * ntiles, 0);
    std::atomic<int> error{kNone};
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& rc) {
        for (std::size_t c = rc.begin(); c != rc.end(); ++c) {
            std::size_t* cnt = &counts[c * ntiles];
            int err = kNone;
            for (std::size_t t = c * chunk; t < std::min(n, (c + 1) * chunk); ++t) {
                const TileRange r = tile_range(m, &tris.index[3 * t], ax, ay, az, l, err);
                range[t] = r;
                for (int tx = r.tx0; tx <= r.tx1; ++tx)
                    for (int ty = r.ty0; ty <= r.ty1; ++ty) ++cnt[static_cast<std::size_t>(tx) * l.nty + ty];
            }
            if (err != kNone) error = err;
        }
    });
    if (error == kIndex) throw std::invalid_argument("grid: a face index is out of range");
    if (error == kNonFinite) throw std::invalid_argument("grid: a vertex used by a face has a non-finite coordinate");
    // offsets: tile-major, then chunk (so each tile's list is in triangle order)
    Bins bins;
    bins.offsets.assign(ntiles + 1, 0);
    std::size_t total = 0;
    for (std::size_t tile = 0; tile < ntiles; ++tile) {
        bins.offsets[tile] = total;
        for (std::size_t c = 0; c < chunks; ++c) {
            const std::size_t k = counts[c * ntiles + tile];
            counts[c * ntiles + tile] = total;
            total += k;
        }
    }
    bins.offsets[ntiles] = total;
    bins.entries.resize(total);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks, 1), [&](const tbb::blocked_range<std::size_t>& rc) {
        for (std::size_t c = rc.begin(); c != rc.end(); ++c) {
            std::size_t* next = &counts[c * ntiles];
            for (std::size_t t = c * chunk; t < std::min(n, (c + 1) * chunk); ++t) {
                const TileRange& r = range[t];
                for (int tx = r.tx0; tx <= r.tx1; ++tx)
                    for (int ty = r.ty0; ty <= r.ty1; ++ty)
                        bins.entries[next[static_cast<std::size_t>(tx) * l.nty + ty]++] = static_cast<uint32_t>(t);
            }
        }
    });
    return bins;
}

struct Workspace {
    grid::ClipBuffers clip;
    grid::Polygon tri;
    grid::TileSums sums;
    std::vector<grid::TileSums> level_sums;  // the union's (and the intersection's) pieces
    std::vector<uint8_t> state;              // bodies × tile cells: BodyCell
    std::vector<double> level_column;        // levels × nz: their scans of one column
    std::vector<uint8_t> level_state;        // nz
    std::vector<double> column, column_moments;  // one body's scan of a column (blocks not reaching the top)
};

struct Partial {
    std::vector<exact::ExactSum> body_volume;
    std::vector<std::size_t> pieces, full, empty, cut;
    exact::ExactSum union_volume, intersection_volume;
    std::size_t u_full = 0, u_empty = 0, u_cut = 0, u_contact = 0;
    explicit Partial(std::size_t bodies)
        : body_volume(bodies), pieces(bodies, 0), full(bodies, 0), empty(bodies, 0), cut(bodies, 0) {}
};

grid::Polygon& load_triangle(grid::Polygon& poly, const MeshView& m, const uint32_t* v) {
    poly.n = 3;
    for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a) poly.p[c].v[a] = m.positions[3 * std::size_t{v[c]} + a];
    for (int c = 0; c < 3; ++c) poly.s[c] = grid::make_segment(poly.p[c], poly.p[c == 2 ? 0 : c + 1]);
    return poly;
}

// A level's pieces on the crossed triangles: their fan triangles as a mesh
// of unshared vertices, with the unit normal of the triangle each lies in.
struct FanMesh {
    std::vector<double> positions;
    std::vector<uint32_t> index;
    std::vector<std::array<double, 3>> normal;
    Triangles tris;
    Bins bins;
    MeshView view() const { return {positions, {}, index}; }
};

struct Job {
    std::span<const MeshView> bodies;
    const GridAxes& g;
    const GridOutput& out;
    const Layout& l;
    const Axis &ax, &ay, &az;
    const std::vector<Triangles>& tris;
    const std::vector<Bins>& bins;
    bool moments, want_union, surface;
    // Several bodies: level 0 the union, level 1 (if asked for) the intersection.
    const boolean::LevelPieces* levels;
    const std::vector<FanMesh>& fans;
};

void add_surface(std::span<double> area, std::span<double> normal, std::size_t cell, double a, const double v[3]) {
    if (!area.empty()) area[cell] += a;
    if (!normal.empty())
        for (int c = 0; c < 3; ++c) normal[3 * cell + c] += v[c];
}

// Clips one body's triangles listed for a tile and scatters their pieces.
template <bool kMoments>
std::size_t scatter_tile(const Job& job, std::size_t b, std::size_t tile, int ix0, int ix1, int iy0, int iy1,
                         Workspace& ws) {
    const MeshView& m = job.bodies[b];
    const Bins& bins = job.bins[b];
    const double* xs = job.g.x.data();
    const double* ys = job.g.y.data();
    const double* zs = job.g.z.data();
    const int nz = static_cast<int>(job.g.nz()), k0 = job.l.k0, k1 = k0 + job.l.bnz;
    const uint8_t* on_level = job.levels ? job.levels->whole[b].data() : nullptr;
    std::size_t pieces = 0;
    for (std::size_t e = bins.offsets[tile]; e < bins.offsets[tile + 1]; ++e) {
        const uint32_t t = bins.entries[e];
        const uint8_t levels = on_level ? on_level[t] : 1;  // one body: its surface is the union's
        const uint32_t* v = &job.tris[b].index[3 * std::size_t{t}];
        grid::clip_to_cells(load_triangle(ws.tri, m, v), job.ax, job.ay, job.az, ix0, ix1, iy0, iy1, k0, ws.clip,
                            [&](const grid::Polygon& piece, int i, int j, int k) {
                                const int kt = std::min(k + 1, nz);
                                const double corner[3] = {xs[i], ys[j], zs[k]};
                                const double far[3] = {xs[i + 1], ys[j + 1], zs[kt]};
                                const grid::PieceIntegrals r = grid::piece_integrals<kMoments>(piece, corner, far);
                                ws.sums.scatter(i - ix0, j - iy0, k - k0, r);
                                for (std::size_t l = 0; l < ws.level_sums.size(); ++l)
                                    if (levels & (1u << l)) ws.level_sums[l].scatter(i - ix0, j - iy0, k - k0, r);
                                ++pieces;
                                if (job.surface && k < k1) {  // tiles own their cells: no race
                                    double a[3];
                                    grid::piece_vector_area(piece, corner, a);
                                    const double area = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
                                    const std::size_t cell = job.l.out_cell(i, j, k - k0);
                                    add_surface(job.out.wetted_area, job.out.surface_normal,
                                                b * job.l.out_cells() + cell, area, a);
                                    if (levels & 1u)
                                        add_surface(job.out.union_wetted_area, job.out.union_surface_normal, cell,
                                                    area, a);
                                }
                            });
    }
    return pieces;
}

// Clips a level's fan triangles listed for a tile into its sums; the
// union's surface gets each piece's area signed by the side it faces
// (a · n of the triangle it lies in), so the fans' overlaps cancel.
void scatter_fans(const Job& job, std::size_t level, std::size_t tile, int ix0, int ix1, int iy0, int iy1,
                  Workspace& ws) {
    const FanMesh& f = job.fans[level];
    const MeshView m = f.view();
    const double* xs = job.g.x.data();
    const double* ys = job.g.y.data();
    const double* zs = job.g.z.data();
    const int nz = static_cast<int>(job.g.nz()), k0 = job.l.k0, k1 = k0 + job.l.bnz;
    const bool surface = level == 0 && (!job.out.union_wetted_area.empty() || !job.out.union_surface_normal.empty());
    for (std::size_t e = f.bins.offsets[tile]; e < f.bins.offsets[tile + 1]; ++e) {
        const uint32_t t = f.bins.entries[e];
        grid::clip_to_cells(load_triangle(ws.tri, m, &f.index[3 * std::size_t{t}]), job.ax, job.ay, job.az, ix0, ix1,
                            iy0, iy1, k0, ws.clip, [&](const grid::Polygon& piece, int i, int j, int k) {
                                const int kt = std::min(k + 1, nz);
                                const double corner[3] = {xs[i], ys[j], zs[k]};
                                const double far[3] = {xs[i + 1], ys[j + 1], zs[kt]};
                                ws.level_sums[level].scatter(i - ix0, j - iy0, k - k0,
                                                             grid::piece_integrals<false>(piece, corner, far));
                                if (surface && k < k1) {
                                    double a[3];
                                    grid::piece_vector_area(piece, corner, a);
                                    const auto& n = f.normal[t];
                                    add_surface(job.out.union_wetted_area, job.out.union_surface_normal,
                                                job.l.out_cell(i, j, k - k0), a[0] * n[0] + a[1] * n[1] + a[2] * n[2], a);
                                }
                            });
    }
}

// Adds the n values of a column to an exact sum. A run of m equal values
// (full cells) is added as the exact product m v = p + e (Dekker's
// TwoProduct, exact for 2^-900 < |v| < 2^900; otherwise one by one).
void add_column(exact::ExactSum& sum, const double* v, int n) {
    int k = 0;
    while (k < n) {
        const double x = v[k];
        int m = 1;
        while (k + m < n && v[k + m] == x) ++m;
        k += m;
        if (x == 0) continue;
        if (m == 1 || !(std::abs(x) > 0x1p-900 && std::abs(x) < 0x1p900)) {
            for (int r = 0; r < m; ++r) sum.add(x);
        } else {
            double p, e;
            exact::two_prod_dekker(x, static_cast<double>(m), p, e);
            sum.add(p);
            sum.add(e);
        }
    }
}

// Cells of each kind among n states.
grid::ColumnCounts count_states(const uint8_t* state, int n) {
    grid::ColumnCounts c;
    for (int k = 0; k < n; ++k) (state[k] == grid::kEmpty ? c.empty : state[k] == grid::kFull ? c.full : c.cut) += 1;
    return c;
}

void run_tile(const Job& job, std::size_t tile, Workspace& ws, Partial& part) {
    const Layout& l = job.l;
    const int tx = static_cast<int>(tile / l.nty), ty = static_cast<int>(tile % l.nty);
    const int ix0 = l.i0 + tx * l.tile, ix1 = std::min(l.i0 + l.nx, ix0 + l.tile) - 1;
    const int iy0 = l.j0 + ty * l.tile, iy1 = std::min(l.j0 + l.ny, iy0 + l.tile) - 1;
    const int tw = ix1 - ix0 + 1, th = iy1 - iy0 + 1;
    const std::size_t nb = job.bodies.size();
    const std::size_t tile_cells = static_cast<std::size_t>(tw) * th * l.nz;
    const std::size_t cells = l.out_cells();
    const double* z = job.g.z.data() + l.k0;  // the scanned layers' planes
    ws.state.resize(nb * tile_cells);
    if (!l.direct()) {
        ws.column.resize(l.nz);
        ws.column_moments.resize(job.moments ? 3 * std::size_t(l.nz) : 0);
    }
    const std::size_t nlevels = job.fans.size();
    ws.level_sums.resize(nlevels);
    for (grid::TileSums& sums : ws.level_sums) sums.reset(l.tile, l.nz + 1, false);
    for (std::size_t b = 0; b < nb; ++b) {
        ws.sums.reset(l.tile, l.nz + 1, job.moments);
        part.pieces[b] += job.moments ? scatter_tile<true>(job, b, tile, ix0, ix1, iy0, iy1, ws)
                                      : scatter_tile<false>(job, b, tile, ix0, ix1, iy0, iy1, ws);
        for (int ci = 0; ci < tw; ++ci) {
            for (int cj = 0; cj < th; ++cj) {
                const int i = ix0 + ci, j = iy0 + cj;
                const std::size_t cell0 = l.out_cell(i, j, 0);
                double* vol = &job.out.volumes[b * cells + cell0];
                double* mom = job.moments ? &job.out.first_moments[3 * (b * cells + cell0)] : nullptr;
                uint8_t* state = &ws.state[b * tile_cells + (static_cast<std::size_t>(ci) * th + cj) * l.nz];
                const grid::ColumnGeometry geom{job.g.x[i], job.g.x[i + 1], job.g.y[j], job.g.y[j + 1], z, l.nz};
                grid::ColumnCounts counts;
                if (l.direct()) {
                    counts = grid::scan_column(ws.sums, ci, cj, geom, vol, mom, state);
                } else {
                    // A block below the grid's top: scan down to its floor, keep its layers.
                    grid::scan_column(ws.sums, ci, cj, geom, ws.column.data(), mom ? ws.column_moments.data() : nullptr,
                                      state);
                    std::copy_n(ws.column.data(), l.bnz, vol);
                    if (mom) std::copy_n(ws.column_moments.data(), 3 * l.bnz, mom);
                    counts = count_states(state, l.bnz);
                }
                part.empty[b] += counts.empty;
                part.full[b] += counts.full;
                part.cut[b] += counts.cut;
                if (counts.empty != static_cast<std::size_t>(l.bnz)) add_column(part.body_volume[b], vol, l.bnz);
            }
        }
    }
    if (!job.want_union) return;
    for (std::size_t level = 0; level < nlevels; ++level) scatter_fans(job, level, tile, ix0, ix1, iy0, iy1, ws);
    ws.level_column.resize(nlevels * l.nz);
    ws.level_state.resize(l.nz);
    const bool want_intersection = !job.out.intersection_volumes.empty();
    for (int ci = 0; ci < tw; ++ci) {
        for (int cj = 0; cj < th; ++cj) {
            const int i = ix0 + ci, j = iy0 + cj;
            const std::size_t cell0 = l.out_cell(i, j, 0);
            const std::size_t local0 = (static_cast<std::size_t>(ci) * th + cj) * l.nz;
            const grid::ColumnGeometry geom{job.g.x[i], job.g.x[i + 1], job.g.y[j], job.g.y[j + 1], z, l.nz};
            for (std::size_t level = 0; level < nlevels; ++level)
                grid::scan_column(ws.level_sums[level], ci, cj, geom, &ws.level_column[level * l.nz], nullptr,
                                  ws.level_state.data());
            for (int k = 0; k < l.bnz; ++k) {
                // The bodies' own values decide the cell unless two or more surfaces enter it.
                std::size_t full = 0, cut = 0, cut_body = 0;
                for (std::size_t b = 0; b < nb; ++b) {
                    const uint8_t st = ws.state[b * tile_cells + local0 + k];
                    if (st == grid::kFull) ++full;
                    if (st == grid::kCut) {
                        ++cut;
                        cut_body = b;
                    }
                }
                const double cell_volume = job.g.cell_volume(i, j, l.k0 + k);
                const double one_cut = cut == 1 ? job.out.volumes[cut_body * cells + cell0 + k] : 0;
                const double u = full > 0 ? cell_volume : cut <= 1 ? one_cut : ws.level_column[k];
                const std::size_t c = cell0 + k;
                if (!job.out.union_volumes.empty()) job.out.union_volumes[c] = u;
                if (u != 0) part.union_volume.add(u);
                const CellClass cls = full > 0  ? CellClass::full
                                      : cut == 0 ? CellClass::empty
                                      : cut == 1 ? CellClass::cut
                                                 : CellClass::contact;
                if (!job.out.cell_class.empty()) job.out.cell_class[c] = cls;
                switch (cls) {
                    case CellClass::empty: ++part.u_empty; break;
                    case CellClass::full: ++part.u_full; break;
                    case CellClass::cut: ++part.u_cut; break;
                    case CellClass::contact: ++part.u_contact; break;
                }
                if (!want_intersection) continue;
                // The intersection: 0 if some body is empty, else as above.
                const double x = full + cut < nb ? 0
                                 : full == nb   ? cell_volume
                                 : cut == 1     ? one_cut
                                                : ws.level_column[l.nz + k];
                job.out.intersection_volumes[c] = x;
                if (x != 0) part.intersection_volume.add(x);
            }
        }
    }
}

// Every tile on the CPU's threads (run_tile), then the threads' partial sums
// and counts into the summary and the exact sums.
void run_tiles(const Job& job, const GridOptions& options, GridSummary& s, std::vector<exact::ExactSum>& body_volume,
               exact::ExactSum& union_volume, exact::ExactSum& intersection_volume) {
    const std::size_t nb = job.bodies.size();
    tbb::enumerable_thread_specific<Workspace> workspaces;
    tbb::enumerable_thread_specific<Partial> partials([nb] { return Partial(nb); });
    const std::size_t ntiles = job.l.tiles();
    core::ProgressCounter progress(options.progress, ntiles);  // tiles done
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, ntiles, 1), [&](const tbb::blocked_range<std::size_t>& r) {
        Workspace& ws = workspaces.local();
        Partial& part = partials.local();
        for (std::size_t tile = r.begin(); tile != r.end(); ++tile) {
            run_tile(job, tile, ws, part);
            progress.add();
        }
    });
    for (const Partial& p : partials) {
        for (std::size_t b = 0; b < nb; ++b) {
            body_volume[b].merge(p.body_volume[b]);
            s.bodies[b].pieces += p.pieces[b];
            s.bodies[b].full_cells += p.full[b];
            s.bodies[b].empty_cells += p.empty[b];
            s.bodies[b].cut_cells += p.cut[b];
        }
        union_volume.merge(p.union_volume);
        intersection_volume.merge(p.intersection_volume);
        s.full_cells += p.u_full;
        s.empty_cells += p.u_empty;
        s.cut_cells += p.u_cut;
        s.contact_cells += p.u_contact;
    }
}

// The union's pieces as the device takes them: every level's fan triangles
// in one mesh, each level's tile lists one after the other.
grid::DeviceLevels device_levels(const std::vector<FanMesh>& fans) {
    grid::DeviceLevels d;
    d.count = fans.size();
    std::size_t triangles = 0;
    for (const FanMesh& f : fans) triangles += f.normal.size();
    if (triangles >= (std::size_t{1} << 32) / 3) throw std::invalid_argument("grid: too many crossing pieces");
    for (const FanMesh& f : fans) {
        const auto vertex0 = static_cast<uint32_t>(d.positions.size() / 3);
        const auto triangle0 = static_cast<uint32_t>(d.triangles.size() / 3);
        d.positions.insert(d.positions.end(), f.positions.begin(), f.positions.end());
        for (const uint32_t v : f.index) d.triangles.push_back(vertex0 + v);
        for (const auto& n : f.normal) d.normals.insert(d.normals.end(), n.begin(), n.end());
        const std::size_t entry0 = d.entries.size();
        for (const std::size_t o : f.bins.offsets) d.offsets.push_back(entry0 + o);
        for (const uint32_t t : f.bins.entries) d.entries.push_back(triangle0 + t);
    }
    return d;
}

// The per-column work on an OpenCL device when one is asked for: fills the
// outputs, the summary's counts and the exact sums and returns "opencl:
// NAME"; else returns why the CPU runs ("cpu (...)"), or nothing for a CPU
// request.
std::optional<std::string> device_block_volumes(const DeviceRequest& request, const Job& job, GridSummary& s,
                                                std::vector<exact::ExactSum>& body_volume,
                                                exact::ExactSum& union_volume, exact::ExactSum& intersection_volume) {
    if (request.kind != DeviceKind::opencl) return std::nullopt;
    std::string note;
    device::Device* d = device::resolve(request, note);
    if (!d) return "cpu (" + note + ")";
    const std::size_t nb = job.bodies.size();
    std::vector<grid::DeviceBody> dev;
    for (std::size_t b = 0; b < nb; ++b)
        dev.push_back({job.bodies[b].positions, job.tris[b].index, job.bins[b].offsets, job.bins[b].entries,
                       job.levels ? std::span<const uint8_t>(job.levels->whole[b]) : std::span<const uint8_t>()});
    const grid::DeviceLayout dl{job.l.i0, job.l.j0, job.l.k0, job.l.nx, job.l.ny, job.l.bnz, job.l.tile, job.l.nty};
    std::optional<grid::DeviceLevels> levels;
    if (job.want_union) levels = device_levels(job.fans);
    grid::DeviceResult r;
    if (!grid::device_columns(*d, job.g, dl, dev, levels ? &*levels : nullptr, job.out, r)) {
        // The CPU path adds into the surfaces: clear what the device wrote.
        for (const auto span : {job.out.wetted_area, job.out.surface_normal, job.out.union_wetted_area,
                                job.out.union_surface_normal})
            std::fill(span.begin(), span.end(), 0.0);
        return "cpu (a clipped polygon exceeded the device kernel's capacity)";
    }
    const std::size_t cells = job.l.out_cells();
    for (std::size_t b = 0; b < nb; ++b) {
        s.bodies[b].pieces = r.bodies[b].pieces;
        s.bodies[b].empty_cells = r.bodies[b].empty;
        s.bodies[b].full_cells = r.bodies[b].full;
        s.bodies[b].cut_cells = r.bodies[b].cut;
        // Each body's exact sum of its cells, column by column (exact, so in any order).
        const std::size_t columns = static_cast<std::size_t>(job.l.nx) * job.l.ny;
        tbb::enumerable_thread_specific<exact::ExactSum> sums;
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, columns, 256), [&](const auto& range) {
            exact::ExactSum& sum = sums.local();
            for (std::size_t c = range.begin(); c != range.end(); ++c)
                add_column(sum, &job.out.volumes[b * cells + c * job.l.bnz], job.l.bnz);
        });
        for (const exact::ExactSum& part : sums) body_volume[b].merge(part);
    }
    s.full_cells = r.full;
    s.empty_cells = r.empty;
    s.cut_cells = r.cut;
    s.contact_cells = r.contact;
    s.device_kernel_seconds = r.kernel_seconds;
    s.device_transfer_seconds = r.transfer_seconds;
    s.device_build_seconds = r.build_seconds;
    union_volume.merge(r.union_volume);
    intersection_volume.merge(r.intersection_volume);
    return "opencl: " + d->info.name;
}

}  // namespace

GridSummary grid_volumes(std::span<const MeshView> bodies, const GridAxes& g, const GridOutput& out,
                         const GridOptions& options) {
    return grid_block_volumes(bodies, g, GridBlock{{0, 0, 0}, {g.nx(), g.ny(), g.nz()}}, out, options);
}

GridSummary grid_block_volumes(std::span<const MeshView> bodies, const GridAxes& g, const GridBlock& block,
                               const GridOutput& out, const GridOptions& options) {
    check_axis(g.x, "x");
    check_axis(g.y, "y");
    check_axis(g.z, "z");
    const std::size_t nb = bodies.size();
    if (nb == 0) throw std::invalid_argument("grid: no bodies");
    for (int a = 0; a < 3; ++a)
        if (!(block.lo[a] < block.hi[a] && block.hi[a] <= (a == 0 ? g.nx() : a == 1 ? g.ny() : g.nz())))
            throw std::invalid_argument("grid: the block must be a non-empty range of cells within the grid");
    const std::size_t cells = block.cell_count();
    if (out.volumes.size() != nb * cells)
        throw std::invalid_argument("grid: volumes must hold bodies * cells = " + std::to_string(nb * cells) +
                                    " values, not " + std::to_string(out.volumes.size()));
    const bool moments = !out.first_moments.empty();
    if (moments && out.first_moments.size() != 3 * nb * cells)
        throw std::invalid_argument("grid: first_moments must hold 3 * bodies * cells values");
    for (const std::size_t size : {out.union_volumes.size(), out.intersection_volumes.size(), out.cell_class.size(),
                                   out.union_wetted_area.size()})
        if (size != 0 && size != cells)
            throw std::invalid_argument("grid: union and intersection outputs must hold one value per cell");
    if (!out.union_surface_normal.empty() && out.union_surface_normal.size() != 3 * cells)
        throw std::invalid_argument("grid: union_surface_normal must hold 3 * cells values");
    if (!out.wetted_area.empty() && out.wetted_area.size() != nb * cells)
        throw std::invalid_argument("grid: wetted_area must hold bodies * cells values");
    if (!out.surface_normal.empty() && out.surface_normal.size() != 3 * nb * cells)
        throw std::invalid_argument("grid: surface_normal must hold 3 * bodies * cells values");
    const bool surface = !out.wetted_area.empty() || !out.surface_normal.empty() || !out.union_wetted_area.empty() ||
                         !out.union_surface_normal.empty();
    for (const auto span : {out.wetted_area, out.surface_normal, out.union_wetted_area, out.union_surface_normal})
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, span.size(), 1 << 16), [&](const auto& r) {
            std::fill(span.begin() + static_cast<std::ptrdiff_t>(r.begin()), span.begin() + static_cast<std::ptrdiff_t>(r.end()), 0.0);
        });
    const bool union_outputs = !out.union_volumes.empty() || !out.intersection_volumes.empty() ||
                               !out.cell_class.empty() || !out.union_wetted_area.empty() ||
                               !out.union_surface_normal.empty();

    const Axis ax(g.x), ay(g.y), az(g.z);
    const Layout layout = choose_layout(g, block, moments);
    std::vector<Triangles> tris;
    std::vector<Bins> bins;
    for (const MeshView& m : bodies) {
        tris.push_back(fan_triangles(m));
        if (tris.back().count() >= (std::size_t{1} << 32))
            throw std::invalid_argument("grid: at most 2^32 - 1 triangles per body");
        bins.push_back(bin_triangles(m, tris.back(), ax, ay, az, layout));
    }

    // Several bodies: the union's (and the intersection's) boundary pieces.
    std::optional<boolean::LevelPieces> levels;
    std::vector<FanMesh> fans;
    if (nb > 1 && union_outputs) {
        std::vector<int> level_values{1};
        if (!out.intersection_volumes.empty()) level_values.push_back(static_cast<int>(nb));
        try {
            levels = boolean::level_pieces(bodies, level_values);
        } catch (const std::invalid_argument& e) {
            throw std::invalid_argument(std::string("grid: the union is undefined: ") + e.what());
        }
        fans.resize(level_values.size());
        for (std::size_t k = 0; k < fans.size(); ++k) {
            FanMesh& f = fans[k];
            for (const boolean::FanTriangle& t : levels->fans[k]) {
                for (int c = 0; c < 3; ++c) f.index.push_back(static_cast<uint32_t>(f.positions.size() / 3 + c));
                f.positions.insert(f.positions.end(), t.p.begin(), t.p.end());
                f.normal.push_back(t.normal);
            }
            if (f.normal.size() >= (std::size_t{1} << 32) / 3)
                throw std::invalid_argument("grid: too many crossing pieces");
            f.tris.index = f.index;
            f.bins = bin_triangles(f.view(), f.tris, ax, ay, az, layout);
        }
    }

    GridSummary s;
    s.bodies.resize(nb);
    std::vector<exact::ExactSum> body_volume(nb);
    const Job job{bodies, g, out, layout, ax, ay, az, tris, bins, moments, union_outputs, surface,
                  levels ? &*levels : nullptr, fans};
    exact::ExactSum union_volume, intersection_volume;
    if (const auto device =
            device_block_volumes(options.device, job, s, body_volume, union_volume, intersection_volume))
        s.device = *device;
    const bool on_device = s.device.starts_with("opencl");
    if (on_device) {
        if (options.progress) options.progress(1.0);
    } else {
        run_tiles(job, options, s, body_volume, union_volume, intersection_volume);
    }
    for (std::size_t b = 0; b < nb; ++b) {
        s.bodies[b].volume = body_volume[b].round();
        s.bodies[b].triangles = tris[b].count();
    }
    s.intersection_volume = std::numeric_limits<double>::quiet_NaN();
    if (levels) s.crossing_pairs = levels->crossing_pairs;
    if (union_outputs) {
        s.union_volume = union_volume.round();
        if (!out.intersection_volumes.empty()) s.intersection_volume = intersection_volume.round();
    } else if (nb == 1) {
        s.union_volume = s.bodies[0].volume;
        s.full_cells = s.bodies[0].full_cells;
        s.empty_cells = s.bodies[0].empty_cells;
        s.cut_cells = s.bodies[0].cut_cells;
    } else {
        s.union_volume = std::numeric_limits<double>::quiet_NaN();  // not asked for
    }
    return s;
}

}  // namespace polyvol

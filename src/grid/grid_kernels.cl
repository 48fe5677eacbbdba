// grid/grid_kernels.cl — the grid's per-column work on an OpenCL device
// (OpenCL C 1.2), replaying the CPU path's arithmetic operation for operation:
// clip.hpp (the pieces), piece.hpp (their integrals), tile_sums.hpp (the
// double-double sums in triangle order) and column_scan.cpp (the scan). Each
// function below names the C++ function it replays; a change to one is a
// change to both, and tests/grid/device_test.cpp compares every output bit
// for bit. Conventions: min/max/clamp are the C++ standard library's
// ternaries (not fmin/fmax, which differ on signed zeros); no contraction.
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#pragma OPENCL FP_CONTRACT OFF

#ifndef PV_CAP
#define PV_CAP 32  // vertices of a clipped polygon (a triangle in a box has at most 9)
#endif

typedef struct {
    double a[3], b[3];
} Segment;

typedef struct {
    int n;
    double p[PV_CAP][3];
    Segment s[PV_CAP];
    int pos[PV_CAP];
} Polygon;

// std::min, std::max, std::clamp
static double pv_min(double a, double b) { return b < a ? b : a; }
static double pv_max(double a, double b) { return a < b ? b : a; }
static double pv_clamp(double v, double lo, double hi) { return v < lo ? lo : (hi < v ? hi : v); }

// clip.hpp lex_less / make_segment
static int lex_less(const double* a, const double* b) {
    if (a[0] != b[0]) return a[0] < b[0];
    if (a[1] != b[1]) return a[1] < b[1];
    return a[2] < b[2];
}
static void make_segment(Segment* s, const double* p, const double* q) {
    const int swap = lex_less(q, p);
    for (int k = 0; k < 3; ++k) {
        s->a[k] = swap ? q[k] : p[k];
        s->b[k] = swap ? p[k] : q[k];
    }
}

// clip.hpp crossing
static void crossing(const Segment* s, int axis, double c, const double* p, const double* q, double* r) {
    const double t = (c - s->a[axis]) / (s->b[axis] - s->a[axis]);
    for (int k = 0; k < 3; ++k) {
        if (k == axis) {
            r[k] = c;
            continue;
        }
        const double x = s->a[k] + t * (s->b[k] - s->a[k]);
        const double lo = pv_min(p[k], q[k]), hi = pv_max(p[k], q[k]);
        r[k] = pv_clamp(x, lo, hi);
    }
}

// clip.hpp detail::push; 0 when the polygon is full
static int push(Polygon* out, const double* p, int pos, int cap) {
    if (out->n == cap) return 0;
    for (int k = 0; k < 3; ++k) out->p[out->n][k] = p[k];
    out->pos[out->n] = pos;
    ++out->n;
    return 1;
}

// clip.hpp detail::assign_supports
static void assign_supports(const Polygon* in, Polygon* out) {
    if (out->n < 3) {
        out->n = 0;
        return;
    }
    const int n2 = 2 * in->n;
    for (int j = 0; j < out->n; ++j) {
        const int jn = j + 1 == out->n ? 0 : j + 1;
        const int a = out->pos[j];
        int d = out->pos[jn] - a;
        if (d <= 0) d += n2;
        if (d == 1 || (d == 2 && (a & 1) == 0))
            out->s[j] = in->s[a >> 1];
        else
            make_segment(&out->s[j], out->p[j], out->p[jn]);
    }
}

static int side_of(const double* p, int axis, double c) { return p[axis] < c ? -1 : (p[axis] > c ? 1 : 0); }

// clip.hpp split; 0 on overflow of the capacity
static int split(const Polygon* in, int axis, double c, Polygon* lo, Polygon* hi, int cap) {
    lo->n = hi->n = 0;
    const int n = in->n;
    int sa = side_of(in->p[0], axis, c);
    const int s0 = sa;
    int ok = 1;
    for (int i = 0; i < n; ++i) {
        const int inext = i + 1 == n ? 0 : i + 1;
        const int sb = inext == 0 ? s0 : side_of(in->p[inext], axis, c);
        if (sa <= 0) ok &= push(lo, in->p[i], 2 * i, cap);
        if (sa >= 0) ok &= push(hi, in->p[i], 2 * i, cap);
        if (sa * sb < 0) {
            double x[3];
            crossing(&in->s[i], axis, c, in->p[i], in->p[inext], x);
            ok &= push(lo, x, 2 * i + 1, cap);
            ok &= push(hi, x, 2 * i + 1, cap);
        }
        sa = sb;
    }
    assign_supports(in, lo);
    assign_supports(in, hi);
    return ok;
}

// axis.hpp count_le / count_lt by binary search (the CPU's guess-and-walk
// gives the same integers): the number of planes <= v, < v.
static int count_le(__global const double* c, int n, double v) {
    int lo = 0, hi = n + 1;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (c[mid] <= v) lo = mid + 1; else hi = mid;
    }
    return lo;
}
static int count_lt(__global const double* c, int n, double v) {
    int lo = 0, hi = n + 1;
    while (lo < hi) {
        const int mid = (lo + hi) / 2;
        if (c[mid] < v) lo = mid + 1; else hi = mid;
    }
    return lo;
}

// The extent of a polygon along an axis and its slabs (clip.hpp split_into_slabs, axis.hpp slab_range).
static void slab_range(const Polygon* poly, int axis, __global const double* c, int n, int* first, int* last) {
    double mn = poly->p[0][axis], mx = mn;
    for (int i = 1; i < poly->n; ++i) {
        mn = pv_min(mn, poly->p[i][axis]);
        mx = pv_max(mx, poly->p[i][axis]);
    }
    *first = count_le(c, n, mn) - 1;
    *last = mx > mn ? max(*first, count_lt(c, n, mx) - 1) : *first;
}

// split_into_slabs with keep range [s, s]: the part of `in` in slab s, the
// same bits whatever range the CPU keeps (its parts below are split off the
// same way). Returns the index in pool[] of the part, -1 for none, -2 on
// overflow. pool[in] is the input; the three buffers used are the others.
static int part_in_slab(Polygon* pool, int in, int axis, __global const double* c, int n, int s, int cap) {
    int first, last;
    slab_range(&pool[in], axis, c, n, &first, &last);
    if (last < s || first > s) return -1;
    int free_[3], f = 0;
    for (int b = 0; b < 5 && f < 3; ++b)
        if (b != in) free_[f++] = b;
    int cur = in, lo = free_[0], hi = free_[1], spare = free_[2];
    for (int m = first + 1; m <= last; ++m) {
        if (!split(&pool[cur], axis, c[m], &pool[lo], &pool[hi], cap)) return -2;
        if (m - 1 >= s) return pool[lo].n > 0 ? lo : -1;
        const int done = cur == in ? spare : cur;
        cur = hi;
        hi = done;
        if (pool[cur].n == 0) return -1;
    }
    return cur;
}

// tile_sums.hpp DD::add (exact::two_sum)
static void dd_add(__global double* d, double x) {
    const double a = d[0];
    const double s = a + x;
    const double bb = s - a;
    const double e = (a - (s - bb)) + (x - bb);
    d[0] = s;
    d[1] += e;
}
static void dd_add_dd(double* hi, double* lo, __global const double* x) {
    const double a = *hi, b = x[0];
    const double s = a + b;
    const double bb = s - a;
    const double e = (a - (s - bb)) + (b - bb);
    *hi = s;
    *lo += e;
    *lo += x[1];
}

// column_scan.cpp round_integer
static double round_integer(double x) {
    if (!(fabs(x) < 4503599627370496.0)) return x;
    const long i = (long)(fabs(x) + 0.5);
    return x < 0 ? -(double)i : (double)i;
}

// Per cell of a column's scratch: nsum double-doubles (P, Q, then Px, Py,
// Qx, Qy, Qz with moments), 2 doubles each; flags bit 0: a piece, bit 1: interior.
#define PV_P 0
#define PV_Q 2
#define PV_PX 4
#define PV_PY 6
#define PV_QX 8
#define PV_QY 10
#define PV_QZ 12

// piece.hpp piece_integrals: r = P, Q, Px, Py, Qx, Qy, Qz (the last five
// with moments); returns whether the piece enters the cell's interior.
static int piece_integrals(const Polygon* poly, const double* corner, const double* far, int moments, double* r) {
    const int n = poly->n;
    double xi[PV_CAP], eta[PV_CAP], zeta[PV_CAP];
    int on_lo[3] = {1, 1, 1}, on_hi[3] = {1, 1, 1};
    for (int v = 0; v < n; ++v) {
        xi[v] = poly->p[v][0] - corner[0];
        eta[v] = poly->p[v][1] - corner[1];
        zeta[v] = poly->p[v][2] - corner[2];
        for (int a = 0; a < 3; ++a) {
            on_lo[a] = on_lo[a] && poly->p[v][a] == corner[a];
            on_hi[a] = on_hi[a] && poly->p[v][a] == far[a];
        }
    }
    double c_sum = 0, q_sum = 0, px_sum = 0, py_sum = 0, qx_sum = 0, qy_sum = 0, qz_sum = 0;
    for (int t = 1; t + 1 < n; ++t) {
        const double c = (xi[t] - xi[0]) * (eta[t + 1] - eta[0]) - (eta[t] - eta[0]) * (xi[t + 1] - xi[0]);
        const double sz = zeta[0] + zeta[t] + zeta[t + 1];
        c_sum += c;
        q_sum += c * sz;
        if (moments) {
            const double sx = xi[0] + xi[t] + xi[t + 1];
            const double sy = eta[0] + eta[t] + eta[t + 1];
            px_sum += c * sx;
            py_sum += c * sy;
            qx_sum += c * ((xi[0] * zeta[0] + xi[t] * zeta[t] + xi[t + 1] * zeta[t + 1]) + sx * sz);
            qy_sum += c * ((eta[0] * zeta[0] + eta[t] * zeta[t] + eta[t + 1] * zeta[t + 1]) + sy * sz);
            qz_sum += c * ((zeta[0] * zeta[0] + zeta[t] * zeta[t] + zeta[t + 1] * zeta[t + 1]) + sz * sz);
        }
    }
    r[0] = c_sum / 2;
    r[1] = q_sum / 6;
    if (moments) {
        r[2] = px_sum / 6;
        r[3] = py_sum / 6;
        r[4] = qx_sum / 24;
        r[5] = qy_sum / 24;
        r[6] = qz_sum / 48;
    }
    return !(on_lo[0] || on_lo[1] || on_lo[2] || on_hi[0] || on_hi[1] || on_hi[2]);
}

// tile_sums.hpp TileSums::scatter: one piece's integrals into its cell's
// double-doubles (nsum / 2 of them) and flags.
static void add_to_cell(__global double* cell, __global uchar* flag, const double* r, int interior, int nsum) {
    *flag |= (uchar)(1 | (interior ? 2 : 0));
    for (int m = 0; m < nsum / 2; ++m) dd_add(cell + 2 * m, r[m]);
}

// piece.hpp piece_vector_area
static void vector_area(const Polygon* poly, const double* corner, double* out) {
    out[0] = out[1] = out[2] = 0;
    double q[PV_CAP][3];
    for (int v = 0; v < poly->n; ++v)
        for (int a = 0; a < 3; ++a) q[v][a] = poly->p[v][a] - corner[a];
    for (int t = 1; t + 1 < poly->n; ++t) {
        const double u[3] = {q[t][0] - q[0][0], q[t][1] - q[0][1], q[t][2] - q[0][2]};
        const double w[3] = {q[t + 1][0] - q[0][0], q[t + 1][1] - q[0][1], q[t + 1][2] - q[0][2]};
        out[0] += 0.5 * (u[1] * w[2] - u[2] * w[1]);
        out[1] += 0.5 * (u[2] * w[0] - u[0] * w[2]);
        out[2] += 0.5 * (u[0] * w[1] - u[1] * w[0]);
    }
}

// Which outputs the caller asked for (bits of `what`).
#define PV_MOMENTS 1
#define PV_AREA 2
#define PV_NORMAL 4
#define PV_UNION_AREA 8
#define PV_UNION_NORMAL 16

typedef struct {
    __global const double *xs, *ys, *zs;
    int gnx, gny, gnz, k0, bnz, what, cap;
} Column;

// Where one triangle's pieces go: a body's sums (nsum doubles a cell, its
// own flags) and the levels its whole triangle lies on (grid_volumes.cpp
// scatter_tile), or a level's fan triangle (scatter_fans: `fan` set, the
// union's surface signed by its normal). Layer-indexed pointers of the column.
typedef struct {
    __global double* sums;
    __global uchar* flags;
    int nsum;
    __global double* level_sums;  // level l at + l * level_stride * 4
    __global uchar* level_flags;  // level l at + l * level_stride
    size_t level_stride;
    int nlevels;
    int level_bits;
    int fan;
    double normal[3];  // the fan triangle's unit normal
    size_t out0;       // the column's first output cell of its body
    size_t union0;     // the column's first cell of the union's outputs
    __global double *area, *surface_normal, *union_area, *union_normal;
} Sink;

static void emit(const Column* g, Sink* o, const Polygon* piece, int i, int j, int k) {
    const int kt = min(k + 1, g->gnz);
    const double corner[3] = {g->xs[i], g->ys[j], g->zs[k]};
    const double far[3] = {g->xs[i + 1], g->ys[j + 1], g->zs[kt]};
    const int layer = k - g->k0;
    const int moments = !o->fan && (g->what & PV_MOMENTS);
    double r[7];
    const int interior = piece_integrals(piece, corner, far, moments, r);
    if (!o->fan) add_to_cell(o->sums + (size_t)layer * o->nsum, o->flags + layer, r, interior, o->nsum);
    for (int l = 0; l < o->nlevels; ++l)
        if (o->level_bits & (1 << l))
            add_to_cell(o->level_sums + (l * o->level_stride + (size_t)layer) * 4,
                        o->level_flags + l * o->level_stride + layer, r, interior, 4);
    if (layer >= g->bnz) return;
    const size_t cell = o->out0 + (size_t)layer, ucell = o->union0 + (size_t)layer;
    if (o->fan) {
        if (g->what & (PV_UNION_AREA | PV_UNION_NORMAL)) {
            double a[3];
            vector_area(piece, corner, a);
            if (g->what & PV_UNION_AREA)
                o->union_area[ucell] += a[0] * o->normal[0] + a[1] * o->normal[1] + a[2] * o->normal[2];
            if (g->what & PV_UNION_NORMAL)
                for (int c = 0; c < 3; ++c) o->union_normal[3 * ucell + c] += a[c];
        }
        return;
    }
    if (g->what & (PV_AREA | PV_NORMAL | PV_UNION_AREA | PV_UNION_NORMAL)) {
        double a[3];
        vector_area(piece, corner, a);
        const double ar = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        if (g->what & PV_AREA) o->area[cell] += ar;
        if (g->what & PV_NORMAL)
            for (int c = 0; c < 3; ++c) o->surface_normal[3 * cell + c] += a[c];
        if (o->level_bits & 1) {
            if (g->what & PV_UNION_AREA) o->union_area[ucell] += ar;
            if (g->what & PV_UNION_NORMAL)
                for (int c = 0; c < 3; ++c) o->union_normal[3 * ucell + c] += a[c];
        }
    }
}

// The pieces of one triangle (pool[0]) in column (i, j), every layer from k0
// up (clip.hpp clip_to_cells with the keep ranges [i, i] and [j, j]).
// Returns 0 on overflow of the capacity.
static int clip_triangle(const Column* g, Sink* o, Polygon* pool, int i, int j, uint* pieces) {
    const int px = part_in_slab(pool, 0, 0, g->xs, g->gnx, i, g->cap);
    if (px < 0) return px == -1;
    const int py = part_in_slab(pool, px, 1, g->ys, g->gny, j, g->cap);
    if (py < 0) return py == -1;
    // split_into_slabs along z with the keep range [k0, gnz], every part emitted
    int first, last;
    slab_range(&pool[py], 2, g->zs, g->gnz, &first, &last);
    if (last < g->k0 || first > g->gnz) return 1;
    int free_[3], f = 0;
    for (int b = 0; b < 5 && f < 3; ++b)
        if (b != py) free_[f++] = b;
    int cur = py, lo = free_[0], hi = free_[1], spare = free_[2];
    for (int m = first + 1; m <= last; ++m) {
        if (!split(&pool[cur], 2, g->zs[m], &pool[lo], &pool[hi], g->cap)) return 0;
        if (m - 1 >= g->k0 && pool[lo].n > 0) {
            emit(g, o, &pool[lo], i, j, m - 1);
            ++*pieces;
        }
        if (m - 1 >= g->gnz) return 1;
        const int done = cur == py ? spare : cur;
        cur = hi;
        hi = done;
        if (pool[cur].n == 0) return 1;
    }
    emit(g, o, &pool[cur], i, j, last);
    ++*pieces;
    return 1;
}

static void load_triangle(Polygon* p, __global const double* pos, __global const uint* tri, uint t) {
    p->n = 3;
    for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a) p->p[c][a] = pos[3 * (size_t)tri[3 * (size_t)t + c] + a];
    for (int c = 0; c < 3; ++c) make_segment(&p->s[c], p->p[c], p->p[c == 2 ? 0 : c + 1]);
}

// column_scan.cpp scan_column, one cell at a time from the top down: the
// cross-section above (A, and Ax, Ay with moments) as double-doubles.
typedef struct {
    double a_hi, a_lo, ax_hi, ax_lo, ay_hi, ay_lo;
    double x0, y0, area, cx, cy;
    __global const double* z;  // the scanned layers' planes
    int nsum, moments;
} Scan;

static void scan_start(Scan* sc, const Column* g, int i, int j, __global const double* top, uchar top_flag, int nsum,
                       int moments) {
    sc->x0 = g->xs[i];
    sc->y0 = g->ys[j];
    const double x1 = g->xs[i + 1], y1 = g->ys[j + 1];
    const double dx = x1 - sc->x0, dy = y1 - sc->y0;
    sc->area = dx * dy;
    sc->cx = 0.5 * (sc->x0 + x1);
    sc->cy = 0.5 * (sc->y0 + y1);
    sc->z = g->zs + g->k0;
    sc->nsum = nsum;
    sc->moments = moments;
    sc->a_hi = sc->a_lo = sc->ax_hi = sc->ax_lo = sc->ay_hi = sc->ay_lo = 0;
    if (top_flag & 1) {
        sc->a_hi = top[PV_P];
        sc->a_lo = top[PV_P + 1];
        if (moments) {
            sc->ax_hi = top[PV_PX];
            sc->ax_lo = top[PV_PX + 1];
            sc->ay_hi = top[PV_PY];
            sc->ay_lo = top[PV_PY + 1];
        }
    }
}

// Cell k's volume (and first moments m[3], its state 0 empty, 1 full, 2 cut),
// then its pieces' cross-section added to the one above the next cell.
static double scan_cell(Scan* sc, int k, __global const double* c, uchar f, double* m, uchar* st) {
    double v;
    m[0] = m[1] = m[2] = 0;
    if ((f & 1) && (f & 2)) {
        const double z0 = sc->z[k], h = sc->z[k + 1] - z0;
        v = (c[PV_Q] + h * sc->a_hi) + (c[PV_Q + 1] + h * sc->a_lo);
        *st = 2;
        if (sc->moments) {
            const double mx = (c[PV_QX] + h * sc->ax_hi) + (c[PV_QX + 1] + h * sc->ax_lo);
            const double my = (c[PV_QY] + h * sc->ay_hi) + (c[PV_QY + 1] + h * sc->ay_lo);
            const double hh = 0.5 * h * h;
            const double mz = (c[PV_QZ] + hh * sc->a_hi) + (c[PV_QZ + 1] + hh * sc->a_lo);
            m[0] = sc->x0 * v + mx;
            m[1] = sc->y0 * v + my;
            m[2] = z0 * v + mz;
        }
    } else {
        // no piece enters: the winding number of the cross-section above
        const double w = round_integer((sc->a_hi + sc->a_lo) / sc->area);
        *st = w == 0 ? 0 : (w >= 1 ? 1 : 2);
        if (w == 0) {
            v = 0.0;
        } else {
            v = w * (sc->area * (sc->z[k + 1] - sc->z[k]));
            m[0] = v * sc->cx;
            m[1] = v * sc->cy;
            m[2] = v * (0.5 * (sc->z[k] + sc->z[k + 1]));
        }
    }
    if (f & 1) {
        dd_add_dd(&sc->a_hi, &sc->a_lo, c + PV_P);
        if (sc->moments) {
            dd_add_dd(&sc->ax_hi, &sc->ax_lo, c + PV_PX);
            dd_add_dd(&sc->ay_hi, &sc->ay_lo, c + PV_PY);
        }
    }
    return v;
}

#define PV_COLUMN_SETUP()                                  \
    const int col = (int)get_global_id(0);                 \
    if (col >= columns) return;                            \
    const int i = i0 + row0 + col / ny, j = j0 + col % ny; \
    Column g;                                              \
    g.xs = xs;                                             \
    g.ys = ys;                                             \
    g.zs = zs;                                             \
    g.gnx = gnx;                                           \
    g.gny = gny;                                           \
    g.gnz = gnz;                                           \
    g.k0 = k0;                                             \
    g.bnz = bnz;                                           \
    g.what = what;                                         \
    g.cap = min(cap, PV_CAP);                              \
    const int layers = gnz - k0 + 1;                       \
    const size_t tile_index = (size_t)((i - i0) / tile) * nty + (j - j0) / tile

// One body's cells of one column per work-item: the column's triangles (its
// tile's list, in triangle order) clipped to it, their pieces summed per
// cell (and per level their whole triangle lies on), then the scan
// (grid_volumes.cpp scatter_tile + run_tile). Column `col` of the batch is
// (i, j) = (i0 + row0 + col / ny, j0 + col % ny); its outputs start at
// body_base + col * bnz (the union's surface at col * bnz); counts: empty,
// full, cut cells and pieces at 4 * (column_base + col).
__kernel void polyvol_grid_body(
    __global const double* xs, __global const double* ys, __global const double* zs, int gnx, int gny, int gnz,
    int i0, int j0, int k0, int ny, int bnz, int row0, int columns, int tile, int nty,
    __global const double* pos, __global const uint* tri, __global const ulong* offsets, __global const uint* entries,
    __global const uchar* on_level, int nlevels, __global double* sums, __global uchar* flags,
    __global double* level_sums, __global uchar* level_flags, ulong level_stride, int what, int cap,
    ulong column_base, __global double* volumes, __global double* moments, __global uchar* states,
    __global double* area, __global double* normal, __global double* union_area, __global double* union_normal,
    __global uint* counts, __global int* error) {
    PV_COLUMN_SETUP();
    Sink o;
    o.nsum = (what & PV_MOMENTS) ? 14 : 4;
    o.sums = sums + (size_t)col * layers * o.nsum;
    o.flags = flags + (size_t)col * layers;
    o.level_sums = level_sums + (size_t)col * layers * 4;
    o.level_flags = level_flags + (size_t)col * layers;
    o.level_stride = level_stride;
    o.nlevels = nlevels;
    o.fan = 0;
    o.out0 = ((size_t)column_base + col) * bnz;
    o.union0 = (size_t)col * bnz;
    o.area = area;
    o.surface_normal = normal;
    o.union_area = union_area;
    o.union_normal = union_normal;
    for (int k = 0; k < layers * o.nsum; ++k) o.sums[k] = 0;
    for (int k = 0; k < layers; ++k) o.flags[k] = 0;
    uint pieces = 0;
    Polygon pool[5];
    for (ulong e = offsets[tile_index]; e < offsets[tile_index + 1]; ++e) {
        const uint t = entries[e];
        o.level_bits = nlevels > 0 ? on_level[t] : 1;  // one body: its surface is the union's
        load_triangle(&pool[0], pos, tri, t);
        if (!clip_triangle(&g, &o, pool, i, j, &pieces)) {
            *error = 1;  // a polygon beyond the capacity: the host redoes the grid on the CPU
            return;
        }
    }
    Scan sc;
    const int nz = layers - 1;
    scan_start(&sc, &g, i, j, o.sums + (size_t)nz * o.nsum, o.flags[nz], o.nsum, (what & PV_MOMENTS) != 0);
    uint empty = 0, full = 0, cut = 0;
    for (int k = nz - 1; k >= 0; --k) {
        double m[3];
        uchar st;
        const double v = scan_cell(&sc, k, o.sums + (size_t)k * o.nsum, o.flags[k], m, &st);
        if (k >= bnz) continue;
        const size_t c = o.out0 + (size_t)k;
        volumes[c] = v;
        states[c] = st;
        if (what & PV_MOMENTS)
            for (int a = 0; a < 3; ++a) moments[3 * c + a] = m[a];
        if (st == 0) ++empty; else if (st == 1) ++full; else ++cut;
    }
    __global uint* n = counts + 4 * ((size_t)column_base + col);
    n[0] = empty;
    n[1] = full;
    n[2] = cut;
    n[3] = pieces;
}

// The union's (and the intersection's) cells of one column per work-item,
// after every body's kernel (grid_volumes.cpp run_tile): each level's fan
// triangles clipped into its sums, the levels scanned, and each cell taken
// from the bodies' values where those decide it. Fans of level l: triangles
// fan_entries[fan_offsets[l * (tiles + 1) + tile] ...]; bodies' volumes and
// states at b * body_stride + col * bnz + k. counts: full, empty, cut,
// contact cells at 4 * col.
__kernel void polyvol_grid_union(
    __global const double* xs, __global const double* ys, __global const double* zs, int gnx, int gny, int gnz,
    int i0, int j0, int k0, int ny, int bnz, int row0, int columns, int tile, int nty, int what, int cap,
    int nb, int nlevels, int intersection, __global const double* fan_pos, __global const uint* fan_tri,
    __global const double* fan_normal, __global const ulong* fan_offsets, __global const uint* fan_entries,
    ulong tiles, __global double* level_sums, __global uchar* level_flags, ulong level_stride,
    __global const double* volumes, __global const uchar* states, ulong body_stride,
    __global double* union_volumes, __global double* intersection_volumes, __global uchar* cell_class,
    __global double* union_area, __global double* union_normal, __global uint* counts, __global int* error) {
    PV_COLUMN_SETUP();
    Sink o;
    o.nsum = 4;
    o.fan = 1;
    o.level_sums = level_sums + (size_t)col * layers * 4;
    o.level_flags = level_flags + (size_t)col * layers;
    o.level_stride = level_stride;
    o.nlevels = nlevels;
    o.out0 = o.union0 = (size_t)col * bnz;
    o.union_area = union_area;
    o.union_normal = union_normal;
    uint pieces = 0;
    Polygon pool[5];
    for (int l = 0; l < nlevels; ++l) {
        o.level_bits = 1 << l;
        g.what = l == 0 ? what : 0;  // only the union's surface
        __global const ulong* off = fan_offsets + (size_t)l * (tiles + 1);
        for (ulong e = off[tile_index]; e < off[tile_index + 1]; ++e) {
            const uint t = fan_entries[e];
            for (int c = 0; c < 3; ++c) o.normal[c] = fan_normal[3 * (size_t)t + c];
            load_triangle(&pool[0], fan_pos, fan_tri, t);
            if (!clip_triangle(&g, &o, pool, i, j, &pieces)) {
                *error = 1;
                return;
            }
        }
    }
    Scan lv[2];
    const int nz = layers - 1;
    for (int l = 0; l < nlevels; ++l)
        scan_start(&lv[l], &g, i, j, o.level_sums + (l * level_stride + (size_t)nz) * 4,
                   o.level_flags[l * level_stride + nz], 4, 0);
    uint ufull = 0, uempty = 0, ucut = 0, ucontact = 0;
    for (int k = nz - 1; k >= 0; --k) {
        double level[2] = {0, 0}, m[3];
        uchar st;
        for (int l = 0; l < nlevels; ++l)
            level[l] = scan_cell(&lv[l], k, o.level_sums + (l * level_stride + (size_t)k) * 4,
                                 o.level_flags[l * level_stride + k], m, &st);
        if (k >= bnz) continue;
        // The bodies' own values decide the cell unless two or more surfaces enter it.
        int full = 0, cut = 0, cut_body = 0;
        const size_t c = o.out0 + (size_t)k;
        for (int b = 0; b < nb; ++b) {
            const uchar s = states[b * body_stride + c];
            if (s == 1) ++full;
            if (s == 2) {
                ++cut;
                cut_body = b;
            }
        }
        const double cell_volume = (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]) * (zs[k0 + k + 1] - zs[k0 + k]);
        const double one_cut = cut == 1 ? volumes[cut_body * body_stride + c] : 0;
        union_volumes[c] = full > 0 ? cell_volume : cut <= 1 ? one_cut : level[0];
        const uchar cls = full > 0 ? 1 : cut == 0 ? 0 : cut == 1 ? 2 : 3;  // CellClass
        cell_class[c] = cls;
        if (cls == 1) ++ufull; else if (cls == 0) ++uempty; else if (cls == 2) ++ucut; else ++ucontact;
        if (intersection)  // level 1 is there whenever two surfaces can enter a cell
            intersection_volumes[c] = full + cut < nb ? 0 : full == nb ? cell_volume : cut == 1 ? one_cut : level[1];
    }
    __global uint* n = counts + 4 * (size_t)col;
    n[0] = ufull;
    n[1] = uempty;
    n[2] = ucut;
    n[3] = ucontact;
}

// The device's arithmetic against the host's on cases where a contraction,
// flushed denormals, an inexact division or square root, or fmin's signed
// zeros would change bits (device_grid.cpp compares them).
__kernel void polyvol_canary(__global const double* in, __global double* out) {
    out[0] = in[0] * in[1] + in[2];
    out[1] = in[3] * in[4];
    out[2] = in[5] / in[6];
    out[3] = sqrt(in[7]);
    out[4] = pv_min(in[8], in[9]);
    out[5] = pv_max(in[9], in[8]);
    out[6] = round_integer(in[10]);
}

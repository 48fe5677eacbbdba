// boolean/prepared_body.cpp — prepared_body.hpp: the body welded and
// bucketed once, the windings at many cells' points in one pass.
#include "boolean/prepared_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "boolean/exact_terms.hpp"
#include "boolean/operand.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/topology.hpp"

namespace polyvol::boolean {

struct PreparedBody {
    Operand body;  // welded, moved by δ (shift 1)
    int e0 = 0;    // the lowest bit exponent of its coordinates
    double max_coordinate = 0;
    int n = 1;     // buckets per axis over body.bounds, holding each triangle whose box meets them
    std::vector<uint32_t> offsets, items;

    // The triangles whose box meets `box`, increasing.
    void triangles_meeting(const std::array<double, 6>& box, std::vector<uint32_t>& out) const;
};

namespace {

// The bucket of x among n over [lo, hi], clamped (in double: a box
// coordinate may be ±inf, a float box of a coordinate beyond FLT_MAX).
int bucket_of(double x, double lo, double hi, int n) {
    if (!(hi > lo)) return 0;
    const double f = std::floor((x - lo) / (hi - lo) * n);
    return f > 0 ? static_cast<int>(std::min(f, static_cast<double>(n - 1))) : 0;
}

// Checks that every coordinate of op's triangles is in the exact predicates'
// range (std::invalid_argument naming `what` otherwise), and lowers e0 to the
// lowest bit exponent and raises max_coordinate to the largest magnitude
// among them (boolean_volumes' common scale).
void widen_scale(const Operand& op, const char* what, int& e0, double& max_coordinate) {
    if (!op.scale.in_range)
        throw std::invalid_argument(std::string("a coordinate of the ") + what +
                                    " is not finite or outside 0 and 2^-160 .. 2^180");
    e0 = std::min(e0, op.scale.e0);
    max_coordinate = std::max(max_coordinate, op.scale.max_coordinate);
}

// The buckets (n per axis over `all`) a box (xmin ymin zmin xmax ymax zmax) meets, per axis.
template <class T>
void bucket_range(const std::array<double, 6>& all, int n, const T* box, int* lo, int* hi) {
    for (int k = 0; k < 3; ++k) {
        lo[k] = bucket_of(box[k], all[k], all[3 + k], n);
        hi[k] = bucket_of(box[3 + k], all[k], all[3 + k], n);
    }
}

}  // namespace

void PreparedBody::triangles_meeting(const std::array<double, 6>& b, std::vector<uint32_t>& out) const {
    out.clear();
    const std::array<double, 6>& all = body.bounds;
    for (int k = 0; k < 3; ++k)
        if (b[k] > all[3 + k] || all[k] > b[3 + k]) return;
    int lo[3], hi[3];
    bucket_range(all, n, b.data(), lo, hi);
    for (int i = lo[0]; i <= hi[0]; ++i)
        for (int j = lo[1]; j <= hi[1]; ++j)
            for (int k = lo[2]; k <= hi[2]; ++k) {
                const std::size_t bucket = (static_cast<std::size_t>(i) * n + j) * n + k;
                for (uint32_t x = offsets[bucket]; x < offsets[bucket + 1]; ++x) {
                    const float* t = &body.box[6 * std::size_t{items[x]}];
                    if (t[0] <= b[3] && b[0] <= t[3] && t[1] <= b[4] && b[1] <= t[4] && t[2] <= b[5] && b[2] <= t[5])
                        out.push_back(items[x]);
                }
            }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
}

bool meets_box(const PreparedBody& body, const std::array<double, 6>& box) {
    std::vector<uint32_t> near;
    body.triangles_meeting(box, near);
    return !near.empty();
}

std::shared_ptr<const PreparedBody> prepare_body(const MeshView& view) {
    if (!check_closed(view).closed) throw std::invalid_argument("the body is not a closed surface");
    if (signed_volume(view) < 0) throw std::invalid_argument("the body is inside out (negative volume)");
    auto prepared = std::make_shared<PreparedBody>();
    PreparedBody& p = *prepared;
    p.body = make_operand(view, 1);
    int e0 = std::numeric_limits<int>::max();
    widen_scale(p.body, "body", e0, p.max_coordinate);
    p.e0 = e0 == std::numeric_limits<int>::max() ? 0 : e0;
    // Buckets: about one triangle each, per axis the cube root.
    const std::size_t nt = p.body.triangles();
    p.n = std::max(1, static_cast<int>(std::cbrt(static_cast<double>(nt))));
    const int n = p.n;
    const auto& all = p.body.bounds;
    auto for_each_bucket = [&](auto&& fn) {
        for (uint32_t t = 0; t < nt; ++t) {
            const float* b = &p.body.box[6 * std::size_t{t}];
            int lo[3], hi[3];
            bucket_range(all, n, b, lo, hi);
            for (int i = lo[0]; i <= hi[0]; ++i)
                for (int j = lo[1]; j <= hi[1]; ++j)
                    for (int k = lo[2]; k <= hi[2]; ++k) fn((static_cast<std::size_t>(i) * n + j) * n + k, t);
        }
    };
    std::vector<uint32_t> count(static_cast<std::size_t>(n) * n * n + 1, 0);
    for_each_bucket([&](std::size_t bucket, uint32_t) { ++count[bucket + 1]; });
    for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
    p.offsets = count;
    p.items.resize(count.back());
    for_each_bucket([&](std::size_t bucket, uint32_t t) { p.items[count[bucket]++] = t; });
    return prepared;
}

std::vector<int32_t> windings_at(const PreparedBody& body, std::span<const double> points,
                                 std::span<const uint32_t> triangles) {
    Operand s;
    s.mesh.positions.assign(points.begin(), points.end());
    s.mesh.indices.assign(triangles.begin(), triangles.end());
    s.tri = s.mesh.indices;
    s.body_shift = {0};
    int e0 = 0;
    double max_coordinate = 0;
    finish_operand(s);
    widen_scale(s, "mesh", e0, max_coordinate);  // the range check (of the scale finish_operand takes)
    const Crossings cross = find_crossings(s, body.body);
    return vertex_windings(s, body.body, cross.a_hits);
}

double cell_intersection(const PreparedBody& body, std::span<const double> points, std::span<const uint32_t> triangles,
                         std::span<const int32_t> winding, CellSurface* surface) {
    // A: the cell, unmoved; B: the body's triangles near it, moved by δ as in boolean_volumes.
    Operand A;
    A.mesh.positions.assign(points.begin(), points.end());
    A.mesh.indices.assign(triangles.begin(), triangles.end());
    A.tri = A.mesh.indices;
    A.body_shift = {0};
    finish_operand(A);
    std::vector<uint32_t> near;
    body.triangles_meeting(A.bounds, near);
    // The near triangles over their own vertices (sorted body indices, a
    // few dozen: a search per corner, not a table of the whole body per cell).
    Operand B;
    B.body_shift = {1};
    std::vector<uint32_t> used;
    used.reserve(3 * near.size());
    for (const uint32_t t : near)
        for (int i = 0; i < 3; ++i) used.push_back(body.body.tri[3 * std::size_t{t} + i]);
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    B.mesh.positions.reserve(3 * used.size());
    for (const uint32_t v : used)
        B.mesh.positions.insert(B.mesh.positions.end(), body.body.point(v), body.body.point(v) + 3);
    B.tri.reserve(3 * near.size());
    for (const uint32_t t : near)
        for (int i = 0; i < 3; ++i) {
            const uint32_t v = body.body.tri[3 * std::size_t{t} + i];
            B.tri.push_back(static_cast<uint32_t>(std::lower_bound(used.begin(), used.end(), v) - used.begin()));
        }
    B.mesh.indices = B.tri;
    finish_operand(B);

    int e0 = body.e0;
    double max_coordinate = body.max_coordinate;
    widen_scale(A, "mesh", e0, max_coordinate);
    if (surface == nullptr)
        return intersection_given_windings(A, B, std::vector<int32_t>(winding.begin(), winding.end()), e0,
                                           max_coordinate);
    SurfaceInside inside;
    const double volume = intersection_given_windings(A, B, std::vector<int32_t>(winding.begin(), winding.end()), e0,
                                                      max_coordinate, &inside);
    // Each sum is 2 ×: halved and rounded once (half an ulp more).
    surface->area = inside.area.sum.round_div(2);
    double largest = std::fabs(surface->area);
    for (int k = 0; k < 3; ++k) {
        surface->normal[k] = inside.normal.sum[k].round_div(2);
        largest = std::max(largest, std::fabs(surface->normal[k]));
    }
    surface->bound = (std::max(inside.area.bound, inside.normal.bound) / 2 + 0x1p-53 * largest) * (1 + 0x1p-40);
    return volume;
}

}  // namespace polyvol::boolean

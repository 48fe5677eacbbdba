#include "topology/winding.hpp"
#include "core/portable_math.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <numbers>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace polyvol::topology {

double solid_angle(const double* p, const double* a, const double* b, const double* c) {
    const double ax = a[0] - p[0], ay = a[1] - p[1], az = a[2] - p[2];
    const double bx = b[0] - p[0], by = b[1] - p[1], bz = b[2] - p[2];
    const double cx = c[0] - p[0], cy = c[1] - p[1], cz = c[2] - p[2];
    const double la = std::sqrt(ax * ax + ay * ay + az * az);
    const double lb = std::sqrt(bx * bx + by * by + bz * bz);
    const double lc = std::sqrt(cx * cx + cy * cy + cz * cz);
    const double det = ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
    const double den = la * lb * lc + (ax * bx + ay * by + az * bz) * lc +
                       (bx * cx + by * cy + bz * cz) * la + (cx * ax + cy * ay + cz * az) * lb;
    // det + 0.0 turns -0 into +0: a point inside a coplanar triangle (det 0,
    // den < 0) gets +2π, half a winding, whatever the sign of the rounded
    // zero. A point on another closed shell's face thus counts as inside it
    // (the corpus reference does the same).
    return 2 * core::portable_atan2(det + 0.0, den);  // the same bits in every build (core/portable_math.hpp)
}

namespace {

// Far-field data of a set of triangles (see winding.hpp).
struct Cluster {
    double n[3] = {0, 0, 0};  // Σ area vectors ½(b-a)×(c-a)
    double area = 0;          // Σ |area vector|
    double c[3] = {0, 0, 0};  // area-weighted centroid
    double m[9] = {};         // m[3l+k] = Σ (c_t - c)_l N_t,k
};

struct TriangleMoments {
    double n[3], area, centroid[3];
};

TriangleMoments triangle_moments(const double* a, const double* b, const double* c) {
    TriangleMoments t;
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    t.n[0] = 0.5 * (uy * vz - uz * vy);
    t.n[1] = 0.5 * (uz * vx - ux * vz);
    t.n[2] = 0.5 * (ux * vy - uy * vx);
    t.area = std::sqrt(t.n[0] * t.n[0] + t.n[1] * t.n[1] + t.n[2] * t.n[2]);
    for (int k = 0; k < 3; ++k) t.centroid[k] = (a[k] + b[k] + c[k]) / 3.0;
    return t;
}

// Cluster of triangles given by a callback over 0..count-1; `fallback` is
// its centre when the total area is zero.
template <class Tri>
Cluster cluster_of(std::size_t count, Tri&& tri, const double* fallback) {
    Cluster cl;
    double weighted[3] = {0, 0, 0};
    for (std::size_t i = 0; i < count; ++i) {
        const TriangleMoments t = tri(i);
        cl.area += t.area;
        for (int k = 0; k < 3; ++k) {
            cl.n[k] += t.n[k];
            weighted[k] += t.area * t.centroid[k];
        }
    }
    for (int k = 0; k < 3; ++k) cl.c[k] = cl.area > 0 ? weighted[k] / cl.area : fallback[k];
    for (std::size_t i = 0; i < count; ++i) {
        const TriangleMoments t = tri(i);
        for (int l = 0; l < 3; ++l)
            for (int k = 0; k < 3; ++k) cl.m[3 * l + k] += (t.centroid[l] - cl.c[l]) * t.n[k];
    }
    return cl;
}

Cluster merge(const Cluster& x, const Cluster& y) {
    Cluster r;
    r.area = x.area + y.area;
    for (int k = 0; k < 3; ++k) {
        r.n[k] = x.n[k] + y.n[k];
        r.c[k] = r.area > 0 ? (x.area * x.c[k] + y.area * y.c[k]) / r.area : 0.5 * (x.c[k] + y.c[k]);
    }
    for (int l = 0; l < 3; ++l)
        for (int k = 0; k < 3; ++k)
            r.m[3 * l + k] = x.m[3 * l + k] + (x.c[l] - r.c[l]) * x.n[k] + y.m[3 * l + k] +
                             (y.c[l] - r.c[l]) * y.n[k];
    return r;
}

// Ω ≈ N·r/d³ + Σ_kl J_kl M_lk, J_kl = δ_kl/d³ - 3 r_k r_l/d⁵, r = c - p.
double far_solid_angle(const Cluster& cl, const double* p) {
    const double r[3] = {cl.c[0] - p[0], cl.c[1] - p[1], cl.c[2] - p[2]};
    const double d2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    const double d = std::sqrt(d2), d3 = d2 * d, d5 = d3 * d2;
    double omega = (cl.n[0] * r[0] + cl.n[1] * r[1] + cl.n[2] * r[2]) / d3;
    omega += (cl.m[0] + cl.m[4] + cl.m[8]) / d3;
    double rmr = 0;
    for (int l = 0; l < 3; ++l)
        for (int k = 0; k < 3; ++k) rmr += r[k] * r[l] * cl.m[3 * l + k];
    return omega - 3 * rmr / d5;
}

struct Box {
    double lo[3], hi[3];
    static Box empty() {
        constexpr double inf = std::numeric_limits<double>::infinity();
        return {{inf, inf, inf}, {-inf, -inf, -inf}};
    }
    void add(const double* p) {
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    }
    void add(const Box& b) { add(b.lo), add(b.hi); }
    bool contains(const double* p) const {
        return lo[0] <= p[0] && p[0] <= hi[0] && lo[1] <= p[1] && p[1] <= hi[1] && lo[2] <= p[2] &&
               p[2] <= hi[2];
    }
};

struct Node {
    Box box;
    Cluster cluster;
    double radius = 0;          // of the ball about cluster.c holding the box
    uint32_t begin = 0, end = 0;// item range in the bvh order
    uint32_t left = kNone, right = kNone;  // children; leaf when left == kNone
    bool all_balanced = false;  // (shell tree) every shell in it is a closed 2-cycle
    std::size_t open_triangles = 0;  // (shell tree) triangles of its open shells
};

double ball_radius(const Box& b, const double* c) {
    double r2 = 0;
    for (int corner = 0; corner < 8; ++corner) {
        double s = 0;
        for (int k = 0; k < 3; ++k) {
            const double x = (corner >> k & 1 ? b.hi[k] : b.lo[k]) - c[k];
            s += x * x;
        }
        r2 = std::max(r2, s);
    }
    return std::sqrt(r2);
}

// A bounding volume hierarchy built by median splits on the longest axis of
// the item centres (depth <= log2(n) + 1). Items expose box(i), centre(i, k)
// and cluster(order span) for a leaf; leaves hold at most leaf_size items.
template <class Items>
class Bvh {
public:
    std::vector<Node> nodes;
    std::vector<uint32_t> order;  // item ids in leaf order

    void build(const Items& items, std::size_t count, std::size_t leaf_size) {
        order.resize(count);
        for (uint32_t i = 0; i < count; ++i) order[i] = i;
        nodes.clear();
        nodes.reserve(2 * (count / std::max<std::size_t>(leaf_size, 1)) + 1);
        if (count > 0) build_node(items, 0, static_cast<uint32_t>(count), leaf_size);
    }

private:
    uint32_t build_node(const Items& items, uint32_t begin, uint32_t end, std::size_t leaf_size) {
        const auto id = static_cast<uint32_t>(nodes.size());
        nodes.emplace_back();
        Box box = Box::empty(), centres = Box::empty();
        for (uint32_t k = begin; k < end; ++k) {
            box.add(items.box(order[k]));
            const double c[3] = {items.centre(order[k], 0), items.centre(order[k], 1),
                                 items.centre(order[k], 2)};
            centres.add(c);
        }
        Node node;
        node.box = box;
        node.begin = begin;
        node.end = end;
        if (end - begin <= leaf_size) {
            // A leaf's triangles in index order: the tree, and so every sum
            // over it, is then the same whichever standard library split it.
            std::sort(order.begin() + begin, order.begin() + end);
            node.cluster = items.cluster(std::span(order).subspan(begin, end - begin), box);
            node.all_balanced = items.all_balanced(std::span(order).subspan(begin, end - begin));
            node.open_triangles = items.open_triangles(std::span(order).subspan(begin, end - begin));
        } else {
            int axis = 0;
            for (int k = 1; k < 3; ++k)
                if (centres.hi[k] - centres.lo[k] > centres.hi[axis] - centres.lo[axis]) axis = k;
            const uint32_t mid = begin + (end - begin) / 2;
            std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                             [&](uint32_t x, uint32_t y) {  // ties by index: a strict total order
                                 const double cx = items.centre(x, axis), cy = items.centre(y, axis);
                                 return cx < cy || (cx == cy && x < y);
                             });
            node.left = build_node(items, begin, mid, leaf_size);
            node.right = build_node(items, mid, end, leaf_size);
            node.cluster = merge(nodes[node.left].cluster, nodes[node.right].cluster);
            node.all_balanced = nodes[node.left].all_balanced && nodes[node.right].all_balanced;
            node.open_triangles = nodes[node.left].open_triangles + nodes[node.right].open_triangles;
        }
        node.radius = ball_radius(box, node.cluster.c);
        nodes[id] = node;
        return id;
    }
};

// Triangles of one shell, as BVH items (global triangle index = first + i).
struct TriangleItems {
    const WeldedMesh& mesh;
    std::span<const std::array<uint32_t, 3>> tris;
    const double* corner(uint32_t i, int j) const { return mesh.position(tris[i][j]); }
    Box box(uint32_t i) const {
        Box b = Box::empty();
        for (int j = 0; j < 3; ++j) b.add(corner(i, j));
        return b;
    }
    double centre(uint32_t i, int k) const {
        return (corner(i, 0)[k] + corner(i, 1)[k] + corner(i, 2)[k]) / 3.0;
    }
    Cluster cluster(std::span<const uint32_t> ids, const Box& b) const {
        const double mid[3] = {(b.lo[0] + b.hi[0]) / 2, (b.lo[1] + b.hi[1]) / 2, (b.lo[2] + b.hi[2]) / 2};
        return cluster_of(ids.size(), [&](std::size_t i) {
            return triangle_moments(corner(ids[i], 0), corner(ids[i], 1), corner(ids[i], 2));
        }, mid);
    }
    bool all_balanced(std::span<const uint32_t>) const { return false; }
    std::size_t open_triangles(std::span<const uint32_t>) const { return 0; }
};

// Shells as BVH items; a shell's far field counts only when it is open (a
// balanced shell contributes exactly 0 outside its box).
struct ShellItems {
    std::span<const ShellGeometry> shells;
    std::span<const Cluster> clusters;  // per shell, or empty when there is no far field
    const ShellTriangles& triangles;
    Box box(uint32_t s) const {
        const auto& b = shells[s].box;
        return {{b[0], b[1], b[2]}, {b[3], b[4], b[5]}};
    }
    double centre(uint32_t s, int k) const { return (shells[s].box[k] + shells[s].box[k + 3]) / 2; }
    Cluster cluster(std::span<const uint32_t> ids, const Box& b) const {
        const double mid[3] = {(b.lo[0] + b.hi[0]) / 2, (b.lo[1] + b.hi[1]) / 2, (b.lo[2] + b.hi[2]) / 2};
        Cluster r;
        for (int k = 0; k < 3; ++k) r.c[k] = mid[k];
        for (uint32_t s : ids)
            if (!clusters.empty() && !shells[s].balanced()) r = merge(r, clusters[s]);
        return r;
    }
    bool all_balanced(std::span<const uint32_t> ids) const {
        return std::all_of(ids.begin(), ids.end(), [&](uint32_t s) { return shells[s].balanced(); });
    }
    std::size_t open_triangles(std::span<const uint32_t> ids) const {
        std::size_t n = 0;
        for (uint32_t s : ids)
            if (!shells[s].balanced()) n += triangles.offsets[s + 1] - triangles.offsets[s];
        return n;
    }
};

constexpr double kNever = std::numeric_limits<double>::infinity();  // far ratio of exact sums
constexpr std::size_t kLeafTriangles = 8;

class WindingEvaluator {
public:
    WindingEvaluator(const WeldedMesh& mesh, const ShellTriangles& triangles,
                     std::span<const ShellGeometry> shells)
        : mesh_(mesh), triangles_(triangles), shells_(shells) {}

    // Solid angles an exact evaluation would compute, counting stops past `limit`.
    double exact_cost(double limit) {
        build_shell_tree(/*with_far_field=*/false);
        std::atomic<double> total{0};
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, shells_.size()), [&](const auto& r) {
            double local = 0;
            for (std::size_t s = r.begin(); s != r.end() && total.load() + local <= limit; ++s)
                local += static_cast<double>(exact_cost_at(shells_[s].probe.data(), static_cast<uint32_t>(s)));
            double expected = total.load();
            while (!total.compare_exchange_weak(expected, expected + local)) {}
        });
        return total.load();
    }

    // Exact sums (far_ratio == inf; reuses the tree exact_cost built) or with the far field of clusters farther than far_ratio × radius.
    // work_limit bounds the solid angles and nodes visited in all (the
    // shells not reached by then get NaN).
    std::vector<double> evaluate(double far_ratio, double work_limit) {
        const bool approximate = std::isfinite(far_ratio);
        if (approximate) build_triangle_trees();
        if (approximate || shell_tree_.nodes.empty()) build_shell_tree(approximate);
        std::vector<double> w(shells_.size(), std::numeric_limits<double>::quiet_NaN());
        std::atomic<double> work{0};
        tbb::parallel_for(tbb::blocked_range<std::size_t>(0, shells_.size()), [&](const auto& r) {
            for (std::size_t s = r.begin(); s != r.end(); ++s) {
                if (approximate && work.load(std::memory_order_relaxed) > work_limit) return;
                const double* p = shells_[s].probe.data();
                double omega = 0;
                std::size_t visited = 0;
                visited += visit(p, static_cast<uint32_t>(s), far_ratio,
                      [&](const Node& n) {
                          omega += far_solid_angle(n.cluster, p);
                          ++visited;
                      },
                      [&](uint32_t t) {
                          omega += shell_solid_angle(t, p, far_ratio);
                          visited += shell_size(t);
                      });
                w[s] = omega / (4 * std::numbers::pi);
                double expected = work.load(std::memory_order_relaxed);
                while (!work.compare_exchange_weak(expected, expected + static_cast<double>(visited))) {}
            }
        });
        return w;
    }

private:
    std::size_t shell_size(uint32_t s) const {
        return triangles_.offsets[s + 1] - triangles_.offsets[s];
    }
    std::span<const std::array<uint32_t, 3>> shell_tris(uint32_t s) const {
        return std::span(triangles_.tris).subspan(triangles_.offsets[s], shell_size(s));
    }

    // Trees only for shells with more triangles than one leaf holds; the
    // others are summed triangle by triangle when not far as a whole.
    void build_triangle_trees() {
        tree_of_shell_.assign(shells_.size(), kNone);
        for (std::size_t s = 0; s < shells_.size(); ++s)
            if (shell_size(static_cast<uint32_t>(s)) > kLeafTriangles) {
                tree_of_shell_[s] = static_cast<uint32_t>(tri_trees_.size());
                tri_trees_.emplace_back();
            }
        tbb::parallel_for(std::size_t{0}, shells_.size(), [&](std::size_t s) {
            const auto id = static_cast<uint32_t>(s);
            if (tree_of_shell_[s] != kNone)
                tri_trees_[tree_of_shell_[s]].build(TriangleItems{mesh_, shell_tris(id)}, shell_size(id), kLeafTriangles);
        });
    }

    // Far field of a whole shell (the root of its tree, or its few triangles).
    Cluster shell_cluster(uint32_t s) const {
        if (tree_of_shell_[s] != kNone) return tri_trees_[tree_of_shell_[s]].nodes[0].cluster;
        const auto tris = shell_tris(s);
        const auto& b = shells_[s].box;
        const double mid[3] = {(b[0] + b[3]) / 2, (b[1] + b[4]) / 2, (b[2] + b[5]) / 2};
        return cluster_of(tris.size(), [&](std::size_t i) {
            return triangle_moments(mesh_.position(tris[i][0]), mesh_.position(tris[i][1]), mesh_.position(tris[i][2]));
        }, mid);
    }

    void build_shell_tree(bool with_far_field) {
        std::vector<Cluster> clusters(with_far_field ? shells_.size() : 0);
        if (with_far_field)
            tbb::parallel_for(std::size_t{0}, shells_.size(), [&](std::size_t s) {
                if (!shells_[s].balanced()) clusters[s] = shell_cluster(static_cast<uint32_t>(s));
            });
        shell_tree_.build(ShellItems{shells_, clusters, triangles_}, shells_.size(), 1);
        position_.assign(shells_.size(), 0);
        for (uint32_t k = 0; k < shell_tree_.order.size(); ++k) position_[shell_tree_.order[k]] = k;
    }

    // Triangles the exact sum for the probe p of shell `self` evaluates:
    // every open shell's, and those of balanced shells whose box holds p.
    std::size_t exact_cost_at(const double* p, uint32_t self) const {
        if (shell_tree_.nodes.empty()) return 0;
        const uint32_t self_at = position_[self];
        std::size_t cost = 0;
        std::vector<uint32_t> stack{0};
        while (!stack.empty()) {
            const Node& n = shell_tree_.nodes[stack.back()];
            stack.pop_back();
            const bool holds_self = n.begin <= self_at && self_at < n.end;
            if (!holds_self && !n.box.contains(p)) {
                cost += n.open_triangles;
            } else if (n.left == kNone) {
                for (uint32_t k = n.begin; k < n.end; ++k) {
                    const uint32_t t = shell_tree_.order[k];
                    if (t != self) cost += shell_size(t);
                }
            } else {
                stack.push_back(n.left);
                stack.push_back(n.right);
            }
        }
        return cost;
    }

    static bool far(const Node& n, const double* p, double ratio) {
        if (!std::isfinite(ratio)) return false;
        const double dx = p[0] - n.cluster.c[0], dy = p[1] - n.cluster.c[1], dz = p[2] - n.cluster.c[2];
        const double limit = ratio * n.radius;
        return dx * dx + dy * dy + dz * dz > limit * limit;
    }

    // Walks the shell tree for the probe p of shell `self`: on_far(node) for
    // far nodes (open shells only), on_shell(t) for each other shell that
    // must be summed.
    // Returns the number of nodes visited.
    template <class OnFar, class OnShell>
    std::size_t visit(const double* p, uint32_t self, double ratio, OnFar&& on_far, OnShell&& on_shell) const {
        if (shell_tree_.nodes.empty()) return 0;
        const uint32_t self_at = position_[self];
        std::vector<uint32_t> stack{0};
        std::size_t visited = 0;
        while (!stack.empty()) {
            const Node& n = shell_tree_.nodes[stack.back()];
            stack.pop_back();
            ++visited;
            const bool holds_self = n.begin <= self_at && self_at < n.end;
            if (!holds_self) {
                if (n.all_balanced && !n.box.contains(p)) continue;
                if (far(n, p, ratio)) {
                    on_far(n);
                    continue;
                }
            }
            if (n.left == kNone) {
                for (uint32_t k = n.begin; k < n.end; ++k) {
                    const uint32_t t = shell_tree_.order[k];
                    if (t != self) on_shell(t);
                }
            } else {
                stack.push_back(n.left);
                stack.push_back(n.right);
            }
        }
        return visited;
    }

    double shell_solid_angle(uint32_t t, const double* p, double ratio) const {
        const auto tris = shell_tris(t);
        double omega = 0;
        if (!std::isfinite(ratio) || tree_of_shell_[t] == kNone) {
            for (const auto& tri : tris)
                omega += solid_angle(p, mesh_.position(tri[0]), mesh_.position(tri[1]), mesh_.position(tri[2]));
            return omega;
        }
        const Bvh<TriangleItems>& tree = tri_trees_[tree_of_shell_[t]];
        std::vector<uint32_t> stack{0};
        while (!stack.empty()) {
            const Node& n = tree.nodes[stack.back()];
            stack.pop_back();
            if (far(n, p, ratio)) {
                omega += far_solid_angle(n.cluster, p);
            } else if (n.left == kNone) {
                for (uint32_t k = n.begin; k < n.end; ++k) {
                    const auto& tri = tris[tree.order[k]];
                    omega += solid_angle(p, mesh_.position(tri[0]), mesh_.position(tri[1]), mesh_.position(tri[2]));
                }
            } else {
                stack.push_back(n.left);
                stack.push_back(n.right);
            }
        }
        return omega;
    }

    const WeldedMesh& mesh_;
    const ShellTriangles& triangles_;
    std::span<const ShellGeometry> shells_;
    std::vector<uint32_t> tree_of_shell_;  // index into tri_trees_, or kNone
    std::vector<Bvh<TriangleItems>> tri_trees_;
    Bvh<ShellItems> shell_tree_;
    std::vector<uint32_t> position_;  // of each shell in shell_tree_.order
};

}  // namespace

std::vector<double> winding_of_other_shells(const WeldedMesh& mesh, const ShellTriangles& triangles,
                                            std::span<const ShellGeometry> shells,
                                            const WindingOptions& options) {
    if (shells.size() < 2) return std::vector<double>(shells.size(), 0.0);
    WindingEvaluator evaluator(mesh, triangles, shells);
    const bool exact = evaluator.exact_cost(options.exact_budget) <= options.exact_budget;
    return evaluator.evaluate(exact ? kNever : options.far_ratio, options.work_limit);
}

}  // namespace polyvol::topology

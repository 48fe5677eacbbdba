// simplicial/orient.cpp — orient_chain: consistent orientation by a
// breadth-first walk over the faces used exactly twice, then one sign per
// component from its volume and its nesting depth (see simplicial.hpp).
//
// Nesting: a point q on component A (the centroid of its first simplex) is
// inside component B when a ray from q crosses B an odd number of times (B a
// closed boundary not meeting A). The ray's direction is random; a ray that
// passes within a relative 1e-9 of a face's boundary, or starts on B, is
// drawn again (up to 16 times, then the component is left undecided).
#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <deque>
#include <random>

#include "polyvol/simplicial.hpp"
#include "simplicial/topology.hpp"

namespace polyvol {

namespace {

using namespace polyvol::simplicial;

// Parity of the crossings of the ray q + t r (t > 0) with the given simplices:
// 0 or 1, or -1 when some crossing is too close to call.
int ray_parity(const ChainView& c, const std::vector<uint32_t>& simplices, const Eigen::VectorXd& q,
               const Eigen::VectorXd& r, double scale) {
    const int n = c.dimension;
    Eigen::MatrixXd m(n, n);
    Eigen::VectorXd rhs(n);
    int hits = 0;
    constexpr double tol = 1e-9;
    for (uint32_t s : simplices) {
        const auto simplex = c.simplex(s);
        const Eigen::Map<const Eigen::VectorXd> v0(&c.coordinates[std::size_t{simplex[0]} * n], n);
        m.col(0) = r;
        for (int j = 1; j < n; ++j)
            m.col(j) = v0 - Eigen::Map<const Eigen::VectorXd>(&c.coordinates[std::size_t{simplex[j]} * n], n);
        rhs = v0 - q;
        const Eigen::PartialPivLU<Eigen::MatrixXd> lu(m);
        const Eigen::VectorXd x = lu.solve(rhs);
        if (!x.allFinite()) continue;  // the ray is parallel to the simplex
        // Residual check: a nearly singular system is a near-parallel ray.
        if ((m * x - rhs).norm() > 1e-8 * (rhs.norm() + scale)) return -1;
        const double t = x[0] / scale;
        double lambda_min = 1 - x.tail(n - 1).sum();
        for (int j = 1; j < n; ++j) lambda_min = std::min(lambda_min, x[j]);
        if (std::abs(t) <= tol && lambda_min >= -tol) return -1;            // q on B
        if (t > tol && std::abs(lambda_min) <= tol) return -1;             // through a face's boundary
        if (t > tol && lambda_min > tol) ++hits;
    }
    return hits & 1;
}

}  // namespace

OrientResult orient_chain(Chain& chain) {
    const ChainView view = chain.view();
    const Topology t = analyze(view, true);
    const int n = view.dimension;
    const std::size_t k = view.simplex_count();
    OrientResult res;
    res.components = t.report.components;

    // 1. Consistency within components.
    std::vector<int8_t> flip(k, -1);
    std::deque<uint32_t> queue;
    for (std::size_t s0 = 0; s0 < k; ++s0) {
        if (t.degenerate[s0] || flip[s0] >= 0) continue;
        flip[s0] = 0;
        queue.push_back(static_cast<uint32_t>(s0));
        while (!queue.empty()) {
            const uint32_t a = queue.front();
            queue.pop_front();
            for (int p = 0; p < n; ++p) {
                const std::size_t i = std::size_t{a} * n + p;
                const uint32_t b = t.nb[i];
                if (b == kNone) continue;
                const int8_t want = static_cast<int8_t>(flip[a] ^ t.same[i]);
                if (flip[b] < 0) {
                    flip[b] = want;
                    queue.push_back(b);
                } else if (flip[b] != want) {
                    res.orientable = false;
                    res.components = t.report.components;
                    return res;
                }
            }
        }
    }
    Chain work = chain;
    for (std::size_t s = 0; s < k; ++s)
        if (flip[s] == 1) std::swap(work.simplices[s * n], work.simplices[s * n + 1]);
    const ChainView wv = work.view();

    // 2. Each component's volume, with its rigorous bound.
    const std::size_t nc = t.report.components;
    std::vector<std::vector<uint32_t>> members(nc);
    for (std::size_t s = 0; s < k; ++s)
        if (t.component[s] != kNone) members[t.component[s]].push_back(static_cast<uint32_t>(s));
    std::vector<int> vol_sign(nc, 0);
    {
        ChainOptions o;
        o.accuracy = ChainAccuracy::bounded;
        o.centroid = false;
        std::vector<uint32_t> simplices;
        for (std::size_t comp = 0; comp < nc; ++comp) {
            simplices.clear();
            for (uint32_t s : members[comp])
                simplices.insert(simplices.end(), wv.simplices.begin() + std::size_t{s} * n,
                                 wv.simplices.begin() + (std::size_t{s} + 1) * n);
            const ChainVolume v = chain_volume({n, wv.coordinates, simplices}, o);
            // An open component (cut off by faces used more than twice) has no inside: its
            // volume's sign depends on the origin, so it is left as wound (undecided).
            if (v.topology.closed() && std::isfinite(v.volume) && std::abs(v.volume) > v.volume_error_bound)
                vol_sign[comp] = v.volume > 0 ? 1 : -1;
        }
    }

    // 3. Nesting depth by ray parity, then one sign per component.
    std::vector<int> depth(nc, 0);
    std::vector<uint8_t> undecided(nc, 0);
    if (nc > 1) {
        double scale = 0;
        for (double x : wv.coordinates) scale = std::max(scale, std::abs(x));
        scale = scale > 0 ? scale : 1;
        std::mt19937_64 rng(0x5EEDu);
        std::normal_distribution<double> normal;
        for (std::size_t a = 0; a < nc; ++a) {
            const auto first = wv.simplex(members[a][0]);
            Eigen::VectorXd q = Eigen::VectorXd::Zero(n);
            for (uint32_t v : first) q += Eigen::Map<const Eigen::VectorXd>(&wv.coordinates[std::size_t{v} * n], n);
            q /= n;
            for (std::size_t b = 0; b < nc && !undecided[a]; ++b) {
                if (b == a) continue;
                int parity = -1;
                for (int attempt = 0; attempt < 16 && parity < 0; ++attempt) {
                    Eigen::VectorXd r(n);
                    for (int i = 0; i < n; ++i) r[i] = normal(rng);
                    r.normalize();
                    parity = ray_parity(wv, members[b], q, r, scale);
                }
                if (parity < 0) undecided[a] = 1;
                depth[a] += parity > 0 ? 1 : 0;
            }
        }
    }
    for (std::size_t comp = 0; comp < nc; ++comp) {
        if (undecided[comp] || vol_sign[comp] == 0) {
            ++res.undecided;
            continue;
        }
        const int target = depth[comp] % 2 == 0 ? 1 : -1;
        if (vol_sign[comp] != target)
            for (uint32_t s : members[comp]) flip[s] = static_cast<int8_t>(flip[s] ^ 1);
    }
    for (std::size_t s = 0; s < k; ++s) {
        if (flip[s] != 1) continue;
        std::swap(chain.simplices[s * n], chain.simplices[s * n + 1]);
        ++res.flipped;
    }
    return res;
}

}  // namespace polyvol

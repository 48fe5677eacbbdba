// Seeding the continuation: a coarse scan over a sublattice whose size does
// not depend on h, and user seed points.
//
// The negative box-boundary vertices met on the way seed the face walks
// (SurfaceBuilder::close_faces), which also start surface walks from the
// face simplices the surface crosses.
//
// Coarse scan. Along axis k the coarse lattice uses the fine indices
// S_k = {round(j N_k / M_k) : j = 0 .. M_k} (M_k = min(coarse_cells, N_k)), plus
// the virtual ends -1 and N_k + 1 (always positive). Every coarse line (axis k,
// the other coordinates in their S) is read in order; between two successive
// coarse vertices of different signs the fine line holds a sign change, found
// by bisection (log2(N_k / M_k) samples), and the Kuhn simplex whose first edge
// is that fine edge is crossed: it seeds a walk unless an earlier walk visited
// it (all simplices around a crossed edge belong to one component, so a
// component is walked once). A component of the PL surface that separates two
// coarse vertices is crossed an odd number of times by a coarse path between
// them, hence on some coarse segment with ends of different signs: it is found.
#include <cmath>
#include <vector>

#include "implicit/surface.hpp"

namespace polyvol::implicit {

namespace {

// The fine edge (u, u + e_axis) with a sign change between fine indices a < b
// on the line through `line` along `axis` (signs at a and b differ).
Index bisect(const Index& line, int axis, int32_t a, int32_t b, Sampler& sampler) {
    Index p = line;
    p[axis] = a;
    const bool sign_a = sampler.positive(p);
    while (b - a > 1) {
        const int32_t m = a + (b - a) / 2;
        p[axis] = m;
        if (sampler.positive(p) == sign_a)
            a = m;
        else
            b = m;
    }
    p[axis] = a;
    return p;
}

void coarse_scan(const Lattice& lattice, Sampler& sampler, SurfaceBuilder& builder, int coarse_cells) {
    const int n = lattice.n;
    std::array<std::vector<int32_t>, kMaxDim> real;  // S_k
    for (int k = 0; k < n; ++k) {
        const int32_t cells = lattice.cells[k];
        const int32_t m = std::min(coarse_cells, cells);
        for (int32_t j = 0; j <= m; ++j)
            real[k].push_back(static_cast<int32_t>(std::llround(static_cast<double>(j) * cells / m)));
    }
    std::vector<Index> along, between;  // one line's coarse vertices; a segment's fine ones
    if (sampler.lookahead()) {
        // F a batch function: the whole coarse lattice in calls of 8192 points
        // (every line below then finds its values).
        std::array<std::size_t, kMaxDim> digit{};
        while (true) {
            Index v{};
            for (int k = 0; k < n; ++k) v[k] = real[k][digit[k]];
            along.push_back(v);
            if (along.size() == 8192) {
                sampler.prefetch(along);
                along.clear();
            }
            int k = 0;
            for (; k < n; ++k) {
                if (++digit[k] < real[k].size()) break;
                digit[k] = 0;
            }
            if (k == n) break;
        }
        sampler.prefetch(along);
    }
    for (int axis = 0; axis < n; ++axis) {
        // Odometer over the other axes' coarse indices.
        std::array<std::size_t, kMaxDim> digit{};
        while (true) {
            Index line{};
            for (int k = 0; k < n; ++k) line[k] = k == axis ? 0 : real[k][digit[k]];
            Index p = line;
            int32_t previous = -1;  // virtual: positive
            bool previous_positive = true;
            const std::size_t count = real[axis].size();
            along.resize(count);
            for (std::size_t j = 0; j < count; ++j) {
                along[j] = line;
                along[j][axis] = real[axis][j];
            }
            sampler.prefetch(along);
            for (std::size_t j = 0; j <= count; ++j) {
                const int32_t index = j < count ? real[axis][j] : lattice.cells[axis] + 1;
                p[axis] = index;
                const bool positive = sampler.positive(p);
                // A sign change next to a virtual end is a vertex on the box
                // boundary with F <= 0: the sampler keeps it for close_faces.
                if (positive != previous_positive && previous >= 0 && index <= lattice.cells[axis]) {
                    if (sampler.lookahead()) {  // the segment's fine vertices in one call, for the bisection
                        between.clear();
                        for (int32_t i = previous + 1; i < index; ++i) {
                            between.push_back(line);
                            between.back()[axis] = i;
                        }
                        sampler.prefetch(between);
                    }
                    const Index u = bisect(line, axis, previous, index, sampler);
                    builder.walk_from(kuhn_simplex_with_edge(u, n, axis, lattice.cells));
                }
                previous = index;
                previous_positive = positive;
            }
            int k = 0;
            for (; k < n; ++k) {
                if (k == axis) continue;
                if (++digit[k] < real[k].size()) break;
                digit[k] = 0;
            }
            if (k == n) break;
        }
    }
}

// From the lattice vertex nearest to x, follow +x_1 to the first sign change.
void seed_point(const Lattice& lattice, Sampler& sampler, SurfaceBuilder& builder, std::span<const double> x) {
    const int n = lattice.n;
    Index u{};
    for (int k = 0; k < n; ++k) {
        const double i = std::round((x[k] - lattice.lo[k]) / lattice.spacing[k]);
        u[k] = static_cast<int32_t>(std::clamp(std::isnan(i) ? 0.0 : i, 0.0, static_cast<double>(lattice.cells[k])));
    }
    const bool start = sampler.positive(u);
    for (Index p = u; p[0] < lattice.cells[0]; ++p[0]) {
        Index q = p;
        ++q[0];
        if (sampler.positive(q) != start) {
            builder.walk_from(kuhn_simplex_with_edge(p, n, 0, lattice.cells));
            return;
        }
    }
}

}  // namespace

void seed_and_walk(const Lattice& lattice, Sampler& sampler, SurfaceBuilder& builder, int coarse_cells,
                   std::span<const double> seed_points) {
    const auto n = static_cast<std::size_t>(lattice.n);
    for (std::size_t s = 0; s + n <= seed_points.size(); s += n) seed_point(lattice, sampler, builder, seed_points.subspan(s, n));
    if (coarse_cells > 0) coarse_scan(lattice, sampler, builder, coarse_cells);
    builder.close_faces();
}

}  // namespace polyvol::implicit

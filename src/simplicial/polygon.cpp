// simplicial/polygon.cpp — polygons with holes and islands as 2D chains.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "polyvol/simplicial.hpp"

namespace polyvol {

Chain polygon_chain(const PolygonsView& p) {
    const std::size_t loops = p.loop_count();
    if (p.coordinates.size() % 2 != 0) throw std::invalid_argument("polygon coordinates: odd size");
    if (loops > 0 && (p.loop_offsets[0] != 0 || p.loop_offsets[loops] > p.indices.size()))
        throw std::invalid_argument("polygon loop_offsets: must start at 0 and end within indices");
    Chain c;
    c.dimension = 2;
    c.coordinates.assign(p.coordinates.begin(), p.coordinates.end());
    const std::size_t m = p.vertex_count();
    for (std::size_t l = 0; l < loops; ++l) {
        const uint32_t b = p.loop_offsets[l], e = p.loop_offsets[l + 1];
        if (e < b) throw std::invalid_argument("polygon loop_offsets: decreasing");
        if (e - b < 2) continue;  // a point encloses nothing
        for (uint32_t i = b; i < e; ++i) {
            const uint32_t v = p.indices[i];
            const uint32_t w = p.indices[i + 1 < e ? i + 1 : b];
            if (v >= m || w >= m)
                throw std::invalid_argument("polygon: vertex index " + std::to_string(v >= m ? v : w) +
                                            " >= vertex count");
            c.simplices.push_back(v);
            c.simplices.push_back(w);
        }
    }
    return c;
}

namespace {

// Twice the signed area of loop l (the shoelace sum), its box, and a vertex.
struct LoopShape {
    double twice_area = 0;
    double lo[2] = {0, 0}, hi[2] = {0, 0};
    double x = 0, y = 0;
};

LoopShape loop_shape(const PolygonsView& p, std::size_t l) {
    LoopShape s;
    const uint32_t b = p.loop_offsets[l], e = p.loop_offsets[l + 1];
    const auto at = [&](uint32_t i) { return p.coordinates.subspan(2 * std::size_t{p.indices[i]}, 2); };
    s.x = at(b)[0];
    s.y = at(b)[1];
    s.lo[0] = s.hi[0] = s.x;
    s.lo[1] = s.hi[1] = s.y;
    for (uint32_t i = b; i < e; ++i) {
        const auto v = at(i), w = at(i + 1 < e ? i + 1 : b);
        s.twice_area += v[0] * w[1] - w[0] * v[1];
        for (int k = 0; k < 2; ++k) {
            s.lo[k] = std::min(s.lo[k], v[k]);
            s.hi[k] = std::max(s.hi[k], v[k]);
        }
    }
    return s;
}

// Whether (x, y) is inside loop l: the parity of the loop's crossings of
// the ray to +x (half-open in y, so a vertex on the ray counts once).
bool inside_loop(const PolygonsView& p, std::size_t l, double x, double y) {
    const uint32_t b = p.loop_offsets[l], e = p.loop_offsets[l + 1];
    bool inside = false;
    for (uint32_t i = b; i < e; ++i) {
        const auto v = p.coordinates.subspan(2 * std::size_t{p.indices[i]}, 2);
        const auto w = p.coordinates.subspan(2 * std::size_t{p.indices[i + 1 < e ? i + 1 : b]}, 2);
        if ((v[1] > y) == (w[1] > y)) continue;
        const double cross_x = v[0] + (y - v[1]) * (w[0] - v[0]) / (w[1] - v[1]);
        if (cross_x > x) inside = !inside;
    }
    return inside;
}

}  // namespace

std::vector<uint32_t> loops_wound_like_their_container(const PolygonsView& p) {
    const std::size_t loops = p.loop_count();
    std::vector<LoopShape> shape(loops);
    for (std::size_t l = 0; l < loops; ++l)
        if (p.loop_offsets[l + 1] - p.loop_offsets[l] >= 3) shape[l] = loop_shape(p, l);
    std::vector<uint32_t> against;
    for (std::size_t l = 0; l < loops; ++l) {
        if (shape[l].twice_area == 0) continue;
        // The innermost loop containing l: the smallest in area among those whose box holds l's and that hold its vertex.
        std::size_t container = loops;
        for (std::size_t c = 0; c < loops; ++c) {
            const LoopShape& s = shape[c];
            if (c == l || s.twice_area == 0 || std::fabs(s.twice_area) <= std::fabs(shape[l].twice_area)) continue;
            if (s.lo[0] > shape[l].lo[0] || s.lo[1] > shape[l].lo[1] || s.hi[0] < shape[l].hi[0] ||
                s.hi[1] < shape[l].hi[1])
                continue;
            if (!inside_loop(p, c, shape[l].x, shape[l].y)) continue;
            if (container == loops || std::fabs(s.twice_area) < std::fabs(shape[container].twice_area)) container = c;
        }
        if (container < loops && (shape[container].twice_area > 0) == (shape[l].twice_area > 0))
            against.push_back(static_cast<uint32_t>(l));
    }
    return against;
}

ChainVolume polygon_area(const PolygonsView& polygons, const ChainOptions& options) {
    const Chain c = polygon_chain(polygons);
    return chain_volume(c.view(), options);
}

}  // namespace polyvol

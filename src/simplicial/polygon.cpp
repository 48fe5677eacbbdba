// simplicial/polygon.cpp — polygons with holes and islands as 2D chains.
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

ChainVolume polygon_area(const PolygonsView& polygons, const ChainOptions& options) {
    const Chain c = polygon_chain(polygons);
    return chain_volume(c.view(), options);
}

}  // namespace polyvol

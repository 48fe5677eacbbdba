// fuzz/pipeline_target.cpp — what `polyvol measure` and `check` do with a
// file: read (any format, by content), analyze_topology, mass_properties by
// every method, and for a closed mesh the solid of its shells and the
// self-crossing search. Errors are answers (ReadError, a status, a NaN with
// a flag); crashes, leaks, hangs and huge allocations are not. A binary STL
// is also streamed (soup.hpp): its volume, first moments and centroid must
// be the loaded mesh's bit for bit (one result type, the same guarantees),
// and its bounded moments within their bound; a difference traps.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

#include "polyvol/boolean.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
#include "polyvol/soup.hpp"
#include "polyvol/topology.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* bytes, std::size_t size) {
    using namespace polyvol;
    LoadedMesh loaded;
    try {
        loaded = read_mesh_memory({reinterpret_cast<const std::byte*>(bytes), size}, "f");
    } catch (const ReadError&) {
        return 0;
    }
    const MeshView view = loaded.mesh.view();
    const TopologyReport t = analyze_topology(view);
    for (const Method m : {Method::cone, Method::prism, Method::pyramid, Method::vtnb}) {
        MeasureOptions o;
        o.method = m;
        (void)mass_properties(view, o);
    }
    // The records as they stand in the input: binary STL by the size rule on
    // the bytes themselves (the reader also skips a UTF-8 byte-order mark,
    // after which other bytes are the records).
    uint32_t count = 0;
    if (size >= 84) std::memcpy(&count, bytes + 80, 4);
    if (loaded.format == Format::stl && loaded.encoding == "binary_le" && size >= 84 &&
        size - 84 == 50 * std::size_t{count}) {
        const std::span<const std::byte> records(reinterpret_cast<const std::byte*>(bytes) + 84, size - 84);
        const SoupResult exact = soup_properties(stl_records(records), 1);
        const SoupResult bounded = soup_properties(stl_records(records), 1, SoupWants{.moments = Accuracy::fast});
        MeasureOptions o;
        o.second_moments = false;
        o.edge_length = false;
        const MassProperties m = mass_properties(view, o);
        const auto same = [](double a, double b) { return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b); };
        if (!exact.nonfinite) {
            if (!same(exact.properties.volume, m.volume) || !same(bounded.properties.volume, m.volume))
                __builtin_trap();
            double largest = 0;
            for (int k = 0; k < 3; ++k) largest = std::max(largest, std::fabs(bounded.properties.first_moments[k]));
            for (int k = 0; k < 3; ++k) {
                if (!same(exact.properties.first_moments[k], m.first_moments[k]) ||
                    !same(exact.properties.centroid[k], m.centroid[k]))
                    __builtin_trap();
                // Within the bound of the exact value, so within it and half an ulp of the rounded one.
                const double e = bounded.properties.moments_relative_error * largest + 0x1p-53 * std::fabs(m.first_moments[k]);
                if (std::fabs(bounded.properties.first_moments[k] - m.first_moments[k]) > e) __builtin_trap();
            }
        }
    }
    if (t.closed_2_cycle && view.triangle_count() <= 2000) {
        (void)solid_volume(view, {.moments = true, .within_shells = true});
        (void)self_crossings(view);
    }
    return 0;
}

// fuzz/pipeline_target.cpp — what `polyvol measure` and `check` do with a
// file: read (any format, by content), analyze_topology, mass_properties by
// every method, and for a closed mesh the solid of its shells and the
// self-crossing search. Errors are answers (ReadError, a status, a NaN with
// a flag); crashes, leaks, hangs and huge allocations are not.
#include <cstddef>
#include <cstdint>
#include <span>

#include "polyvol/boolean.hpp"
#include "polyvol/io.hpp"
#include "polyvol/measure.hpp"
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
    if (t.closed_2_cycle && view.triangle_count() <= 2000) {
        (void)solid_volume(view, true, true);
        (void)self_crossings(view);
    }
    return 0;
}

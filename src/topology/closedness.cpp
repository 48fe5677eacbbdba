// topology/closedness.cpp — fingerprint_closedness and check_closed
// (polyvol/topology.hpp): the fingerprint's pass over the mesh is core's
// (core/fingerprint.cpp), which measure's vtnb asks too.
#include "core/fingerprint.hpp"
#include "polyvol/topology.hpp"
#include "topology/welded.hpp"

namespace polyvol {

Closedness fingerprint_closedness(const MeshView& mesh) { return core::fingerprint::mesh_closedness(mesh); }

Closedness fingerprint_closedness(const MeshView& mesh, uint64_t seed) {
    return core::fingerprint::mesh_closedness(mesh, seed);
}

ClosednessCheck check_closed(const MeshView& mesh, const ClosednessOptions& options) {
    ClosednessCheck c;
    if (options.fingerprint) {
        topology::check_mesh_arrays(mesh);  // the fingerprint reads indices unchecked
        c.by_fingerprint = fingerprint_closedness(mesh) == Closedness::closed;
    }
    if (!c.by_fingerprint) c.topology = analyze_topology(mesh, options.report);
    c.closed = c.by_fingerprint || c.topology->closed_2_cycle;
    return c;
}

}  // namespace polyvol

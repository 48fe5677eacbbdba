// topology/closedness.cpp — fingerprint_closedness (polyvol/topology.hpp):
// the pass over the mesh is core's (core/fingerprint.cpp), which measure's
// vtnb asks too.
#include "core/fingerprint.hpp"
#include "polyvol/topology.hpp"

namespace polyvol {

Closedness fingerprint_closedness(const MeshView& mesh) { return core::fingerprint::mesh_closedness(mesh); }

Closedness fingerprint_closedness(const MeshView& mesh, uint64_t seed) {
    return core::fingerprint::mesh_closedness(mesh, seed);
}

}  // namespace polyvol

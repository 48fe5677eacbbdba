// boolean/self_crossings.cpp — where a surface crosses itself: the pairs of
// triangles of one of solid_volume's bodies (bodies.hpp) that share no
// vertex and cross along a segment, by the crossing search of the booleans
// (crossings.cpp) with exact predicates; each pair's later triangle is
// moved by δ, so touching without crossing does not count.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "boolean/bodies.hpp"
#include "boolean/operand.hpp"
#include "boolean/exact_terms.hpp"
#include "polyvol/boolean.hpp"

namespace polyvol {

namespace boolean {

SelfCrossings self_crossings_of(const MeshView& mesh, const topology::WeldedMesh& wm,
                                const topology::ShellLabels& labels, std::vector<uint8_t>* crossing) {
    SelfCrossings r;
    Operand op;
    op.mesh.positions = wm.xyz;
    for (const double x : op.mesh.positions)
        if (!in_predicate_range(x)) {
            r.status = BooleanStatus::invalid_coordinates;
            return r;
        }
    std::vector<uint32_t> face_of;
    for (uint32_t f = 0, poly = 0; f < mesh.face_count(); ++f) {
        const auto c = mesh.face(f);
        if (c.size() < 3) continue;
        const uint32_t body = labels.of_polygon[poly++];
        for (std::size_t i = 1; i + 1 < c.size(); ++i) {
            for (const uint32_t v : {c[0], c[i], c[i + 1]}) op.tri.push_back(wm.id[v]);
            op.body_of_triangle.push_back(body);
            face_of.push_back(f);
        }
    }
    op.body_shift.assign(std::max<std::size_t>(labels.count, 1), 0);  // unused: each pair is moved apart by its order
    finish_operand(op);
    Crossings c;
    try {
        c = find_crossings(op, op, Pairs::same_body_apart);
    } catch (const Contradiction&) {
        r.status = BooleanStatus::shell_crosses_itself;  // a pair the search cannot resolve
        return r;
    }
    r.candidate_pairs = c.candidate_pairs;
    r.pairs = c.cuts.size();
    if (!c.cuts.empty()) r.example = {face_of[c.cuts.front().a], face_of[c.cuts.front().b]};  // cuts are in triangle order
    if (crossing) {
        crossing->assign(labels.count, 0);
        for (const Cut& cut : c.cuts) (*crossing)[op.body(cut.a)] = 1;
    }
    return r;
}

}  // namespace boolean

SelfCrossings self_crossings(const MeshView& mesh) {
    topology::check_mesh_arrays(mesh);
    // The bodies solid_volume uses; each one's fan triangles on welded vertices.
    const topology::WeldedMesh wm = topology::weld_polygons(mesh);
    return boolean::self_crossings_of(mesh, wm, boolean::bodies_of(wm), nullptr);
}

}  // namespace polyvol

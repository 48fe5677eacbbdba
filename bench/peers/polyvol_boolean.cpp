// polyvol in the boolean peers' harness shape (bench/boolean_compare.sh):
// read both files into memory (read_mesh_file), then time ROUNDS calls of
//   CALL:   boolean_volumes(A, B), the exact core on two closed meshes;
//   POLICY: what `polyvol overlap` runs after reading — make_solid on a copy
//           of each operand (closedness, the shells' overlaps and the search
//           for a surface crossing itself), then solid_booleans.
// The copies POLICY works on are made outside the timed calls.
// Prints: polyvol-boolean VOLUME LOAD_SECONDS CALL_SECONDS POLICY_SECONDS (medians)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "polyvol/boolean.hpp"
#include "polyvol/io.hpp"
#include "polyvol/solid.hpp"
#include "timing.hpp"

int main(int argc, char** argv) {
    if (argc != 4) return 1;
    const int rounds = std::atoi(argv[3]);
    const auto t0 = std::chrono::steady_clock::now();
    polyvol::LoadedMesh a, b;
    try {
        a = polyvol::read_mesh_file(argv[1]);
        b = polyvol::read_mesh_file(argv[2]);
    } catch (const polyvol::ReadError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    }
    const double load = peers::seconds_since(t0);
    double volume = 0;
    const double call = peers::median_seconds(
        rounds, [&] { return polyvol::boolean_volumes(a.mesh.view(), b.mesh.view()).intersection; }, &volume);

    polyvol::SolidOptions policy;  // as cli/commands/overlap.cpp sets it
    policy.closedness_by_fingerprint = true;
    policy.shells = false;
    std::vector<double> t;
    double policy_volume = 0;
    for (int r = 0; r < rounds; ++r) {
        polyvol::Mesh ma = a.mesh, mb = b.mesh;
        const auto t1 = std::chrono::steady_clock::now();
        const polyvol::MeshSolid sa = polyvol::make_solid(ma, policy);
        const polyvol::MeshSolid sb = polyvol::make_solid(mb, policy);
        if (sa.status != polyvol::SolidStatus::ok || sb.status != polyvol::SolidStatus::ok) return 3;
        policy_volume = polyvol::solid_booleans(ma.view(), sa, mb.view(), sb).intersection;
        t.push_back(peers::seconds_since(t1));
    }
    std::sort(t.begin(), t.end());
    if (policy_volume != volume) {
        std::fprintf(stderr, "polyvol-boolean: the policy's route gave another volume\n");
        return 4;
    }
    std::printf("polyvol-boolean %.17g %.6f %.6f %.6f\n", volume, load, call, t[t.size() / 2]);
    return 0;
}

// The one policy (polyvol/solid.hpp) on the files every door must agree on:
// a clean box, two overlapping boxes, an inside-out box, a flipped face, an
// open box — statuses, notes, repairs and the solid's figures.
#include <gtest/gtest.h>

#include <algorithm>

#include "common/shapes.hpp"
#include "polyvol/solid.hpp"

namespace polyvol {
namespace {

Mesh two_boxes() {
    Mesh m = test::box({0, 0, 0}, {2, 2, 2});
    test::add_box(m, {1, 1, 1}, {3, 3, 3});
    return m;
}

bool has_note(const MeshSolid& s, SolidNote::Kind kind) {
    return std::any_of(s.notes.begin(), s.notes.end(), [&](const SolidNote& n) { return n.kind == kind; });
}

TEST(MakeSolid, ACleanBoxIsItsOwnSolid) {
    Mesh m = test::box({0, 0, 0}, {2, 2, 2});
    const MeshSolid s = make_solid(m);
    EXPECT_EQ(s.status, SolidStatus::ok);
    EXPECT_TRUE(s.closed);
    EXPECT_FALSE(s.resolved());
    EXPECT_TRUE(s.notes.empty());
    EXPECT_TRUE(repairs_needed(s).empty());
    EXPECT_TRUE(s.self && s.self->pairs == 0);
}

TEST(MakeSolid, OverlappingShellsAreResolvedAndMeasured) {
    Mesh m = two_boxes();
    const SolidMass r = measure_solid(m, {.face_shells = true}, {});  // face shells: for solid_as_union
    ASSERT_EQ(r.solid.status, SolidStatus::ok);
    ASSERT_TRUE(r.solid.resolved());
    EXPECT_EQ(r.solid.solid->overlapping_shells, 2u);
    EXPECT_EQ(r.mass->volume, 15.0);
    EXPECT_TRUE(r.mass->volume_correctly_rounded);
    EXPECT_NEAR(r.mass->area, 42.0, 42.0 * r.mass->area_relative_error);
    EXPECT_NEAR(r.mass->centroid[0], 1.5, 1e-15);
    EXPECT_TRUE(repairs_needed(r.solid).empty());  // a slicer prints the solid: no repair
    const std::vector<Mesh> parts = solid_as_union(m.view(), r.solid);
    EXPECT_EQ(parts.size(), 2u);  // the two boxes meet: one group each
}

TEST(MakeSolid, InsideOutShellsAreTurnedUnlessSigned) {
    Mesh m = test::box({0, 0, 0}, {2, 2, 2}, {.inverted = true});
    Mesh kept = m;
    const MeshSolid turned = make_solid(m);
    ASSERT_EQ(turned.status, SolidStatus::ok);
    ASSERT_TRUE(turned.turned_outward);
    EXPECT_EQ(turned.turned_outward->flipped, 12u);
    EXPECT_TRUE(has_note(turned, SolidNote::Kind::turned_outward));
    EXPECT_EQ(signed_volume(m.view()), 8.0);
    // The cheap path (fingerprint, no shells' report) turns it too.
    Mesh cheap = kept;
    const MeshSolid fast = make_solid(cheap, {.closedness_by_fingerprint = true, .shells = false});
    EXPECT_TRUE(fast.turned_outward);
    EXPECT_EQ(signed_volume(cheap.view()), 8.0);
    const MeshSolid as_is = make_solid(kept, {.keep_signed = true});
    EXPECT_FALSE(as_is.turned_outward);
    EXPECT_EQ(signed_volume(kept.view()), -8.0);
    const std::vector<std::string> repairs = repairs_needed(as_is);
    ASSERT_EQ(repairs.size(), 1u);
    EXPECT_EQ(repairs[0], "1 inside-out shell (fix: --orient)");
}

TEST(MakeSolid, OpenAndMisorientedSurfacesAreRefusedWithTheirWords) {
    Mesh open = test::box({0, 0, 0}, {2, 2, 2});
    open.indices.resize(open.indices.size() - 3);  // one triangle less
    const MeshSolid o = make_solid(open);
    EXPECT_EQ(o.status, SolidStatus::open);
    EXPECT_NE(o.message.find("not a closed surface: 3 unbalanced edges"), std::string::npos) << o.message;
    EXPECT_NE(repairs_needed(o)[0].find("not closed"), std::string::npos);
    Mesh measured = test::box({0, 0, 0}, {2, 2, 2});
    measured.indices.resize(measured.indices.size() - 3);
    const MeshSolid allowed = make_solid(measured, {.allow_open = true});
    EXPECT_EQ(allowed.status, SolidStatus::ok);
    EXPECT_TRUE(has_note(allowed, SolidNote::Kind::measured_open));
    EXPECT_FALSE(repairs_needed(allowed).empty());  // still not a solid as it is

    Mesh flipped = test::box({0, 0, 0}, {2, 2, 2});
    std::swap(flipped.indices[1], flipped.indices[2]);  // one triangle wound the other way
    const MeshSolid f = make_solid(flipped);
    EXPECT_EQ(f.status, SolidStatus::misoriented);
    EXPECT_NE(f.message.find("misoriented"), std::string::npos) << f.message;
    Mesh oriented = test::box({0, 0, 0}, {2, 2, 2});
    std::swap(oriented.indices[1], oriented.indices[2]);
    const MeshSolid fixed = make_solid(oriented, {.orient = true});
    EXPECT_EQ(fixed.status, SolidStatus::ok);
    EXPECT_EQ(signed_volume(oriented.view()), 8.0);
}

}  // namespace
}  // namespace polyvol

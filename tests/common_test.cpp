// The shared leaf: one classification both meshes map to and from, one size rule, one error
// hierarchy.
//
//   tet mesh class       shared classification       surface class
//   Interior   <->  Volume
//   Surface    <->  Surface                  <->  Smooth
//   Ridge      <->  Curve                    <->  Ridge
//                   Curve (open boundary)    <->  Boundary
//   Corner     <->  Corner                   <->  Corner

#include <doctest/doctest.h>

#include "common/classification.h"
#include "common/errors.h"
#include "common/size_quality.h"
#include "surface/surface_mesh.h"
#include "volume/mesh/tet_mesh.h"

using namespace hdimesh;

TEST_CASE("every vertex class of either mesh survives the round trip through the classification")
{
    using V = volume::VertexClass;
    for (V c : {V::Interior, V::Surface, V::Ridge, V::Corner})
        CHECK(volume::to_vertex_class(volume::to_classification(c, 7)) == c);
    using S = surface::VertexClass;
    for (S c : {S::Smooth, S::Ridge, S::Boundary, S::Corner})
        CHECK(surface::to_vertex_class(surface::to_classification(c, 3)) == c);
}

TEST_CASE("the two meshes agree on what a ridge, a corner and a surface vertex lie on")
{
    using S = surface::VertexClass;
    CHECK(to_classification(volume::VertexClass::Ridge).dimension == Dimension::Curve);
    CHECK(surface::to_classification(S::Ridge) == to_classification(volume::VertexClass::Ridge));
    CHECK(surface::to_classification(S::Corner) == to_classification(volume::VertexClass::Corner));
    CHECK(surface::to_classification(S::Smooth) == to_classification(volume::VertexClass::Surface));
    // an open-boundary curve is a curve to the tet mesh, a boundary curve to the surface
    const Classification open = surface::to_classification(S::Boundary, 2);
    CHECK(open.dimension == Dimension::Curve);
    CHECK(open.id == 2);
    CHECK(volume::to_vertex_class(open) == volume::VertexClass::Ridge);
}

TEST_CASE("Qt and the 0.66 threshold: too long and too short on either side of h")
{
    const double h = 1.0;
    CHECK(size_quality(2.0, h) == doctest::Approx(0.5));
    CHECK(size_quality(0.5, h) == doctest::Approx(0.5));
    CHECK(is_too_long(1.0 / 0.65, h));
    CHECK_FALSE(is_too_long(1.0 / 0.67, h));
    CHECK(is_too_short(0.65, h));
    CHECK_FALSE(is_too_short(0.67, h));
    CHECK_FALSE(is_too_long(0.5, h));  // short edges are never too long
    // the size of an edge is the size at its midpoint, not the mean of its ends
    const auto quadratic = [](const Vec3& p) { return 1.0 + p.x() * p.x(); };
    CHECK(size_at_midpoint(quadratic, Vec3(0, 0, 0), Vec3(2, 0, 0)) == doctest::Approx(2.0));
}

TEST_CASE("every hdimesh exception is an hdimesh::Error")
{
    CHECK_THROWS_AS(throw InputError("f.mesh: line 3: bad"), Error);
    CHECK_THROWS_AS(throw IoError("f.mesh: cannot open"), Error);
    CHECK_THROWS_AS(throw TopologyError("tet 4: face 2 in three tets"), Error);
}

// repair_boundary: the triangles TetGen's -g and tets-only files bring, made the tets' boundary
// and interfaces; the checker is clean after it, and a second repair changes nothing.

#include "volume/check/boundary_repair.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <utility>

#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/mesh/boundary.h"
#include "volume/mesh/tet_tables.h"

using namespace hdimesh;

namespace
{

/// Every face of every tet as a triangle, the boundary ones turned inward, as TetGen -g writes.
void list_every_face_inward(TetMesh& mesh)
{
    mesh.triangles.clear();
    mesh.triangle_refs.clear();
    const FaceGroups groups = group_tet_faces(mesh);
    for (int k = 0; k < groups.num_faces(); ++k)
    {
        Triangle face = face_vertices(mesh, groups.uses[groups.start[k]]);
        std::swap(face[1], face[2]);
        mesh.add_triangle(face, 5);
    }
}

}  // namespace

TEST_CASE("a TetGen -g cube: interior triangles dropped, the boundary turned outward")
{
    // kuhn_cube: 6 tets around the diagonal, 12 boundary faces and 6 interior ones
    TetMesh mesh = fixtures::kuhn_cube();
    list_every_face_inward(mesh);
    REQUIRE(mesh.triangles.size() == 18);
    REQUIRE_FALSE(check_mesh(mesh).empty());

    const BoundaryRepair repair = repair_boundary(mesh);
    CHECK(repair.dropped_interior == 6);
    CHECK(repair.turned_outward == 12);
    CHECK(repair.added_boundary == 0);
    CHECK(repair.lines().size() == 2);
    CHECK(mesh.triangles.size() == 12);
    CHECK(std::all_of(mesh.triangle_refs.begin(), mesh.triangle_refs.end(),
                      [](int r) { return r == 5; }));  // the file's refs are kept
    CHECK(check_mesh(mesh).empty());
    CHECK_FALSE(repair_boundary(mesh).any());
}

TEST_CASE("tets only, two refs: the boundary from the tets, the interface between them")
{
    //   z
    //   |  tets 0-2 ref 4, tets 3-5 ref 2 (the Kuhn tets split by ref): the faces between
    //   +-- x   the two halves are an interface, ref 2 (Mmg's: the smaller)
    TetMesh mesh = fixtures::kuhn_cube();
    mesh.triangles.clear();
    mesh.triangle_refs.clear();
    for (int t = 0; t < 6; ++t) mesh.tet_refs[t] = t < 3 ? 4 : 2;

    const BoundaryRepair repair = repair_boundary(mesh);
    CHECK(repair.added_boundary == 12);
    CHECK(repair.added_interface >= 1);
    CHECK(check_mesh(mesh).empty());
    const FaceGroups groups = group_tet_faces(mesh);
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        // each triangle takes the ref of its tet, an interface the smaller one
        const Triangle key = sorted_triple(mesh.triangles[i]);
        for (int k = 0; k < groups.num_faces(); ++k)
        {
            const TetFace& first = groups.uses[groups.start[k]];
            if (sorted_triple(face_vertices(mesh, first)) != key) continue;
            int ref = mesh.tet_refs[first.tet];
            if (groups.start[k + 1] - groups.start[k] == 2)
                ref = std::min(ref, mesh.tet_refs[groups.uses[groups.start[k] + 1].tet]);
            CHECK(mesh.triangle_refs[i] == ref);
        }
    }
    CHECK_FALSE(repair_boundary(mesh).any());

    // without interfaces (a converter's choice), the checker accepts the boundary alone
    TetMesh plain = fixtures::kuhn_cube();
    plain.triangles.clear();
    plain.triangle_refs.clear();
    plain.tet_refs = mesh.tet_refs;
    BoundaryRepairOptions no_interfaces;
    no_interfaces.add_interfaces = false;
    const BoundaryRepair boundary_only = repair_boundary(plain, no_interfaces);
    CHECK(boundary_only.added_boundary == 12);
    CHECK(boundary_only.added_interface == 0);
    CHECK(check_mesh(plain).empty());
}

TEST_CASE("repeated triangles dropped, a required interior one kept and renumbered")
{
    TetMesh mesh = fixtures::kuhn_cube();
    list_every_face_inward(mesh);
    const FaceGroups groups = group_tet_faces(mesh);
    auto interior = [&](const Triangle& tri) {
        for (int k = 0; k < groups.num_faces(); ++k)
            if (sorted_triple(face_vertices(mesh, groups.uses[groups.start[k]])) ==
                sorted_triple(tri))
                return groups.start[k + 1] - groups.start[k] == 2;
        return false;
    };
    int boundary = -1, last_interior = -1;
    for (int i = 0; i < 18; ++i)
    {
        if (!interior(mesh.triangles[i]) && boundary < 0) boundary = i;
        if (interior(mesh.triangles[i])) last_interior = i;
    }
    REQUIRE(boundary >= 0);
    REQUIRE(last_interior >= 0);
    mesh.add_triangle(mesh.triangles[boundary], 5);  // a repeat
    // a required interior triangle is never dropped; its index follows the renumbering
    const Triangle required = mesh.triangles[last_interior];
    mesh.required_triangles = {last_interior};

    const BoundaryRepair repair = repair_boundary(mesh);
    CHECK(repair.dropped_duplicates == 1);
    CHECK(repair.dropped_interior == 5);
    CHECK(mesh.triangles.size() == 13);
    REQUIRE(mesh.required_triangles.size() == 1);
    CHECK(mesh.triangles[mesh.required_triangles[0]] == required);
    // what is left is the checker's to name: a triangle between two tets of the same ref
    CHECK_FALSE(check_mesh(mesh).empty());
    CheckOptions options;
    options.allow_interior_triangles = true;
    CHECK(check_mesh(mesh, options).empty());
}

TEST_CASE("the curves where three regions meet are ridges")
{
    //   the Kuhn cube in two refs (tets 0-2, 3-5): the interface between them meets the outer
    //   boundary along edges of three triangles (two boundary, one interface)
    TetMesh mesh = fixtures::kuhn_cube();
    mesh.triangles.clear();
    mesh.triangle_refs.clear();
    for (int t = 0; t < 6; ++t) mesh.tet_refs[t] = t < 3 ? 1 : 2;
    repair_boundary(mesh);
    const RegionCurves curves = mark_region_curves(mesh);
    CHECK(curves.ridges > 0);
    CHECK(mesh.ridges.size() == static_cast<std::size_t>(curves.ridges));
    for (int e : mesh.ridges)
        for (int v : mesh.edges[e]) CHECK(mesh.vertex_classes[v] != VertexClass::Surface);
    CHECK(check_mesh(mesh).empty());
    // a second call adds nothing; one ref alone has no such curve
    CHECK(mark_region_curves(mesh).ridges == 0);
    TetMesh single = fixtures::kuhn_cube();
    CHECK(mark_region_curves(single).ridges == 0);
}

// slide_curve_vertex: a curve vertex next to a narrow corner slides along its curve to open the
// corner's triangle; refusals leave the mesh untouched.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "surface/local_ops.h"
#include "surface/surface_quality.h"
#include "surface_fixtures.h"

using namespace hdimesh::surface;

namespace
{

// Flat, in z = 0 (the model: fixtures::PlaneProjector). Two curves leave the corner C with a
// 16.7° sector between them: curve 0 straight along x (C-A-A2), curve 1 bending away from it
// (C-R-W). T and U are smooth; A2 and W end their curves (corners).
//
//          T (0.3,1.2)
//          |  \    .
//          |     W (1.9,1.0)
//          |   /  \  .
//          | R     \ .       R = (1, 0.3)
//          |/ \  U (1.6,0.45)
//          C---A----A2       A = (1, 0), A2 = (2, 0)
//
// Faces: C A R (the sector), A A2 U, A U R, R U W, C R T, R W T.
struct NarrowCorner
{
    SurfaceMesh mesh;
    VertexHandle c, a, a2, r, w, t, u;

    NarrowCorner()
    {
        c = mesh.add_vertex(Vec3d(0, 0, 0));
        a = mesh.add_vertex(Vec3d(1, 0, 0));
        a2 = mesh.add_vertex(Vec3d(2, 0, 0));
        r = mesh.add_vertex(Vec3d(1, 0.3, 0));
        w = mesh.add_vertex(Vec3d(1.9, 1.0, 0));
        t = mesh.add_vertex(Vec3d(0.3, 1.2, 0));
        u = mesh.add_vertex(Vec3d(1.6, 0.45, 0));
        mesh.add_face(c, a, r);
        mesh.add_face(a, a2, u);
        mesh.add_face(a, u, r);
        mesh.add_face(r, u, w);
        mesh.add_face(c, r, t);
        mesh.add_face(r, w, t);
        fixtures::mark_all_smooth(mesh);
        SurfaceProperties props(mesh);
        for (VertexHandle v : {c, a2, w})
            mesh.property(props.vertex_class, v) = VertexClass::Corner;
        mesh.property(props.vertex_class, a) = mesh.property(props.vertex_class, r) =
            VertexClass::Ridge;
        mesh.property(props.vertex_curve, a) = 0;
        mesh.property(props.vertex_curve, r) = 1;
        mesh.property(props.edge_curve, edge(c, a)) = mesh.property(props.edge_curve, edge(a, a2)) =
            0;
        mesh.property(props.edge_curve, edge(c, r)) = mesh.property(props.edge_curve, edge(r, w)) =
            1;
    }

    EdgeHandle edge(VertexHandle x, VertexHandle y) const
    {
        return mesh.edge_handle(mesh.find_halfedge(x, y));
    }

    double worst_angle_around(VertexHandle v) const
    {
        double worst = 180.0;
        for (auto f : mesh.vf_range(v))
        {
            std::vector<Vec3d> p;
            for (auto x : mesh.fv_range(f)) p.push_back(mesh.point(x));
            worst = std::min(worst, triangle_min_angle_deg(p[0], p[1], p[2]));
        }
        return worst;
    }

    // Every face keeps its counter-clockwise orientation about +z.
    bool all_faces_up() const
    {
        for (auto f : mesh.faces())
        {
            std::vector<Vec3d> p;
            for (auto x : mesh.fv_range(f)) p.push_back(mesh.point(x));
            if (!(OpenMesh::cross(p[1] - p[0], p[2] - p[0])[2] > 0.0)) return false;
        }
        return true;
    }

    std::vector<Vec3d> points() const { return fixtures::points_of(mesh); }
};

// The plane z = 0, with the two curves as input polylines: curve 0 = C-A-A2, curve 1 =
// C-R-M-W, where M = (1.5, 0.8) bends off the chord R-W (a curve vertex is projected onto its
// own polyline, as SurfaceModel does; anything else straight down).
class CornerModel final : public Projector
{
public:
    ProjectedPoint project(const Vec3d& p, VertexClass cls, int curve) const override
    {
        ProjectedPoint out;
        out.normal = Vec3d(0, 0, 1);
        out.ok = true;
        out.point = Vec3d(p[0], p[1], 0.0);
        if ((cls == VertexClass::Ridge || cls == VertexClass::Boundary) &&
            (curve == 0 || curve == 1))
            out.point = closest_on_polyline(out.point, polylines()[curve]);
        return out;
    }

    static double distance_to_curve(const Vec3d& p, int curve)
    {
        return (closest_on_polyline(p, polylines()[curve]) - p).norm();
    }

private:
    static const std::vector<std::vector<Vec3d>>& polylines()
    {
        static const std::vector<std::vector<Vec3d>> lines = {
            {Vec3d(0, 0, 0), Vec3d(1, 0, 0), Vec3d(2, 0, 0)},
            {Vec3d(0, 0, 0), Vec3d(1, 0.3, 0), Vec3d(1.5, 0.8, 0), Vec3d(1.9, 1.0, 0)}};
        return lines;
    }

    static Vec3d closest_on_polyline(const Vec3d& p, const std::vector<Vec3d>& line)
    {
        Vec3d best = line.front();
        for (std::size_t i = 0; i + 1 < line.size(); ++i)
        {
            const Vec3d d = line[i + 1] - line[i];
            const double t = std::clamp(OpenMesh::dot(p - line[i], d) / d.sqrnorm(), 0.0, 1.0);
            const Vec3d q = line[i] + t * d;
            if ((q - p).norm() < (best - p).norm()) best = q;
        }
        return best;
    }
};

}  // namespace

TEST_CASE("slide_curve_vertex opens a narrow corner by sliding along the bending curve")
{
    NarrowCorner m;
    const CornerModel model;
    SurfaceHooks hooks;
    int moves = 0;
    Vec3d reported_old(0, 0, 0);
    hooks.on_move = [&](const SurfaceMesh&, VertexHandle v, const Vec3d& old_point) {
        CHECK(v == m.r);
        reported_old = old_point;
        ++moves;
    };
    OperatorContext ctx(m.mesh, model, hooks);
    const double corner_before = std::atan2(0.3, 1.0) * 180.0 / M_PI;
    const double worst_before = m.worst_angle_around(m.r);
    CHECK(worst_before == doctest::Approx(corner_before).epsilon(1e-9));

    const OpResult result = slide_curve_vertex(ctx, m.r);
    REQUIRE(result.done());
    // R is on its own input curve (the polyline through M, not the chord R-W the trials were
    // taken on), moved away from the corner, and the sector opened.
    const Vec3d moved = m.mesh.point(m.r);
    CHECK(CornerModel::distance_to_curve(moved, 1) < 1e-12);
    const Vec3d chord = Vec3d(1.9, 1.0, 0) - Vec3d(1, 0.3, 0);
    CHECK(OpenMesh::cross(chord, moved - Vec3d(1, 0.3, 0)).norm() > 1e-3);
    CHECK(OpenMesh::dot(chord, moved - Vec3d(1, 0.3, 0)) > 0.0);
    CHECK(m.worst_angle_around(m.r) > worst_before + 0.1);
    CHECK(m.all_faces_up());
    // The hook saw the one move, with the old point.
    CHECK(moves == 1);
    CHECK(reported_old == Vec3d(1, 0.3, 0));
    // Nothing else moved.
    CHECK(m.mesh.point(m.c) == Vec3d(0, 0, 0));
    CHECK(m.mesh.point(m.a) == Vec3d(1, 0, 0));
}

TEST_CASE("slide_curve_vertex refuses smooth vertices, corners, and slides out of the edge band")
{
    NarrowCorner m;
    const fixtures::PlaneProjector plane;
    OperatorContext ctx(m.mesh, plane, {});
    const auto before = m.points();
    CHECK(slide_curve_vertex(ctx, m.t).status == OpStatus::Class);  // smooth
    CHECK(slide_curve_vertex(ctx, m.c).status == OpStatus::Class);  // the corner itself
    // No edge of R's ball may grow beyond 0.95 (only R-A is shorter now): a slide toward W
    // lengthens R-C, one toward C lengthens R-W, both already longer.
    SlideOptions tight;
    tight.max_length = 0.95;
    CHECK(slide_curve_vertex(ctx, m.r, tight).status == OpStatus::Geometry);
    CHECK(m.points() == before);
}

TEST_CASE("slide_curve_vertex asks allow_move and commits nothing on a veto")
{
    NarrowCorner m;
    const CornerModel model;
    SurfaceHooks hooks;
    int asked = 0, moved = 0;
    hooks.allow_move = [&](const SurfaceMesh&, VertexHandle v, const Vec3d& point) {
        CHECK(v == m.r);
        CHECK(CornerModel::distance_to_curve(point, 1) < 1e-12);
        ++asked;
        return false;
    };
    hooks.on_move = [&](const SurfaceMesh&, VertexHandle, const Vec3d&) { ++moved; };
    OperatorContext ctx(m.mesh, model, hooks);
    const auto before = m.points();
    CHECK(slide_curve_vertex(ctx, m.r).status == OpStatus::Hook);
    CHECK(asked == 1);
    CHECK(moved == 0);
    CHECK(m.points() == before);
}

TEST_CASE("slide_curve_vertex leaves a vertex alone where no slide raises the worst angle")
{
    // Both curves straight: sliding R along C-R-W's straight line keeps the corner's angle.
    NarrowCorner m;
    m.mesh.set_point(m.w, Vec3d(2.0, 0.6, 0));  // W on the line C-R
    m.mesh.set_point(m.u, Vec3d(1.7, 0.3, 0));
    const fixtures::PlaneProjector plane;
    OperatorContext ctx(m.mesh, plane, {});
    const auto before = m.points();
    const double corner = std::atan2(0.3, 1.0) * 180.0 / M_PI;
    CHECK(m.worst_angle_around(m.r) == doctest::Approx(corner).epsilon(1e-9));
    CHECK(slide_curve_vertex(ctx, m.r).status == OpStatus::Quality);
    CHECK(m.points() == before);
}

// Low-poly and CAD-like models (flat facets, creases real whatever their length): surfremesh's
// pipeline keeps them on their facets to round-off and keeps every crease, whatever the size.
//
//   dodecahedron: pentagons at 116.6 degrees; stepped pyramid: five slabs, risers 0.03 high;
//   chamfered box: a unit cube whose edges are cut 0.01 wide (creases a length rule would drop
//   as noise).

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "surface/remesh_surface.h"
#include "surface/surface_io.h"
#include "surface/surface_quality.h"

using namespace hdimesh::surface;
using hdimesh::surface::Vec3d;

namespace
{

/// The boundary of the convex hull of points in general enough position: each supporting plane
/// through three points is a face, its points ordered around its centroid and fanned. The soup's
/// orientation is left to build_surface (it turns a closed component outward).
TriangleSoup convex_hull(const std::vector<Vec3d>& points)
{
    TriangleSoup soup;
    soup.points = points;
    const int n = static_cast<int>(points.size());
    std::vector<std::vector<int>> faces;
    for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j)
            for (int k = j + 1; k < n; ++k)
            {
                Vec3d normal = OpenMesh::cross(points[j] - points[i], points[k] - points[i]);
                if (normal.norm() < 1e-12) continue;
                normal.normalize();
                std::vector<int> on;
                int above = 0, below = 0;
                for (int m = 0; m < n; ++m)
                {
                    const double d = OpenMesh::dot(points[m] - points[i], normal);
                    if (std::abs(d) < 1e-12) on.push_back(m);
                    above += d > 1e-12;
                    below += d < -1e-12;
                }
                if (above > 0 && below > 0) continue;
                if (std::find(faces.begin(), faces.end(), on) != faces.end()) continue;
                faces.push_back(on);
            }
    for (std::vector<int> face : faces)
    {
        Vec3d centre(0, 0, 0);
        for (int v : face) centre += points[v] / static_cast<double>(face.size());
        const Vec3d u = (points[face[0]] - centre).normalized();
        const Vec3d w = OpenMesh::cross(centre.normalized(), u);
        std::sort(face.begin(), face.end(), [&](int a, int b) {
            const Vec3d pa = points[a] - centre, pb = points[b] - centre;
            return std::atan2(OpenMesh::dot(pa, w), OpenMesh::dot(pa, u)) <
                   std::atan2(OpenMesh::dot(pb, w), OpenMesh::dot(pb, u));
        });
        for (std::size_t k = 1; k + 1 < face.size(); ++k)
        {
            soup.triangles.push_back({face[0], face[k], face[k + 1]});
            soup.refs.push_back(0);
        }
    }
    return soup;
}

TriangleSoup dodecahedron()
{
    const double phi = (1 + std::sqrt(5.0)) / 2;
    std::vector<Vec3d> p;
    for (int s = 0; s < 8; ++s) p.emplace_back(s & 1 ? 1 : -1, s & 2 ? 1 : -1, s & 4 ? 1 : -1);
    for (int a : {-1, 1})
        for (int b : {-1, 1})
        {
            p.emplace_back(0, a / phi, b * phi);
            p.emplace_back(a / phi, b * phi, 0);
            p.emplace_back(b * phi, 0, a / phi);
        }
    return convex_hull(p);
}

/// Every permutation of (±0.5, ±0.49, ±0.49): a unit cube whose edges are cut by 0.01.
TriangleSoup chamfered_box()
{
    std::vector<Vec3d> p;
    for (int axis = 0; axis < 3; ++axis)
        for (int s = 0; s < 8; ++s)
        {
            Vec3d q;
            for (int c = 0; c < 3; ++c) q[c] = ((s >> c) & 1 ? 1 : -1) * (c == axis ? 0.5 : 0.49);
            p.push_back(q);
        }
    return convex_hull(p);
}

/// Five square slabs 0.03 high, each 0.18 narrower than the one below.
TriangleSoup stepped_pyramid()
{
    TriangleSoup soup;
    auto square = [&](double w, double z) {
        const int first = static_cast<int>(soup.points.size());
        soup.points.emplace_back(-w, -w, z);
        soup.points.emplace_back(w, -w, z);
        soup.points.emplace_back(w, w, z);
        soup.points.emplace_back(-w, w, z);
        return first;
    };
    auto quad = [&](int a, int b, int c, int d) {
        soup.triangles.push_back({a, b, c});
        soup.triangles.push_back({a, c, d});
        soup.refs.insert(soup.refs.end(), {0, 0});
    };
    const int levels = 5;
    int low = square(1.0, 0.0);
    quad(low, low + 3, low + 2, low + 1);
    for (int k = 0; k < levels; ++k)
    {
        const double z = 0.03 * (k + 1), w = 1.0 - 0.18 * k;
        const int up = square(w, z);
        for (int i = 0; i < 4; ++i) quad(low + i, low + (i + 1) % 4, up + (i + 1) % 4, up + i);
        if (k + 1 == levels)
        {
            quad(up, up + 1, up + 2, up + 3);
            break;
        }
        const int inner = square(w - 0.18, z);
        for (int i = 0; i < 4; ++i) quad(up + i, up + (i + 1) % 4, inner + (i + 1) % 4, inner + i);
        low = inner;
    }
    return soup;
}

/// The input's creases (dihedral over 10 degrees), sampled; each sample's distance to the
/// nearest crease edge of the output, the worst.
double worst_crease_distance(const SurfaceMesh& input, const SurfaceMesh& output)
{
    auto creases = [](const SurfaceMesh& mesh) {
        std::vector<std::array<Vec3d, 2>> out;
        for (auto e : mesh.edges())
        {
            if (mesh.is_boundary(e)) continue;
            const auto h = mesh.halfedge_handle(e, 0);
            const Vec3d n0 = mesh.calc_face_normal(mesh.face_handle(h));
            const Vec3d n1 =
                mesh.calc_face_normal(mesh.face_handle(mesh.opposite_halfedge_handle(h)));
            if (OpenMesh::dot(n0, n1) < std::cos(10.0 * M_PI / 180.0))
                out.push_back(
                    {mesh.point(mesh.from_vertex_handle(h)), mesh.point(mesh.to_vertex_handle(h))});
        }
        return out;
    };
    const auto in = creases(input), out = creases(output);
    double worst = 0;
    for (const auto& edge : in)
        for (int k = 0; k <= 10; ++k)
        {
            const Vec3d p = edge[0] + (k / 10.0) * (edge[1] - edge[0]);
            double best = 1e300;
            for (const auto& o : out)
            {
                const Vec3d ab = o[1] - o[0];
                const double t =
                    std::clamp(OpenMesh::dot(p - o[0], ab) / OpenMesh::dot(ab, ab), 0.0, 1.0);
                best = std::min(best, (o[0] + t * ab - p).norm());
            }
            worst = std::max(worst, best);
        }
    return worst;
}

}  // namespace

TEST_CASE("low-poly models stay on their facets and keep every crease")
{
    struct Model
    {
        const char* name;
        TriangleSoup soup;
    };
    for (const Model& model :
         {Model{"dodecahedron", dodecahedron()}, Model{"stepped pyramid", stepped_pyramid()},
          Model{"chamfered box", chamfered_box()}})
    {
        const SurfaceMesh input = build_surface(model.soup, model.name);
        const double diagonal = bounding_box_diagonal(input);
        for (const double fraction : {0.02, 0.1})
        {
            CAPTURE(model.name);
            CAPTURE(fraction);
            SurfaceMesh mesh = input;
            SurfaceRemeshSettings settings;
            settings.sizing.hsiz = fraction * diagonal;
            const SurfaceRemeshResult result = remesh_surface(mesh, settings);
            CHECK(result.features.dropped_ridge_chains == 0);
            const auto d = hausdorff_distance(mesh, input);
            CHECK(std::max(d[0], d[1]) <= 1e-6 * diagonal);
            CHECK(worst_crease_distance(input, mesh) <= 1e-9 * diagonal);
            CHECK(mesh.n_faces() > input.n_faces());
        }
    }
}

namespace
{

/// A flat sheet bounded by a closed polygon in z = 0 (star-shaped from `centre`), fanned from
/// one inner point: a CAD-like open outline, its boundary turning at every polygon vertex.
TriangleSoup flat_outline(const std::vector<Vec3d>& polygon, const Vec3d& centre)
{
    TriangleSoup soup;
    soup.points = polygon;
    soup.points.push_back(centre);
    const int n = static_cast<int>(polygon.size());
    for (int i = 0; i < n; ++i) soup.triangles.push_back({n, i, (i + 1) % n});
    soup.refs.assign(soup.triangles.size(), 0);
    return soup;
}

}  // namespace

TEST_CASE("a flat open outline keeps the turns of its boundary as corners, on its input")
{
    //   star: 7 tips (turns 117°) and 7 notches (66°);   L: an L cut 0.15 at every corner
    //   (turns of 45°, above the crease angle but below the old boundary rule's 75°)
    std::vector<Vec3d> star, ell;
    for (int i = 0; i < 14; ++i)
    {
        const double r = i % 2 == 0 ? 1.0 : 0.62, a = 3.14159265358979323846 * i / 7;
        star.emplace_back(r * std::cos(a), r * std::sin(a), 0);
    }
    const double c = 0.15;
    for (const auto& [x, y] : std::vector<std::array<double, 2>>{{c, 0},
                                                                 {2 - c, 0},
                                                                 {2, c},
                                                                 {2, 1 - c},
                                                                 {2 - c, 1},
                                                                 {1 + c, 1},
                                                                 {1, 1 + c},
                                                                 {1, 2 - c},
                                                                 {1 - c, 2},
                                                                 {c, 2},
                                                                 {0, 2 - c},
                                                                 {0, c}})
        ell.emplace_back(x, y, 0);
    struct Outline
    {
        const char* name;
        TriangleSoup soup;
        std::size_t turns;
    };
    for (const Outline& outline :
         {Outline{"star", flat_outline(star, Vec3d(0, 0, 0)), star.size()},
          Outline{"chamfered L", flat_outline(ell, Vec3d(0.5, 0.5, 0)), ell.size()}})
    {
        const SurfaceMesh input = build_surface(outline.soup, outline.name);
        const double diagonal = bounding_box_diagonal(input);
        for (const double fraction : {0.0, 0.02, 0.06})
        {
            CAPTURE(outline.name);
            CAPTURE(fraction);
            SurfaceMesh mesh = input;
            SurfaceRemeshSettings settings;
            settings.sizing.hsiz = fraction * diagonal;  // 0: the curvature-adaptive default
            const SurfaceRemeshResult result = remesh_surface(mesh, settings);
            CHECK(result.features.corners == outline.turns);
            // every turn of the outline is still a vertex of the output
            for (std::size_t i = 0; i < outline.turns; ++i)
            {
                double nearest = 1e300;
                for (auto v : mesh.vertices())
                    nearest = std::min(nearest, (mesh.point(v) - outline.soup.points[i]).norm());
                CHECK(nearest <= 1e-12 * diagonal);
            }
            const auto d = hausdorff_distance(mesh, input);
            CHECK(std::max(d[0], d[1]) <= 1e-6 * diagonal);
            CHECK(mesh.n_faces() > input.n_faces());
        }
    }
}

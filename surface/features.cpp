#include "surface/features.h"

#include <cassert>
#include <vector>

namespace hdimesh::surface
{

FeatureSummary detect_features(SurfaceMesh& mesh, const FeatureOptions& options)
{
    SurfaceProperties props(mesh);
    // The mesh as arrays, in handle order: its own edges (halfedge 0's direction) and its
    // faces' vertices as they circulate, so that curves are numbered as the mesh's edges.
    std::vector<hdi::Vec3> points;
    points.reserve(mesh.n_vertices());
    for (auto v : mesh.vertices())
    {
        assert(v.idx() == static_cast<int>(points.size()) && "no deleted vertices");
        const Vec3d& p = mesh.point(v);
        points.emplace_back(p[0], p[1], p[2]);
    }
    std::vector<hdi::Triangle3> triangles;
    std::vector<int> refs;
    triangles.reserve(mesh.n_faces());
    refs.reserve(mesh.n_faces());
    for (auto f : mesh.faces())
    {
        assert(f.idx() == static_cast<int>(triangles.size()) && "no deleted faces");
        auto fv = mesh.cfv_iter(f);
        const int a = fv->idx(), b = (++fv)->idx(), c = (++fv)->idx();
        triangles.push_back({a, b, c});
        refs.push_back(mesh.property(props.face_ref, f));
    }
    std::vector<hdi::EdgeEnds> edges;
    edges.reserve(mesh.n_edges());
    for (auto e : mesh.edges())
    {
        assert(e.idx() == static_cast<int>(edges.size()) && "no deleted edges");
        const auto h = mesh.halfedge_handle(e, 0);
        edges.push_back({mesh.from_vertex_handle(h).idx(), mesh.to_vertex_handle(h).idx()});
    }

    const hdi::FeatureClassification found =
        hdi::classify_features(points, triangles, options, edges, refs);
    for (auto v : mesh.vertices())
    {
        const Classification& c = found.vertex_class[static_cast<std::size_t>(v.idx())];
        mesh.property(props.vertex_class, v) = to_vertex_class(c);
        mesh.property(props.vertex_curve, v) = c.dimension == Dimension::Curve ? c.id : kNoCurve;
    }
    for (auto e : mesh.edges())
    {
        const Classification& c = found.edge_class[static_cast<std::size_t>(e.idx())];
        mesh.property(props.edge_curve, e) = c.dimension == Dimension::Curve ? c.id : kNoCurve;
    }
    return found.summary;
}

}  // namespace hdimesh::surface

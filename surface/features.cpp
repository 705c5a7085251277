#include "surface/features.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "surface/surface_quality.h"

namespace hdimesh::surface
{
namespace
{

struct Chain
{
    std::vector<EdgeHandle> edges;
    double length = 0.0;
    bool boundary = false;
};

// The cosine of the angle between a and b; 1 (no angle) when either is zero.
double cosine_between(const Vec3d& a, const Vec3d& b)
{
    const double na = a.norm(), nb = b.norm();
    if (!(na > 0.0) || !(nb > 0.0)) return 1.0;
    return std::clamp(OpenMesh::dot(a, b) / (na * nb), -1.0, 1.0);
}

double angle_between_deg(const Vec3d& a, const Vec3d& b) { return std::acos(cosine_between(a, b)) * 180.0 / M_PI; }

class FeatureGraph
{
public:
    FeatureGraph(const SurfaceMesh& mesh, const FeatureOptions& options, std::vector<char> sharp)
        : mesh_(mesh), options_(options), sharp_(std::move(sharp))
    {
    }

    /// Degree in the sharp-edge graph and the corner test (curves end, meet or turn).
    void find_corners()
    {
        corner_.assign(mesh_.n_vertices(), 0);
        // Each vertex's degree in the sharp-edge graph, from one pass over the edges (not a
        // circulation per vertex and per neighbour: the cone-tip test asks it of the 1-ring).
        sharp_degree_.assign(mesh_.n_vertices(), 0);
        for (auto e : mesh_.edges())
        {
            if (!sharp_[e.idx()]) continue;
            const auto h = mesh_.halfedge_handle(e, 0);
            ++sharp_degree_[mesh_.from_vertex_handle(h).idx()];
            ++sharp_degree_[mesh_.to_vertex_handle(h).idx()];
        }
        // Whether a neighbour has a sharp edge (the cone-tip test's isolation), marked around the
        // sharp vertices (few) rather than asked by a circulation around every other vertex
        // each round (measured on stanford-bunny: find_corners' share of detect_features and a
        // copy of the mesh 26 % -> 22 %).
        beside_sharp_.assign(mesh_.n_vertices(), 0);
        for (auto v : mesh_.vertices())
            if (sharp_degree_[v.idx()] > 0)
                for (auto w : mesh_.vv_range(v)) beside_sharp_[w.idx()] = 1;
        std::vector<std::pair<double, VertexHandle>> turn_corners;
        for (auto v : mesh_.vertices())
        {
            const int degree = sharp_degree_[v.idx()];
            if (degree == 0)
            {
                if (is_cone_tip(v)) corner_[v.idx()] = 1;
                continue;
            }
            if (degree != 2)
            {
                corner_[v.idx()] = 1;
                continue;
            }
            VertexHandle ends[2];
            int found = 0;
            for (auto h : mesh_.voh_range(v))
                if (sharp_[mesh_.edge_handle(h).idx()] && found < 2) ends[found++] = mesh_.to_vertex_handle(h);
            // An open boundary of a scan zig-zags: only its sharpest turns are corners.
            const double limit = mesh_.is_boundary(v) ? options_.boundary_corner_turn_angle_deg
                                                      : options_.corner_turn_angle_deg;
            const Vec3d p = mesh_.point(v);
            const double turn = angle_between_deg(p - mesh_.point(ends[0]), mesh_.point(ends[1]) - p);
            if (turn <= limit) continue;
            if (mesh_.is_boundary(v)) turn_corners.emplace_back(turn, v);  // may be thinned below
            else corner_[v.idx()] = 1;  // a ridge that turns sharply is a corner of the part
        }
        // Boundary turn corners closer than min_corner_spacing to a kept corner are zig-zag noise
        // at the scale of the target mesh: the sharpest turn of a cluster stays, the rest slide.
        std::sort(turn_corners.begin(), turn_corners.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
        std::vector<Vec3d> kept;
        for (auto v : mesh_.vertices())
            if (corner_[v.idx()]) kept.push_back(mesh_.point(v));
        for (const auto& [turn, v] : turn_corners)
        {
            const Vec3d p = mesh_.point(v);
            const bool crowded = std::any_of(kept.begin(), kept.end(), [&](const Vec3d& q) {
                return (q - p).norm() < options_.min_corner_spacing;
            });
            if (crowded) continue;
            corner_[v.idx()] = 1;
            kept.push_back(p);
        }
    }

    /// A spike of the input (a cone tip: angle defect above cone_defect_deg) is kept as a
    /// corner, or remeshing would cut it off; only when its cone is wide enough for fair
    /// triangles around it (angle sum at least cone_min_angle_sum_deg). Reads beside_sharp_.
    bool is_cone_tip(VertexHandle v)
    {
        if (mesh_.is_boundary(v) || !(options_.cone_defect_deg < 360.0)) return false;
        // Only an isolated spike: next to a ridge the defect belongs to the ridge's geometry.
        if (beside_sharp_[v.idx()]) return false;
        // The angle sum is geometry only: computed once, though find_corners runs each round
        // of detect_features (measured on the bunny: find_corners' acos over all rounds were a
        // third of detect_features).
        if (angle_sum_.empty()) angle_sum_.assign(mesh_.n_vertices(), -1.0);
        double& sum = angle_sum_[v.idx()];
        if (sum < 0.0)
        {
            sum = 0.0;
            for (auto h : mesh_.voh_range(v))
            {
                const Vec3d p = mesh_.point(v);
                const Vec3d a = mesh_.point(mesh_.to_vertex_handle(h));
                const Vec3d b = mesh_.point(mesh_.to_vertex_handle(mesh_.next_halfedge_handle(h)));
                sum += angle_between_deg(a - p, b - p);
            }
        }
        return 360.0 - sum > options_.cone_defect_deg && sum >= options_.cone_min_angle_sum_deg;
    }

    /// Maximal runs of sharp edges between corners (closed loops have no corner).
    std::vector<Chain> chains() const
    {
        std::vector<Chain> out;
        std::vector<char> visited(mesh_.n_edges(), 0);
        for (auto e : mesh_.edges())
        {
            if (!sharp_[e.idx()] || visited[e.idx()]) continue;
            Chain chain;
            chain.boundary = mesh_.is_boundary(e);
            std::vector<EdgeHandle> forward, backward;
            visited[e.idx()] = 1;
            walk(mesh_.halfedge_handle(e, 0), visited, forward);
            walk(mesh_.halfedge_handle(e, 1), visited, backward);
            chain.edges.assign(backward.rbegin(), backward.rend());
            chain.edges.push_back(e);
            chain.edges.insert(chain.edges.end(), forward.begin(), forward.end());
            for (auto ce : chain.edges) chain.length += mesh_.calc_edge_length(ce);
            out.push_back(std::move(chain));
        }
        return out;
    }

    std::vector<char>& sharp() { return sharp_; }
    const std::vector<char>& corner() const { return corner_; }

private:
    // Follows the curve from the tip of h through non-corner vertices of degree 2.
    void walk(HalfedgeHandle h, std::vector<char>& visited, std::vector<EdgeHandle>& out) const
    {
        VertexHandle v = mesh_.to_vertex_handle(h);
        EdgeHandle came = mesh_.edge_handle(h);
        while (!corner_[v.idx()])
        {
            EdgeHandle next;
            for (auto oh : mesh_.voh_range(v))
            {
                const EdgeHandle ne = mesh_.edge_handle(oh);
                if (ne != came && sharp_[ne.idx()]) next = ne;
            }
            if (!next.is_valid() || visited[next.idx()]) return;
            visited[next.idx()] = 1;
            out.push_back(next);
            const HalfedgeHandle nh = mesh_.halfedge_handle(next, 0);
            v = mesh_.from_vertex_handle(nh) == v ? mesh_.to_vertex_handle(nh) : mesh_.from_vertex_handle(nh);
            came = next;
        }
    }

    const SurfaceMesh& mesh_;
    const FeatureOptions& options_;
    std::vector<char> sharp_;
    std::vector<char> corner_;
    std::vector<int> sharp_degree_;  // per vertex: its sharp edges (find_corners' round)
    std::vector<char> beside_sharp_; // per vertex: a neighbour has a sharp edge (the same round)
    std::vector<double> angle_sum_;  // per vertex: the sum of its corner angles (-1: not yet)
};

}  // namespace

FeatureSummary detect_features(SurfaceMesh& mesh, const FeatureOptions& options)
{
    SurfaceProperties props(mesh);
    const double diagonal = bounding_box_diagonal(mesh);

    std::vector<Vec3d> face_normal(mesh.n_faces());
    for (auto f : mesh.faces())
    {
        auto fv = mesh.fv_iter(f);
        const Vec3d a = mesh.point(*fv), b = mesh.point(*++fv), c = mesh.point(*++fv);
        face_normal[f.idx()] = triangle_normal(a, b, c);
    }
    // An edge whose face normals' cosine is above that of the lowest sharp angle by a clear
    // margin is flat: its angle (an acos) is not computed. 1e-9 on the cosine is above 5e-8°
    // on the angle, far above the rounding of acos and of the degree conversion: the same
    // decisions. (Most edges are flat; measured on stanford-bunny: detect_features 13 % faster.)
    const double lowest_sharp_deg = std::min(options.ridge_angle_deg, options.crease_angle_deg);
    const double flat_cosine = lowest_sharp_deg > 0.0 ? std::cos(lowest_sharp_deg * M_PI / 180.0) + 1e-9
                                                      : std::numeric_limits<double>::infinity();
    std::vector<char> sharp(mesh.n_edges(), 0);
    for (auto e : mesh.edges())
    {
        if (mesh.is_boundary(e))
        {
            sharp[e.idx()] = 1;
            continue;
        }
        const FaceHandle f0 = mesh.face_handle(mesh.halfedge_handle(e, 0));
        const FaceHandle f1 = mesh.face_handle(mesh.halfedge_handle(e, 1));
        if (mesh.property(props.face_ref, f0) != mesh.property(props.face_ref, f1))
        {
            sharp[e.idx()] = 1;  // a border between refs is kept like a ridge
            continue;
        }
        if (!options.detect_ridges) continue;
        const double cosine = cosine_between(face_normal[f0.idx()], face_normal[f1.idx()]);
        if (cosine >= flat_cosine) continue;
        const double angle = std::acos(cosine) * 180.0 / M_PI;
        if (angle > options.ridge_angle_deg) sharp[e.idx()] = 1;
        else if (angle > options.crease_angle_deg) sharp[e.idx()] = 2;  // a crease: kept only in long chains
    }

    FeatureSummary summary;
    FeatureGraph graph(mesh, options, std::move(sharp));
    std::vector<Chain> chains;
    // Dropping a noise chain can turn a corner into a plain curve vertex and merge two chains,
    // so classify again until nothing more is dropped.
    for (int round = 0; round < 8; ++round)
    {
        graph.find_corners();
        chains = graph.chains();
        // A chain long enough is a ridge; a shorter one only when both its ends are ends of
        // ridges (a short ridge between corners of a machined part); the rest is noise.
        std::vector<char> kept(chains.size(), 0);
        std::vector<char> ridge_end(mesh.n_vertices(), 0);
        auto ends_of = [&](const Chain& c) {
            const auto h0 = mesh.halfedge_handle(c.edges.front(), 0), h1 = mesh.halfedge_handle(c.edges.back(), 0);
            const VertexHandle a0 = mesh.from_vertex_handle(h0), a1 = mesh.to_vertex_handle(h0);
            const VertexHandle b0 = mesh.from_vertex_handle(h1), b1 = mesh.to_vertex_handle(h1);
            // the free end of the first and of the last edge (the one not shared with the chain)
            auto free_end = [&](VertexHandle x, VertexHandle y, EdgeHandle neighbour) {
                if (c.edges.size() == 1) return std::make_pair(x, y);
                const auto hn = mesh.halfedge_handle(neighbour, 0);
                const bool x_shared = mesh.from_vertex_handle(hn) == x || mesh.to_vertex_handle(hn) == x;
                return std::make_pair(x_shared ? y : x, x_shared ? y : x);
            };
            if (c.edges.size() == 1) return std::make_pair(a0, a1);
            return std::make_pair(free_end(a0, a1, c.edges[1]).first, free_end(b0, b1, c.edges[c.edges.size() - 2]).first);
        };
        for (std::size_t i = 0; i < chains.size(); ++i)
        {
            const Chain& c = chains[i];
            const bool crease_only = std::all_of(c.edges.begin(), c.edges.end(),
                                                 [&](EdgeHandle e) { return graph.sharp()[e.idx()] == 2; });
            const double needed = (crease_only ? 2.0 : 1.0) * options.min_ridge_length * diagonal;
            if (c.boundary || c.length >= needed)
            {
                kept[i] = 1;
                const auto [a, b] = ends_of(c);
                ridge_end[a.idx()] = ridge_end[b.idx()] = 1;
            }
        }
        for (bool grew = true; grew;)
        {
            grew = false;
            for (std::size_t i = 0; i < chains.size(); ++i)
            {
                if (kept[i] || static_cast<int>(chains[i].edges.size()) < 1) continue;
                const auto [a, b] = ends_of(chains[i]);
                if (!ridge_end[a.idx()] || !ridge_end[b.idx()]) continue;
                kept[i] = 1;
                grew = true;
            }
        }
        bool dropped = false;
        for (std::size_t i = 0; i < chains.size(); ++i)
        {
            if (kept[i]) continue;
            for (auto e : chains[i].edges) graph.sharp()[e.idx()] = 0;
            ++summary.dropped_ridge_chains;
            dropped = true;
        }
        if (!dropped) break;
    }

    for (auto v : mesh.vertices())
    {
        mesh.property(props.vertex_class, v) = VertexClass::Smooth;
        mesh.property(props.vertex_curve, v) = kNoCurve;
    }
    for (auto e : mesh.edges()) mesh.property(props.edge_curve, e) = kNoCurve;
    int curve = 0;
    for (const Chain& c : chains)
    {
        for (auto e : c.edges)
        {
            mesh.property(props.edge_curve, e) = curve;
            for (int i = 0; i < 2; ++i)
            {
                const VertexHandle v = mesh.to_vertex_handle(mesh.halfedge_handle(e, i));
                mesh.property(props.vertex_class, v) = c.boundary ? VertexClass::Boundary : VertexClass::Ridge;
                mesh.property(props.vertex_curve, v) = curve;
            }
            (c.boundary ? summary.boundary_edges : summary.ridge_edges) += 1;
        }
        ++curve;
    }
    for (auto v : mesh.vertices())
    {
        if (!graph.corner()[v.idx()]) continue;
        mesh.property(props.vertex_class, v) = VertexClass::Corner;
        mesh.property(props.vertex_curve, v) = kNoCurve;
    }
    for (auto v : mesh.vertices())
    {
        switch (mesh.property(props.vertex_class, v))
        {
        case VertexClass::Ridge: ++summary.ridge_vertices; break;
        case VertexClass::Boundary: ++summary.boundary_vertices; break;
        case VertexClass::Corner: ++summary.corners; break;
        case VertexClass::Smooth: break;
        }
    }
    summary.curves = static_cast<std::size_t>(curve);
    return summary;
}

}  // namespace hdimesh::surface

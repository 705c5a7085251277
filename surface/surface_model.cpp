#include "surface/surface_model.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/errors.h"
#include "surface/detail/closest_point_tree.h"
#include "surface/detail/prefetch.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface
{
namespace
{

// A vertex placed by project_near takes the foot its descent from the hint reached when that
// foot is within this fraction of its face's shortest edge (a vertex moved in the tangent plane
// is); farther, the search decides. Below it a local foot is the global one in practice
// (docs/tuning.md).
constexpr double kPlacementFraction = 1e-2;

Eigen::Vector3d to_eigen(const Vec3d& p) { return {p[0], p[1], p[2]}; }

// The input's vertex stars, circulated once: the neighbours of v are
// neighbours[offsets[v] .. offsets[v + 1]) in OpenMesh's vv_range order (the order of the 2-ring,
// hence of the fit's sums), and area_normals[v] the sum of its faces' normals times their areas
// in vf_range order (both circulators walk v's outgoing halfedges from the same one; the faces
// are those of the halfedges that have one). Circulating the 2-ring of every vertex anew
// (seven circulations per vertex) cost more than the fit itself.
struct VertexStars
{
    std::vector<int> offsets, neighbours;
    std::vector<Vec3d> area_normals;

    VertexStars(const SurfaceMesh& mesh, const std::vector<Vec3d>& face_normal,
                const std::vector<double>& face_area)
    {
        offsets.reserve(mesh.n_vertices() + 1);
        neighbours.reserve(2 * mesh.n_edges());
        area_normals.assign(mesh.n_vertices(), Vec3d(0, 0, 0));
        offsets.push_back(0);
        for (auto v : mesh.vertices())
        {
            Vec3d& n = area_normals[v.idx()];
            for (auto h : mesh.voh_range(v))
            {
                neighbours.push_back(mesh.to_vertex_handle(h).idx());
                const FaceHandle f = mesh.face_handle(h);
                if (f.is_valid()) n += face_normal[f.idx()] * face_area[f.idx()];
            }
            offsets.push_back(static_cast<int>(neighbours.size()));
        }
    }
};

// The 2-ring buffers of quadric_curvature, kept from one vertex to the next (the fit itself
// works on fixed-size matrices).
struct QuadricFitScratch
{
    std::vector<int> ring;
    std::vector<int> in_ring_of;  // per vertex: the vertex whose ring holds it (-1: none yet)
};

// max(|k1|, |k2|) at v from z = a x² + b xy + c y² + d x + e y fitted to its 2-ring in the frame
// of the vertex normal; 0 when the ring is too small to fit. The second ring grows from smooth
// neighbours only: beyond a feature vertex lies another patch, whose turn is not curvature.
double quadric_curvature(const std::vector<Vec3d>& points, const VertexStars& stars,
                         const std::vector<char>& smooth, int v, const Vec3d& normal,
                         QuadricFitScratch& scratch)
{
    // The 2-ring without v, each vertex once (a vertex is stamped with the index of the ring it
    // was put in).
    std::vector<int>& ring = scratch.ring;
    std::vector<int>& stamp = scratch.in_ring_of;
    if (stamp.size() != points.size()) stamp.assign(points.size(), -1);
    ring.clear();
    stamp[v] = v;
    auto add = [&](int u) {
        if (stamp[u] == v) return;
        stamp[u] = v;
        ring.push_back(u);
    };
    const int* const neighbours = stars.neighbours.data();
    const int* const offsets = stars.offsets.data();
    for (int i = offsets[v]; i < offsets[v + 1]; ++i)
    {
        const int w = neighbours[i];
        add(w);
        if (!smooth[w]) continue;
        for (int k = offsets[w]; k < offsets[w + 1]; ++k) add(neighbours[k]);
    }
    if (ring.size() < 6 || !(normal.norm() > 0.0)) return 0.0;
    const Eigen::Vector3d n = to_eigen(normal).normalized();
    const Eigen::Vector3d seed =
        std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    const Eigen::Vector3d e1 = n.cross(seed).normalized();
    const Eigen::Vector3d e2 = n.cross(e1);
    const Eigen::Vector3d origin = to_eigen(points[v]);
    // The least-squares fit by its 5×5 normal equations, in coordinates scaled by the ring's
    // size (so the matrix is well scaled whatever the model's units); a rank-revealing solve of
    // fixed size. (A QR of the whole ring matrix cost much more.)
    double scale = 0.0;
    for (const int idx : ring) scale = std::max(scale, (to_eigen(points[idx]) - origin).norm());
    if (!(scale > 0.0)) return 0.0;
    // The lower triangle of row·rowᵀ summed, element by element as Eigen's rank-one update of
    // a selfadjoint view does it (the same products and sums, without its generic dynamic-size
    // kernel), in named scalars: an array of the row's entries was stored and read back as
    // pairs, which waited on the stores.
    double xxxx = 0, xxxy = 0, xxyy = 0, xxx = 0, xxy = 0;  // (x², xy, y², x, y) times x²
    double xyxy = 0, xyyy = 0, xyx = 0, xyy = 0;            // ... times xy
    double yyyy = 0, yyx = 0, yyy = 0;                      // ... times y²
    double xx = 0, xy = 0, yy = 0;                          // ... times x and y
    double zxx = 0, zxy = 0, zyy = 0, zx = 0, zy = 0;       // z times the row
    for (const int idx : ring)
    {
        const Eigen::Vector3d d = (to_eigen(points[idx]) - origin) / scale;
        const double x = d.dot(e1), y = d.dot(e2);
        const double r0 = x * x, r1 = x * y, r2 = y * y;
        xxxx += r0 * r0, xxxy += r0 * r1, xxyy += r0 * r2, xxx += r0 * x, xxy += r0 * y;
        xyxy += r1 * r1, xyyy += r1 * r2, xyx += r1 * x, xyy += r1 * y;
        yyyy += r2 * r2, yyx += r2 * x, yyy += r2 * y;
        xx += x * x, xy += x * y, yy += y * y;
        const double z = d.dot(n);
        zxx += z * r0, zxy += z * r1, zyy += z * r2, zx += z * x, zy += z * y;
    }
    Eigen::Matrix<double, 5, 5> normal_matrix;
    normal_matrix << xxxx, xxxy, xxyy, xxx, xxy,  //
        xxxy, xyxy, xyyy, xyx, xyy,               //
        xxyy, xyyy, yyyy, yyx, yyy,               //
        xxx, xyx, yyx, xx, xy,                    //
        xxy, xyy, yyy, xy, yy;
    const Eigen::Matrix<double, 5, 1> rhs(zxx, zxy, zyy, zx, zy);
    const Eigen::Matrix<double, 5, 1> c = normal_matrix.colPivHouseholderQr().solve(rhs);
    if (!c.allFinite()) return 0.0;
    Eigen::Matrix2d shape;
    shape << 2 * c(0), c(1), c(1), 2 * c(2);
    const Eigen::Vector2d k = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(shape).eigenvalues();
    // Scaled back: z/scale = f(x/scale, y/scale) has curvatures scale times the true ones.
    return std::max(std::abs(k(0)), std::abs(k(1))) / scale;
}

// The model numbers input vertices and faces by handle index: a mesh with deleted elements
// (an operator's result before its garbage collection) would leave holes in every table.
void check_no_deleted_elements(const SurfaceMesh& input)
{
    if (input.has_vertex_status() && input.has_face_status())
    {
        for (auto v : input.all_vertices())
            if (input.status(v).deleted())
                throw InputError("SurfaceModel: the input mesh has deleted vertices (e.g. vertex " +
                                 std::to_string(v.idx()) + "): garbage-collect it first");
        for (auto f : input.all_faces())
            if (input.status(f).deleted())
                throw InputError("SurfaceModel: the input mesh has deleted faces (e.g. face " +
                                 std::to_string(f.idx()) + "): garbage-collect it first");
    }
}

// An edge's curve (kNoCurve: none, or an unclassified input).
int edge_curve_of(const SurfaceMesh& input, bool classified, OpenMesh::EPropHandleT<int> edge_curve,
                  EdgeHandle e)
{
    return classified ? input.property(edge_curve, e) : kNoCurve;
}

// Whether a vertex is smooth (every vertex of an unclassified input is).
bool vertex_is_smooth(const SurfaceMesh& input, bool classified,
                      OpenMesh::VPropHandleT<VertexClass> vertex_class, VertexHandle v)
{
    return !classified || input.property(vertex_class, v) == VertexClass::Smooth;
}

}  // namespace

SurfaceModel::~SurfaceModel() = default;

std::size_t SurfaceModel::curve_count() const { return curves_.size(); }

SurfaceModel::SurfaceModel(const SurfaceMesh& input)
{
    check_no_deleted_elements(input);
    // Read-only look-up: an unclassified input is all smooth, without curves.
    OpenMesh::VPropHandleT<VertexClass> vertex_class;
    OpenMesh::EPropHandleT<int> edge_curve;
    const bool classified = input.get_property_handle(vertex_class, property_names::vertex_class) &&
                            input.get_property_handle(edge_curve, property_names::edge_curve);
    diagonal_ = bounding_box_diagonal(input);
    points_.reserve(input.n_vertices());
    for (auto v : input.vertices()) points_.push_back(input.point(v));

    std::vector<Vec3d> face_normal_by_index;
    std::vector<int> model_face_by_index;  // face handle index -> index here
    build_faces(input, face_normal_by_index, model_face_by_index);
    build_vertex_faces();
    build_curves(input, classified, edge_curve, face_normal_by_index, model_face_by_index);
    build_curvatures(input, classified, vertex_class, face_normal_by_index);
}

// The input's faces: their points, normals and planes, the tree over them, their neighbours
// across each edge; per input face handle index its normal and its index here.
void SurfaceModel::build_faces(const SurfaceMesh& input, std::vector<Vec3d>& face_normal_by_index,
                               std::vector<int>& model_face_by_index)
{
    std::vector<std::array<Vec3d, 3>> tris;
    tris.reserve(input.n_faces());
    face_vertices_.reserve(input.n_faces());
    face_normals_.reserve(input.n_faces());
    face_planes_.reserve(input.n_faces());
    face_normal_by_index.assign(input.n_faces(), Vec3d());
    model_face_by_index.assign(input.n_faces(), -1);
    for (auto f : input.faces())
    {
        auto vi = input.cfv_iter(f);
        const int i0 = vi->idx(), i1 = (++vi)->idx(), i2 = (++vi)->idx();
        const Vec3d a = points_[i0], b = points_[i1], c = points_[i2];
        tris.push_back({a, b, c});
        face_vertices_.push_back({i0, i1, i2});
        face_normals_.push_back(triangle_normal(a, b, c));
        face_planes_.push_back(face_plane(a, b, c, face_normals_.back()));
        face_normal_by_index[f.idx()] = face_normals_.back();
        model_face_by_index[f.idx()] = static_cast<int>(face_vertices_.size()) - 1;
    }
    triangles_ =
        std::make_unique<const ClosestPointTree>(ClosestPointTree::from_triangles(std::move(tris)));
    face_neighbours_.reserve(face_vertices_.size());
    for (auto f : input.faces())
    {
        std::array<int, 3> across{-1, -1, -1};
        int k = 0;
        for (auto h : input.fh_range(f))
        {
            const auto g = input.face_handle(input.opposite_halfedge_handle(h));
            if (k < 3 && g.is_valid()) across[k] = model_face_by_index[g.idx()];
            ++k;
        }
        face_neighbours_.push_back(across);
    }
}

// The faces around each vertex (CSR) and the angle-weighted vertex normals.
void SurfaceModel::build_vertex_faces()
{
    vertex_face_offsets_.assign(points_.size() + 1, 0);
    for (const auto& fv : face_vertices_)
        for (const int v : fv) ++vertex_face_offsets_[v + 1];
    for (std::size_t v = 0; v < points_.size(); ++v)
        vertex_face_offsets_[v + 1] += vertex_face_offsets_[v];
    vertex_faces_.resize(vertex_face_offsets_.back());
    {
        std::vector<int> next(vertex_face_offsets_.begin(), vertex_face_offsets_.end() - 1);
        for (std::size_t f = 0; f < face_vertices_.size(); ++f)
            for (const int v : face_vertices_[f]) vertex_faces_[next[v]++] = static_cast<int>(f);
    }
    // Angle-weighted vertex normals: the normal of a foot at a vertex, whichever face the search
    // names there (the faces around a sharp tip disagree by up to their dihedral angle).
    vertex_normals_.assign(points_.size(), Vec3d(0, 0, 0));
    for (std::size_t f = 0; f < face_vertices_.size(); ++f)
    {
        const auto& fv = face_vertices_[f];
        for (int k = 0; k < 3; ++k)
        {
            const Vec3d u = points_[fv[(k + 1) % 3]] - points_[fv[k]],
                        w = points_[fv[(k + 2) % 3]] - points_[fv[k]];
            const double lu = u.norm(), lw = w.norm();
            if (!(lu > 0.0 && lw > 0.0)) continue;
            const double angle = std::acos(std::clamp(OpenMesh::dot(u, w) / (lu * lw), -1.0, 1.0));
            vertex_normals_[fv[k]] += angle * face_normals_[f];
        }
    }
    for (Vec3d& n : vertex_normals_)
        if (n.norm() > 0.0) n.normalize();
}

// The feature curves: a tree over each curve's segments, and per segment the mean normal and a
// face beside it.
void SurfaceModel::build_curves(const SurfaceMesh& input, bool classified,
                                OpenMesh::EPropHandleT<int> edge_curve,
                                const std::vector<Vec3d>& face_normal_by_index,
                                const std::vector<int>& model_face_by_index)
{
    int curve_count = 0;
    for (auto e : input.edges())
        curve_count = std::max(curve_count, edge_curve_of(input, classified, edge_curve, e) + 1);
    std::vector<std::vector<std::array<Vec3d, 2>>> segments(curve_count);
    curve_normals_.assign(curve_count, {});
    curve_faces_.assign(curve_count, {});
    for (auto e : input.edges())
    {
        const int c = edge_curve_of(input, classified, edge_curve, e);
        if (c < 0) continue;
        const auto h = input.halfedge_handle(e, 0);
        segments[c].push_back(
            {input.point(input.from_vertex_handle(h)), input.point(input.to_vertex_handle(h))});
        Vec3d n(0, 0, 0);
        int beside = -1;
        for (int i = 0; i < 2; ++i)
        {
            const auto f = input.face_handle(input.halfedge_handle(e, i));
            if (!f.is_valid()) continue;
            n += face_normal_by_index[f.idx()];
            if (beside < 0) beside = model_face_by_index[f.idx()];
        }
        curve_faces_[c].push_back(beside);
        const double len = n.norm();
        curve_normals_[c].push_back(len > 0 ? n / len : n);
    }
    for (const auto& s : segments) curves_.push_back(ClosestPointTree::from_segments(s));
}

// The curvature of each smooth vertex, from a quadric fit of its 2-ring.
void SurfaceModel::build_curvatures(const SurfaceMesh& input, bool classified,
                                    OpenMesh::VPropHandleT<VertexClass> vertex_class,
                                    const std::vector<Vec3d>& face_normal_by_index)
{
    curvature_.assign(input.n_vertices(), 0.0);
    // Each face's area once (the vertex normals of the fit read those of their faces).
    std::vector<double> face_area(input.n_faces());
    for (auto f : input.faces()) face_area[f.idx()] = input.calc_face_area(f);
    const VertexStars stars(input, face_normal_by_index, face_area);
    QuadricFitScratch scratch;
    std::vector<char> smooth(input.n_vertices());
    for (auto v : input.vertices())
        smooth[v.idx()] = vertex_is_smooth(input, classified, vertex_class, v);
    for (auto v : input.vertices())
        if (smooth[v.idx()])
            curvature_[v.idx()] = quadric_curvature(points_, stars, smooth, v.idx(),
                                                    stars.area_normals[v.idx()], scratch);
}

// For the descent's bound (FacePlane). Every sine of the triangle's angles is at least
// |ab × ac| / longest² (twice the area over the product of two edges); at 1e-4 or more the
// normal's direction is within 1e-11 of the exact plane's and the closest point the descent
// computes within 1e-14 (|a| + |b| + |c|) of that plane: the margin 1e-9 (|a| + |b| + |c|)
// covers both with a wide berth. A flatter triangle gets no bound (an infinite margin).
SurfaceModel::FacePlane SurfaceModel::face_plane(const Vec3d& a, const Vec3d& b, const Vec3d& c,
                                                 const Vec3d& unit_normal)
{
    FacePlane plane;
    plane.normal = unit_normal;
    plane.offset = OpenMesh::dot(unit_normal, a);
    const double cross = OpenMesh::cross(b - a, c - a).norm();
    const double longest2 = std::max({(b - a).sqrnorm(), (c - b).sqrnorm(), (a - c).sqrnorm()});
    const bool well_shaped = cross > 0.0 && cross >= 1e-4 * longest2 && std::isfinite(longest2);
    plane.margin = well_shaped ? 1e-9 * (a.norm() + b.norm() + c.norm())
                               : std::numeric_limits<double>::infinity();
    return plane;
}

SurfaceModel::Descent SurfaceModel::descend(const Vec3d& p, int face, double stop_d2) const
{
    // Most descents end in a step or two (a shifted vertex moves by a fraction of the output
    // size, the input is finer or as fine); a longer one means a poor hint.
    constexpr int kMaxDescentSteps = 32;
    auto foot_on = [&](int f) {
        const auto& fv = face_vertices_[f];
        return closest_point_on_triangle(p, points_[fv[0]], points_[fv[1]], points_[fv[2]]);
    };
    // The rounding of a plane distance at p (FacePlane::margin is the triangle's part): the
    // coordinates' sum bounds |p|.
    const double p_margin = 1e-9 * (std::abs(p[0]) + std::abs(p[1]) + std::abs(p[2]));
    const bool proof_search = stop_d2 >= 0.0;
    Descent out;
    out.face = face;
    // The input's tables are larger than the cache and a descent's reads wait for one another
    // (face, its neighbours, their corners): each is asked for as soon as its address is known.
    detail::prefetch(&face_neighbours_[face]);
    if (!proof_search)  // the first step's neighbours will be read: their corners too
        for (const int g : face_neighbours_[face])
            if (g >= 0) detail::prefetch(&face_vertices_[g]), detail::prefetch(&face_planes_[g]);
    out.foot = foot_on(face);
    double d2 = (out.foot - p).sqrnorm();
    // The face the last step came from: its foot was farther than the present one, so it
    // cannot be nearer than it (the same decision without its foot).
    int came_from = -1;
    for (int step = 0; step < kMaxDescentSteps && !(d2 <= stop_d2); ++step)
    {
        // Across the edges (three faces, the usual way down); for a foot at a corner of the
        // face, also the other faces around that corner (they may rise nearer to p).
        int next = -1;
        Vec3d next_foot(0, 0, 0);
        double next_d2 = d2;
        // A descent with a stop distance (near_model's proof search) steps to the first nearer
        // neighbour instead of the nearest: its caller's answer does not depend on the path
        // (a face within the distance proves it; else the exact search decides): fewer feet per
        // descent than computing all its neighbours' at each step. (Such a descent may end
        // at kMaxDescentSteps more often; the exact search decides then.)
        bool found_nearer = false;
        auto consider = [&](int g) {
            if (g == came_from || found_nearer) return;
            // A face whose plane is clearly farther than the nearest foot so far cannot have a
            // nearer foot (its triangle lies in that plane): the same decision without its foot.
            // (Not in a proof search, which steps to the first nearer face: there the bound
            // costs more than it saves.)
            if (!proof_search)
            {
                const FacePlane& plane = face_planes_[g];
                const double beyond = std::abs(OpenMesh::dot(plane.normal, p) - plane.offset) -
                                      (plane.margin + p_margin);
                if (beyond > 0.0 && beyond * beyond > next_d2 * (1.0 + 1e-12))
                {
                    assert(!((foot_on(g) - p).sqrnorm() < next_d2));
                    return;
                }
            }
            const Vec3d q = foot_on(g);
            const double g_d2 = (q - p).sqrnorm();
            if (g_d2 < next_d2)
                next = g, next_foot = q, next_d2 = g_d2, found_nearer = proof_search;
        };
        const std::array<int, 3>& across = face_neighbours_[out.face];
        for (const int g : across)
            if (g >= 0 && g != came_from)
            {
                if (!proof_search) detail::prefetch(&face_planes_[g]);
                for (const int v : face_vertices_[g]) detail::prefetch(&points_[v]);
            }
        for (const int g : across)
            if (g >= 0) consider(g);
        if (next < 0)
            for (const int v : face_vertices_[out.face])
            {
                if (!(points_[v] == out.foot))
                    continue;  // (the corner region returns the corner itself)
                for (int k = vertex_face_offsets_[v]; k < vertex_face_offsets_[v + 1]; ++k)
                    if (vertex_faces_[k] != out.face) consider(vertex_faces_[k]);
            }
        if (next < 0)
        {
            out.converged = true;
            return out;
        }
        detail::prefetch(&face_neighbours_[next]);
        came_from = out.face;
        out.face = next;
        out.foot = next_foot;
        d2 = next_d2;
    }
    return out;
}

bool SurfaceModel::within_fraction_of_face(int face, double d2, double fraction) const
{
    const auto& fv = face_vertices_[face];
    const double shortest2 = std::min({(points_[fv[0]] - points_[fv[1]]).sqrnorm(),
                                       (points_[fv[1]] - points_[fv[2]]).sqrnorm(),
                                       (points_[fv[2]] - points_[fv[0]]).sqrnorm()});
    return d2 <= fraction * fraction * shortest2;
}

Vec3d SurfaceModel::foot_normal(int face, const Vec3d& foot) const
{
    // At a corner of the face: the vertex normal. On an edge (the foot's distance to its line a
    // rounding of its coordinates): the mean of the two faces'. Inside: the face's own.
    const auto& fv = face_vertices_[face];
    for (const int v : fv)
        if (points_[v] == foot) return vertex_normals_[v];
    for (int k = 0; k < 3; ++k)
    {
        const Vec3d& a = points_[fv[k]];
        const Vec3d edge = points_[fv[(k + 1) % 3]] - a;
        const double off_line2 = OpenMesh::cross(edge, foot - a).sqrnorm();
        // A foot clearly off the edge's line, by a bound of rounding² below without its square
        // roots ((|e| + |a|)² ≤ 2 (|e|² + |a|²), a relative margin far above the arithmetic's
        // rounding; in the range where no product under- or overflows): the same decision.
        // Nearly every foot is inside its face: its edges' six square roots are not needed.
        const double e2 = edge.sqrnorm(), a2 = a.sqrnorm();
        const double bound2 = 2e-24 * e2 * (e2 + a2) * (1.0 + 1e-9);
        if (bound2 >= 1e-280 && off_line2 > bound2) continue;
        // (The foot's rounding scales with its coordinates, not with the edge's length alone.)
        const double rounding = 1e-12 * edge.norm() * (edge.norm() + a.norm());
        if (off_line2 > rounding * rounding) continue;
        // fv is the face's vertex circulation (the to-vertices of its halfedges from its first);
        // face_neighbours_ is across its halfedges in the same order, so across the edge from
        // fv[k] to fv[k + 1] is entry k + 1.
        const int across = face_neighbours_[face][(k + 1) % 3];
        if (across < 0) return face_normals_[face];
        Vec3d n = face_normals_[face] + face_normals_[across];
        return n.norm() > 0.0 ? n.normalized() : face_normals_[face];
    }
    return face_normals_[face];
}

ProjectedPoint SurfaceModel::closest_on_input(const Vec3d& p, int face_hint,
                                              double local_fraction) const
{
    ProjectedPoint out;
    if (face_hint >= 0 && face_hint < static_cast<int>(face_vertices_.size()))
    {
        detail::prefetch(
            &face_normals_[face_hint]);  // where most descents stop (foot_normal's read)
        const Descent descent = descend(p, face_hint);
        if (descent.converged && local_fraction > 0.0 &&
            within_fraction_of_face(descent.face, (descent.foot - p).sqrnorm(), local_fraction))
        {
            out.point = descent.foot;
            out.normal = foot_normal(descent.face, descent.foot);
            out.face = descent.face;
            out.ok = true;
            return out;
        }
        face_hint = descent.face;  // where the descent stopped: a tight bound for the search
    }
    const auto hit = triangles_->closest(p, face_hint);
    if (hit.primitive < 0) return out;
    out.point = hit.point;
    out.normal = foot_normal(hit.primitive, hit.point);
    out.face = hit.primitive;
    out.ok = true;
    return out;
}

double SurfaceModel::interpolate(const Vec3d& p, const std::vector<double>& values,
                                 int face_hint) const
{
    int face = -1;
    Vec3d q;
    // Sizes are looked up at points just projected onto the hint face: a point within rounding of
    // that face is taken on it without a search. Another face as near can only share its edge or
    // corner (or touch it within rounding), where the piecewise-linear field is continuous.
    if (face_hint >= 0 && face_hint < static_cast<int>(face_vertices_.size()))
    {
        const auto& fv = face_vertices_[face_hint];
        q = closest_point_on_triangle(p, points_[fv[0]], points_[fv[1]], points_[fv[2]]);
        const double on_face = 1e-12 * diagonal_;
        if ((q - p).sqrnorm() <= on_face * on_face) face = face_hint;
    }
    if (face < 0)
    {
        const ProjectedPoint hit = closest_on_input(p, face_hint, 0.0);
        if (!hit.ok) return 0.0;
        face = hit.face;
        q = hit.point;
    }
    const auto& fv = face_vertices_[face];
    const Vec3d a = points_[fv[0]], b = points_[fv[1]], c = points_[fv[2]];
    // Barycentric coordinates of the closest point by sub-areas.
    const double area = OpenMesh::cross(b - a, c - a).norm();
    if (!(area > 0.0)) return (values[fv[0]] + values[fv[1]] + values[fv[2]]) / 3.0;
    const double wa = OpenMesh::cross(b - q, c - q).norm() / area;
    const double wb = OpenMesh::cross(c - q, a - q).norm() / area;
    const double wc = std::max(0.0, 1.0 - wa - wb);
    return (wa * values[fv[0]] + wb * values[fv[1]] + wc * values[fv[2]]) /
           std::max(wa + wb + wc, 1e-300);
}

double SurfaceModel::distance_to_curve(const Vec3d& p, int curve) const
{
    if (curve < 0 || curve >= static_cast<int>(curves_.size()) || curves_[curve].empty())
        return std::numeric_limits<double>::infinity();
    return curves_[curve].closest(p).distance;
}

ProjectedPoint SurfaceModel::project(const Vec3d& p, VertexClass cls, int curve) const
{
    return project_near(p, cls, curve, -1);
}

double SurfaceModel::distance_to_surface(const Vec3d& p, int face_hint) const
{
    if (smooth_) return Projector::distance_to_surface(p, face_hint);
    const ProjectedPoint on_input = closest_on_input(p, face_hint, 0.0);
    return on_input.ok ? (on_input.point - p).norm() : 0.0;
}

bool SurfaceModel::near_model(const Vec3d& p, double distance, int face_hint) const
{
    if (smooth_) return Projector::near_model(p, distance, face_hint);
    if (face_hint >= 0 && face_hint < static_cast<int>(face_vertices_.size()))
    {
        // A face within the distance found by the descent is a proof (the closest face can
        // only be nearer; the same arithmetic as the search's distance).
        const Descent descent = descend(p, face_hint, distance * distance);
        if ((descent.foot - p).norm() <= distance) return true;
        face_hint = descent.face;
    }
    const auto hit = triangles_->closest(p, face_hint);
    return hit.primitive < 0 || hit.distance <= distance;
}

ProjectedPoint SurfaceModel::project_near(const Vec3d& p, VertexClass cls, int curve,
                                          int face_hint) const
{
    switch (cls)
    {
        case VertexClass::Corner:
        {
            ProjectedPoint out = closest_on_input(p, face_hint, kPlacementFraction);
            out.point = p;
            return out;
        }
        case VertexClass::Ridge:
        case VertexClass::Boundary:
        {
            if (curve < 0 || curve >= static_cast<int>(curves_.size()) || curves_[curve].empty())
                return {};
            const auto hit = curves_[curve].closest(p);
            ProjectedPoint out;
            out.point = hit.point;
            out.normal = curve_normals_[curve][hit.primitive];
            out.face = curve_faces_[curve][hit.primitive];
            out.ok = true;
            return out;
        }
        case VertexClass::Smooth:
            if (smooth_)
            {
                ProjectedPoint out = smooth_(p);
                if (out.ok) return out;
            }
            return closest_on_input(p, face_hint, kPlacementFraction);
    }
    return {};
}

double SurfaceModel::chord_error(int face) const
{
    if (face < 0) return 0.0;
    const auto& f = face_vertices_[face];
    const double longest =
        std::max({(points_[f[0]] - points_[f[1]]).norm(), (points_[f[1]] - points_[f[2]]).norm(),
                  (points_[f[2]] - points_[f[0]]).norm()});
    const double curvature = std::max({curvature_[f[0]], curvature_[f[1]], curvature_[f[2]]});
    return curvature * longest * longest / 8.0;
}

double SurfaceModel::coarse_area_fraction(double tolerance) const
{
    const std::vector<int> one_shell(face_vertices_.size(), 0);
    const std::vector<double> fractions = coarse_area_fractions(tolerance, one_shell);
    return fractions.empty() ? 0.0 : fractions.front();
}

std::vector<int> SurfaceModel::face_shells() const
{
    std::vector<int> parent(points_.size());
    for (std::size_t v = 0; v < parent.size(); ++v) parent[v] = static_cast<int>(v);
    auto root = [&parent](int v) {
        while (parent[v] != v) v = parent[v] = parent[parent[v]];
        return v;
    };
    for (const auto& f : face_vertices_)
        for (int k = 1; k < 3; ++k) parent[root(f[k])] = root(f[0]);
    std::vector<int> shell_of_root(points_.size(), -1), shells;
    shells.reserve(face_vertices_.size());
    int count = 0;
    for (const auto& f : face_vertices_)
    {
        int& shell = shell_of_root[root(f[0])];
        if (shell < 0) shell = count++;
        shells.push_back(shell);
    }
    return shells;
}

std::vector<double> SurfaceModel::coarse_area_fractions(double tolerance,
                                                        const std::vector<int>& face_shell) const
{
    const int shells =
        face_shell.empty() ? 0 : *std::max_element(face_shell.begin(), face_shell.end()) + 1;
    std::vector<double> total(shells, 0.0), coarse(shells, 0.0);
    for (int f = 0; f < static_cast<int>(face_vertices_.size()); ++f)
    {
        const auto& v = face_vertices_[f];
        const double area =
            0.5 *
            OpenMesh::cross(points_[v[1]] - points_[v[0]], points_[v[2]] - points_[v[0]]).norm();
        total[face_shell[f]] += area;
        if (chord_error(f) > tolerance) coarse[face_shell[f]] += area;
    }
    for (int s = 0; s < shells; ++s) coarse[s] = total[s] > 0.0 ? coarse[s] / total[s] : 0.0;
    return coarse;
}

double SurfaceModel::shortest_edge(int face) const
{
    if (face < 0) return 0.0;
    const auto& f = face_vertices_[face];
    return std::min({(points_[f[0]] - points_[f[1]]).norm(), (points_[f[1]] - points_[f[2]]).norm(),
                     (points_[f[2]] - points_[f[0]]).norm()});
}

}  // namespace hdimesh::surface

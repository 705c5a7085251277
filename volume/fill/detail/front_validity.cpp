// The tests a candidate tet of the advancing front must pass before it is committed: no front
// face folded onto a new one, no front face or vertex crossed (volume/fill/detail/front_mesher.h).
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <vector>

#include "volume/fill/detail/front_mesher.h"
#include "volume/mesh/predicates.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume::detail::front_mesher
{

/// True when front face t, sharing an edge with a new side face of `tet`, lies flat against it
/// on the same side of the edge: the pocket between them would need a tet flat in doubles.
bool FrontMesher::folds_onto(const TetVertices& tet, int shared_mask, const Triangle& t) const
{
    int edge[2], n = 0, w = -1;
    for (int j = 0; j < 4; ++j)
        if (shared_mask & (1 << j)) edge[n++] = tet[j];
    for (int v : t)
        if (v != edge[0] && v != edge[1]) w = v;
    const Vec3 &X = points_[edge[0]], &Y = points_[edge[1]], &W = points_[w];
    const Vec3 e = Y - X;
    const double e2 = e.squaredNorm();
    if (!(e2 > 0)) return false;
    const Vec3 uw = (W - X) - e * ((W - X).dot(e) / e2);
    // the tet's faces through the edge other than the base (which leaves the front)
    for (int j = 0; j < 4; ++j)
    {
        const int q = tet[j];
        if (q == edge[0] || q == edge[1]) continue;
        int other = -1;
        for (int k = 0; k < 4; ++k)
            if (tet[k] != edge[0] && tet[k] != edge[1] && tet[k] != q) other = tet[k];
        // the face (edge, q) is the base when the fourth vertex is the apex
        if (other == tet[3]) continue;
        const Vec3& Q = points_[q];
        const Vec3 uq = (Q - X) - e * ((Q - X).dot(e) / e2);
        if (!(uq.dot(uw) > 0)) continue;
        const double sine = uq.cross(uw).norm() / (uq.norm() * uw.norm());
        if (sine < kFoldSine && front_.find({edge[0], edge[1], q}) < 0) return true;
    }
    return false;
}

bool FrontMesher::valid_tet(int face, int p, bool is_new)
{
    const Triangle& base = front_.vertices[face];
    const int a = base[0], b = base[1], c = base[2];
    const Vec3 &A = points_[a], &B = points_[b], &C = points_[c], &P = points_[p];
    if (orient3d(A, B, C, P) <= 0) return false;

    // A new face that is already on the front the same way would overlap the tets behind it.
    const std::array<Triangle, 3> sides{{{a, b, p}, {b, c, p}, {c, a, p}}};
    if (!is_new)
        for (const Triangle& s : sides)
        {
            const int g = front_.find(s);
            if (g >= 0 && same_orientation(s, front_.vertices[g])) return false;
        }

    const TetVertices tet{a, b, c, p};
    const Box tet_box{A.cwiseMin(B).cwiseMin(C).cwiseMin(P), A.cwiseMax(B).cwiseMax(C).cwiseMax(P)};
    // the four face planes of the tet, outward normals, for the floating-point quick rejects
    std::array<Vec3, 4> normal, origin;
    std::array<double, 4> scale;
    for (int i = 0; i < 4; ++i)
    {
        const auto& fv = tet::kFaceVertices[i];
        const Vec3 &u = points_[tet[fv[0]]], &v = points_[tet[fv[1]]], &w = points_[tet[fv[2]]];
        const Vec3 e1 = v - u, e2 = w - u;
        normal[i] = e1.cross(e2);
        origin[i] = u;
        scale[i] = (e1.cwiseAbs().sum()) * (e2.cwiseAbs().sum());
    }
    auto surely_outside = [&](int i, int v) {
        return surely_positive(origin[i], normal[i], scale[i], points_[v]);
    };
    // Per vertex, once per call (a front vertex is in about six of the local faces): bit i when
    // it is surely outside face plane i or a vertex of face i; bit 4 + j when it is tet[j].
    if (vertex_stamp_.size() < points_.size())
    {
        vertex_stamp_.resize(points_.size() + points_.size() / 2 + 16, 0);
        vertex_mask_.resize(vertex_stamp_.size(), 0);
    }
    if (++stamp_ == 0)
    {
        std::fill(vertex_stamp_.begin(), vertex_stamp_.end(), 0);
        stamp_ = 1;
    }
    for (int j = 0; j < 4; ++j)
    {
        vertex_stamp_[tet[j]] = stamp_;
        vertex_mask_[tet[j]] = static_cast<std::uint8_t>((0xF & ~(1 << j)) | (1 << (4 + j)));
    }
    auto mask_of = [&](int v) {
        if (vertex_stamp_[v] != stamp_)
        {
            vertex_stamp_[v] = stamp_;
            std::uint8_t m = 0;
            for (int i = 0; i < 4; ++i)
                if (surely_outside(i, v)) m |= static_cast<std::uint8_t>(1 << i);
            vertex_mask_[v] = m;
        }
        return vertex_mask_[v];
    };

    // true when front face `entry` forbids the tet
    auto blocks = [&](const detail::BucketGrid::FaceEntry& entry) {
        const Triangle& t = entry.vertices;
        if (!tet_box.overlaps({Vec3(entry.lo[0], entry.lo[1], entry.lo[2]),
                               Vec3(entry.hi[0], entry.hi[1], entry.hi[2])}))
            return false;
        const std::uint8_t m0 = mask_of(t[0]), m1 = mask_of(t[1]), m2 = mask_of(t[2]);
        const int shared_mask = (m0 | m1 | m2) >> 4;
        const int shared = ((m0 >> 4) != 0) + ((m1 >> 4) != 0) + ((m2 >> 4) != 0);
        if (shared == 3) return false;  // the face the new tet closes against
        if (shared == 2 && folds_onto(tet, shared_mask, t)) return true;
        // quick reject: every vertex of t strictly outside one face plane or on it as a vertex
        if (m0 & m1 & m2 & 0xF) return false;
        // quick reject: the tet's other vertices strictly on one side of t's plane
        {
            const Vec3 &u = points_[t[0]], e1 = points_[t[1]] - u, e2 = points_[t[2]] - u;
            const Vec3 n = e1.cross(e2);
            const double n_scale = e1.cwiseAbs().sum() * e2.cwiseAbs().sum();
            int above = 0, below = 0, others = 0;
            for (int j = 0; j < 4; ++j)
            {
                if (shared_mask & (1 << j)) continue;
                ++others;
                const Vec3& X = points_[tet[j]];
                above += surely_positive(u, n, n_scale, X);
                below += surely_positive(u, -n, n_scale, X);
            }
            if (above == others || below == others) return false;
        }
        return tet_triangle_intersect(points_, tet, t);
    };
    // The face that refused the attempt's last candidate is tried first: the same obstacle
    // usually stands in the way of the next ones.
    if (last_blocker_ >= 0 && blocks(local_faces_[last_blocker_])) return false;
    for (std::size_t k = 0; k < local_faces_.size(); ++k)
        if (static_cast<int>(k) != last_blocker_ && blocks(local_faces_[k]))
        {
            last_blocker_ = static_cast<int>(k);
            return false;
        }

    for (int v : local_vertices_)
    {
        if (v == a || v == b || v == c || v == p) continue;
        const Vec3& X = points_[v];
        if (X[0] < tet_box.lo[0] || X[0] > tet_box.hi[0] || X[1] < tet_box.lo[1] ||
            X[1] > tet_box.hi[1] || X[2] < tet_box.lo[2] || X[2] > tet_box.hi[2])
            continue;
        bool outside = false;
        for (int i = 0; i < 4 && !outside; ++i) outside = surely_outside(i, v);
        if (outside) continue;
        if (point_in_tet(points_, v, tet)) return false;
    }
    return true;
}

}  // namespace hdimesh::volume::detail::front_mesher

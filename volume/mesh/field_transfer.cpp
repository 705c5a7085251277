#include "volume/mesh/field_transfer.h"

#include <algorithm>
#include <iterator>
#include <string>

#include "common/errors.h"
#include "volume/mesh/boundary.h"
#include "volume/mesh/geometry.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace
{

/// A point near an interface finds the tet of its own region among the tets sharing a vertex
/// with the located one; a second and third ring cover an interface that moved by an element.
constexpr int kRegionSearchRings = 3;

}  // namespace

TransferSource::TransferSource(const TetMesh& mesh)
    : locator_(mesh), points_(mesh.points), tets_(mesh.tets), tet_refs_(mesh.tet_refs)
{
    tet_refs_.resize(tets_.size(), 0);
    const int nv = num_vertices();
    vertex_tets_start_.assign(nv + 1, 0);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t))
            for (int v : tets_[t]) ++vertex_tets_start_[v + 1];
    for (int v = 0; v < nv; ++v) vertex_tets_start_[v + 1] += vertex_tets_start_[v];
    vertex_tets_.resize(vertex_tets_start_[nv]);
    std::vector<int> fill(vertex_tets_start_.begin(), vertex_tets_start_.end() - 1);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        if (!mesh.is_dead(t))
            for (int v : tets_[t]) vertex_tets_[fill[v]++] = t;

    // a face of one tet only is on the boundary (the locator's outward faces); the groups come
    // in sorted key order
    const FaceGroups groups = group_tet_faces(mesh);
    for (int k = 0; k < groups.num_faces(); ++k)
        if (groups.start[k + 1] - groups.start[k] == 1)
        {
            const TetFace& use = groups.uses[groups.start[k]];
            boundary_faces_.push_back({sorted_triple(face_vertices(mesh, use)), use.tet});
        }
}

std::array<double, 4> TransferSource::weights(int t, const Vec3& p) const
{
    const auto& v = tets_[t];
    const Vec3 &a = points_[v[0]], &b = points_[v[1]], &c = points_[v[2]], &d = points_[v[3]];
    const double six_volume = signed_volume6(a, b, c, d);
    return {signed_volume6(p, b, c, d) / six_volume, signed_volume6(a, p, c, d) / six_volume,
            signed_volume6(a, b, p, d) / six_volume, signed_volume6(a, b, c, p) / six_volume};
}

int TransferSource::tet_of_boundary_face(Triangle face) const
{
    const Triangle key = sorted_triple(face);
    const auto it = std::lower_bound(
        boundary_faces_.begin(), boundary_faces_.end(), key,
        [](const std::pair<Triangle, int>& item, const Triangle& k) { return item.first < k; });
    return it != boundary_faces_.end() && it->first == key ? it->second : -1;
}

int TransferSource::nearest_in_region(int from, const Vec3& p, int ref) const
{
    // ring by ring over the tets sharing a vertex, each ring in id order (deterministic)
    std::vector<int> ring = {from}, seen = {from}, next, merged;
    int best = -1;
    double best_weight = -std::numeric_limits<double>::infinity();
    for (int r = 0; r < kRegionSearchRings && best < 0 && !ring.empty(); ++r)
    {
        next.clear();
        for (int t : ring)
            for (int v : tets_[t])
                for (int n = vertex_tets_start_[v]; n < vertex_tets_start_[v + 1]; ++n)
                    next.push_back(vertex_tets_[n]);
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        next.erase(
            std::remove_if(next.begin(), next.end(),
                           [&](int u) { return std::binary_search(seen.begin(), seen.end(), u); }),
            next.end());
        for (int u : next)
        {
            if (tet_refs_[u] != ref) continue;
            const auto w = weights(u, p);
            const double least = *std::min_element(w.begin(), w.end());
            if (least > best_weight)
            {
                best_weight = least;
                best = u;
            }
        }
        merged.clear();
        std::merge(seen.begin(), seen.end(), next.begin(), next.end(), std::back_inserter(merged));
        seen.swap(merged);
        ring.swap(next);
    }
    return best;
}

TransferSource::Source TransferSource::find(const Vec3& p, int ref) const
{
    Source source;
    if (const auto located = locator_.locate(p))
    {
        source.tet = located->tet;
        source.weights = located->weights;
    }
    else
    {
        const BoundaryPoint nearest = locator_.nearest_boundary_point(p);
        source.tet = tet_of_boundary_face(nearest.vertices);
        source.outside = true;
        source.distance = nearest.distance;
        // (the locator's boundary faces are the faces of one tet: always found)
        if (source.tet < 0) source.tet = vertex_tets_[vertex_tets_start_[nearest.vertices[0]]];
        source.weights = weights(source.tet, p);
    }
    if (ref != kAnyRegion && tet_refs_[source.tet] != ref)
        if (const int own = nearest_in_region(source.tet, p, ref); own >= 0)
        {
            source.tet = own;
            source.weights = weights(own, p);
            source.other_region = true;
        }
    return source;
}

void check_vertex_fields(const std::vector<VertexField>& fields, int num_vertices)
{
    const std::size_t n = static_cast<std::size_t>(num_vertices);
    for (std::size_t k = 0; k < fields.size(); ++k)
    {
        const VertexField& field = fields[k];
        if (field.components < 1)
            throw InputError("field " + std::to_string(k + 1) + ": " +
                             std::to_string(field.components) + " components per vertex");
        if (field.values.size() != n * field.components)
            throw InputError("field " + std::to_string(k + 1) + " has " +
                             std::to_string(field.values.size()) + " values, not " +
                             std::to_string(n) + " vertices x " + std::to_string(field.components));
    }
}

TransferReport transfer_fields(const TransferSource& source, const std::vector<VertexField>& fields,
                               const TetMesh& target, const TransferOptions& options)
{
    check_vertex_fields(fields, source.num_vertices());

    // each vertex's region: the lowest ref among its tets (an interface vertex takes the lower)
    const int nv = target.num_vertices();
    std::vector<int> region(nv, TransferSource::kAnyRegion);
    for (int t = 0; t < target.num_tet_slots(); ++t)
    {
        if (target.is_dead(t)) continue;
        const int ref = t < static_cast<int>(target.tet_refs.size()) ? target.tet_refs[t] : 0;
        for (int v : target.tets[t])
            if (region[v] == TransferSource::kAnyRegion || ref < region[v]) region[v] = ref;
    }

    std::vector<TransferSource::Source> sources(nv);
    parallel_for(options.workers, nv, [&](std::size_t first, std::size_t last) {
        for (std::size_t v = first; v < last; ++v)
            sources[v] = source.find(target.points[v], region[v]);
    });

    TransferReport report;
    report.vertices = nv;
    for (const auto& s : sources)
    {
        report.outside += s.outside;
        report.other_region += s.other_region;
        if (s.outside)
            report.max_outside_distance = std::max(report.max_outside_distance, s.distance);
    }
    for (const VertexField& field : fields)
    {
        VertexField carried;
        carried.components = field.components;
        const std::size_t k = field.components;
        carried.values.assign(static_cast<std::size_t>(nv) * k, 0.0);
        parallel_for(options.workers, nv, [&](std::size_t first, std::size_t last) {
            for (std::size_t v = first; v < last; ++v)
            {
                const auto& s = sources[v];
                const TetVertices& tv = source.tet(s.tet);
                for (std::size_t c = 0; c < k; ++c)
                {
                    double value = 0;
                    for (int i = 0; i < 4; ++i) value += s.weights[i] * field.values[tv[i] * k + c];
                    carried.values[v * k + c] = value;
                }
            }
        });
        report.fields.push_back(std::move(carried));
    }
    return report;
}

}  // namespace hdimesh::volume

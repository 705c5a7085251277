// The adaptor on several ranks, ParMmg's scheme on our own decomposition: each rank adapts
// its cells with the faces it shares with another rank frozen (required triangles of
// kRankCutRef: the refinement splits them, both sides alike, nothing else changes them), the
// vertices are numbered again (a cut's by position), and the cells move to the ranks of a
// Morton decomposition whose cuts lie elsewhere (blocks.h's shifted rounds), so the faces
// frozen in one round are adapted in the next. After the last round PETSc builds the
// new DM from the ranks' cells (DMPlexCreateFromCellListParallelPetsc), labels attached.
// Deterministic for a given rank count: every rank runs one thread and every exchange is
// ordered by rank.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common/morton.h"
#include "plex_convert.h"
#include "volume/check/boundary_repair.h"
#include "volume/io/tet_io.h"
#include "volume/mesh/blocks.h"
#include "volume/mesh/tet_tables.h"
#include "volume/size/metric_fields.h"

namespace hdimesh_petsc
{
namespace
{

using hdimesh::volume::TetMesh;
using hdimesh::volume::Vec3;
using Key = std::array<PetscInt, 3>;

/// A rank's cells between rounds.
struct Part
{
    TetMesh mesh;                ///< tets (positive), labelled and boundary triangles
    std::vector<PetscInt> gid;   ///< global id per vertex
    std::vector<double> metric;  ///< per vertex: a size, or 6 values in Medit's order
    int components = 1;          ///< 1 or 6
    std::vector<char> owned;     ///< after number(): this rank gives the vertex to PETSc
    std::vector<hdimesh::volume::Triangle> cut;  ///< after a round: its cut's faces
};

/// Every rank's `mine`, in rank order; counts[r] items came from rank r.
template <class T>
std::vector<T> allgather(MPI_Comm comm, const std::vector<T>& mine, std::vector<int>* counts)
{
    int ranks;
    MPI_Comm_size(comm, &ranks);
    const int bytes = static_cast<int>(mine.size() * sizeof(T));
    std::vector<int> sizes(ranks), offsets(ranks, 0);
    MPI_Allgather(&bytes, 1, MPI_INT, sizes.data(), 1, MPI_INT, comm);
    for (int r = 1; r < ranks; ++r) offsets[r] = offsets[r - 1] + sizes[r - 1];
    std::vector<T> all((offsets[ranks - 1] + sizes[ranks - 1]) / sizeof(T));
    MPI_Allgatherv(mine.data(), bytes, MPI_BYTE, all.data(), sizes.data(), offsets.data(), MPI_BYTE,
                   comm);
    if (counts)
    {
        counts->resize(ranks);
        for (int r = 0; r < ranks; ++r) (*counts)[r] = static_cast<int>(sizes[r] / sizeof(T));
    }
    return all;
}

/// send[r] to rank r; what each rank sent here, in rank order.
template <class T>
std::vector<T> alltoall(MPI_Comm comm, const std::vector<std::vector<T>>& send,
                        std::vector<int>& counts)
{
    const int ranks = static_cast<int>(send.size());
    std::vector<int> sizes(ranks), offsets(ranks, 0), in_sizes(ranks), in_offsets(ranks, 0);
    std::vector<T> flat;
    for (int r = 0; r < ranks; ++r)
    {
        sizes[r] = static_cast<int>(send[r].size() * sizeof(T));
        if (r > 0) offsets[r] = offsets[r - 1] + sizes[r - 1];
        flat.insert(flat.end(), send[r].begin(), send[r].end());
    }
    MPI_Alltoall(sizes.data(), 1, MPI_INT, in_sizes.data(), 1, MPI_INT, comm);
    for (int r = 1; r < ranks; ++r) in_offsets[r] = in_offsets[r - 1] + in_sizes[r - 1];
    std::vector<T> in((in_offsets[ranks - 1] + in_sizes[ranks - 1]) / sizeof(T));
    MPI_Alltoallv(flat.data(), sizes.data(), offsets.data(), MPI_BYTE, in.data(), in_sizes.data(),
                  in_offsets.data(), MPI_BYTE, comm);
    counts.resize(ranks);
    for (int r = 0; r < ranks; ++r) counts[r] = static_cast<int>(in_sizes[r] / sizeof(T));
    return in;
}

Key sorted_key(PetscInt a, PetscInt b, PetscInt c)
{
    Key k{a, b, c};
    std::sort(k.begin(), k.end());
    return k;
}

Key face_key(const Part& p, const hdimesh::volume::Triangle& t)
{
    return sorted_key(p.gid[t[0]], p.gid[t[1]], p.gid[t[2]]);
}

using Point = std::array<double, 3>;

Point position(const Vec3& x) { return {x[0], x[1], x[2]}; }

/// The label values of every rank, as one LabelRefs.
LabelRefs global_refs(MPI_Comm comm, const LabelRefs& local)
{
    LabelRefs all;
    all.values = allgather(comm, local.values, nullptr);
    std::sort(all.values.begin(), all.values.end());
    all.values.erase(std::unique(all.values.begin(), all.values.end()), all.values.end());
    return all;
}

/// dm's cells on this rank (not the overlap's), their faces bdLabel marks and the metric, with
/// PETSc's global vertex numbers.
PetscErrorCode read_part(DM dm, Vec metric, DMLabel bdLabel, DMLabel rgLabel, Part& part,
                         LabelRefs& face_refs, LabelRefs& cell_refs)
{
    PetscFunctionBeginUser;
    MPI_Comm comm;
    PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
    PetscInt cStart, cEnd, fStart, fEnd, vStart, vEnd;
    PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
    PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    LabelRefs local_faces, local_cells;
    PetscCall(label_refs(bdLabel, fStart, fEnd, local_faces));
    // without bdLabel the boundary is marked 1, as "_boundary_" will be
    if (!bdLabel) local_faces.values = {1};
    PetscCall(label_refs(rgLabel, cStart, cEnd, local_cells));
    face_refs = global_refs(comm, local_faces);
    cell_refs = global_refs(comm, local_cells);

    // an overlap's cells are leaves of the point SF: two ranks would adapt them
    PetscSF sf;
    const PetscInt* leaves;
    PetscInt num_leaves;
    PetscCall(DMGetPointSF(dm, &sf));
    PetscCall(PetscSFGetGraph(sf, nullptr, &num_leaves, &leaves, nullptr));
    for (PetscInt i = 0; i < num_leaves; ++i)
    {
        const PetscInt p = leaves ? leaves[i] : i;
        PetscCheck(p < cStart || p >= cEnd, PETSC_COMM_SELF, PETSC_ERR_ARG_WRONG,
                   "hdimesh: cell %" PetscInt_FMT
                   " is another rank's (an overlap): distribute "
                   "the DM with overlap 0",
                   p);
    }

    PlexInput in;
    PetscCall(read_plex(dm, bdLabel, rgLabel, in));
    TetMesh& mesh = in.mesh;
    // read_plex numbered refs by this rank's values: renumber them by every rank's
    for (int& r : mesh.tet_refs)
    {
        PetscInt value;
        r = in.cell_refs.value(r, value) ? cell_refs.ref(value) : 0;
    }
    for (int& r : mesh.triangle_refs)
    {
        PetscInt value;
        r = in.face_refs.value(r, value) ? face_refs.ref(value) : 0;
    }
    // read_plex added the faces on the rank's cut as boundary: they are found again each round
    std::vector<hdimesh::volume::Triangle> triangles;
    std::vector<int> triangle_refs;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        if (mesh.triangle_refs[i] != 0)
        {
            triangles.push_back(mesh.triangles[i]);
            triangle_refs.push_back(mesh.triangle_refs[i]);
        }
    mesh.triangles = std::move(triangles);
    mesh.triangle_refs = std::move(triangle_refs);

    hdimesh::volume::SizeSpec size;
    PetscCall(read_metric(dm, metric, mesh.num_vertices(), size));
    part.components = size.vertex_metrics.empty() ? 1 : 6;
    part.metric = part.components == 1 ? size.vertex_sizes : size.vertex_metrics;
    IS numbering;
    const PetscInt* global;
    PetscCall(DMPlexGetVertexNumbering(dm, &numbering));
    PetscCall(ISGetIndices(numbering, &global));
    part.gid.resize(mesh.num_vertices());
    for (int v = 0; v < mesh.num_vertices(); ++v)
        part.gid[v] = global[v] >= 0 ? global[v] : -(global[v] + 1);
    PetscCall(ISRestoreIndices(numbering, &global));

    part.mesh = std::move(mesh);
    PetscFunctionReturn(0);
}

/// Freezes the faces this rank shares with another (required triangles of kRankCutRef, plus
/// the domain's ref of a labelled one; their vertices required: the refinement splits them,
/// both sides alike, nothing else changes them) and adds the boundary faces no label marks
/// (boundary_ref). `hold`: the refinement may not split them either (kHeldCutRef).
void freeze_cut(MPI_Comm comm, Part& p, int boundary_ref, bool hold)
{
    const int cut_ref = hold ? hdimesh::volume::kHeldCutRef : hdimesh::volume::kRankCutRef;
    TetMesh& mesh = p.mesh;
    mesh.build_adjacency();
    struct Open
    {
        Key key;
        hdimesh::volume::Triangle face;
    };
    std::vector<Open> open;
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
        for (int f = 0; f < 4; ++f)
            if (mesh.neighbors[t][f] == hdimesh::volume::kNoTet)
            {
                const auto& fv = hdimesh::volume::tet::kFaceVertices[f];
                const hdimesh::volume::Triangle face{mesh.tets[t][fv[0]], mesh.tets[t][fv[1]],
                                                     mesh.tets[t][fv[2]]};
                open.push_back({face_key(p, face), face});
            }
    std::vector<Key> mine;
    for (const Open& o : open) mine.push_back(o.key);
    std::sort(mine.begin(), mine.end());
    std::vector<int> counts;
    const std::vector<Key> all = allgather(comm, mine, &counts);
    int rank;
    MPI_Comm_rank(comm, &rank);
    // the other ranks' open faces, sorted
    std::vector<Key> others;
    for (int r = 0, at = 0; r < static_cast<int>(counts.size()); at += counts[r], ++r)
        if (r != rank) others.insert(others.end(), all.begin() + at, all.begin() + at + counts[r]);
    std::sort(others.begin(), others.end());

    std::map<Key, int> triangle_of;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        triangle_of.emplace(face_key(p, mesh.triangles[i]), static_cast<int>(i));
    std::vector<char> frozen(mesh.num_vertices(), 0);
    for (const Open& o : open)
    {
        const bool cut = std::binary_search(others.begin(), others.end(), o.key);
        const auto it = triangle_of.find(o.key);
        int index = it != triangle_of.end() ? it->second : -1;
        if (index < 0) index = mesh.add_triangle(o.face, cut ? cut_ref : boundary_ref);
        if (!cut) continue;
        // the cut is checked and modelled as a cut, a label on it kept in its ref
        int& ref = mesh.triangle_refs[index];
        if (!hdimesh::volume::is_rank_cut_ref(ref)) ref = cut_ref + std::max(ref, 0);
        mesh.required_triangles.push_back(index);
        for (int v : o.face) frozen[v] = 1;
    }
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (frozen[v]) mesh.required_vertices.push_back(v);
}

/// Triangle i's ref on the domain: its own, or a labelled cut face's label; false for a cut
/// face no label marks.
bool domain_ref(const TetMesh& mesh, std::size_t i, int& ref)
{
    ref = mesh.triangle_refs[i];
    if (!hdimesh::volume::is_rank_cut_ref(ref)) return true;
    ref = hdimesh::volume::rank_cut_domain_ref(ref);
    return ref > 0;
}

/// The domain's boundary, every rank's piece of it once (a labelled face on a cut too), with
/// the curves where regions meet: the geometry every round's model is fitted to.
std::shared_ptr<const TetMesh> gather_boundary(MPI_Comm comm, const Part& p)
{
    const TetMesh& mesh = p.mesh;
    std::vector<std::array<PetscInt, 4>> faces;  // global ids, ref
    std::vector<std::array<double, 9>> corners;  // their positions
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        int ref;
        if (!domain_ref(mesh, i, ref)) continue;
        const auto& t = mesh.triangles[i];
        faces.push_back({p.gid[t[0]], p.gid[t[1]], p.gid[t[2]], ref});
        std::array<double, 9> x;
        for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 3; ++d) x[3 * k + d] = mesh.points[t[k]][d];
        corners.push_back(x);
    }
    const auto all_faces = allgather(comm, faces, nullptr);
    const auto all_corners = allgather(comm, corners, nullptr);
    auto geometry = std::make_shared<TetMesh>();
    std::map<PetscInt, int> point_of;
    std::map<Key, char> seen;
    for (std::size_t i = 0; i < all_faces.size(); ++i)
    {
        const auto& f = all_faces[i];
        if (!seen.emplace(sorted_key(f[0], f[1], f[2]), 1).second) continue;
        hdimesh::volume::Triangle t;
        for (int k = 0; k < 3; ++k)
        {
            const auto [it, added] = point_of.emplace(f[k], geometry->num_vertices());
            if (added)
            {
                const double* x = &all_corners[i][3 * k];
                geometry->add_vertex(Vec3(x[0], x[1], x[2]));
            }
            t[k] = it->second;
        }
        geometry->add_triangle(t, static_cast<int>(f[3]));
    }
    geometry->classify_vertices();
    hdimesh::volume::mark_region_curves(*geometry);
    return geometry;
}

/// The adapted cells as the next round's part, to be numbered: the metric the field's at the
/// vertices, the cut's faces (old ones and the children both sides made) kept aside and
/// dropped but labelled ones.
Part adapted_part(hdimesh::coupling::AdaptResult& result, int components)
{
    Part p;
    p.mesh = std::move(result.mesh);
    p.mesh.compact();
    TetMesh& mesh = p.mesh;
    p.gid.assign(mesh.num_vertices(), -1);
    p.components = components;
    hdimesh::Solutions at = hdimesh::volume::field_at_vertices(mesh, *result.field);
    p.metric = std::move(at.solutions.at(0).values);
    std::vector<hdimesh::volume::Triangle> triangles;
    std::vector<int> refs;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        if (hdimesh::volume::is_rank_cut_ref(mesh.triangle_refs[i]))
            p.cut.push_back(mesh.triangles[i]);
        int ref;
        if (!domain_ref(mesh, i, ref)) continue;
        triangles.push_back(mesh.triangles[i]);
        refs.push_back(ref);
    }
    mesh.triangles = std::move(triangles);
    mesh.triangle_refs = std::move(refs);
    // the cut's requirements go with it (the next round's cut is found again)
    mesh.required_triangles.clear();
    mesh.required_vertices.clear();
    return p;
}

/// A shared vertex's position and its new global id.
struct Named
{
    Point x;
    PetscInt gid;
    bool operator<(const Named& o) const { return x < o.x || (x == o.x && gid < o.gid); }
};

/// New global ids, owned ones contiguous per rank: a vertex on the cut (found on the other
/// side by its exact position: both sides made the same midpoints) belongs to the lowest rank
/// that holds it, every other vertex to its rank.
void number(MPI_Comm comm, Part& p)
{
    int rank;
    MPI_Comm_rank(comm, &rank);
    const int nv = p.mesh.num_vertices();
    std::vector<char> shared(nv, 0);  // on the cut
    for (const auto& t : p.cut)
        for (int v : t) shared[v] = 1;
    std::vector<Point> mine;
    for (int v = 0; v < nv; ++v)
        if (shared[v]) mine.push_back(position(p.mesh.points[v]));
    std::sort(mine.begin(), mine.end());
    std::vector<int> counts;
    const std::vector<Point> all = allgather(comm, mine, &counts);
    std::vector<Point> lower;  // shared positions a lower rank holds
    for (int r = 0, at = 0; r < rank; at += counts[r], ++r)
        lower.insert(lower.end(), all.begin() + at, all.begin() + at + counts[r]);
    std::sort(lower.begin(), lower.end());
    p.owned.assign(nv, 1);
    PetscInt n_owned = 0;
    for (int v = 0; v < nv; ++v)
    {
        if (shared[v] && std::binary_search(lower.begin(), lower.end(), position(p.mesh.points[v])))
            p.owned[v] = 0;
        n_owned += p.owned[v];
    }
    PetscInt first = 0;
    MPI_Exscan(&n_owned, &first, 1, MPIU_INT, MPI_SUM, comm);
    if (rank == 0) first = 0;
    std::vector<Named> named;  // the owned shared vertices
    for (int v = 0, next = 0; v < nv; ++v)
        if (p.owned[v])
        {
            p.gid[v] = first + next++;
            if (shared[v]) named.push_back({position(p.mesh.points[v]), p.gid[v]});
        }
    std::vector<Named> every = allgather(comm, named, nullptr);
    std::sort(every.begin(), every.end());
    for (int v = 0; v < nv; ++v)
        if (!p.owned[v])
        {
            const Point x = position(p.mesh.points[v]);
            const auto it = std::lower_bound(every.begin(), every.end(), Named{x, PETSC_MIN_INT});
            // (the lowest rank holding x owns it and named it)
            p.gid[v] = it->gid;
        }
}

/// The faces of the ranks' cuts that did not come back from both sides split alike (on every
/// rank): the refinement marked an edge of the cut on one side only (a deferred split, a stalled
/// pass).
int cut_mismatches(MPI_Comm comm, const Part& p)
{
    std::vector<Key> mine;
    for (const auto& t : p.cut) mine.push_back(face_key(p, t));
    std::sort(mine.begin(), mine.end());
    std::vector<Key> all = allgather(comm, mine, nullptr);
    std::sort(all.begin(), all.end());
    int unmatched = 0;
    for (const Key& k : mine)
    {
        const auto range = std::equal_range(all.begin(), all.end(), k);
        unmatched += range.second - range.first != 2;
    }
    MPI_Allreduce(MPI_IN_PLACE, &unmatched, 1, MPI_INT, MPI_SUM, comm);
    return unmatched;
}

/// The rank of each tet on a Morton curve of the centroids over every rank's tets, in equal
/// runs; `round` shifts the curve's cells as blocks.h's rounds do, so the cuts move.
std::vector<int> morton_ranks(MPI_Comm comm, const Part& p, int round)
{
    int ranks, rank;
    MPI_Comm_size(comm, &ranks);
    MPI_Comm_rank(comm, &rank);
    const TetMesh& mesh = p.mesh;
    const int nt = mesh.num_tet_slots();
    std::vector<Vec3> centroids(nt);
    double low[3] = {1e300, 1e300, 1e300}, high[3] = {-1e300, -1e300, -1e300};
    for (int t = 0; t < nt; ++t)
    {
        const auto& tv = mesh.tets[t];
        centroids[t] = 0.25 * (mesh.points[tv[0]] + mesh.points[tv[1]] + mesh.points[tv[2]] +
                               mesh.points[tv[3]]);
        for (int k = 0; k < 3; ++k)
        {
            low[k] = std::min(low[k], centroids[t][k]);
            high[k] = std::max(high[k], centroids[t][k]);
        }
    }
    MPI_Allreduce(MPI_IN_PLACE, low, 3, MPI_DOUBLE, MPI_MIN, comm);
    MPI_Allreduce(MPI_IN_PLACE, high, 3, MPI_DOUBLE, MPI_MAX, comm);
    const double extent = std::max({high[0] - low[0], high[1] - low[1], high[2] - low[2], 1e-300});
    // a part spans about extent / cbrt(ranks); the shift moves the cuts by a part of that
    const double shift = round * 0.381966 * extent / std::cbrt(static_cast<double>(ranks));
    const double scale = static_cast<double>(hdimesh::kMortonCellMax) / (extent + shift);
    std::vector<std::uint64_t> keys(nt);
    for (int t = 0; t < nt; ++t)
    {
        std::uint64_t cell[3];
        for (int k = 0; k < 3; ++k)
            cell[k] = static_cast<std::uint64_t>((centroids[t][k] - low[k] + shift) * scale);
        // the axes turn each round too: with few ranks the top-level cut is a plane normal to
        // another axis, so the faces frozen in one round lie inside a part in the next
        keys[t] =
            hdimesh::morton_key(cell[round % 3], cell[(round + 1) % 3], cell[(round + 2) % 3]);
    }
    std::vector<int> counts;
    const std::vector<std::uint64_t> all = allgather(comm, keys, &counts);
    // (key, rank, index): one order on every rank
    std::vector<std::array<std::uint64_t, 3>> order;
    order.reserve(all.size());
    for (int r = 0, at = 0; r < ranks; at += counts[r], ++r)
        for (int i = 0; i < counts[r]; ++i)
            order.push_back(
                {all[at + i], static_cast<std::uint64_t>(r), static_cast<std::uint64_t>(i)});
    std::sort(order.begin(), order.end());
    // the runs start elsewhere on the curve each round (a cyclic shift by a golden fraction):
    // with median cuts every round's cut would pass through the same middle
    std::vector<int> target(nt, rank);
    const long long n = static_cast<long long>(order.size());
    const double phase = round * 0.381966 - std::floor(round * 0.381966);
    const long long offset = static_cast<long long>(phase * static_cast<double>(n));
    for (long long i = 0; i < n; ++i)
        if (order[i][1] == static_cast<std::uint64_t>(rank))
            target[order[i][2]] = static_cast<int>((i + offset) % n * ranks / n);
    return target;
}

/// Moves each tet to its rank in `target`, with its vertices (position, metric) and the
/// triangles on its faces; each rank's part comes out in one order whatever the old one.
void migrate(MPI_Comm comm, Part& p, const std::vector<int>& target)
{
    int ranks;
    MPI_Comm_size(comm, &ranks);
    const TetMesh& mesh = p.mesh;
    const int nc = p.components;
    std::map<Key, int> triangle_of;
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
        triangle_of.emplace(face_key(p, mesh.triangles[i]), static_cast<int>(i));
    // per rank: ints (3 counts, then tets [4 ids, ref], vertex ids, triangles [3 ids, ref])
    // and doubles (per vertex: x y z, the metric)
    std::vector<std::vector<PetscInt>> ints(ranks);
    std::vector<std::vector<double>> reals(ranks);
    for (int r = 0; r < ranks; ++r)
    {
        std::vector<int> tets, vertices, triangles;
        for (int t = 0; t < mesh.num_tet_slots(); ++t)
            if (target[t] == r) tets.push_back(t);
        if (tets.empty()) continue;
        for (int t : tets)
        {
            for (int v : mesh.tets[t]) vertices.push_back(v);
            for (int f = 0; f < 4; ++f)
            {
                const auto& fv = hdimesh::volume::tet::kFaceVertices[f];
                const auto it = triangle_of.find(
                    face_key(p, {mesh.tets[t][fv[0]], mesh.tets[t][fv[1]], mesh.tets[t][fv[2]]}));
                if (it != triangle_of.end()) triangles.push_back(it->second);
            }
        }
        std::sort(vertices.begin(), vertices.end());
        vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
        std::sort(triangles.begin(), triangles.end());
        triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
        std::vector<PetscInt>& out = ints[r];
        out = {static_cast<PetscInt>(tets.size()), static_cast<PetscInt>(vertices.size()),
               static_cast<PetscInt>(triangles.size())};
        for (int t : tets)
        {
            for (int v : mesh.tets[t]) out.push_back(p.gid[v]);
            out.push_back(mesh.tet_refs[t]);
        }
        for (int v : vertices)
        {
            out.push_back(p.gid[v]);
            for (int k = 0; k < 3; ++k) reals[r].push_back(mesh.points[v][k]);
            reals[r].insert(reals[r].end(), p.metric.begin() + nc * v,
                            p.metric.begin() + nc * (v + 1));
        }
        for (int i : triangles)
        {
            for (int v : mesh.triangles[i]) out.push_back(p.gid[v]);
            out.push_back(mesh.triangle_refs[i]);
        }
    }
    std::vector<int> int_counts, real_counts;
    const std::vector<PetscInt> in = alltoall(comm, ints, int_counts);
    const std::vector<double> in_reals = alltoall(comm, reals, real_counts);

    // what arrived, in an order that does not depend on where it came from: vertices by
    // position, tets and triangles by their vertices (turned to start at the least)
    std::map<PetscInt, std::vector<double>> vertex_data;  // the first copy: the lowest rank's
    std::vector<std::array<PetscInt, 5>> tets;
    std::vector<std::array<PetscInt, 4>> triangles;
    for (std::size_t at = 0, real_at = 0; at < in.size();)
    {
        const PetscInt nt = in[at], nv = in[at + 1], ntri = in[at + 2];
        const PetscInt* t = &in[at + 3];
        for (PetscInt i = 0; i < nt; ++i, t += 5) tets.push_back({t[0], t[1], t[2], t[3], t[4]});
        for (PetscInt i = 0; i < nv; ++i, real_at += 3 + nc)
            vertex_data.emplace(
                in[at + 3 + 5 * nt + i],
                std::vector<double>(&in_reals[real_at], &in_reals[real_at] + 3 + nc));
        const PetscInt* f = &in[at + 3 + 5 * nt + nv];
        for (PetscInt i = 0; i < ntri; ++i, f += 4) triangles.push_back({f[0], f[1], f[2], f[3]});
        at += 3 + 5 * nt + nv + 4 * ntri;
    }
    std::vector<std::pair<std::vector<double>, PetscInt>> vertices;
    for (auto& [g, data] : vertex_data) vertices.push_back({std::move(data), g});
    std::sort(vertices.begin(), vertices.end());
    Part next;
    next.components = nc;
    std::map<PetscInt, int> local;
    for (const auto& [data, g] : vertices)
    {
        local[g] = next.mesh.add_vertex(Vec3(data[0], data[1], data[2]));
        next.gid.push_back(g);
        next.metric.insert(next.metric.end(), data.begin() + 3, data.end());
    }
    std::vector<std::array<int, 5>> local_tets;
    for (const auto& t : tets)
    {
        std::array<int, 4> v{local[t[0]], local[t[1]], local[t[2]], local[t[3]]};
        // an even permutation brings the least first: the orientation stays
        const int m = static_cast<int>(std::min_element(v.begin(), v.end()) - v.begin());
        if (m == 1) v = {v[1], v[0], v[3], v[2]};
        if (m == 2) v = {v[2], v[3], v[0], v[1]};
        if (m == 3) v = {v[3], v[2], v[1], v[0]};
        local_tets.push_back({v[0], v[1], v[2], v[3], static_cast<int>(t[4])});
    }
    std::sort(local_tets.begin(), local_tets.end());
    for (const auto& t : local_tets) next.mesh.add_tet({t[0], t[1], t[2], t[3]}, t[4]);
    std::vector<std::array<int, 4>> local_triangles;
    for (const auto& f : triangles)
    {
        std::array<int, 3> v{local[f[0]], local[f[1]], local[f[2]]};
        std::rotate(v.begin(), std::min_element(v.begin(), v.end()), v.end());
        local_triangles.push_back({v[0], v[1], v[2], static_cast<int>(f[3])});
    }
    std::sort(local_triangles.begin(), local_triangles.end());
    std::map<Key, char> seen;
    for (const auto& f : local_triangles)
    {
        if (seen.emplace(sorted_key(f[0], f[1], f[2]), 1).second)
            next.mesh.add_triangle({f[0], f[1], f[2]}, f[3]);
    }
    p = std::move(next);
}

/// The new DM from every rank's cells (owned vertices give the coordinates), with the labels.
PetscErrorCode write_distributed(MPI_Comm comm, const Part& p, const LabelRefs& face_refs,
                                 const LabelRefs& cell_refs, const char* bd_name,
                                 const char* rg_name, DM* dmNew)
{
    PetscFunctionBeginUser;
    const TetMesh& mesh = p.mesh;
    const PetscInt nc = mesh.num_tet_slots();
    std::vector<PetscInt> cells(4 * static_cast<std::size_t>(nc));
    for (PetscInt c = 0; c < nc; ++c)
    {
        const auto& t = mesh.tets[c];
        const int order[4] = {t[1], t[0], t[2], t[3]};  // Plex's inward order
        for (int k = 0; k < 4; ++k) cells[4 * c + k] = p.gid[order[k]];
    }
    std::vector<PetscReal> xyz;
    PetscInt n_owned = 0;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (p.owned[v])
        {
            ++n_owned;
            for (int k = 0; k < 3; ++k) xyz.push_back(mesh.points[v][k]);
        }
    // (3.18 crashes when asked for the vertex SF and the vertices' global ids)
    PetscCall(DMPlexCreateFromCellListParallelPetsc(comm, 3, nc, n_owned, PETSC_DECIDE, 4,
                                                    PETSC_TRUE, cells.data(), 3, xyz.data(),
                                                    nullptr, nullptr, dmNew));
    PetscInt vStart, vEnd;
    PetscCall(DMPlexGetDepthStratum(*dmNew, 0, &vStart, &vEnd));
    // PETSc numbers a rank's vertices in the order of their global ids: checked on the
    // coordinates it fetched
    std::vector<PetscInt> ids = cells;
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    PetscCheck(static_cast<PetscInt>(ids.size()) == vEnd - vStart, PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "hdimesh: the new DM has %" PetscInt_FMT " vertices here, not %zu", vEnd - vStart,
               ids.size());
    std::map<PetscInt, PetscInt> point_of;
    for (std::size_t i = 0; i < ids.size(); ++i)
        point_of[ids[i]] = vStart + static_cast<PetscInt>(i);
    Vec coordinates;
    PetscSection section;
    const PetscScalar* x;
    PetscCall(DMGetCoordinatesLocal(*dmNew, &coordinates));
    PetscCall(DMGetCoordinateSection(*dmNew, &section));
    PetscCall(VecGetArrayRead(coordinates, &x));
    int misplaced = 0;
    for (int v = 0; v < mesh.num_vertices(); ++v)
    {
        PetscInt off;
        PetscCall(PetscSectionGetOffset(section, point_of.at(p.gid[v]), &off));
        for (int k = 0; k < 3; ++k) misplaced += PetscRealPart(x[off + k]) != mesh.points[v][k];
    }
    PetscCall(VecRestoreArrayRead(coordinates, &x));
    PetscCheck(misplaced == 0, PETSC_COMM_SELF, PETSC_ERR_PLIB,
               "hdimesh: the new DM's vertices are not in the order of their global ids");

    std::vector<PetscInt> point(mesh.num_vertices());
    for (int v = 0; v < mesh.num_vertices(); ++v) point[v] = point_of.at(p.gid[v]);
    PetscCall(attach_labels(*dmNew, mesh, point, face_refs, cell_refs, bd_name, rg_name));
    PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode adapt_distributed(DM dm, Vec metric, DMLabel bdLabel, DMLabel rgLabel,
                                 const char* bd_name, const char* rg_name, DM* dmNew)
{
    PetscFunctionBeginUser;
    MPI_Comm comm;
    PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
    Part part;
    LabelRefs face_refs, cell_refs;
    // a rank that refuses its part (an overlap, a bad metric) tells the others, who would
    // otherwise wait for it in the first exchange
    const PetscErrorCode read = read_part(dm, metric, bdLabel, rgLabel, part, face_refs, cell_refs);
    int refused = read != 0;
    PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &refused, 1, MPI_INT, MPI_MAX, comm));
    PetscCall(read);
    PetscCheck(!refused, comm, PETSC_ERR_ARG_WRONG, "hdimesh: another rank refused its part");
    hdimesh::coupling::AdaptRequest request;
    PetscCall(read_options(dm, request));
    // a piece's boundary has cuts, required triangles the coupled surface pass refuses: no
    // surface pass there (where one rank's run has one, the ranks' result is that run's
    // without it: docs/tuning.md), and no sliding of boundary vertices, whose classes on the
    // piece do not know the domain's sharp edges
    request.switches.nosurf = true;
    // the first decomposition is ours too: the result depends on the rank count, not on how
    // the DM was distributed
    migrate(comm, part, morton_ranks(comm, part, 0));
    PetscInt rounds;
    PetscCall(DMPlexMetricGetNumIterations(dm, &rounds));
    rounds = std::max<PetscInt>(rounds, 1);
    // one more round, swaps and smoothing only, around the last round's cut
    const PetscInt all_rounds = rounds + 1;
    for (PetscInt round = 0; round < all_rounds; ++round)
    {
        if (round == rounds) request.switches.optim = true;
        // a round whose cut came back split on one side only runs again with the cut held
        const Part before = part;
        for (bool hold = false;; hold = true)
        {
            freeze_cut(comm, part, bdLabel ? 0 : face_refs.ref(1), hold);
            if (!request.geometry) request.geometry = gather_boundary(comm, part);
            request.size.vertex_sizes.clear();
            request.size.vertex_metrics.clear();
            (part.components == 1 ? request.size.vertex_sizes : request.size.vertex_metrics) =
                part.metric;
            hdimesh::coupling::AdaptResult result;
            const std::string failure = run_request(std::move(part.mesh), request, result);
            // every rank learns of a failure, so none waits in the next exchange
            int failed = failure.empty() ? 0 : 1;
            PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, comm));
            PetscCheck(failure.empty(), PETSC_COMM_SELF, PETSC_ERR_LIB, "hdimesh: round %d: %s",
                       static_cast<int>(round), failure.c_str());
            PetscCheck(!failed, comm, PETSC_ERR_LIB, "hdimesh: another rank failed in round %d",
                       static_cast<int>(round));
            part = adapted_part(result, part.components);
            number(comm, part);
            const int mismatched = cut_mismatches(comm, part);
            if (mismatched == 0) break;
            PetscCheck(!hold, comm, PETSC_ERR_PLIB,
                       "hdimesh: round %d: %d faces between ranks came back split on one side "
                       "only, the cut held",
                       static_cast<int>(round), mismatched);
            part = before;
        }
        if (round + 1 < all_rounds) migrate(comm, part, morton_ranks(comm, part, round + 1));
    }
    PetscCall(write_distributed(comm, part, face_refs, cell_refs, bd_name, rg_name, dmNew));
    PetscFunctionReturn(0);
}

}  // namespace hdimesh_petsc

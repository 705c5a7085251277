#pragma once
// Solution transfer: fields given at the vertices of a tet mesh carried onto another mesh of
// the same domain (the adapted one). Each new vertex takes the P1 interpolation in the source
// tet that contains it, from a tet of its own region where regions meet (the lowest ref among
// the new tets around it), and, outside every source tet (a boundary moved onto the curved
// model), the P1 function of the nearest source tet evaluated there: linear fields are carried
// exactly, unlike a nearest-vertex fallback (ParMmg's).

#include <array>
#include <limits>
#include <utility>
#include <vector>

#include "common/parallel.h"
#include "volume/mesh/point_locator.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// A field at a mesh's vertices: `components` values per vertex, vertex after vertex.
struct VertexField
{
    int components = 1;
    std::vector<double> values;
};

/// The mesh fields are carried from, kept apart from it (adapt then changes the mesh): its
/// point locator, tets and refs, the tets around each vertex and the tet of each boundary face.
class TransferSource
{
public:
    /// Throws InputError as TetLocator does (no live tet, a bad id, a non-positive tet).
    explicit TransferSource(const TetMesh& mesh);

    int num_vertices() const { return static_cast<int>(points_.size()); }

    /// Where target point p takes its values: the tet (id in the source) and the weights of
    /// its vertices (sum 1; some negative outside the tet).
    struct Source
    {
        int tet = -1;
        std::array<double, 4> weights{};
        bool outside = false;       ///< p is in no source tet: extrapolated
        bool other_region = false;  ///< p lies in a tet of another ref than the wanted one
        double distance = 0;        ///< outside: p's distance to the source's boundary
    };
    /// The tet for p in region `ref` (any region when ref is kAnyRegion).
    Source find(const Vec3& p, int ref) const;

    const TetVertices& tet(int t) const { return tets_[t]; }

    static constexpr int kAnyRegion = std::numeric_limits<int>::min();

private:
    std::array<double, 4> weights(int t, const Vec3& p) const;
    int tet_of_boundary_face(Triangle face) const;
    /// Among the tets of ref `ref` within a few vertex-sharing rings of `from`, the one p is
    /// least outside of (largest minimum weight); -1 when none.
    int nearest_in_region(int from, const Vec3& p, int ref) const;

    TetLocator locator_;
    std::vector<Vec3> points_;
    std::vector<TetVertices> tets_;  ///< the source's slots (dead ones never referenced)
    std::vector<int> tet_refs_;
    std::vector<int> vertex_tets_start_, vertex_tets_;      ///< live tets around each vertex
    std::vector<std::pair<Triangle, int>> boundary_faces_;  ///< sorted face -> its tet, by face
};

struct TransferOptions
{
    Workers* workers = nullptr;  ///< null: one thread; the result is the same for any count
};

struct TransferReport
{
    std::vector<VertexField> fields;  ///< at the target's vertices, in the order given
    int vertices = 0;                 ///< target vertices
    int outside = 0;       ///< in no source tet: extrapolated from the nearest source tet
    int other_region = 0;  ///< located in another region's tet, taken from their own region's
    double max_outside_distance = 0;  ///< the farthest outside vertex from the source boundary
};

/// Throws InputError naming the first field whose component count is below 1 or whose size is
/// not num_vertices x components.
void check_vertex_fields(const std::vector<VertexField>& fields, int num_vertices);

/// Carries `fields` (each source vertices x components values) onto `target`'s vertices.
/// Throws InputError naming the field when its size does not match the source or its
/// component count is below 1.
TransferReport transfer_fields(const TransferSource& source, const std::vector<VertexField>& fields,
                               const TetMesh& target, const TransferOptions& options = {});

}  // namespace hdimesh::volume

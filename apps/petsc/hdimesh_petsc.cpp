// The PETSc adaptor: a DMPlex and its DMPlexMetric in, one run_adapt call, a DMPlex out. Like
// the other apps it only converts: the tets, the labelled faces and cells and the metric become
// an AdaptRequest; the result becomes a new DMPlex with the same labels.
#include "hdimesh_petsc.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "common/errors.h"
#include "coupling/adapt_request.h"
#include "plex_convert.h"
#include "volume/io/tet_io.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh_petsc
{

using hdimesh::volume::TetMesh;
using hdimesh::volume::Vec3;

/// The values label gives points [pStart, pEnd), sorted and without the default (-1).
PetscErrorCode label_refs(DMLabel label, PetscInt pStart, PetscInt pEnd, LabelRefs& refs)
{
    PetscFunctionBeginUser;
    refs.values.clear();
    if (label)
    {
        for (PetscInt p = pStart; p < pEnd; ++p)
        {
            PetscInt value;
            PetscCall(DMLabelGetValue(label, p, &value));
            if (value != -1) refs.values.push_back(value);
        }
        std::sort(refs.values.begin(), refs.values.end());
        refs.values.erase(std::unique(refs.values.begin(), refs.values.end()), refs.values.end());
    }
    PetscFunctionReturn(0);
}

/// The vertex points in the closure of point p, in closure order.
PetscErrorCode closure_vertices(DM dm, PetscInt p, PetscInt vStart, PetscInt vEnd,
                                std::vector<PetscInt>& out)
{
    PetscFunctionBeginUser;
    out.clear();
    PetscInt* closure = nullptr;
    PetscInt size = 0;
    PetscCall(DMPlexGetTransitiveClosure(dm, p, PETSC_TRUE, &size, &closure));
    for (PetscInt i = 0; i < 2 * size; i += 2)
        if (closure[i] >= vStart && closure[i] < vEnd) out.push_back(closure[i]);
    PetscCall(DMPlexRestoreTransitiveClosure(dm, p, PETSC_TRUE, &size, &closure));
    PetscFunctionReturn(0);
}

double signed_volume(const TetMesh& m, const std::array<int, 4>& t)
{
    const Vec3 a = m.points[t[1]] - m.points[t[0]];
    const Vec3 b = m.points[t[2]] - m.points[t[0]];
    const Vec3 c = m.points[t[3]] - m.points[t[0]];
    return a.dot(b.cross(c));
}

/// dm's tets (positive), its coordinates, every boundary face and every face bdLabel marks as
/// triangles (refs from bdLabel; 0 for an unmarked boundary face) and rgLabel's cell refs.
PetscErrorCode read_plex(DM dm, DMLabel bdLabel, DMLabel rgLabel, PlexInput& in)
{
    PetscFunctionBeginUser;
    PetscInt cStart, cEnd, fStart, fEnd, vStart, vEnd;
    PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
    PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
    PetscCall(DMPlexGetDepthStratum(dm, 0, &vStart, &vEnd));
    TetMesh& mesh = in.mesh;

    Vec coordinates;
    PetscSection coord_section;
    const PetscScalar* xyz;
    PetscCall(DMGetCoordinatesLocal(dm, &coordinates));
    PetscCall(DMGetCoordinateSection(dm, &coord_section));
    PetscCall(VecGetArrayRead(coordinates, &xyz));
    for (PetscInt v = vStart; v < vEnd; ++v)
    {
        PetscInt off;
        PetscCall(PetscSectionGetOffset(coord_section, v, &off));
        mesh.points.emplace_back(PetscRealPart(xyz[off]), PetscRealPart(xyz[off + 1]),
                                 PetscRealPart(xyz[off + 2]));
    }
    PetscCall(VecRestoreArrayRead(coordinates, &xyz));

    PetscCall(label_refs(rgLabel, cStart, cEnd, in.cell_refs));
    std::vector<PetscInt> vs;
    for (PetscInt c = cStart; c < cEnd; ++c)
    {
        DMPolytopeType type;
        PetscCall(DMPlexGetCellType(dm, c, &type));
        PetscCheck(type == DM_POLYTOPE_TETRAHEDRON, PETSC_COMM_SELF, PETSC_ERR_SUP,
                   "hdimesh adapts tetrahedra; cell %" PetscInt_FMT " is a %s", c,
                   DMPolytopeTypes[type]);
        PetscCall(closure_vertices(dm, c, vStart, vEnd, vs));
        std::array<int, 4> t;
        for (int k = 0; k < 4; ++k) t[k] = static_cast<int>(vs[k] - vStart);
        // Plex lists a tet's vertices inward; ours turn outward
        if (signed_volume(mesh, t) < 0) std::swap(t[0], t[1]);
        PetscInt value = -1;
        if (rgLabel) PetscCall(DMLabelGetValue(rgLabel, c, &value));
        mesh.add_tet(t, in.cell_refs.ref(value));
    }

    // every boundary face, so the mesh's boundary is whole even where bdLabel is silent
    DMLabel outer;
    PetscCall(DMLabelCreate(PETSC_COMM_SELF, "hdimesh_outer", &outer));
    PetscCall(DMPlexMarkBoundaryFaces(dm, 1, outer));
    PetscCall(label_refs(bdLabel, fStart, fEnd, in.face_refs));
    for (PetscInt f = fStart; f < fEnd; ++f)
    {
        PetscInt value = -1, on_boundary = -1;
        if (bdLabel) PetscCall(DMLabelGetValue(bdLabel, f, &value));
        PetscCall(DMLabelGetValue(outer, f, &on_boundary));
        if (value == -1 && on_boundary == -1) continue;
        PetscCall(closure_vertices(dm, f, vStart, vEnd, vs));
        std::array<int, 3> tri{static_cast<int>(vs[0] - vStart), static_cast<int>(vs[1] - vStart),
                               static_cast<int>(vs[2] - vStart)};
        // outward from the face's first cell: its fourth vertex lies behind the triangle
        const PetscInt* support;
        PetscCall(DMPlexGetSupport(dm, f, &support));
        PetscCall(closure_vertices(dm, support[0], vStart, vEnd, vs));
        int apex = -1;
        for (PetscInt w : vs)
            if (std::find(tri.begin(), tri.end(), static_cast<int>(w - vStart)) == tri.end())
                apex = static_cast<int>(w - vStart);
        if (signed_volume(mesh, {tri[0], tri[1], tri[2], apex}) > 0) std::swap(tri[0], tri[1]);
        mesh.add_triangle(tri, in.face_refs.ref(value));
    }
    PetscCall(DMLabelDestroy(&outer));
    PetscFunctionReturn(0);
}

/// The metric Vec as sizes (isotropic) or Medit-order tensors per vertex, checked.
PetscErrorCode read_metric(DM dm, Vec metric, int nv, hdimesh::volume::SizeSpec& size)
{
    PetscFunctionBeginUser;
    PetscBool isotropic, uniform;
    PetscCall(DMPlexMetricIsIsotropic(dm, &isotropic));
    PetscCall(DMPlexMetricIsUniform(dm, &uniform));
    PetscInt n;
    PetscCall(VecGetLocalSize(metric, &n));
    const PetscInt expected = uniform ? 1 : isotropic ? nv : 9 * static_cast<PetscInt>(nv);
    PetscCheck(n >= expected, PETSC_COMM_SELF, PETSC_ERR_ARG_SIZ,
               "hdimesh: the metric holds %" PetscInt_FMT
               " values for %d vertices; give the "
               "local vector of DMPlexMetricCreate (%" PetscInt_FMT " values)",
               n, nv, expected);
    const PetscScalar* m;
    PetscCall(VecGetArrayRead(metric, &m));
    if (isotropic || uniform)
    {
        size.vertex_sizes.resize(nv);
        for (int v = 0; v < nv; ++v)
        {
            const double lambda = PetscRealPart(m[uniform ? 0 : v]);
            PetscCheck(lambda > 0 && std::isfinite(lambda), PETSC_COMM_SELF,
                       PETSC_ERR_ARG_OUTOFRANGE,
                       "hdimesh: the metric at vertex %d is %g, not positive", v, lambda);
            size.vertex_sizes[v] = 1.0 / std::sqrt(lambda);
        }
    }
    else
    {
        // PETSc's full row-major 3x3 to Medit's m11 m12 m22 m13 m23 m33
        static const int kEntry[6] = {0, 1, 4, 2, 5, 8};
        size.vertex_metrics.resize(6 * static_cast<std::size_t>(nv));
        for (int v = 0; v < nv; ++v)
            for (int k = 0; k < 6; ++k)
                size.vertex_metrics[6 * v + k] = PetscRealPart(m[9 * v + kEntry[k]]);
    }
    PetscCall(VecRestoreArrayRead(metric, &m));
    PetscFunctionReturn(0);
}

/// PETSc's metric options that have a meaning here, as Mmg's switches; the report to PETSc's
/// output when verbose.
PetscErrorCode read_options(DM dm, hdimesh::coupling::AdaptRequest& request)
{
    PetscFunctionBeginUser;
    PetscReal hmin, hmax, gradation, hausd;
    PetscBool noinsert, noswap, nomove, nosurf;
    PetscInt verbosity, threads = 1;
    PetscCall(DMPlexMetricGetMinimumMagnitude(dm, &hmin));
    PetscCall(DMPlexMetricGetMaximumMagnitude(dm, &hmax));
    PetscCall(DMPlexMetricGetGradationFactor(dm, &gradation));
    PetscCall(DMPlexMetricGetHausdorffNumber(dm, &hausd));
    PetscCall(DMPlexMetricNoInsertion(dm, &noinsert));
    PetscCall(DMPlexMetricNoSwapping(dm, &noswap));
    PetscCall(DMPlexMetricNoMovement(dm, &nomove));
    PetscCall(DMPlexMetricNoSurf(dm, &nosurf));
    PetscCall(DMPlexMetricGetVerbosity(dm, &verbosity));
    // one thread per rank unless asked: ranks already share the cores
    PetscCall(
        PetscOptionsGetInt(nullptr, nullptr, "-dm_adaptor_hdimesh_threads", &threads, nullptr));
    // PETSc's defaults (1e-30, 1e30) mean "no bound"
    if (hmin > 1e-29) request.size.hmin = hmin;
    if (hmax < 1e29) request.size.hmax = hmax;
    if (gradation > 1) request.size.hgrad = gradation;
    if (hausd > 0) request.hausd = hausd;
    request.switches.noinsert = noinsert;
    request.switches.noswap = noswap;
    request.switches.nomove = nomove;
    request.switches.nosurf = nosurf;
    request.verbosity = std::clamp<int>(static_cast<int>(verbosity), 0, 2);
    request.threads = static_cast<int>(threads);
    request.source = "DMPlex";
    if (request.verbosity > 0)
        request.messages = [](hdimesh::MessageKind kind, const std::string& text) {
            // a log, not a terminal: no status lines that overwrite each other
            if (kind != hdimesh::MessageKind::Progress)
                PetscPrintf(PETSC_COMM_SELF, "%s", text.c_str());
        };
    PetscFunctionReturn(0);
}

std::string run_request(TetMesh mesh, const hdimesh::coupling::AdaptRequest& request,
                        hdimesh::coupling::AdaptResult& result)
{
    try
    {
        // the checks a file read makes (positive tets, no face in three tets), naming the tet
        hdimesh::volume::finish_mesh(mesh, request.source);
        result = hdimesh::coupling::run_adapt(
            hdimesh::coupling::adapt_input_from_mesh(std::move(mesh)), request);
    }
    catch (const std::exception& e)
    {
        return e.what();
    }
    return {};
}

PetscErrorCode attach_labels(DM dm, const TetMesh& mesh, const std::vector<PetscInt>& point,
                             const LabelRefs& face_refs, const LabelRefs& cell_refs,
                             const char* bd_name, const char* rg_name)
{
    PetscFunctionBeginUser;
    PetscInt cStart, cEnd, fStart, fEnd;
    PetscCall(DMPlexGetHeightStratum(dm, 0, &cStart, &cEnd));
    PetscCall(DMPlexGetHeightStratum(dm, 1, &fStart, &fEnd));
    DMLabel bd, rg;
    PetscCall(DMCreateLabel(dm, bd_name));
    PetscCall(DMGetLabel(dm, bd_name, &bd));
    for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
    {
        PetscInt value;
        if (!face_refs.value(mesh.triangle_refs[i], value)) continue;
        PetscInt points[3];
        for (int k = 0; k < 3; ++k) points[k] = point[mesh.triangles[i][k]];
        PetscInt n;
        const PetscInt* join;
        PetscCall(DMPlexGetFullJoin(dm, 3, points, &n, &join));
        PetscCheck(n == 1 && join[0] >= fStart && join[0] < fEnd, PETSC_COMM_SELF, PETSC_ERR_PLIB,
                   "hdimesh: output triangle %zu is not a face of the new DM", i);
        PetscCall(DMLabelSetValue(bd, join[0], value));
        PetscCall(DMPlexRestoreJoin(dm, 3, points, &n, &join));
    }
    PetscCall(DMCreateLabel(dm, rg_name));
    PetscCall(DMGetLabel(dm, rg_name, &rg));
    for (PetscInt c = cStart; c < cEnd; ++c)
    {
        PetscInt value;
        if (cell_refs.value(mesh.tet_refs[c - cStart], value))
            PetscCall(DMLabelSetValue(rg, c, value));
    }
    PetscFunctionReturn(0);
}

PetscErrorCode write_plex(MPI_Comm comm, TetMesh& mesh, const PlexInput& in, const char* bd_name,
                          const char* rg_name, DM* dmNew)
{
    PetscFunctionBeginUser;
    mesh.compact();
    const PetscInt nc = mesh.num_live_tets(), nv = mesh.num_vertices();
    std::vector<PetscInt> cells(4 * static_cast<std::size_t>(nc));
    for (PetscInt c = 0; c < nc; ++c)
    {
        const auto& t = mesh.tets[c];
        // back to Plex's inward order
        const int order[4] = {t[1], t[0], t[2], t[3]};
        for (int k = 0; k < 4; ++k) cells[4 * c + k] = order[k];
    }
    std::vector<PetscReal> xyz(3 * static_cast<std::size_t>(nv));
    for (PetscInt v = 0; v < nv; ++v)
        for (int k = 0; k < 3; ++k) xyz[3 * v + k] = mesh.points[v][k];
    PetscCall(DMPlexCreateFromCellListPetsc(comm, 3, nc, nv, 4, PETSC_TRUE, cells.data(), 3,
                                            xyz.data(), dmNew));

    PetscInt vStart, vEnd;
    PetscCall(DMPlexGetDepthStratum(*dmNew, 0, &vStart, &vEnd));
    std::vector<PetscInt> point(mesh.num_vertices());
    for (int v = 0; v < mesh.num_vertices(); ++v) point[v] = vStart + v;
    PetscCall(attach_labels(*dmNew, mesh, point, in.face_refs, in.cell_refs, bd_name, rg_name));
    PetscFunctionReturn(0);
}

}  // namespace hdimesh_petsc

namespace
{

const char* const kBoundaryName = "_boundary_";
const char* const kRegionsName = "_regions_";

PetscErrorCode forget_registration(void);
PetscBool registered = PETSC_FALSE;

PetscErrorCode forget_registration(void)
{
    registered = PETSC_FALSE;
    return 0;
}

}  // namespace

PetscErrorCode DMAdaptMetric_Hdimesh_Plex(DM dm, Vec metric, DMLabel bdLabel, DMLabel rgLabel,
                                          DM* dmNew)
{
    PetscFunctionBeginUser;
    MPI_Comm comm;
    PetscCall(PetscObjectGetComm((PetscObject)dm, &comm));
    const char* bd_name = kBoundaryName;
    const char* rg_name = kRegionsName;
    PetscBool same;
    if (bdLabel)
    {
        PetscCall(PetscObjectGetName((PetscObject)bdLabel, &bd_name));
        PetscCall(PetscStrcmp(bd_name, kBoundaryName, &same));
        PetscCheck(!same, comm, PETSC_ERR_ARG_WRONG,
                   "hdimesh: \"%s\" is reserved; name the boundary label otherwise", bd_name);
    }
    if (rgLabel)
    {
        PetscCall(PetscObjectGetName((PetscObject)rgLabel, &rg_name));
        PetscCall(PetscStrcmp(rg_name, kRegionsName, &same));
        PetscCheck(!same, comm, PETSC_ERR_ARG_WRONG,
                   "hdimesh: \"%s\" is reserved; name the region label otherwise", rg_name);
    }
    PetscInt dim, depth;
    PetscCall(DMGetDimension(dm, &dim));
    PetscCall(DMPlexGetDepth(dm, &depth));
    PetscCheck(dim == 3, comm, PETSC_ERR_SUP,
               "hdimesh adapts 3-D meshes, this DM is %" PetscInt_FMT "-D", dim);
    PetscCheck(depth == dim, comm, PETSC_ERR_ARG_WRONG,
               "hdimesh: the DM has no faces; interpolate it first (DMPlexInterpolate)");
    PetscMPIInt ranks;
    PetscCallMPI(MPI_Comm_size(comm, &ranks));
    if (ranks > 1)
    {
        PetscCall(hdimesh_petsc::adapt_distributed(dm, metric, bdLabel, rgLabel, bd_name, rg_name,
                                                   dmNew));
        PetscFunctionReturn(0);
    }

    hdimesh_petsc::PlexInput in;
    // without bdLabel every boundary face is marked 1, as "_boundary_" will be
    DMLabel marked = bdLabel;
    if (!bdLabel)
    {
        PetscCall(DMLabelCreate(PETSC_COMM_SELF, kBoundaryName, &marked));
        PetscCall(DMPlexMarkBoundaryFaces(dm, 1, marked));
    }
    PetscErrorCode read = hdimesh_petsc::read_plex(dm, marked, rgLabel, in);
    if (!bdLabel) PetscCall(DMLabelDestroy(&marked));
    PetscCall(read);

    hdimesh::coupling::AdaptRequest request;
    PetscCall(hdimesh_petsc::read_metric(dm, metric, in.mesh.num_vertices(), request.size));
    PetscCall(hdimesh_petsc::read_options(dm, request));
    hdimesh::coupling::AdaptResult result;
    const std::string failure = hdimesh_petsc::run_request(std::move(in.mesh), request, result);
    PetscCheck(failure.empty(), comm, PETSC_ERR_LIB, "hdimesh: %s", failure.c_str());
    PetscCall(hdimesh_petsc::write_plex(comm, result.mesh, in, bd_name, rg_name, dmNew));
    PetscFunctionReturn(0);
}

PetscErrorCode HdimeshPetscRegister(void)
{
    PetscFunctionBeginUser;
    // DMAdaptMetric runs every entry of a name: register once per PetscInitialize
    if (registered) PetscFunctionReturn(0);
    PetscCall(DMGenerateRegister("hdimesh", nullptr, nullptr, DMAdaptMetric_Hdimesh_Plex, -1));
    PetscCall(PetscRegisterFinalize(forget_registration));
    registered = PETSC_TRUE;
    PetscFunctionReturn(0);
}

// What PETSc calls when -dll_append loads libhdimesh_petsc.so
PETSC_EXTERN PetscErrorCode PetscDLLibraryRegister_hdimesh_petsc(void)
{
    return HdimeshPetscRegister();
}

#pragma once
// Tet-mesh files, format chosen by extension:
//
//   .mesh   Medit ASCII        read + write  Vertices, Edges, Triangles, Tetrahedra, Ridges,
//   .meshb  Medit binary       read + write  Corners, Required{Vertices,Edges,Triangles,
//                                            Tetrahedra}, all refs kept
//   .msh    Gmsh 2.2 / 4.1     read + write  ASCII and binary; physical tag <-> ref; $NodeData
//                                            read by read_point_fields, written from
//                                            WriteOptions::point_fields
//   .vtu    VTK XML            write         raw appended binary; cell data "ref", "Qe";
//                                            point data "size" when given (for ParaView)
//   .sol / .solb  Medit solution, one scalar per vertex: read_sol/write_sol in common/sol_io.h
//
// What each format keeps:
//  - Medit keeps everything in TetMesh. Normals, Tangents, NormalAtVertices,
//    TangentAtVertices and TangentAtEdgeVertices are skipped on reading: they are derived
//    data that the HDI model recomputes. Empty Quadrilaterals/Prisms/Pyramids/Hexahedra
//    sections are accepted; non-empty ones are errors (dropping them would lose part of the
//    domain), and so is any other keyword, naming its line.
//    "End" is required, so a file truncated at a section boundary is still detected.
//    .meshb versions 1-4 are read (either byte order); version 2 is written (float64
//    coordinates, int32 indices), version 3 when the file exceeds 2 GiB.
//  - Gmsh keeps vertices, tets, triangles, edges (line elements) and corners (point elements),
//    each element's ref as its physical tag (one elementary entity per ref; ref 0 = no
//    physical group). Vertex refs survive only on corners; ridges and required entities have
//    no Gmsh equivalent and are not written. Gmsh's tet numbering (reference nodes (0,0,0),
//    (1,0,0), (0,1,0), (0,0,1)) is ours, so tets are taken as listed. Unknown $Sections are
//    skipped, as the Gmsh format specifies; unsupported element types are errors.
//  - Tets must be positive: a tet with zero or negative volume is an InputError naming it.
//
// Dead tets (TetMesh::kill_tet) are not written; required tets are renumbered accordingly.

#include <functional>
#include <string>
#include <vector>

#include "common/sol_io.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

enum class MeshFormat
{
    Medit,        ///< .mesh
    MeditBinary,  ///< .meshb
    Gmsh,         ///< .msh
    Vtu,          ///< .vtu (write only)
};

/// The format of a path by its extension (case-insensitive). InputError for any other.
MeshFormat mesh_format_from_path(const std::string& path);

/// Reads .mesh/.meshb (Medit ASCII/binary, versions 1-4), .msh (Gmsh 2.2 and 4.1, ASCII and
/// binary). Returns vertices/tets/triangles/edges/ridges/corners/required* with refs; calls
/// mesh.build_adjacency() and mesh.classify_vertices().
/// Throws InputError ("file:line: message" or "file: tetrahedron 12: message") on any bad
/// content, IoError when the file cannot be opened.
TetMesh read_mesh(const std::string& path);

/// What every read ends with, for a mesh built in memory (the Python module's arrays): the
/// same checks (ids in range, finite coordinates, positive tets, no face shared by three
/// tets), refs sized, adjacency built, vertices classified. Throws InputError naming `source`
/// and the element (numbered from 1, as in the files).
void finish_mesh(TetMesh& mesh, const std::string& source);

/// A named array at the vertices: components values per vertex, vertex after vertex.
struct PointField
{
    std::string name;
    int components = 1;
    std::vector<double> values;
};

struct WriteOptions
{
    std::vector<double> vertex_sizes;  ///< optional point data "size" for .vtu (and nothing else)
    std::string gmsh_version = "4.1";  ///< "2.2" or "4.1" for .msh
    bool gmsh_binary = false;
    /// More point data: .vtu point data, .msh $NodeData sections (name as the string tag;
    /// 1, 3 or 9 components there); other formats have none.
    std::vector<PointField> point_fields;
};

/// The $NodeData sections of a .msh file (Gmsh 2.2 or 4.1, ASCII or binary) as fields at the
/// vertices of `mesh`, in the file's order, named by their first string tag ("field<k>" when
/// none). A file with $Nodes must hold mesh's vertices, in order and at the same places (the
/// mesh read from it, or from a file written from that mesh): node tags map through it. A file
/// with only $NodeData numbers nodes 1..n as the vertices. Each section must give every vertex
/// once, with 1, 3 or 9 finite components; a name may not come twice (several time steps).
/// InputError "path:line: ..." (binary: "path: byte N: ...") otherwise, IoError when the file
/// cannot be opened. A .msh read by read_mesh keeps no $NodeData: carrying them is opt-in.
std::vector<PointField> read_point_fields(const std::string& path, const TetMesh& mesh);

/// The sizing a file gives at the mesh's vertices, as `-sol` takes it: a Medit .sol/.solb
/// (read_sol_sizing: sizes, or metrics in Medit's order), or a Gmsh .msh with one $NodeData of
/// 1 component (sizes) or 9 (a metric, row-major, symmetric). InputError naming the file, the
/// field and the vertex (from 1) otherwise.
SolSizing read_vertex_sizing(const std::string& path, const TetMesh& mesh);

/// Writes by extension: .mesh, .meshb, .msh, .vtu (raw appended binary, cell data "ref" and
/// "Qe", point data "size" when given). Atomic (temporary file + rename): a failed write
/// leaves no partial file. InputError for a bad option (unknown gmsh_version, vertex_sizes or a
/// point field of the wrong length), IoError when the file system refuses.
void write_mesh(const TetMesh& mesh, const std::string& path, const WriteOptions& options = {});

}  // namespace hdimesh::volume

#pragma once
// Private machinery of the tet-mesh readers and writers (medit_io.cpp, gmsh_io.cpp, vtu_io.cpp):
// the validation every reader ends with, the live-tet numbering every writer uses, and the
// per-format entry points. Private (detail/): only volume/*_io.cpp include it, and it is not
// installed.

#include <ostream>
#include <string>
#include <vector>

#include "common/buffer_io.h"
#include "common/errors.h"
#include "common/medit_reader.h"
#include "volume/io/tet_io.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume::io_detail
{

using io::BinaryReader;
using io::load_file;
using io::lower_extension;
using io::TextReader;
using io::TextWriter;
using io::throw_input;
namespace gmf = medit::gmf;

/// Where each tet came from, for error messages naming the element ("tetrahedron 12").
/// Checks every index against its array (vertex ids, ridges/required edges into edges, ...),
/// rejects non-positive tets and faces shared by more than two tets, then builds adjacency
/// and classifies vertices. Messages: "path: tetrahedron 12: ..." (1-based file order).
void finish_read(TetMesh& mesh, const std::string& path);

/// Live tet ids in order, and old -> file index (1-based) for live tets (0 for dead ones).
struct LiveTets
{
    std::vector<int> ids;
    std::vector<int> file_index;
};
LiveTets live_tets(const TetMesh& mesh);

// --- per-format entry points (dispatched by extension in tet_io.cpp)
TetMesh read_medit(const std::string& path, const std::string& data);
void write_medit_ascii(const TetMesh& mesh, std::ostream& out);
void write_medit_binary(const TetMesh& mesh, std::ostream& out);
TetMesh read_gmsh(const std::string& path, const std::string& data);
std::vector<PointField> read_gmsh_fields(const std::string& path, const std::string& data,
                                         const TetMesh& target);
void write_gmsh(const TetMesh& mesh, std::ostream& out, const WriteOptions& options);
void write_vtu(const TetMesh& mesh, std::ostream& out, const WriteOptions& options);

}  // namespace hdimesh::volume::io_detail

#pragma once
// Medit solution files with one scalar per vertex (SolAtVertices, type 1), the usual way to
// hand a size field to Mmg-like tools: .sol (ASCII) and .solb (libMeshb binary). Both meshes
// read their --sol through here. Fields carried through an adaptation (adapt --field) are
// files of several solutions of any type (scalars, vectors, symmetric tensors): read_solutions.

#include <string>
#include <vector>

namespace hdimesh
{

/// Medit .sol (ASCII) or .solb (binary): SolAtVertices, one scalar per vertex.
/// expected_vertices < 0: don't check the count. Values must be finite. InputError naming the
/// file and the line (.sol) or byte (.solb) on bad content, IoError when it cannot be read.
std::vector<double> read_sol(const std::string& path, int expected_vertices = -1);

/// read_sol for a size field: every value must also be positive (InputError naming the file and
/// the vertex otherwise).
std::vector<double> read_sol_sizes(const std::string& path, int expected_vertices);

/// Writes .sol or .solb by extension, atomically.
void write_sol(const std::vector<double>& values, const std::string& path);

/// Medit's solution types at a vertex in 3D (GmfSca, GmfVec, GmfSymMat).
enum class SolType
{
    Scalar = 1,
    Vector = 2,  ///< 3 values
    Tensor = 3,  ///< a symmetric 3x3 matrix: 6 values in Medit's order (m11 m12 m22 m13 m23 m33)
};

/// Values per vertex of a solution of this type: 1, 3 or 6.
int sol_components(SolType type);

/// One solution: sol_components(type) values per vertex, vertex after vertex.
struct Solution
{
    SolType type = SolType::Scalar;
    std::vector<double> values;
};

/// A SolAtVertices section with its solutions in the file's order.
struct Solutions
{
    int num_vertices = 0;
    std::vector<Solution> solutions;
};

/// Medit .sol or .solb with one or several solutions of types 1, 2 or 3 at the vertices.
/// expected_vertices < 0: don't check the count. InputError naming the file and the line
/// (.sol) or byte (.solb) on a wrong count, a value that is not finite or an unknown type.
Solutions read_solutions(const std::string& path, int expected_vertices = -1);

/// The sizing a .sol/.solb gives at the vertices, as Mmg reads it: one scalar solution (sizes,
/// each > 0) or one tensor solution (metrics, 6 values per vertex in Medit's order, each
/// symmetric positive definite). InputError naming the file and the vertex otherwise.
struct SolSizing
{
    std::vector<double> sizes;    ///< a scalar file's, else empty
    std::vector<double> metrics;  ///< a tensor file's, 6 per vertex, else empty
};
SolSizing read_sol_sizing(const std::string& path, int expected_vertices);

/// Writes .sol or .solb by extension, atomically, the solutions in their order. InputError
/// when a solution's value count is not num_vertices times its components.
void write_solutions(const Solutions& solutions, const std::string& path);

}  // namespace hdimesh

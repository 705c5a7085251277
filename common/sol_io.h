#pragma once
// Medit solution files with one scalar per vertex (SolAtVertices, type 1), the usual way to
// hand a size field to Mmg-like tools: .sol (ASCII) and .solb (libMeshb binary). Both meshes
// read their --sol through here.

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

}  // namespace hdimesh

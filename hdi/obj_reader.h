#pragma once
// Reads the vertices and faces of a Wavefront OBJ file: the triangle surface an HDI model is
// built from. Only what the model needs (no normals, texture coordinates or groups); polygons are
// split into fans. Lives in hdi/ because hdi/ may not use OpenMesh, and the tests and benchmarks
// of the model load the shared surfaces with it.

#include <string>
#include <vector>

#include "hdi/point_cloud.h"

namespace hdimesh::hdi
{

struct TriangleSurface
{
    std::vector<Vec3> points;
    std::vector<Triangle3> triangles;
};

/// Throws IoError when the file cannot be read, InputError naming the file and line for
/// a malformed vertex or face (negative indices count from the end, as OBJ allows).
TriangleSurface read_obj(const std::string& path);

}  // namespace hdimesh::hdi

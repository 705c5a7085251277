#pragma once
// A triangle soup: what the readers produce before a mesh is built from it.

#include <array>
#include <vector>

#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

struct TriangleSoup
{
    std::vector<Vec3d> points;
    std::vector<std::array<int, 3>> triangles;
    std::vector<int> refs;  // per triangle (0 when the format has none)
};

}  // namespace hdimesh::surface

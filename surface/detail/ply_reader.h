#pragma once
// The PLY reader of read_triangle_soup (surface_io.h): the vertex element's x, y, z and the face
// element's vertex_indices list; every other element and property is read and skipped.

#include <string>

#include "surface/surface_io.h"

namespace hdimesh::surface::detail
{

/// The soup of a PLY file, ASCII or binary of either byte order (InputError or IoError naming
/// the file and the line or byte otherwise).
TriangleSoup read_ply(const std::string& path);

}  // namespace hdimesh::surface::detail

#pragma once
// How each refinement pattern is built from a tet's local points (its 4 vertices, 6 edge
// midpoints and the Steiner point): the children and how their faces meet, made once from the
// pattern table (volume/refine/refine_patterns.h). Refinement's private machinery.

#include <array>
#include <cstdint>
#include <vector>

namespace hdimesh::volume::detail
{

/// Children of one way of building one pattern, over local points, with how their faces meet:
/// link[4 * child + face] is the partner child face (4 * child + face) inside the parent, or
/// -(1 + f) for a face on the parent's face f; on_parent_face[f] lists those child faces.
struct ChildBuild
{
    std::vector<std::array<std::uint8_t, 4>> tets;
    std::vector<int> link;
    std::array<std::vector<int>, 4> on_parent_face;
    bool new_point = false;
};

/// Per pattern, the table's own children and the cone of its boundary triangles to the Steiner
/// point.
struct PatternBuilds
{
    std::vector<ChildBuild> table, cone;  // indexed by pattern

    PatternBuilds();
};

/// The builds of every pattern, made on first use.
const PatternBuilds& pattern_builds();

}  // namespace hdimesh::volume::detail

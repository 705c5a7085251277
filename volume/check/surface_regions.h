#pragma once
// The regions a closed surface bounds: its connected shells, which shell lies inside which
// (winding numbers), and from that the solids to fill. A shell inside no other, or inside an
// even number of others, is the outer boundary of a region; a shell inside an odd number is a
// void of the region its innermost container bounds. Disjoint solids are separate regions,
// each with its own ref; a solid inside a void is a region of its own.
//
//        +---------------------+
//        |  region 1           |     shells: A (outer), B (void of 1), C (outer of 3),
//        |   +-------------+   |             D (outer of 2)
//        |   | B void      |   |   +-----+
//        |   |   +-----+   |   |   | D   |
//        |   |   | C 3 |   |   |   |  2  |
//        |   |   +-----+   |   |   +-----+
//        |   +-------------+   |
//        +---------------------+  A
//
// Each region's faces are oriented outward of the region: the outer shell's normals point
// away from it, a void's into the void. The input may orient every shell outward as a solid
// (the common convention of OBJ/STL exports) or already so; shells are turned as needed.

#include <vector>

#include "volume/mesh/geometry.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

struct SurfaceShell
{
    std::vector<int> faces;  ///< indices into the input triangles, ascending
    /// Signed volume it encloses as given (> 0: its normals point away from its inside).
    double volume = 0;
    int depth = 0;        ///< how many other shells contain it
    int parent = -1;      ///< the innermost shell containing it (-1: none)
    int region = -1;      ///< index into SurfaceRegions::regions
    bool turned = false;  ///< its faces were reversed to face out of its region
};

struct SurfaceRegion
{
    int ref = 0;  ///< tet ref for the region: 1, 2, ... in shell order
    int outer_shell = -1;
    std::vector<int> void_shells;
};

struct SurfaceRegions
{
    /// Shells in a geometric order, independent of the numbering: by their lexicographically
    /// smallest point (x, then y, then z), which disjoint shells never share.
    std::vector<SurfaceShell> shells;
    std::vector<SurfaceRegion> regions;
    /// The input triangles, each turned when its shell was: every region's faces outward.
    std::vector<Triangle> triangles;
    int turned_shells = 0;

    /// The faces of region r (outer shell, then voids), from `triangles`: the input of one
    /// fill_cavity call.
    std::vector<Triangle> region_faces(int r) const;
};

/// Shells, nesting and regions of a surface that passed check_closed_surface (closed,
/// consistently oriented, disjoint manifold shells). Containment: the winding number of each
/// shell around a point of another, the sign of each face's solid angle decided by the exact
/// orient3d. O(shells * faces) after a box filter. Deterministic.
SurfaceRegions find_surface_regions(const std::vector<Vec3>& points,
                                    const std::vector<Triangle>& triangles);

/// Winding number of the closed oriented triangles `faces` around p (not on them): +1 inside
/// an outward shell, -1 inside an inward one, 0 outside.
int winding_number(const std::vector<Vec3>& points, const std::vector<Triangle>& triangles,
                   const std::vector<int>& faces, const Vec3& p);

}  // namespace hdimesh::volume

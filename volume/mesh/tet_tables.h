#pragma once
/*
 The reference tetrahedron's local numbering, used by every volume file.

                 3
                /|\            A tet (v0,v1,v2,v3) is positive when
               / | \           det(v1-v0, v2-v0, v3-v0) > 0.
           e2 /  |e5\
             /   |   \         Edges:  e0 = 01, e1 = 02, e2 = 03,
            0----|----2                e3 = 12, e4 = 13, e5 = 23
             \ e1|   /         (edge i and edge 5-i are opposite).
           e0 \  |e4/e3
               \ | /           Face i is opposite vertex i, its vertices
                \|/            listed counter-clockwise seen from outside.
                 1
*/

#include <array>
#include <cstdint>

#include "volume/mesh/namespace.h"

namespace hdimesh::volume::tet
{

/// Local vertices of each edge, lower local index first.
inline constexpr std::array<std::array<int, 2>, 6> kEdgeVertices = {{
    {0, 1},
    {0, 2},
    {0, 3},
    {1, 2},
    {1, 3},
    {2, 3},
}};

/// Local vertices of face i (the face opposite vertex i), outward orientation.
inline constexpr std::array<std::array<int, 3>, 4> kFaceVertices = {{
    {1, 2, 3},
    {0, 3, 2},
    {0, 1, 3},
    {0, 2, 1},
}};

/// Local edges of face i: kFaceEdges[i][k] joins kFaceVertices[i][k] and kFaceVertices[i][k+1 mod
/// 3].
inline constexpr std::array<std::array<int, 3>, 4> kFaceEdges = {{
    {3, 5, 4},
    {2, 5, 1},
    {0, 4, 2},
    {1, 3, 0},
}};

/// Local edge joining two local vertices (symmetric; -1 on the diagonal).
inline constexpr std::array<std::array<int, 4>, 4> kEdgeOfVertices = {{
    {-1, 0, 1, 2},
    {0, -1, 3, 4},
    {1, 3, -1, 5},
    {2, 4, 5, -1},
}};

/// The two faces that contain edge i (the faces opposite the vertices not on it).
inline constexpr std::array<std::array<int, 2>, 6> kEdgeFaces = {{
    {2, 3},
    {1, 3},
    {1, 2},
    {0, 3},
    {0, 2},
    {0, 1},
}};

/// The edge opposite edge i (sharing no vertex with it).
inline constexpr int opposite_edge(int edge) { return 5 - edge; }

}  // namespace hdimesh::volume::tet

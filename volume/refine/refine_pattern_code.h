#pragma once
// The paper's code of a bisection configuration (its eq. 3), header-only so that the pattern
// generator (volume/tools, no library) and the pattern lookup compute it with the same code.
//
// The paper's figures are not in its text; our reading (it maps the paper's example
// 20, 8, 20, 7 -> 1917460 onto a valid configuration, mask {e0,e1,e2,e3}, diagonals 0):
//  - the paper's face F_i is our face kPaperFaceToOurs[i] (our face j is opposite local vertex j);
//  - inside a face, positions P0, P1, P2 are its local vertices in decreasing local index;
//  - interior edge k (k = 0,1,2) joins the midpoints of the two face edges at corner Pk;
//  - interior edge 3+k joins Pk to the midpoint of the face edge opposite Pk.

#include <algorithm>
#include <array>

#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

/// Number of split edges of face f under the mask.
inline int face_split_count(int mask, int face)
{
    int n = 0;
    for (int e : tet::kFaceEdges[face]) n += (mask >> e) & 1;
    return n;
}

inline constexpr int kPaperFaceToOurs[4] = {1, 0, 2, 3};

/// The paper's FaceCode of our face f: the sum of 2^j over the face's interior edges j.
inline int paper_face_code(int mask, int diagonals, int face)
{
    std::array<int, 3> pos = {tet::kFaceVertices[face][0], tet::kFaceVertices[face][1],
                              tet::kFaceVertices[face][2]};
    std::sort(pos.begin(), pos.end(), [](int x, int y) { return x > y; });
    auto split_opposite = [&](int k) {
        return ((mask >> tet::kEdgeOfVertices[pos[(k + 1) % 3]][pos[(k + 2) % 3]]) & 1) != 0;
    };
    switch (face_split_count(mask, face))
    {
        case 0: return 0;
        case 3: return 1 + 2 + 4;
        case 1:
            for (int k = 0; k < 3; ++k)
                if (split_opposite(k)) return 1 << (3 + k);
            return -1;  // unreachable
        default: break;
    }
    int corner = 0;  // opposite the face's one unsplit edge
    while (split_opposite(corner)) ++corner;
    const int a = pos[(corner + 1) % 3], b = pos[(corner + 2) % 3];
    const int from = ((diagonals >> face) & 1) ? std::max(a, b) : std::min(a, b);
    const int from_position = from == a ? (corner + 1) % 3 : (corner + 2) % 3;
    return (1 << corner) + (1 << (3 + from_position));
}

/// The paper's code, eq. 3: sum over its faces F_i of FaceCode(F_i) * 2^(6i). Unique per
/// configuration.
inline int paper_pattern_code(int mask, int diagonals)
{
    int code = 0;
    for (int i = 0; i < 4; ++i)
        code += paper_face_code(mask, diagonals, kPaperFaceToOurs[i]) << (6 * i);
    return code;
}

}  // namespace hdimesh::volume

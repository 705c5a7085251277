#pragma once
// The bisection pattern table (the paper's §3, ../shared/docs/method.md §3): for every way a
// tet's edges can be split at their midpoints and its two-split faces triangulated, the child
// tets over local points. 239 configurations, 14 of them (Schönhardt) with a Steiner point.
// The data is generated and proven by volume/tools/generate_refine_patterns.cpp into
// volume/refine_patterns_table.inc; this header is the lookup.
//
// Local points of a pattern: 0-3 the parent's vertices (volume/tet_tables.h numbering),
// 4 + e the midpoint of local edge e, 10 the Steiner point (the parent's centroid).
//
// Keys: the split mask (bit e: local edge e is split) and the diagonal bits (bit f, meaningful
// only for a face f with exactly two split edges): with c the corner where the face's two split
// edges meet and a < b its other two local vertices, bit 0 = the quad diagonal joins a to the
// midpoint of edge cb, bit 1 = it joins b to the midpoint of edge ca.

#include <cstdint>

#include "volume/namespace.h"

namespace hdimesh::volume
{

inline constexpr int kPatternSteinerPoint = 10;
inline constexpr int kPatternNumLocalPoints = 11;
inline constexpr int kNumRefinePatterns = 239;

/// Local point of the midpoint of local edge e.
constexpr int pattern_midpoint(int edge) { return 4 + edge; }

struct RefinePattern
{
    int mask = 0;
    int diagonals = 0;
    int paper_code = 0;    ///< the paper's eq. 3, see paper_pattern_code()
    bool steiner = false;  ///< uses local point 10
    const std::uint8_t (*tets)[4] = nullptr;  ///< positive child tets over local points
    int num_tets = 0;
    const std::uint8_t (*triangles)[3] = nullptr;  ///< the sub-polyhedron's boundary, outward
    int num_triangles = 0;
};

/// Pattern number i, 0 <= i < kNumRefinePatterns (sorted by mask, then diagonals).
const RefinePattern& refine_pattern(int index);

/// Index of the pattern of (mask, diagonals), or -1 when a diagonal bit is set on a face that
/// does not have exactly two split edges.
int find_refine_pattern(int mask, int diagonals);

/// Bit f set when face f has exactly two split edges under the mask (a diagonal to choose).
int faces_with_two_split_edges(int mask);

/// Number of split edges of face f under the mask.
int face_split_count(int mask, int face);

/// The paper's FaceCode of our face f: the sum of 2^j over the face's interior edges j.
/// The paper's figures are not in its text; our reading (it maps the paper's example
/// 20, 8, 20, 7 -> 1917460 onto a valid configuration, mask {e0,e1,e2,e3}, diagonals 0):
///  - inside a face, positions P0, P1, P2 are its local vertices in decreasing local index;
///  - interior edge k (k = 0,1,2) joins the midpoints of the two face edges at corner Pk;
///  - interior edge 3+k joins Pk to the midpoint of the face edge opposite Pk.
int paper_face_code(int mask, int diagonals, int face);

/// The paper's face F_i is our face kPaperFaceToOurs[i] (our face j is opposite local vertex j).
inline constexpr int kPaperFaceToOurs[4] = {1, 0, 2, 3};

/// The paper's code, eq. 3: sum over its faces F_i of FaceCode(F_i) * 2^(6i). Unique per
/// configuration.
int paper_pattern_code(int mask, int diagonals);

}  // namespace hdimesh::volume

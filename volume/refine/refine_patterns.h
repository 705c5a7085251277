#pragma once
// The bisection pattern table (the paper's §3, ../shared/docs/method.md §3): for every way a
// tet's edges can be split at their midpoints and its two-split faces triangulated, the child
// tets over local points. 239 configurations, 14 of them (Schönhardt) with a Steiner point.
// The data is generated and proven by volume/tools/generate_refine_patterns.cpp into
// volume/refine/refine_patterns_table.inc; this header is the lookup.
//
// Local points of a pattern: 0-3 the parent's vertices (volume/mesh/tet_tables.h numbering),
// 4 + e the midpoint of local edge e, 10 the Steiner point (the parent's centroid).
//
// Keys: the split mask (bit e: local edge e is split) and the diagonal bits (bit f, meaningful
// only for a face f with exactly two split edges): with c the corner where the face's two split
// edges meet and a < b its other two local vertices, bit 0 = the quad diagonal joins a to the
// midpoint of edge cb, bit 1 = it joins b to the midpoint of edge ca.

#include <cstdint>

#include "volume/mesh/namespace.h"
#include "volume/refine/refine_pattern_code.h"

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
    int paper_code = 0;    ///< the paper's eq. 3 (volume/refine/refine_pattern_code.h)
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

}  // namespace hdimesh::volume

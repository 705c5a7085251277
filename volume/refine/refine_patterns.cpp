#include "volume/refine/refine_patterns.h"

#include <algorithm>
#include <array>
#include <cassert>

#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace
{

struct PatternRecord
{
    std::uint8_t mask, diagonals;
    std::int32_t paper_code;
    std::uint8_t steiner;
    std::uint16_t first_tet;
    std::uint8_t num_tets;
    std::uint16_t first_triangle;
    std::uint8_t num_triangles;
};

#include "volume/refine/refine_patterns_table.inc"

static_assert(kTableNumPatterns == kNumRefinePatterns,
              "the generated table must hold 239 patterns");

struct PatternLookup
{
    std::array<RefinePattern, kNumRefinePatterns> patterns;
    std::array<std::int16_t, 64 * 16> index;  // mask * 16 + diagonals -> pattern or -1

    PatternLookup()
    {
        index.fill(-1);
        for (int i = 0; i < kNumRefinePatterns; ++i)
        {
            const PatternRecord& r = kTablePatterns[i];
            RefinePattern& p = patterns[i];
            p.mask = r.mask;
            p.diagonals = r.diagonals;
            p.paper_code = r.paper_code;
            p.steiner = r.steiner != 0;
            p.tets = &kTableTets[r.first_tet];
            p.num_tets = r.num_tets;
            p.triangles = &kTableTriangles[r.first_triangle];
            p.num_triangles = r.num_triangles;
            index[r.mask * 16 + r.diagonals] = static_cast<std::int16_t>(i);
        }
    }
};

const PatternLookup& lookup()
{
    static const PatternLookup table;
    return table;
}

}  // namespace

const RefinePattern& refine_pattern(int index)
{
    assert(index >= 0 && index < kNumRefinePatterns);
    return lookup().patterns[index];
}

int find_refine_pattern(int mask, int diagonals)
{
    if (mask < 0 || mask >= 64 || diagonals < 0 || diagonals >= 16) return -1;
    return lookup().index[mask * 16 + diagonals];
}

int faces_with_two_split_edges(int mask)
{
    int faces = 0;
    for (int f = 0; f < 4; ++f) faces |= (face_split_count(mask, f) == 2) << f;
    return faces;
}

}  // namespace hdimesh::volume

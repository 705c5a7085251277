#include "volume/refine_patterns.h"

#include <algorithm>
#include <array>
#include <cassert>

#include "volume/tet_tables.h"

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

#include "volume/refine_patterns_table.inc"

static_assert(kTableNumPatterns == kNumRefinePatterns, "the generated table must hold 239 patterns");

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

int face_split_count(int mask, int face)
{
    int n = 0;
    for (int e : tet::kFaceEdges[face]) n += (mask >> e) & 1;
    return n;
}

int faces_with_two_split_edges(int mask)
{
    int faces = 0;
    for (int f = 0; f < 4; ++f) faces |= (face_split_count(mask, f) == 2) << f;
    return faces;
}

int paper_face_code(int mask, int diagonals, int face)
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

int paper_pattern_code(int mask, int diagonals)
{
    int code = 0;
    for (int i = 0; i < 4; ++i) code += paper_face_code(mask, diagonals, kPaperFaceToOurs[i]) << (6 * i);
    return code;
}

}  // namespace hdimesh::volume

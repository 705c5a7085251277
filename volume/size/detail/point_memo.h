#pragma once
// What the background fields share to remember their latest answers per thread: an id per
// field (so one table serves every field) and a point's table slot from its exact bits.

#include <atomic>
#include <cstdint>
#include <cstring>

#include "common/point.h"

namespace hdimesh::volume::detail
{

/// A new id for a field's entries in the per-thread tables (one counter for every field kind).
inline std::uint64_t next_field_id()
{
    static std::atomic<std::uint64_t> next{1};
    return next++;
}

/// A point's exact bits, mixed into a slot of a table of `slots` (a power of two) entries.
inline std::size_t point_slot(const Vec3& p, std::size_t slots)
{
    std::uint64_t h = 0x9e3779b97f4a7c15ull;
    for (int i = 0; i < 3; ++i)
    {
        std::uint64_t bits;
        std::memcpy(&bits, &p[i], sizeof bits);
        h = (h ^ bits) * 0xff51afd7ed558ccdull;
        h ^= h >> 33;
    }
    return static_cast<std::size_t>(h) & (slots - 1);
}

}  // namespace hdimesh::volume::detail

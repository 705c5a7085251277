#pragma once
// Morton (Z-order) keys: points close in space get close keys, so sorting by them gives a
// cache-friendly order of vertices or query points. Each caller quantizes its coordinates to
// 21-bit cells its own way; the interleaving is this one.

#include <cstdint>

namespace hdimesh
{

inline constexpr int kMortonBitsPerAxis = 21;  // 63 bits of key
inline constexpr std::uint64_t kMortonCellMax = (std::uint64_t{1} << kMortonBitsPerAxis) - 1;

/// Bit k of the low 21 bits of x moved to bit 3k.
inline std::uint64_t spread_morton_bits(std::uint64_t x)
{
    x &= 0x1fffff;
    x = (x | x << 32) & 0x1f00000000ffffull;
    x = (x | x << 16) & 0x1f0000ff0000ffull;
    x = (x | x << 8) & 0x100f00f00f00f00full;
    x = (x | x << 4) & 0x10c30c30c30c30c3ull;
    x = (x | x << 2) & 0x1249249249249249ull;
    return x;
}

/// The key of cell (x, y, z), each coordinate below 2^21: x in bit 0, y in bit 1, z in bit 2.
inline std::uint64_t morton_key(std::uint64_t x, std::uint64_t y, std::uint64_t z)
{
    return spread_morton_bits(x) | spread_morton_bits(y) << 1 | spread_morton_bits(z) << 2;
}

}  // namespace hdimesh

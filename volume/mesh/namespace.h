#pragma once
// The volume module lives in hdimesh::volume. Call sites that still name its types hdimesh::X
// keep compiling through this using-directive until they say volume:: themselves.

namespace hdimesh::volume
{
}

namespace hdimesh
{
using namespace volume;
}

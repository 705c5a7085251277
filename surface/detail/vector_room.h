#pragma once
// Growing a per-element array with room to spare: the remesher's refinement rounds and the output
// tree rebuilt in each of them need a few more entries every time, and an array grown exactly to
// its length is reallocated at the next round, its memory touched anew (page faults).

#include <cstddef>
#include <vector>

namespace hdimesh::surface::detail
{

// Capacity for n, with a quarter more when v must grow.
template <class T>
void reserve_with_room(std::vector<T>& v, std::size_t n)
{
    if (v.capacity() < n) v.reserve(n + n / 4);
}

// v made n long, with reserve_with_room's spare room (new entries default-inserted: left
// uninitialized for OpenMesh's vectors, whose default constructor does not set them).
template <class T>
void resize_with_room(std::vector<T>& v, std::size_t n)
{
    reserve_with_room(v, n);
    v.resize(n);
}

// The same with the new entries `value`.
template <class T>
void resize_with_room(std::vector<T>& v, std::size_t n, const T& value)
{
    reserve_with_room(v, n);
    v.resize(n, value);
}

}  // namespace hdimesh::surface::detail

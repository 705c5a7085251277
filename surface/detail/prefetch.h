#pragma once
// A hint to the processor to start reading memory a walk reads next: the ring walks of the
// shift, the model's descent and the tree's search wait on memory more than they compute.

namespace hdimesh::surface::detail
{

inline void prefetch(const void* address)
{
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(address);
#else
    (void)address;
#endif
}

}  // namespace hdimesh::surface::detail

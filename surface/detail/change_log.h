#pragma once
// The vertices each change touches, noted from the operators' hooks for the stages that keep a
// cache of the mesh (the refinement's triangles and short edges, the cleanup's small angles):
// every face an operator creates or changes has one of them (a split's new vertex, a flip's new
// edge's ends, a moved vertex, a collapse's kept vertex, a removal's new faces' vertices), so a
// cache brought up to date at their faces matches a full scan.

#include <vector>

#include "surface/local_ops.h"

namespace hdimesh::surface::detail
{

/// One stage's list of changed vertices, filled while it records.
struct ChangedVertices
{
    bool recording = false;
    std::vector<VertexHandle> vertices;  // in the order of the changes (repeats kept)
    /// A collapse or a removal since this was last reset: it deletes edges, which no noted
    /// vertex reaches.
    bool edges_deleted = false;
};

class ChangeLog
{
public:
    ChangeLog() = default;
    // Not copyable: the wrapped hooks keep its address.
    ChangeLog(const ChangeLog&) = delete;
    ChangeLog& operator=(const ChangeLog&) = delete;

    /// `list` is told of every change from now on while it records; it must outlive the hooks.
    void add(ChangedVertices& list) { lists_.push_back(&list); }
    /// The hooks given, and besides each change noted in the recording lists first.
    SurfaceHooks wrap(SurfaceHooks given);

private:
    void note(VertexHandle v);
    void note_deleted_edges();

    std::vector<ChangedVertices*> lists_;
};

}  // namespace hdimesh::surface::detail

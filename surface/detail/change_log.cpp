#include "surface/detail/change_log.h"

namespace hdimesh::surface::detail
{

void ChangeLog::note(VertexHandle v)
{
    for (ChangedVertices* list : lists_)
        if (list->recording) list->vertices.push_back(v);
}

void ChangeLog::note_deleted_edges()
{
    for (ChangedVertices* list : lists_)
        if (list->recording) list->edges_deleted = true;
}

SurfaceHooks ChangeLog::wrap(SurfaceHooks hooks)
{
    ChangeLog* log = this;
    hooks.on_split = [log, given = hooks.on_split](const SurfaceMesh& m, VertexHandle a,
                                                   VertexHandle b, VertexHandle inserted) {
        log->note(inserted);
        if (given) given(m, a, b, inserted);
    };
    hooks.on_flip = [log, given = hooks.on_flip](const SurfaceMesh& m, VertexHandle a,
                                                 VertexHandle b, VertexHandle c, VertexHandle d) {
        log->note(c);
        log->note(d);
        if (given) given(m, a, b, c, d);
    };
    hooks.on_move = [log, given = hooks.on_move](const SurfaceMesh& m, VertexHandle v,
                                                 const Vec3d& old_point) {
        log->note(v);
        if (given) given(m, v, old_point);
    };
    hooks.on_collapse = [log, given = hooks.on_collapse](const SurfaceMesh& m, VertexHandle removed,
                                                         VertexHandle kept) {
        log->note(kept);
        log->note_deleted_edges();
        if (given) given(m, removed, kept);
    };
    hooks.on_remove_vertex = [log, given = hooks.on_remove_vertex](
                                 const SurfaceMesh& m, VertexHandle removed,
                                 const std::vector<FaceHandle>& new_faces) {
        log->note_deleted_edges();
        for (const FaceHandle f : new_faces)
            for (auto v : m.fv_range(f)) log->note(v);
        if (given) given(m, removed, new_faces);
    };
    return hooks;
}

}  // namespace hdimesh::surface::detail

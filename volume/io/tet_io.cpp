// read_mesh / write_mesh dispatch by extension, and the validation that ends every read.

#include "volume/io/tet_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "common/metric.h"
#include "volume/io/detail/io.h"
#include "volume/mesh/tet_tables.h"

namespace hdimesh::volume
{

namespace io_detail
{

// --- validation

namespace
{

std::string entity_error(const char* entity, std::size_t index, const std::string& message)
{
    return std::string(entity) + " " + std::to_string(index + 1) + ": " + message;
}

/// Checks 0-based ids against [0, n), naming the 1-based entity and id on failure.
template <class Array>
void check_ids(const std::string& path, const std::vector<Array>& items, int n, const char* entity,
               const char* target)
{
    for (std::size_t i = 0; i < items.size(); ++i)
        for (int id : items[i])
            if (id < 0 || id >= n)
                throw_input(path, entity_error(entity, i,
                                               std::string(target) + " " + std::to_string(id + 1) +
                                                   " out of range [1, " + std::to_string(n) + "]"));
}

void check_index_list(const std::string& path, const std::vector<int>& items, int n,
                      const char* entity, const char* target)
{
    for (std::size_t i = 0; i < items.size(); ++i)
        if (items[i] < 0 || items[i] >= n)
            throw_input(path,
                        entity_error(entity, i,
                                     std::string(target) + " " + std::to_string(items[i] + 1) +
                                         " out of range [1, " + std::to_string(n) + "]"));
}

}  // namespace

void finish_read(TetMesh& mesh, const std::string& path)
{
    const int nv = mesh.num_vertices();
    mesh.vertex_refs.resize(mesh.points.size(), 0);
    mesh.tet_refs.resize(mesh.tets.size(), 0);
    mesh.triangle_refs.resize(mesh.triangles.size(), 0);
    mesh.edge_refs.resize(mesh.edges.size(), 0);
    for (int v = 0; v < nv; ++v)
        if (!mesh.points[v].allFinite())
            throw_input(path, entity_error("vertex", v, "coordinate is not finite"));

    check_ids(path, mesh.tets, nv, "tetrahedron", "vertex");
    check_ids(path, mesh.triangles, nv, "triangle", "vertex");
    check_ids(path, mesh.edges, nv, "edge", "vertex");
    const int ne = static_cast<int>(mesh.edges.size());
    const int ntri = static_cast<int>(mesh.triangles.size());
    check_index_list(path, mesh.ridges, ne, "ridge", "edge");
    check_index_list(path, mesh.required_edges, ne, "required edge", "edge");
    check_index_list(path, mesh.corners, nv, "corner", "vertex");
    check_index_list(path, mesh.required_vertices, nv, "required vertex", "vertex");
    check_index_list(path, mesh.required_triangles, ntri, "required triangle", "triangle");
    check_index_list(path, mesh.required_tets, mesh.num_tet_slots(), "required tetrahedron",
                     "tetrahedron");

    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        const double volume = mesh.volume(t);
        if (!(volume > 0.0))
        {
            const auto& v = mesh.tets[t];
            std::ostringstream message;
            message.precision(6);
            message << (volume == 0.0 ? "zero" : "negative") << " volume " << volume
                    << " (vertices " << v[0] + 1 << " " << v[1] + 1 << " " << v[2] + 1 << " "
                    << v[3] + 1 << "); tets must be positive: det(v1-v0, v2-v0, v3-v0) > 0";
            throw_input(path, entity_error("tetrahedron", t, message.str()));
        }
    }

    // readers grow some arrays by push_back: give the slack back (a read mesh is usually kept
    // for a whole run)
    mesh.points.shrink_to_fit();
    mesh.vertex_refs.shrink_to_fit();
    mesh.tets.shrink_to_fit();
    mesh.tet_refs.shrink_to_fit();
    mesh.triangles.shrink_to_fit();
    mesh.triangle_refs.shrink_to_fit();
    mesh.edges.shrink_to_fit();
    mesh.edge_refs.shrink_to_fit();

    const int overshared = mesh.build_adjacency();
    if (overshared > 0)
        throw_input(path, std::to_string(overshared) +
                              " face(s) shared by more than two tetrahedra (not a valid tet mesh)");
    mesh.classify_vertices();
}

LiveTets live_tets(const TetMesh& mesh)
{
    LiveTets live;
    live.file_index.assign(mesh.tets.size(), 0);
    live.ids.reserve(mesh.tets.size());
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        live.ids.push_back(t);
        live.file_index[t] = static_cast<int>(live.ids.size());
    }
    return live;
}

}  // namespace io_detail

MeshFormat mesh_format_from_path(const std::string& path)
{
    const std::string ext = io_detail::lower_extension(path);
    if (ext == ".mesh") return MeshFormat::Medit;
    if (ext == ".meshb") return MeshFormat::MeditBinary;
    if (ext == ".msh") return MeshFormat::Gmsh;
    if (ext == ".vtu") return MeshFormat::Vtu;
    throw InputError(path + ": unknown mesh format '" + ext +
                     "' (expected .mesh, .meshb, .msh or .vtu)");
}

TetMesh read_mesh(const std::string& path)
{
    const MeshFormat format = mesh_format_from_path(path);
    if (format == MeshFormat::Vtu)
        throw InputError(path + ": reading .vtu is not supported (write-only, for viewing)");
    const std::string data = io_detail::load_file(path);
    if (data.empty()) throw InputError(path + ": empty file");
    TetMesh mesh = format == MeshFormat::Gmsh ? io_detail::read_gmsh(path, data)
                                              : io_detail::read_medit(path, data);
    io_detail::finish_read(mesh, path);
    return mesh;
}

void finish_mesh(TetMesh& mesh, const std::string& source) { io_detail::finish_read(mesh, source); }

std::vector<PointField> read_point_fields(const std::string& path, const TetMesh& mesh)
{
    if (mesh_format_from_path(path) != MeshFormat::Gmsh)
        throw InputError(path + ": point fields are read from a .msh ($NodeData)");
    const std::string data = io_detail::load_file(path);
    if (data.empty()) throw InputError(path + ": empty file");
    return io_detail::read_gmsh_fields(path, data, mesh);
}

void write_mesh(const TetMesh& mesh, const std::string& path, const WriteOptions& options)
{
    const MeshFormat format = mesh_format_from_path(path);
    if (format == MeshFormat::Gmsh && options.gmsh_version != "2.2" &&
        options.gmsh_version != "4.1")
        throw InputError(path + ": unsupported Gmsh version '" + options.gmsh_version +
                         "' (2.2 or 4.1)");
    if (!options.vertex_sizes.empty() &&
        options.vertex_sizes.size() != static_cast<std::size_t>(mesh.num_vertices()))
        throw InputError(path + ": " + std::to_string(options.vertex_sizes.size()) +
                         " vertex sizes for " + std::to_string(mesh.num_vertices()) + " vertices");
    for (const PointField& field : options.point_fields)
        if (field.components < 1 ||
            field.values.size() != static_cast<std::size_t>(mesh.num_vertices()) * field.components)
            throw InputError(path + ": point field '" + field.name + "' has " +
                             std::to_string(field.values.size()) + " values for " +
                             std::to_string(mesh.num_vertices()) + " vertices x " +
                             std::to_string(field.components));
    if (format == MeshFormat::Gmsh)  // $NodeData: a quoted name, Gmsh's component counts
        for (const PointField& field : options.point_fields)
            if (field.name.find_first_of("\"\n") != std::string::npos ||
                (field.components != 1 && field.components != 3 && field.components != 6 &&
                 field.components != 9))
                throw InputError(path + ": point field '" + field.name +
                                 "' cannot be a $NodeData (a quote or newline in its name, or " +
                                 std::to_string(field.components) +
                                 " components: 1, 3, 6 or 9 are written)");
    write_file_atomically(path, [&](std::ostream& out) {
        switch (format)
        {
            case MeshFormat::Medit: io_detail::write_medit_ascii(mesh, out); break;
            case MeshFormat::MeditBinary: io_detail::write_medit_binary(mesh, out); break;
            case MeshFormat::Gmsh: io_detail::write_gmsh(mesh, out, options); break;
            case MeshFormat::Vtu: io_detail::write_vtu(mesh, out, options); break;
        }
    });
}

SolSizing read_vertex_sizing(const std::string& path, const TetMesh& mesh)
{
    if (io_detail::lower_extension(path) != ".msh")
        return read_sol_sizing(path, mesh.num_vertices());
    std::vector<PointField> fields = read_point_fields(path, mesh);
    if (fields.size() != 1)
        throw InputError(path + ": " + std::to_string(fields.size()) +
                         " $NodeData, a size field is one (1 component: sizes, 9: a metric)");
    PointField& field = fields[0];
    const std::string what = path + ": $NodeData \"" + field.name + "\"";
    SolSizing sizing;
    if (field.components == 1)
    {
        for (std::size_t v = 0; v < field.values.size(); ++v)
            if (!(field.values[v] > 0))
                throw InputError(what + ": size at vertex " + std::to_string(v + 1) +
                                 " is not positive");
        sizing.sizes = std::move(field.values);
        return sizing;
    }
    if (field.components != 9)
        throw InputError(what + ": " + std::to_string(field.components) +
                         " components, a size field has 1 (sizes) or 9 (a metric)");
    for (std::size_t v = 0; 9 * v < field.values.size(); ++v)
    {
        std::string problem;
        const Metric m = metric_from_row_major(&field.values[9 * v], &problem);
        if (problem.empty()) problem = metric_problem(m);
        if (!problem.empty())
            throw InputError(what + ": the metric at vertex " + std::to_string(v + 1) + " is " +
                             problem);
        for (double x : metric_to_medit(m)) sizing.metrics.push_back(x);
    }
    return sizing;
}

}  // namespace hdimesh::volume

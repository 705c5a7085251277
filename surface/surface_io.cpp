#include "surface/surface_io.h"

#include <unistd.h>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>

#include "common/buffer_io.h"
#include "common/errors.h"
#include "common/medit_reader.h"
#include "surface/detail/ply_reader.h"
#include "surface/surface_quality.h"

namespace hdimesh::surface
{
namespace
{

/// Lower-case extension without its dot ("obj"), or "" when there is none.
std::string lower_extension(const std::string& path)
{
    const std::string ext = io::lower_extension(path);
    return ext.empty() ? ext : ext.substr(1);
}

void check_index(io::TextReader& in, long long index, std::size_t count)
{
    if (index < 0 || static_cast<std::size_t>(index) >= count)
        in.fail("vertex index " + std::to_string(index + 1) + " out of range (1.." +
                std::to_string(count) + ")");
}

TriangleSoup read_obj(const std::string& path)
{
    std::ifstream in(path);
    if (!in) throw IoError(path + ": cannot open for reading");
    TriangleSoup soup;
    std::string line;
    int number = 0;
    auto fail = [&](const std::string& what) {
        throw InputError(path + ":" + std::to_string(number) + ": " + what);
    };
    while (std::getline(in, line))
    {
        ++number;
        std::istringstream s(line);
        std::string key;
        if (!(s >> key)) continue;
        if (key == "v")
        {
            Vec3d p;
            if (!(s >> p[0] >> p[1] >> p[2])) fail("a vertex needs three coordinates");
            for (int c = 0; c < 3; ++c)
            {
                if (!std::isfinite(p[c])) fail("a coordinate is not finite");
                if (std::abs(p[c]) > io::kMaxMagnitude) fail("vertex " + io::too_large(p[c]));
            }
            soup.points.push_back(p);
        }
        else if (key == "f")
        {
            std::vector<int> poly;
            std::string w;
            while (s >> w)
            {
                long index = 0;
                try
                {
                    index = std::stol(w.substr(0, w.find('/')));
                }
                catch (const std::logic_error&)
                {
                    fail("bad face index '" + w + "'");
                }
                if (index < 0)
                    index += static_cast<long>(soup.points.size()) + 1;  // relative index
                if (index < 1 || static_cast<std::size_t>(index) > soup.points.size())
                    fail("face index " + std::to_string(index) + " out of range");
                poly.push_back(static_cast<int>(index - 1));
            }
            if (poly.size() < 3) fail("a face needs at least three vertices");
            for (std::size_t k = 1; k + 1 < poly.size(); ++k)
            {
                soup.triangles.push_back({poly[0], poly[k], poly[k + 1]});
                soup.refs.push_back(0);
            }
        }
    }
    return soup;
}

TriangleSoup read_off(const std::string& path)
{
    const std::string data = io::load_file(path);
    io::TextReader in(path, data, '#');
    TriangleSoup soup;
    if (in.token("OFF header") != "OFF") in.set_position(0, 1);  // the header keyword is optional
    const std::size_t nv = in.count("vertex count", 6), nf = in.count("face count", 8);
    in.integer("edge count");
    for (std::size_t i = 0; i < nv; ++i)
    {
        Vec3d p;
        for (int k = 0; k < 3; ++k) p[k] = in.real("vertex coordinate");
        soup.points.push_back(p);
    }
    for (std::size_t i = 0; i < nf; ++i)
    {
        const long long k = in.integer("face vertex count");
        if (k < 3) in.fail("a face needs at least three vertices");
        std::vector<int> poly;
        for (long long j = 0; j < k; ++j)
        {
            const long long idx = in.integer("vertex index");
            check_index(in, idx, soup.points.size());
            poly.push_back(static_cast<int>(idx));
        }
        in.skip_line();  // colour values may follow on the same line
        for (std::size_t j = 1; j + 1 < poly.size(); ++j)
        {
            soup.triangles.push_back({poly[0], poly[j], poly[j + 1]});
            soup.refs.push_back(0);
        }
    }
    return soup;
}

/// Tokens per record of the Medit sections a surface does not use.
int skipped_medit_tokens_per_item(std::string_view keyword)
{
    struct Width
    {
        const char* keyword;
        int tokens;
    };
    static constexpr Width kWidths[] = {{"Edges", 3},
                                        {"Quadrilaterals", 5},
                                        {"Tetrahedra", 5},
                                        {"Hexahedra", 9},
                                        {"Ridges", 1},
                                        {"Corners", 1},
                                        {"RequiredVertices", 1},
                                        {"RequiredEdges", 1},
                                        {"RequiredTriangles", 1},
                                        {"Normals", 3},
                                        {"NormalAtVertices", 2},
                                        {"Tangents", 3},
                                        {"TangentAtVertices", 2}};
    for (const Width& w : kWidths)
        if (keyword == w.keyword) return w.tokens;
    return 0;
}

TriangleSoup read_medit(const std::string& path)
{
    const std::string data = io::load_file(path);
    io::TextReader in(path, data, '#');
    TriangleSoup soup;
    bool has_vertices = false;
    medit::read_ascii_keywords(
        in, medit::EndKeyword::Optional, nullptr, [&](std::string_view keyword) {
            if (keyword == "Vertices")
            {
                const std::size_t n = in.count("Vertices count", 8);
                for (std::size_t i = 0; i < n; ++i)
                {
                    Vec3d p;
                    for (int k = 0; k < 3; ++k) p[k] = in.real("vertex coordinate");
                    in.integer("vertex ref");
                    soup.points.push_back(p);
                }
                has_vertices = true;
            }
            else if (keyword == "Triangles")
            {
                if (!has_vertices) in.fail("Triangles before Vertices");
                const std::size_t n = in.count("Triangles count", 8);
                for (std::size_t i = 0; i < n; ++i)
                {
                    std::array<int, 3> tri;
                    for (int k = 0; k < 3; ++k)
                    {
                        const long long idx = in.integer("vertex index") - 1;
                        check_index(in, idx, soup.points.size());
                        tri[k] = static_cast<int>(idx);
                    }
                    soup.triangles.push_back(tri);
                    soup.refs.push_back(static_cast<int>(in.integer_in("ref", INT_MIN, INT_MAX)));
                }
            }
            else if (const int width = skipped_medit_tokens_per_item(keyword))
            {
                const std::size_t n = in.count("item count", 2 * width);
                for (std::size_t i = 0; i < n * width; ++i) in.real(std::string(keyword).c_str());
            }
            else
                return false;
            return true;
        });
    return soup;
}

// STL as listed: three points per facet, nothing merged (ASCII, or binary when the size
// matches the facet count of its header).
TriangleSoup read_stl_facets(const std::string& path)
{
    const std::string data = io::load_file(path);
    TriangleSoup soup;
    auto add_facet = [&](const std::array<Vec3d, 3>& corners) {
        const int base = static_cast<int>(soup.points.size());
        for (const auto& p : corners) soup.points.push_back(p);
        soup.triangles.push_back({base, base + 1, base + 2});
        soup.refs.push_back(0);
    };
    if (data.size() >= 84)
    {
        std::uint32_t count = 0;
        std::memcpy(&count, data.data() + 80, 4);
        if (data.size() == 84 + 50 * static_cast<std::size_t>(count))
        {
            for (std::size_t f = 0; f < count; ++f)
            {
                const char* facet = data.data() + 84 + 50 * f + 12;  // after the normal
                std::array<Vec3d, 3> corners;
                for (int k = 0; k < 3; ++k)
                    for (int c = 0; c < 3; ++c)
                    {
                        float x;
                        std::memcpy(&x, facet + 12 * k + 4 * c, 4);
                        if (!std::isfinite(x))
                            throw InputError(path + ": facet " + std::to_string(f + 1) +
                                             ": a coordinate is not finite");
                        if (std::abs(x) > io::kMaxMagnitude)
                            throw InputError(path + ": facet " + std::to_string(f + 1) + ": " +
                                             io::too_large(x));
                        corners[k][c] = x;
                    }
                add_facet(corners);
            }
            return soup;
        }
    }
    io::TextReader in(path, data, 0);
    auto expect = [&](const char* word) {
        if (in.token(word) != word) in.fail(std::string("expected '") + word + "'");
    };
    expect("solid");
    in.skip_line();
    while (!in.at_end())
    {
        const std::string_view word = in.token("facet or endsolid");
        if (word == "endsolid")
        {
            in.skip_line();
            if (!in.at_end())
            {
                expect("solid");
                in.skip_line();
            }
            continue;
        }
        if (word != "facet") in.fail("expected 'facet' or 'endsolid'");
        expect("normal");
        for (int c = 0; c < 3; ++c) in.real("normal coordinate");
        expect("outer");
        expect("loop");
        std::array<Vec3d, 3> corners;
        for (auto& p : corners)
        {
            expect("vertex");
            for (int c = 0; c < 3; ++c) p[c] = in.real("vertex coordinate");
        }
        expect("endloop");
        expect("endfacet");
        add_facet(corners);
    }
    return soup;
}

}  // namespace

SurfaceMesh build_surface(TriangleSoup soup, const std::string& source, ReadReport* report_out,
                          const SoupRepairOptions& repair)
{
    ReadReport report;
    repair_soup(soup, source, repair, &report);
    const TriangleSoup& clean = soup;
    SurfaceMesh mesh;
    SurfaceProperties props(mesh);
    std::vector<VertexHandle> handles;
    handles.reserve(clean.points.size());
    for (const auto& p : clean.points) handles.push_back(mesh.add_vertex(p));
    for (std::size_t f = 0; f < clean.triangles.size(); ++f)
    {
        const auto& t = clean.triangles[f];
        const FaceHandle fh = mesh.add_face(handles[t[0]], handles[t[1]], handles[t[2]]);
        if (!fh.is_valid())
            throw InputError(source + ": triangle " + std::to_string(f + 1) + " (vertices " +
                             std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
                             std::to_string(t[2] + 1) + ") cannot be added to the surface");
        mesh.property(props.face_ref, fh) = clean.refs[f];
    }
    for (auto v : mesh.vertices())
    {
        mesh.property(props.vertex_class, v) = VertexClass::Smooth;
        mesh.property(props.vertex_curve, v) = kNoCurve;
        mesh.property(props.vertex_size, v) = 0.0;
    }
    for (auto e : mesh.edges()) mesh.property(props.edge_curve, e) = kNoCurve;

    if (report_out) *report_out = report;
    return mesh;
}

TriangleSoup read_triangle_soup(const std::string& path)
{
    const std::string ext = lower_extension(path);
    if (ext == "obj") return read_obj(path);
    if (ext == "off") return read_off(path);
    if (ext == "mesh") return read_medit(path);
    if (ext == "stl") return read_stl_facets(path);
    if (ext == "ply") return detail::read_ply(path);
    throw InputError(path + ": unknown surface format '" + ext + "' (obj, off, stl, ply, mesh)");
}

bool is_surface_path(const std::string& path)
{
    const std::string ext = lower_extension(path);
    return ext == "obj" || ext == "off" || ext == "mesh" || ext == "stl" || ext == "ply";
}

SurfaceMesh read_surface(const std::string& path, ReadReport* report,
                         const SoupRepairOptions& repair)
{
    return build_surface(read_triangle_soup(path), path, report, repair);
}

namespace
{

void write_medit(const SurfaceMesh& mesh, const std::string& path)
{
    std::ofstream out(path);
    if (!out) throw IoError(path + ": cannot open for writing");
    out.precision(17);
    OpenMesh::VPropHandleT<VertexClass> vertex_class;
    OpenMesh::EPropHandleT<int> edge_curve;
    OpenMesh::FPropHandleT<int> face_ref;
    const bool classes = mesh.get_property_handle(vertex_class, property_names::vertex_class);
    const bool curves = mesh.get_property_handle(edge_curve, property_names::edge_curve);
    const bool refs = mesh.get_property_handle(face_ref, property_names::face_ref);
    std::vector<int> index(mesh.n_vertices(), -1);
    int n = 0;
    for (auto v : mesh.vertices()) index[v.idx()] = ++n;
    out << "MeshVersionFormatted 2\nDimension 3\nVertices\n" << n << "\n";
    for (auto v : mesh.vertices())
    {
        const Vec3d p = mesh.point(v);
        out << p[0] << " " << p[1] << " " << p[2] << " 0\n";
    }
    out << "Triangles\n" << mesh.n_faces() << "\n";
    for (auto f : mesh.faces())
    {
        for (auto v : mesh.fv_range(f)) out << index[v.idx()] << " ";
        out << (refs ? mesh.property(face_ref, f) : 0) << "\n";
    }
    std::vector<EdgeHandle> features;
    for (auto e : mesh.edges())
        if ((curves && mesh.property(edge_curve, e) != kNoCurve) || mesh.is_boundary(e))
            features.push_back(e);
    if (!features.empty())
    {
        out << "Edges\n" << features.size() << "\n";
        for (auto e : features)
        {
            const auto h = mesh.halfedge_handle(e, 0);
            out << index[mesh.from_vertex_handle(h).idx()] << " "
                << index[mesh.to_vertex_handle(h).idx()] << " "
                << (curves ? mesh.property(edge_curve, e) + 1 : 0) << "\n";
        }
        std::vector<int> ridges;
        for (std::size_t i = 0; i < features.size(); ++i)
            if (!mesh.is_boundary(features[i])) ridges.push_back(static_cast<int>(i) + 1);
        out << "Ridges\n" << ridges.size() << "\n";
        for (int r : ridges) out << r << "\n";
    }
    if (classes)
    {
        std::vector<int> corners;
        for (auto v : mesh.vertices())
            if (mesh.property(vertex_class, v) == VertexClass::Corner)
                corners.push_back(index[v.idx()]);
        out << "Corners\n" << corners.size() << "\n";
        for (int c : corners) out << c << "\n";
    }
    out << "End\n";
    out.flush();
    if (!out) throw IoError(path + ": write failed");
}

/// OBJ, OFF and ASCII PLY at full double precision (OpenMesh's writers of them go through
/// floats, 1e-8 off: a round trip would move every vertex).
void write_polygons(const SurfaceMesh& mesh, const std::string& path, const std::string& ext)
{
    std::ofstream out(path);
    if (!out) throw IoError(path + ": cannot open for writing");
    out.precision(17);
    std::vector<int> index(mesh.n_vertices(), -1);
    int n = 0;
    for (auto v : mesh.vertices()) index[v.idx()] = n++;
    if (ext == "off") out << "OFF\n" << n << " " << mesh.n_faces() << " 0\n";
    if (ext == "ply")
        out << "ply\nformat ascii 1.0\nelement vertex " << n
            << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
            << mesh.n_faces() << "\nproperty list uchar int vertex_indices\nend_header\n";
    const bool obj = ext == "obj";
    for (auto v : mesh.vertices())
    {
        const Vec3d p = mesh.point(v);
        out << (obj ? "v " : "") << p[0] << " " << p[1] << " " << p[2] << "\n";
    }
    for (auto f : mesh.faces())
    {
        out << (obj ? "f" : "3");
        for (auto v : mesh.fv_range(f)) out << " " << index[v.idx()] + (obj ? 1 : 0);
        out << "\n";
    }
    out.flush();
    if (!out) throw IoError(path + ": write failed");
}

}  // namespace

void write_surface(const SurfaceMesh& mesh, const std::string& path)
{
    const std::string ext = lower_extension(path);
    if (ext != "obj" && ext != "off" && ext != "stl" && ext != "ply" && ext != "mesh")
        throw InputError(path + ": unknown surface format '" + ext +
                         "' (obj, off, stl, ply, mesh)");
    // Same folder (rename stays on one file system), same extension (OpenMesh picks the writer by
    // it).
    const std::string temp = path + ".tmp" + std::to_string(::getpid()) + "." + ext;
    if (ext == "mesh")
        write_medit(mesh, temp);
    else if (ext != "stl")  // STL holds floats by definition: OpenMesh's writer is exact there
        write_polygons(mesh, temp, ext);
    else
    {
        OpenMesh::IO::Options options;
        std::ofstream probe(temp);
        if (!probe) throw IoError(path + ": cannot open for writing");
        probe.close();
        if (!OpenMesh::IO::write_mesh(mesh, temp, options, 17))
        {
            std::remove(temp.c_str());
            throw IoError(path + ": write failed");
        }
    }
    if (std::rename(temp.c_str(), path.c_str()) != 0)
    {
        std::remove(temp.c_str());
        throw IoError(path + ": cannot rename the temporary file into place");
    }
}

}  // namespace hdimesh::surface

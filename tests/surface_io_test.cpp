// Reading and writing surfaces, and what happens to bad input: repaired where a user expects it
// (duplicate vertices, degenerate and repeated triangles, inconsistent orientation) with a
// warning, a clear error naming the file and the element otherwise (non-manifold edge,
// malformed line), never a crash. Multi-component and open inputs are remeshed as they are.

#include "surface/surface_io.h"

#include <doctest/doctest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <set>
#include <string>

#include "common/errors.h"
#include "surface/remesh_surface.h"
#include "surface/surface_quality.h"

using namespace hdimesh::surface;
using hdimesh::InputError;
using hdimesh::IoError;

namespace
{

std::string temp_path(const std::string& name)
{
    return "/tmp/hdimesh_surface_io_test_" + std::to_string(::getpid()) + "_" + name;
}

std::string write_text(const std::string& name, const std::string& text)
{
    const std::string path = temp_path(name);
    std::ofstream(path) << text;
    return path;
}

// The surface of the tetrahedron (0,0,0) (1,0,0) (0,1,0) (0,0,1), shifted by `dx`, as OBJ lines.
std::string tetra_obj(double dx, int first_index)
{
    std::string s;
    const double p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (const auto& q : p)
        s += "v " + std::to_string(q[0] + dx) + " " + std::to_string(q[1]) + " " +
             std::to_string(q[2]) + "\n";
    const int f[4][3] = {{1, 3, 2}, {1, 2, 4}, {2, 3, 4}, {3, 1, 4}};
    for (const auto& t : f)
        s += "f " + std::to_string(t[0] + first_index) + " " + std::to_string(t[1] + first_index) +
             " " + std::to_string(t[2] + first_index) + "\n";
    return s;
}

double signed_volume(const SurfaceMesh& mesh)
{
    double v = 0.0;
    for (auto f : mesh.faces())
    {
        std::vector<Vec3d> p;
        for (auto x : mesh.fv_range(f)) p.push_back(mesh.point(x));
        v += OpenMesh::dot(p[0], OpenMesh::cross(p[1], p[2])) / 6.0;
    }
    return v;
}

}  // namespace

TEST_CASE("OBJ, OFF, STL, PLY and Medit round trips keep the geometry; Medit keeps refs")
{
    SurfaceMesh mesh = read_surface(write_text("tet.obj", tetra_obj(0.0, 0)));
    CHECK(mesh.n_vertices() == 4);
    CHECK(mesh.n_faces() == 4);
    CHECK(signed_volume(mesh) == doctest::Approx(1.0 / 6.0));
    SurfaceProperties props(mesh);
    int ref = 1;
    for (auto f : mesh.faces()) mesh.property(props.face_ref, f) = ref++;
    for (const char* ext : {"obj", "off", "stl", "ply", "mesh"})
    {
        const std::string path = temp_path(std::string("round.") + ext);
        write_surface(mesh, path);
        const SurfaceMesh back = read_surface(path);
        CHECK(back.n_vertices() == 4);
        CHECK(back.n_faces() == 4);
        CHECK(signed_volume(back) == doctest::Approx(1.0 / 6.0));
        const auto d = hausdorff_distance(mesh, back);
        CHECK(std::max(d[0], d[1]) < 1e-6);
        if (std::string(ext) == "mesh")
        {
            OpenMesh::FPropHandleT<int> refs;
            REQUIRE(back.get_property_handle(refs, property_names::face_ref));
            std::set<int> seen;
            for (auto f : back.faces()) seen.insert(back.property(refs, f));
            CHECK(seen == std::set<int>{1, 2, 3, 4});
        }
        std::remove(path.c_str());
    }
}

TEST_CASE("OBJ, OFF, PLY and Medit keep every bit of a coordinate; STL its float")
{
    //  a tet whose corners are no floats: 1/3, 0.1, ...
    SurfaceMesh mesh = read_surface(write_text("thirds.obj", tetra_obj(0.0, 0)));
    for (auto v : mesh.vertices())
        mesh.set_point(v, mesh.point(v) * (1.0 / 3.0) + Vec3d(0.1, 0.2, 0.7));
    for (const char* ext : {"obj", "off", "ply", "mesh", "stl"})
    {
        const std::string path = temp_path(std::string("exact.") + ext);
        write_surface(mesh, path);
        const SurfaceMesh back = read_surface(path);
        const bool exact = std::string(ext) != "stl";
        double worst = 0;  // over the vertices, matched by nearest
        for (auto v : mesh.vertices())
        {
            double nearest = 1e300;
            for (auto w : back.vertices())
                nearest = std::min(nearest, (mesh.point(v) - back.point(w)).norm());
            worst = std::max(worst, nearest);
        }
        CAPTURE(ext);
        if (exact)
            CHECK(worst == 0.0);
        else
            CHECK(worst < 1e-7);
        std::remove(path.c_str());
    }
}

TEST_CASE(
    "duplicate vertices are merged, degenerate and repeated triangles dropped, orientation "
    "repaired")
{
    //  the tetrahedron written as a soup: every triangle with its own three vertices, one
    //  triangle turned inside out, one repeated, one degenerate (a repeated vertex).
    std::string text;
    const double p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 3, 2} /* inside out */, {2, 0, 3}};
    int n = 0;
    for (const auto& t : f)
    {
        for (int k = 0; k < 3; ++k)
            text += "v " + std::to_string(p[t[k]][0]) + " " + std::to_string(p[t[k]][1]) + " " +
                    std::to_string(p[t[k]][2]) + "\n";
        text += "f " + std::to_string(n + 1) + " " + std::to_string(n + 2) + " " +
                std::to_string(n + 3) + "\n";
        n += 3;
    }
    text += "f 1 2 3\n";  // repeated
    text += "f 1 1 2\n";  // degenerate
    ReadReport report;
    const SurfaceMesh mesh = read_surface(write_text("soup.obj", text), &report);
    CHECK(mesh.n_vertices() == 4);
    CHECK(mesh.n_faces() == 4);
    CHECK(report.merged_vertices == 8);
    CHECK(report.duplicate_faces == 1);
    CHECK(report.degenerate_faces == 1);
    CHECK(report.reoriented_faces >= 1);
    CHECK(report.notes.size() >= 4);
    CHECK(signed_volume(mesh) == doctest::Approx(1.0 / 6.0));  // outward
    for (auto v : mesh.vertices()) CHECK(mesh.is_manifold(v));
}

TEST_CASE("a non-manifold edge is a clear error naming the edge")
{
    //   three triangles on the edge (1, 2): a fin on a folded sheet.
    const std::string path = write_text("fin.obj",
                                        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                                        "f 1 2 3\nf 2 1 4\nf 1 2 5\n");
    try
    {
        read_surface(path);
        FAIL("no error");
    }
    catch (const InputError& e)
    {
        const std::string message = e.what();
        CHECK(message.find(path) != std::string::npos);
        CHECK(message.find("non-manifold edge between vertices 1 and 2") != std::string::npos);
    }
}

TEST_CASE("malformed and missing files are errors naming the file and line")
{
    const std::string bad = write_text("bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 zero\nf 1 2 3\n");
    CHECK_THROWS_WITH_AS(read_surface(bad), (bad + ":3: a vertex needs three coordinates").c_str(),
                         InputError);
    const std::string range = write_text("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
    CHECK_THROWS_AS(read_surface(range), InputError);
    CHECK_THROWS_AS(read_surface(temp_path("does-not-exist.obj")), IoError);
    CHECK_THROWS_AS(read_surface(temp_path("what.xyz")), InputError);
    const std::string medit = write_text(
        "bad.mesh",
        "MeshVersionFormatted 2\nDimension 3\nVertices\n1\n0 0 0 0\nTriangles\n1\n1 2 3 0\nEnd\n");
    CHECK_THROWS_AS(read_surface(medit), InputError);
}

TEST_CASE("PLY binary in both byte orders, other properties and elements skipped")
{
    // a tetrahedron: vertices with a double x, float y/z and a uchar colour; faces with an int
    // list and a float; an extra 'edge' element after them
    const double p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int f[4][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
    for (const bool big : {false, true})
    {
        CAPTURE(big);
        std::string data = std::string("ply\nformat ") +
                           (big ? "binary_big_endian" : "binary_little_endian") +
                           " 1.0\ncomment made in a test\nelement vertex 4\nproperty double x\n"
                           "property float y\nproperty float z\nproperty uchar red\n"
                           "element face 4\nproperty list uchar int vertex_indices\n"
                           "property float quality\nelement edge 1\nproperty int vertex1\n"
                           "property int vertex2\nend_header\n";
        auto put = [&](auto value) {
            char bytes[sizeof value];
            std::memcpy(bytes, &value, sizeof value);
            if (big) std::reverse(bytes, bytes + sizeof value);
            data.append(bytes, sizeof value);
        };
        for (const auto& q : p)
        {
            put(q[0]);
            put(static_cast<float>(q[1]));
            put(static_cast<float>(q[2]));
            put(static_cast<unsigned char>(200));
        }
        for (const auto& t : f)
        {
            put(static_cast<unsigned char>(3));
            for (int v : t) put(v);
            put(0.5f);
        }
        put(0);
        put(1);
        const std::string path = write_text(big ? "big.ply" : "little.ply", data);
        const SurfaceMesh mesh = read_surface(path);
        CHECK(mesh.n_vertices() == 4);
        CHECK(mesh.n_faces() == 4);
        CHECK(signed_volume(mesh) == doctest::Approx(1.0 / 6.0));
        // cut inside the faces: a clear error naming the byte
        CHECK_THROWS_WITH_AS(read_surface(write_text("cut.ply", data.substr(0, data.size() - 30))),
                             doctest::Contains("byte"), InputError);
    }
}

TEST_CASE("a coordinate too large for the geometry is refused where it is read")
{
    // beyond 1e30 the sixth powers of a volume or quality, or a float box, overflow
    const std::string obj = write_text("huge.obj", "v 0 0 0\nv 1e308 0 0\nv 0 1 0\nf 1 2 3\n");
    CHECK_THROWS_WITH_AS(
        read_surface(obj),
        (obj + ":2: vertex 1e+308 exceeds 1e+30 in magnitude, the largest a coordinate or size "
               "may have")
            .c_str(),
        InputError);
    const std::string off =
        write_text("huge.off", "OFF\n3 1 0\n0 0 0\n1 0 -2e31\n0 1 0\n3 0 1 2\n");
    CHECK_THROWS_WITH_AS(read_surface(off), doctest::Contains((off + ":4:").c_str()), InputError);
    const std::string ply = write_text("huge.ply",
                                       "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                                       "property float y\nproperty float z\nelement face 1\n"
                                       "property list uchar int vertex_indices\nend_header\n"
                                       "0 0 0\n1 0 0\n0 1e37 0\n3 0 1 2\n");
    CHECK_THROWS_WITH_AS(read_surface(ply),
                         doctest::Contains((ply + ":12: y 1e+37 exceeds").c_str()), InputError);
}

TEST_CASE("OFF and Medit surfaces: colours and unused sections skipped, errors name the line")
{
    // one triangle; the OFF face line carries a colour, the Medit file a Corners section
    const std::string off = write_text("colour.off",
                                       "OFF # a comment\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n"
                                       "3 0 1 2 255 0 0\n");
    CHECK(read_surface(off).n_faces() == 1);
    const std::string head =
        "MeshVersionFormatted 2\nDimension 3\nVertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\n";
    const std::string medit =
        write_text("corners.mesh", head + "Corners\n1\n1\nTriangles\n1\n1 2 3 7\nEnd\n");
    CHECK(read_surface(medit).n_faces() == 1);
    // line 10 holds the index 4 of a three-vertex file
    const std::string bad = write_text("index.mesh", head + "Triangles\n1\n1 2 4 0\nEnd\n");
    CHECK_THROWS_WITH_AS(read_surface(bad),
                         (bad + ":10: vertex index 4 out of range (1..3)").c_str(), InputError);
    const std::string unknown = write_text("unknown.mesh", head + "Prisms\n0\nEnd\n");
    CHECK_THROWS_WITH_AS(read_surface(unknown), (unknown + ":8: unknown keyword 'Prisms'").c_str(),
                         InputError);
}

TEST_CASE("a multi-component input keeps its components; an open input keeps its boundary")
{
    // Two tetrahedra far apart.
    SurfaceMesh two = read_surface(write_text("two.obj", tetra_obj(0.0, 0) + tetra_obj(5.0, 4)));
    ReadReport report;
    read_surface(write_text("two_again.obj", tetra_obj(0.0, 0) + tetra_obj(5.0, 4)), &report);
    CHECK(report.components == 2);
    SurfaceRemeshSettings settings;
    settings.sizing.hsiz = 0.25;
    remesh_surface(two, settings);
    CHECK(signed_volume(two) == doctest::Approx(2.0 / 6.0));  // flat faces: volume exact
    int euler = static_cast<int>(two.n_vertices()) - static_cast<int>(two.n_edges()) +
                static_cast<int>(two.n_faces());
    CHECK(euler == 4);  // two spheres
    for (auto v : two.vertices()) CHECK(two.is_manifold(v));

    // An open square sheet of two triangles.
    SurfaceMesh sheet = read_surface(
        write_text("sheet.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n"));
    settings.sizing.hsiz = 0.2;
    remesh_surface(sheet, settings);
    double area = 0.0;
    for (auto f : sheet.faces()) area += sheet.calc_face_area(f);
    CHECK(area == doctest::Approx(1.0));
    int boundary_edges = 0;
    double boundary_length = 0.0;
    for (auto e : sheet.edges())
        if (sheet.is_boundary(e))
        {
            ++boundary_edges;
            boundary_length += sheet.calc_edge_length(e);
        }
    CHECK(boundary_length == doctest::Approx(4.0));
    CHECK(boundary_edges >= 16);
    euler = static_cast<int>(sheet.n_vertices()) - static_cast<int>(sheet.n_edges()) +
            static_cast<int>(sheet.n_faces());
    CHECK(euler == 1);
    const QualityReport q = measure_quality(sheet, 0.2);
    CHECK(q.min_angle_deg > 20.0);
}

TEST_CASE("read_triangle_soup: the file's facets as listed, STL ASCII and binary, nothing merged")
{
    // the tet's four facets in ASCII STL, and a fifth one repeating the first
    const double p[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const int f[5][3] = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}, {0, 2, 1}};
    std::string ascii = "solid tet\n";
    std::string binary(80, ' ');
    const std::uint32_t count = 5;
    binary.append(reinterpret_cast<const char*>(&count), 4);
    for (const auto& t : f)
    {
        ascii += " facet normal 0 0 0\n  outer loop\n";
        binary.append(12, '\0');
        for (int v : t)
        {
            ascii += "   vertex " + std::to_string(p[v][0]) + " " + std::to_string(p[v][1]) + " " +
                     std::to_string(p[v][2]) + "\n";
            for (double x : p[v])
            {
                const float xf = static_cast<float>(x);
                binary.append(reinterpret_cast<const char*>(&xf), 4);
            }
        }
        ascii += "  endloop\n endfacet\n";
        binary.append(2, '\0');
    }
    ascii += "endsolid tet\n";
    for (const auto& [name, text] :
         {std::pair<std::string, std::string>{"a.stl", ascii}, {"b.stl", binary}})
    {
        CAPTURE(name);
        const std::string path = write_text(name, text);
        const TriangleSoup soup = read_triangle_soup(path);
        REQUIRE(soup.triangles.size() == 5);
        CHECK(soup.points.size() == 15);
        for (std::size_t k = 0; k < 5; ++k)
            for (int c = 0; c < 3; ++c)
                CHECK(soup.points[soup.triangles[k][c]][0] == doctest::Approx(p[f[k][c]][0]));
        // the repaired mesh drops the repeated facet and merges the points
        const SurfaceMesh mesh = read_surface(path);
        CHECK(mesh.n_faces() == 4);
        CHECK(mesh.n_vertices() == 4);
        std::remove(path.c_str());
    }
    const std::string bad = write_text("bad.stl", "solid x\n facet normal 0 0 0\n  outer lop\n");
    CHECK_THROWS_AS(read_triangle_soup(bad), InputError);
    std::remove(bad.c_str());
}

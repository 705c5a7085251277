// Round trips through every tet-mesh format, and the details each format must get right:
// refs, feature entities, bitwise coordinates, Gmsh numbering and tags, libMeshb versions,
// .sol values, .vtu layout, atomic writes.

#include "volume/io/tet_io.h"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "common/atomic_file.h"
#include "common/errors.h"
#include "fixtures.h"
#include "volume/check/check.h"

using namespace hdimesh;
namespace fs = std::filesystem;

namespace
{

/// A scratch directory per test binary run, removed at exit.
const fixtures::ScratchDir& scratch()
{
    static const fixtures::ScratchDir dir("hdimesh_tet_io_test");
    return dir;
}

void write_text(const std::string& path, const std::string& text)
{
    std::ofstream out(path, std::ios::binary);
    out << text;
}

std::string read_bytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

void require_clean(const TetMesh& mesh)
{
    const auto violations = check_mesh(mesh);
    INFO(format_violations(violations));
    CHECK(violations.empty());
}

/*
  The feature fixture: [0,1]^3 as 2x2x2 Kuhn cubes (48 tets), every entity kind present.

        6-------7-------8        z = 0 layer of vertex ids (0..8); the layers z = 1/2 and
        |       |       |        z = 1 add 9 and 18. Tets left of x = 1/2 get ref 1, the
        3-------4-------5        others ref 2 (an interface without triangles is legal).
        |       |       |        Boundary triangles: ref 10 + axis * 2 + side.
        0-------1-------2        Edges: the 24 half-segments of the 12 cube edges, ref 100 +
                                 edge number; all are ridges; the 8 cube corners are corners.
*/
TetMesh feature_fixture()
{
    const int n = 2;
    TetMesh mesh = fixtures::box_mesh(n, 0.15, 3);
    auto id = [n](int i, int j, int k) { return i + (n + 1) * (j + (n + 1) * k); };
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        Vec3 c = Vec3::Zero();
        for (int v : mesh.tets[t]) c += 0.25 * mesh.points[v];
        mesh.tet_refs[t] = c.x() < 0.5 ? 1 : 2;
    }
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    {
        const auto& tri = mesh.triangles[f];
        const Vec3 c = (mesh.points[tri[0]] + mesh.points[tri[1]] + mesh.points[tri[2]]) / 3.0;
        for (int axis = 0; axis < 3; ++axis)
        {
            if (std::abs(c[axis]) < 1e-12) mesh.triangle_refs[f] = 10 + 2 * axis;
            if (std::abs(c[axis] - 1) < 1e-12) mesh.triangle_refs[f] = 11 + 2 * axis;
        }
    }
    for (int v = 0; v < mesh.num_vertices(); ++v) mesh.vertex_refs[v] = v % 3 - 1;  // -1, 0, 1
    // the 12 cube edges, each as n segments
    int edge_number = 0;
    for (int axis = 0; axis < 3; ++axis)
        for (int a = 0; a <= n; a += n)
            for (int b = 0; b <= n; b += n, ++edge_number)
                for (int s = 0; s < n; ++s)
                {
                    auto at = [&](int along) {
                        int ijk[3];
                        ijk[axis] = along;
                        ijk[(axis + 1) % 3] = a;
                        ijk[(axis + 2) % 3] = b;
                        return id(ijk[0], ijk[1], ijk[2]);
                    };
                    mesh.edges.push_back({at(s), at(s + 1)});
                    mesh.edge_refs.push_back(100 + edge_number);
                    mesh.ridges.push_back(static_cast<int>(mesh.edges.size()) - 1);
                }
    for (int k = 0; k <= n; k += n)
        for (int j = 0; j <= n; j += n)
            for (int i = 0; i <= n; i += n) mesh.corners.push_back(id(i, j, k));
    mesh.required_vertices = {id(1, 1, 1), id(0, 1, 0)};
    mesh.required_edges = {0, 5, 23};
    mesh.required_triangles = {0, 7, 40};
    mesh.required_tets = {3, 17, 47};
    mesh.classify_vertices();
    return mesh;
}

void check_same_geometry_and_elements(const TetMesh& a, const TetMesh& b)
{
    REQUIRE(a.num_vertices() == b.num_vertices());
    REQUIRE(a.num_tet_slots() == b.num_tet_slots());
    REQUIRE(a.triangles.size() == b.triangles.size());
    for (int v = 0; v < a.num_vertices(); ++v)
        for (int k = 0; k < 3; ++k)
        {
            // bitwise, not approximately: the writers print the shortest exact form
            const double x = a.points[v][k], y = b.points[v][k];
            CHECK(std::memcmp(&x, &y, sizeof(double)) == 0);
        }
    CHECK(a.tets == b.tets);
    CHECK(a.tet_refs == b.tet_refs);
    CHECK(a.triangles == b.triangles);
    CHECK(a.triangle_refs == b.triangle_refs);
    CHECK(a.total_volume() == doctest::Approx(b.total_volume()).epsilon(1e-15));
}

void check_same_medit_entities(const TetMesh& a, const TetMesh& b)
{
    check_same_geometry_and_elements(a, b);
    CHECK(a.vertex_refs == b.vertex_refs);
    CHECK(a.edges == b.edges);
    CHECK(a.edge_refs == b.edge_refs);
    CHECK(a.ridges == b.ridges);
    CHECK(a.corners == b.corners);
    CHECK(a.required_vertices == b.required_vertices);
    CHECK(a.required_edges == b.required_edges);
    CHECK(a.required_triangles == b.required_triangles);
    CHECK(a.required_tets == b.required_tets);
    CHECK(a.vertex_classes == b.vertex_classes);
}

/// Elements with their refs, sorted: Gmsh 4.1 groups elements by entity (ref), so only the
/// order within one ref is kept.
template <std::size_t N>
std::vector<std::pair<int, std::array<int, N>>> sorted_with_refs(
    const std::vector<std::array<int, N>>& items, const std::vector<int>& refs)
{
    std::vector<std::pair<int, std::array<int, N>>> out;
    for (std::size_t i = 0; i < items.size(); ++i) out.push_back({refs[i], items[i]});
    std::sort(out.begin(), out.end());
    return out;
}

/// What Gmsh keeps: elements and refs, edges, corners and the corners' vertex refs; 2.2 keeps
/// the element order too.
void check_same_gmsh_entities(const TetMesh& a, const TetMesh& b, bool same_order)
{
    if (same_order)
    {
        check_same_geometry_and_elements(a, b);
        CHECK(a.edges == b.edges);
        CHECK(a.edge_refs == b.edge_refs);
    }
    else
    {
        REQUIRE(a.num_vertices() == b.num_vertices());
        CHECK(a.points == b.points);
        CHECK(sorted_with_refs(a.tets, a.tet_refs) == sorted_with_refs(b.tets, b.tet_refs));
        CHECK(sorted_with_refs(a.triangles, a.triangle_refs) ==
              sorted_with_refs(b.triangles, b.triangle_refs));
        CHECK(sorted_with_refs(a.edges, a.edge_refs) == sorted_with_refs(b.edges, b.edge_refs));
        CHECK(a.total_volume() == doctest::Approx(b.total_volume()).epsilon(1e-15));
    }
    CHECK(a.corners == b.corners);
    for (int c : b.corners) CHECK(a.vertex_refs[c] == b.vertex_refs[c]);
}

struct GmshVariant
{
    const char* version;
    bool binary;
};
constexpr GmshVariant kGmshVariants[] = {
    {"2.2", false}, {"2.2", true}, {"4.1", false}, {"4.1", true}};

}  // namespace

TEST_CASE("sphere480: the shipped example reads as documented")
{
    const TetMesh mesh = read_mesh(fixtures::data_path("sphere480.mesh"));
    CHECK(mesh.num_vertices() == 156);
    CHECK(mesh.num_live_tets() == 483);
    CHECK(mesh.triangles.size() == 256);
    CHECK(mesh.has_adjacency());
    for (int t = 0; t < mesh.num_tet_slots(); ++t) CHECK(mesh.volume(t) > 0);
    require_clean(mesh);
}

TEST_CASE(
    "sphere480 round trips .mesh -> .meshb -> .msh 2.2 -> .msh 4.1 (ASCII and binary) -> .mesh")
{
    const TetMesh original = read_mesh(fixtures::data_path("sphere480.mesh"));
    TetMesh current = original;
    const std::string chain[] = {"a.mesh", "b.meshb", "c.msh", "d.msh", "e.msh", "f.msh", "g.mesh"};
    const WriteOptions options[] = {{},
                                    {},
                                    {{}, "2.2", false, {}},
                                    {{}, "2.2", true, {}},
                                    {{}, "4.1", false, {}},
                                    {{}, "4.1", true, {}},
                                    {}};
    for (std::size_t k = 0; k < std::size(chain); ++k)
    {
        CAPTURE(chain[k]);
        const std::string path = scratch().file("sphere_" + chain[k]);
        write_mesh(current, path, options[k]);
        current = read_mesh(path);
        check_same_geometry_and_elements(original, current);
        require_clean(current);
    }
    // the last .mesh is byte-identical to the first: nothing drifted along the chain
    CHECK(read_bytes(scratch().file("sphere_a.mesh")) ==
          read_bytes(scratch().file("sphere_g.mesh")));
}

TEST_CASE("Medit .mesh and .meshb keep every entity and ref of the feature fixture")
{
    const TetMesh mesh = feature_fixture();
    require_clean(mesh);
    for (const char* name : {"features.mesh", "features.meshb"})
    {
        CAPTURE(name);
        write_mesh(mesh, scratch().file(name));
        const TetMesh back = read_mesh(scratch().file(name));
        check_same_medit_entities(mesh, back);
        CHECK(back.vertex_classes[mesh.corners[0]] == VertexClass::Corner);
        require_clean(back);
    }
}

TEST_CASE("Gmsh 2.2 and 4.1, ASCII and binary, keep elements, physical refs, edges and corners")
{
    const TetMesh mesh = feature_fixture();
    for (const auto& variant : kGmshVariants)
    {
        CAPTURE(std::string(variant.version));
        CAPTURE(variant.binary);
        const std::string path = scratch().file(std::string("features_") + variant.version +
                                                (variant.binary ? "b" : "") + ".msh");
        WriteOptions options;
        options.gmsh_version = variant.version;
        options.gmsh_binary = variant.binary;
        write_mesh(mesh, path, options);
        const TetMesh back = read_mesh(path);
        check_same_gmsh_entities(mesh, back, std::string(variant.version) == "2.2");
        require_clean(back);
    }
}

TEST_CASE("ASCII coordinates are exact for arbitrary doubles")
{
    // random doubles over many magnitudes: %.6g-style printing would lose them
    TetMesh mesh = fixtures::box_mesh(3, 0.2, 11);
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> scale(-30, 30);
    const double factor = std::pow(10.0, scale(rng));
    for (Vec3& p : mesh.points) p = factor * p + Vec3(1.0 / 3.0, -2.0 / 7.0, 1e-300);
    for (const char* name : {"exact.mesh", "exact.msh"})
    {
        write_mesh(mesh, scratch().file(name));
        const TetMesh back = read_mesh(scratch().file(name));
        check_same_geometry_and_elements(mesh, back);
    }
}

TEST_CASE("dead tets are not written and required tets are renumbered")
{
    TetMesh mesh = feature_fixture();
    // kill two tets (their faces become holes: fine for I/O, the checker is not involved)
    mesh.kill_tet(0);
    mesh.kill_tet(10);
    mesh.required_tets = {5, 10, 47};  // 10 is dead: dropped; 5 -> 4, 47 -> 45
    write_mesh(mesh, scratch().file("dead.mesh"));
    write_mesh(mesh, scratch().file("dead.meshb"));
    for (const char* name : {"dead.mesh", "dead.meshb"})
    {
        const TetMesh back = read_mesh(scratch().file(name));
        CHECK(back.num_tet_slots() == 46);
        CHECK(back.required_tets == std::vector<int>{4, 45});
        CHECK(back.tets[4] == mesh.tets[5]);
        CHECK(back.total_volume() == doctest::Approx(mesh.total_volume()));
    }
}

/*
  Gmsh numbering: node tags need not be 1..n nor sorted, element tags are free, and the
  physical tag (first tag in 2.2) is the ref. One tet (0,0,0) (1,0,0) (0,1,0) (0,0,1) listed
  in Gmsh's reference order must come out positive, with its four faces as triangles.
*/
TEST_CASE("Gmsh 2.2 with sparse node tags, physical names and unknown sections")
{
    const std::string text =
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
        "$PhysicalNames\n2\n2 5 \"skin\"\n3 9 \"body with spaces\"\n$EndPhysicalNames\n"
        "$Comments\nanything $Nodes here is ignored\n$EndComments\n"
        "$Nodes\n4\n40 0 0 0\n7 1 0 0\n1000 0 1 0\n3 0 0 1\n$EndNodes\n"
        "$Elements\n5\n"
        "11 4 2 9 1 40 7 1000 3\n"
        "12 2 2 5 2 7 1000 3\n"
        "13 2 2 5 2 40 3 1000\n"
        "14 2 2 5 2 40 7 3\n"
        "15 2 2 5 2 40 1000 7\n"
        "$EndElements\n";
    write_text(scratch().file("sparse22.msh"), text);
    const TetMesh mesh = read_mesh(scratch().file("sparse22.msh"));
    REQUIRE(mesh.num_vertices() == 4);
    CHECK(mesh.points[1] == Vec3(1, 0, 0));
    CHECK(mesh.tets[0] == TetVertices{0, 1, 2, 3});
    CHECK(mesh.tet_refs[0] == 9);
    CHECK(mesh.volume(0) == doctest::Approx(1.0 / 6.0));
    CHECK(mesh.triangle_refs == std::vector<int>{5, 5, 5, 5});
    require_clean(mesh);
}

TEST_CASE("Gmsh 4.1 text: physical tags come from entities, parametric nodes are read")
{
    const std::string text =
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
        "$Entities\n0 0 1 1\n"
        "4 0 0 0 1 1 0 1 21 0\n"
        "6 0 0 0 1 1 1 1 33 1 4\n"
        "$EndEntities\n"
        "$Nodes\n2 4 1 9\n"
        "2 4 1 1\n9\n0 1 0 0.5 0.5\n"
        "3 6 0 3\n1\n2\n5\n0 0 0\n1 0 0\n0 0 1\n"
        "$EndNodes\n"
        "$Elements\n2 2 1 2\n"
        "3 6 4 1\n1 1 2 9 5\n"
        "2 4 2 1\n2 1 9 2\n"
        "$EndElements\n";
    write_text(scratch().file("entities41.msh"), text);
    const TetMesh mesh = read_mesh(scratch().file("entities41.msh"));
    REQUIRE(mesh.num_vertices() == 4);
    CHECK(mesh.points[0] == Vec3(0, 1, 0));  // node 9, listed first
    CHECK(mesh.tet_refs == std::vector<int>{33});
    CHECK(mesh.triangle_refs == std::vector<int>{21});
    CHECK(mesh.volume(0) > 0);
}

namespace
{

/// A libMeshb file built byte by byte for the versions and byte orders we do not write.
class MeshbBuilder
{
public:
    MeshbBuilder(int version, bool swap) : version_(version), swap_(swap)
    {
        put<std::int32_t>(1);
        put<std::int32_t>(version);
    }
    template <class T>
    void put(T value)
    {
        unsigned char bytes[sizeof(T)];
        std::memcpy(bytes, &value, sizeof(T));
        if (swap_)
            for (std::size_t i = 0; i < sizeof(T) / 2; ++i)
                std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
        data_.append(reinterpret_cast<const char*>(bytes), sizeof(T));
    }
    void integer(long long v)
    {
        if (version_ == 4)
            put<std::int64_t>(v);
        else
            put<std::int32_t>(static_cast<std::int32_t>(v));
    }
    void real(double v)
    {
        if (version_ == 1)
            put<float>(static_cast<float>(v));
        else
            put<double>(v);
    }
    /// keyword code, then the next position patched once the block is complete
    void begin(int code)
    {
        put<std::int32_t>(code);
        position_at_ = data_.size();
        if (version_ >= 3)
            put<std::int64_t>(0);
        else
            put<std::int32_t>(0);
    }
    void end_block()
    {
        const long long next = static_cast<long long>(data_.size());
        const std::string after = data_.substr(position_at_ + (version_ >= 3 ? 8 : 4));
        data_.resize(position_at_);
        if (version_ >= 3)
            put<std::int64_t>(next);
        else
            put<std::int32_t>(static_cast<std::int32_t>(next));
        data_ += after;
    }
    std::string bytes() const { return data_; }

private:
    int version_;
    bool swap_;
    std::string data_;
    std::size_t position_at_ = 0;
};

std::string single_tet_meshb(int version, bool swap, bool with_normals)
{
    MeshbBuilder b(version, swap);
    b.begin(3);
    b.put<std::int32_t>(3);
    b.end_block();
    b.begin(4);
    b.integer(4);
    const double xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int v = 0; v < 4; ++v)
    {
        for (double c : xyz[v]) b.real(c);
        b.integer(v + 20);
    }
    b.end_block();
    if (with_normals)
    {
        b.begin(60);  // Normals: skipped through the next position
        b.integer(1);
        for (int k = 0; k < 3; ++k) b.real(1.0);
        b.end_block();
        b.begin(7);  // an empty Quadrilaterals section: harmless
        b.integer(0);
        b.end_block();
    }
    b.begin(8);
    b.integer(1);
    for (long long v : {1, 2, 3, 4, 7}) b.integer(v);
    b.end_block();
    b.begin(13);
    b.integer(1);
    b.integer(4);
    b.end_block();
    b.begin(54);
    return b.bytes();
}

}  // namespace

TEST_CASE("libMeshb versions 1-4, both byte orders, skipping Normals and empty Quadrilaterals")
{
    for (int version = 1; version <= 4; ++version)
        for (bool swap : {false, true})
        {
            CAPTURE(version);
            CAPTURE(swap);
            const std::string path =
                scratch().file("v" + std::to_string(version) + (swap ? "s" : "") + ".meshb");
            write_text(path, single_tet_meshb(version, swap, version % 2 == 0));
            const TetMesh mesh = read_mesh(path);
            REQUIRE(mesh.num_vertices() == 4);
            CHECK(mesh.points[3] == Vec3(0, 0, 1));
            CHECK(mesh.vertex_refs == std::vector<int>{20, 21, 22, 23});
            CHECK(mesh.tet_refs == std::vector<int>{7});
            CHECK(mesh.corners == std::vector<int>{3});
            CHECK(mesh.volume(0) == doctest::Approx(1.0 / 6.0));
        }
}

TEST_CASE("Medit ASCII: comments, keyword layout and skipped derived keywords")
{
    const std::string text =
        "# written by hand\nMeshVersionFormatted 1\nDimension\n3\n"
        "Vertices 4\n0 0 0 1\n1 0 0 1 # trailing comment\n0 1 0 1\n+0 0 1.0e+00 1\n"
        "Normals\n1\n0 0 1\nNormalAtVertices\n1\n1 1\n"
        "Tetrahedra\n1\n1 2 3 4 5\nRequiredTetrahedra\n1\n1\nEnd\n";
    write_text(scratch().file("hand.mesh"), text);
    const TetMesh mesh = read_mesh(scratch().file("hand.mesh"));
    CHECK(mesh.num_vertices() == 4);
    CHECK(mesh.points[3] == Vec3(0, 0, 1));
    CHECK(mesh.tet_refs == std::vector<int>{5});
    CHECK(mesh.required_tets == std::vector<int>{0});
}

/*
  A surface-only file (the input of surface remeshing + tet meshing): the unit tet's four
  outward faces, no Tetrahedra section. Every format keeps it; vertices become Surface.
*/
TEST_CASE("surface-only meshes (triangles, no tets) round trip in every format")
{
    TetMesh surface = fixtures::single_tet();
    surface.tets.clear();
    surface.tet_refs.clear();
    surface.neighbors.clear();
    for (int f = 0; f < 4; ++f) surface.triangle_refs[f] = 20 + f;
    for (const char* name : {"surface.mesh", "surface.meshb", "surface.msh", "SURFACE22.MSH"})
    {
        CAPTURE(name);
        WriteOptions options;
        if (std::string(name) == "SURFACE22.MSH") options.gmsh_version = "2.2";
        write_mesh(surface, scratch().file(name), options);
        const TetMesh back = read_mesh(scratch().file(name));
        CHECK(back.num_tet_slots() == 0);
        CHECK(back.points == surface.points);
        CHECK(back.triangles == surface.triangles);
        CHECK(back.triangle_refs == surface.triangle_refs);
        for (VertexClass c : back.vertex_classes) CHECK(c == VertexClass::Surface);
    }
}

TEST_CASE(".sol and .solb round trip bitwise and check the vertex count")
{
    std::vector<double> values;
    std::mt19937_64 rng(2);
    std::uniform_real_distribution<double> u(1e-4, 10);
    for (int i = 0; i < 257; ++i) values.push_back(u(rng));
    for (const char* name : {"sizes.sol", "sizes.solb"})
    {
        CAPTURE(name);
        write_sol(values, scratch().file(name));
        const auto back = read_sol(scratch().file(name), 257);
        REQUIRE(back.size() == values.size());
        CHECK(std::memcmp(back.data(), values.data(), 8 * values.size()) == 0);
        CHECK_THROWS_AS(read_sol(scratch().file(name), 256), InputError);
    }
}

TEST_CASE(".vtu: header counts and appended arrays are consistent")
{
    const TetMesh mesh = read_mesh(fixtures::data_path("sphere480.mesh"));
    WriteOptions options;
    options.vertex_sizes.assign(mesh.num_vertices(), 0.25);
    write_mesh(mesh, scratch().file("sphere.vtu"), options);
    const std::string vtu = read_bytes(scratch().file("sphere.vtu"));
    CHECK(vtu.find("NumberOfPoints=\"156\"") != std::string::npos);
    CHECK(vtu.find("NumberOfCells=\"739\"") != std::string::npos);  // 483 tets + 256 triangles
    for (const char* name :
         {"\"size\"", "\"ref\"", "\"Qe\"", "\"connectivity\"", "\"offsets\"", "\"types\""})
        CHECK(vtu.find(name) != std::string::npos);
    // the appended block holds exactly the announced arrays (each with its 8-byte size)
    const std::size_t start = vtu.find('_', vtu.find("<AppendedData")) + 1;
    const std::size_t stop = vtu.rfind("\n  </AppendedData>");
    const std::size_t nv = 156, nc = 739;
    const std::size_t expected =
        7 * 8 + 8 * nv + 4 * nc + 8 * nc + 24 * nv + 8 * (4 * 483 + 3 * 256) + 8 * nc + nc;
    CHECK(stop - start == expected);

    options.vertex_sizes.pop_back();
    CHECK_THROWS_AS(write_mesh(mesh, scratch().file("bad.vtu"), options), InputError);
    CHECK_FALSE(fs::exists(scratch().file("bad.vtu")));
}

TEST_CASE("atomic writes: a failing writer leaves the old file intact and no temporary")
{
    const std::string path = scratch().file("atomic.txt");
    write_file_atomically(path, [](std::ostream& out) { out << "old"; });
    CHECK_THROWS_AS(write_file_atomically(path,
                                          [](std::ostream& out) {
                                              out << "partial";
                                              throw IoError("simulated failure");
                                          }),
                    IoError);
    CHECK(read_bytes(path) == "old");
    int files = 0;
    for (const auto& entry : fs::directory_iterator(scratch().path))
        files += entry.path().filename().string().rfind("atomic.txt", 0) == 0;
    CHECK(files == 1);
    CHECK_THROWS_AS(write_mesh(fixtures::single_tet(), scratch().file("no/such/dir/x.mesh")),
                    IoError);
    CHECK_THROWS_AS(write_mesh(fixtures::single_tet(), scratch().file("x.stl")), InputError);
}

// --- Gmsh $NodeData: fields at the vertices written with the mesh and read back

TEST_CASE("Gmsh $NodeData round trips scalars, vectors and tensors in every variant")
{
    const TetMesh mesh = feature_fixture();
    const int nv = mesh.num_vertices();
    PointField u{"u", 1, {}}, w{"velocity field", 3, {}}, m{"metric", 6, {}};
    for (int v = 0; v < nv; ++v)
    {
        const Vec3& p = mesh.points[v];
        u.values.push_back(1 + 2 * p.x() - p.y() + 3 * p.z() + 1e-17 * v);
        for (int k = 0; k < 3; ++k) w.values.push_back(p[k] * (k + 1) - 0.1);
        for (int k = 0; k < 6; ++k) m.values.push_back(v + 0.125 * k);
    }
    for (const auto& variant : kGmshVariants)
    {
        CAPTURE(std::string(variant.version));
        CAPTURE(variant.binary);
        const std::string path = scratch().file(std::string("nodedata_") + variant.version +
                                                (variant.binary ? "b" : "") + ".msh");
        WriteOptions options;
        options.gmsh_version = variant.version;
        options.gmsh_binary = variant.binary;
        options.point_fields = {u, w, m};
        write_mesh(mesh, path, options);
        const TetMesh back = read_mesh(path);  // the mesh reads as before: $NodeData skipped
        check_same_gmsh_entities(mesh, back, std::string(variant.version) == "2.2");
        const std::vector<PointField> fields = read_point_fields(path, back);
        REQUIRE(fields.size() == 3);
        CHECK(fields[0].name == "u");
        CHECK(fields[0].values == u.values);  // bitwise: shortest round-trip text or raw
        CHECK(fields[1].name == "velocity field");
        CHECK(fields[1].components == 3);
        CHECK(fields[1].values == w.values);
        // the symmetric tensor goes out as Gmsh's full 3x3 (m11 m12 m13 m22 m23 m33 -> 9)
        REQUIRE(fields[2].components == 9);
        for (int v = 0; v < nv; ++v)
        {
            const double* full = &fields[2].values[9 * v];
            const double* sym = &m.values[6 * v];
            CHECK(full[1] == sym[1]);
            CHECK(full[3] == sym[1]);
            CHECK(full[4] == sym[3]);
            CHECK(full[7] == sym[4]);
            CHECK(full[8] == sym[5]);
        }
    }
}

namespace
{

const char* kSparseNodes =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
    "$Nodes\n4\n40 0 0 0\n7 1 0 0\n1000 0 1 0\n3 0 0 1\n$EndNodes\n"
    "$Elements\n1\n11 4 2 9 1 40 7 1000 3\n$EndElements\n";

std::string node_data(const std::string& rows, int count = 4, int components = 1)
{
    return "$NodeData\n1\n\"p\"\n1\n0.0\n3\n0\n" + std::to_string(components) + "\n" +
           std::to_string(count) + "\n" + rows + "$EndNodeData\n";
}

}  // namespace

TEST_CASE("Gmsh $NodeData: node tags map through $Nodes, or 1..n without them")
{
    const std::string mesh_path = scratch().file("nd_sparse.msh");
    write_text(mesh_path, std::string(kSparseNodes) + node_data("1000 3.5\n40 1\n3 -2\n7 0.25\n"));
    const TetMesh mesh = read_mesh(mesh_path);
    const std::vector<PointField> fields = read_point_fields(mesh_path, mesh);
    REQUIRE(fields.size() == 1);
    CHECK(fields[0].values == std::vector<double>{1, 0.25, 3.5, -2});

    // only $NodeData (a Gmsh view saved without its mesh): tag k is vertex k
    const std::string view = scratch().file("nd_view.msh");
    write_text(view, "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n" +
                         node_data("2 20\n1 10\n4 40\n3 30\n") +
                         "$NodeData\n0\n0\n3\n0\n3\n4\n1 1 2 3\n2 1 2 3\n3 1 2 3\n4 1 2 3\n"
                         "$EndNodeData\n");
    const std::vector<PointField> only = read_point_fields(view, mesh);
    REQUIRE(only.size() == 2);
    CHECK(only[0].values == std::vector<double>{10, 20, 30, 40});
    CHECK(only[1].name == "field2");
    CHECK(only[1].components == 3);
}

TEST_CASE("Gmsh $NodeData: bad sections are InputErrors naming the file and line")
{
    const TetMesh mesh = [] {
        write_text(scratch().file("nd_base.msh"), kSparseNodes);
        return read_mesh(scratch().file("nd_base.msh"));
    }();
    struct Bad
    {
        const char* name;
        std::string data;
        const char* message;
    };
    const Bad cases[] = {
        {"count", node_data("40 1\n7 2\n3 3\n", 3), "nd_count.msh:23: $NodeData 'p' has 3 values"},
        {"tag", node_data("40 1\n7 2\n8 3\n3 4\n"), "nd_tag.msh:26: $NodeData 'p': node 8 is not"},
        {"nan", node_data("40 1\n7 nan\n1000 3\n3 4\n"), "nd_nan.msh:25:"},
        {"twice", node_data("40 1\n7 2\n40 3\n3 4\n"), "node 40 given twice"},
        {"components", node_data("40 1 1\n", 4, 2), "has 2 components"},
        {"same name", node_data("40 1\n7 2\n1000 3\n3 4\n") + node_data("40 1\n7 2\n1000 3\n3 4\n"),
         "a second $NodeData 'p'"},
        {"none", "", "no $NodeData section"},
    };
    for (const Bad& bad : cases)
    {
        CAPTURE(bad.name);
        const std::string path =
            scratch().file(std::string("nd_") +
                           (bad.name == std::string("same name") ? "same" : bad.name) + ".msh");
        write_text(path, kSparseNodes + bad.data);
        CHECK_THROWS_WITH_AS(read_point_fields(path, mesh), doctest::Contains(bad.message),
                             InputError);
    }
    // another mesh's nodes: the fields would land on the wrong vertices
    TetMesh moved = mesh;
    moved.points[2].x() += 0.5;
    write_text(scratch().file("nd_moved.msh"),
               kSparseNodes + node_data("40 1\n7 2\n1000 3\n3 4\n"));
    CHECK_THROWS_WITH_AS(read_point_fields(scratch().file("nd_moved.msh"), moved),
                         doctest::Contains("node 1000 is not at the mesh's vertex 3"), InputError);
    // the writer refuses what Gmsh cannot hold
    WriteOptions options;
    options.point_fields = {{"two", 2, std::vector<double>(8, 0.0)}};
    CHECK_THROWS_WITH_AS(write_mesh(mesh, scratch().file("nd_out.msh"), options),
                         doctest::Contains("cannot be a $NodeData"), InputError);
}

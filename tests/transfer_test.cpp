// Solution transfer (volume/mesh/field_transfer.h): fields at a coarse mesh's vertices carried
// onto a finer, moved mesh by P1 interpolation, exact for linear fields inside and outside the
// input, from each vertex's own region at an interface; the multi-solution .sol files adapt
// --field reads and writes.

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <random>
#include <string>

#include "common/errors.h"
#include "common/parallel.h"
#include "common/sol_io.h"
#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/io/tet_io.h"
#include "volume/mesh/field_transfer.h"

using namespace hdimesh;
using namespace hdimesh::volume;

namespace
{

const fixtures::ScratchDir& scratch()
{
    static const fixtures::ScratchDir dir("hdimesh_transfer_test");
    return dir;
}

double linear(const Vec3& p) { return 0.7 + 1.3 * p.x() - 2.1 * p.y() + 0.4 * p.z(); }

VertexField scalar_field(const TetMesh& mesh, double (*f)(const Vec3&))
{
    VertexField field;
    for (const Vec3& p : mesh.points) field.values.push_back(f(p));
    return field;
}

/// The refs by the side of the plane x = 0.5 a tet's centroid lies on: 1 left, 2 right.
void split_regions_at_half(TetMesh& mesh)
{
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        Vec3 centroid = Vec3::Zero();
        for (int v : mesh.tets[t]) centroid += 0.25 * mesh.points[v];
        mesh.tet_refs[t] = centroid.x() < 0.5 ? 1 : 2;
    }
}

}  // namespace

//   source: box_mesh(3), jittered         target: box_mesh(7), jittered, its face x = 1
//   +-----+-----+-----+                   bulged outward (x = 1 + 0.05 y z): those vertices
//   |  coarse tets    |   f = a+bx+cy+dz  are in no source tet and are extrapolated
//   +-----+-----+-----+                   from the nearest one, exactly
TEST_CASE("a linear field is carried exactly, inside the input and extrapolated outside it")
{
    const TetMesh source = fixtures::box_mesh(3, 0.2, 7);
    TetMesh target = fixtures::box_mesh(7, 0.2, 11);
    int bulged = 0;
    for (Vec3& p : target.points)
        if (p.x() == 1.0 && p.y() > 0 && p.z() > 0)
        {
            p.x() += 0.05 * p.y() * p.z();
            ++bulged;
        }
    REQUIRE(bulged == 49);
    CHECK(check_mesh(target).empty());

    // a scalar and a vector (three linear components) together
    std::vector<VertexField> fields = {scalar_field(source, linear), {3, {}}};
    for (const Vec3& p : source.points)
        for (int c = 0; c < 3; ++c) fields[1].values.push_back(c - 2 * p[c] + p[(c + 1) % 3]);

    const TransferSource from(source);
    const TransferReport report = transfer_fields(from, fields, target);
    REQUIRE(report.fields.size() == 2);
    CHECK(report.vertices == target.num_vertices());
    CHECK(report.outside == bulged);
    CHECK(report.other_region == 0);
    CHECK(report.max_outside_distance == doctest::Approx(0.05).epsilon(0.01));
    double max_error = 0;
    for (int v = 0; v < target.num_vertices(); ++v)
    {
        const Vec3& p = target.points[v];
        max_error = std::max(max_error, std::abs(report.fields[0].values[v] - linear(p)));
        for (int c = 0; c < 3; ++c)
            max_error = std::max(max_error, std::abs(report.fields[1].values[3 * v + c] -
                                                     (c - 2 * p[c] + p[(c + 1) % 3])));
    }
    MESSAGE("linear field: max error " << max_error);
    CHECK(max_error < 1e-12);

    // the same bits for any thread count
    Workers workers(3);
    TransferOptions options;
    options.workers = &workers;
    const TransferReport threaded = transfer_fields(from, fields, target, options);
    for (int k = 0; k < 2; ++k)
        CHECK(std::memcmp(threaded.fields[k].values.data(), report.fields[k].values.data(),
                          8 * report.fields[k].values.size()) == 0);
}

//   source refs:  1 | 2       f = x left of x = 0.5, 0.5 + 10 (x - 0.5) right (a kink there)
//   target: the interface's vertices moved to x = 0.5 + 0.03 (y - 0.5): half lie in ref 2's
//   tets, half in ref 1's. Each belongs to its lowest ref, 1, so takes x (ref 1's function,
//   extrapolated); a vertex inside one region takes that region's function.
TEST_CASE("at an interface a vertex takes its values from its own region's tet")
{
    TetMesh source = fixtures::box_mesh(4);
    split_regions_at_half(source);
    auto kinked = [](const Vec3& p) { return p.x() <= 0.5 ? p.x() : 0.5 + 10 * (p.x() - 0.5); };
    VertexField field;
    for (const Vec3& p : source.points) field.values.push_back(kinked(p));

    TetMesh target = fixtures::box_mesh(6);
    split_regions_at_half(target);
    std::vector<int> own_ref(target.num_vertices(), 3);
    for (int t = 0; t < target.num_tet_slots(); ++t)
        for (int v : target.tets[t]) own_ref[v] = std::min(own_ref[v], target.tet_refs[t]);
    int interface_vertices = 0;
    for (Vec3& p : target.points)
        if (std::abs(p.x() - 0.5) < 1e-12)
        {
            p.x() = 0.5 + 0.03 * (p.y() - 0.5);
            ++interface_vertices;
        }
    REQUIRE(interface_vertices == 49);

    const TransferReport report = transfer_fields(TransferSource(source), {field}, target);
    double max_error = 0;
    for (int v = 0; v < target.num_vertices(); ++v)
    {
        const Vec3& p = target.points[v];
        const double expected = own_ref[v] == 1 ? p.x() : 0.5 + 10 * (p.x() - 0.5);
        max_error = std::max(max_error, std::abs(report.fields[0].values[v] - expected));
    }
    CHECK(max_error < 1e-12);
    // the vertices moved into ref 2 (y > 0.5: 21) were found in its tets and sent back to ref 1
    CHECK(report.other_region >= 21);
    CHECK(report.outside == 0);
}

TEST_CASE("a field of the wrong size is refused, naming it")
{
    const TetMesh mesh = fixtures::box_mesh(2);
    const TransferSource from(mesh);
    VertexField short_field;
    short_field.values.assign(mesh.num_vertices() - 1, 1.0);
    try
    {
        transfer_fields(from, {short_field}, mesh);
        FAIL("no InputError");
    }
    catch (const InputError& e)
    {
        CHECK(std::string(e.what()).find("field 1 has 26 values, not 27 vertices") !=
              std::string::npos);
    }
}

TEST_CASE(".sol and .solb with several solutions round trip bitwise, types and order kept")
{
    Solutions written;
    written.num_vertices = 5;
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-10, 10);
    for (SolType type : {SolType::Vector, SolType::Scalar, SolType::Tensor, SolType::Scalar})
    {
        Solution solution{type, {}};
        for (int i = 0; i < 5 * sol_components(type); ++i) solution.values.push_back(u(rng));
        written.solutions.push_back(solution);
    }
    for (const char* name : {"fields.sol", "fields.solb"})
    {
        CAPTURE(name);
        write_solutions(written, scratch().file(name));
        const Solutions back = read_solutions(scratch().file(name), 5);
        CHECK(back.num_vertices == 5);
        REQUIRE(back.solutions.size() == 4);
        for (std::size_t k = 0; k < 4; ++k)
        {
            CHECK(back.solutions[k].type == written.solutions[k].type);
            REQUIRE(back.solutions[k].values.size() == written.solutions[k].values.size());
            CHECK(std::memcmp(back.solutions[k].values.data(), written.solutions[k].values.data(),
                              8 * written.solutions[k].values.size()) == 0);
        }
        CHECK_THROWS_AS(read_solutions(scratch().file(name), 6), InputError);
        // the single-scalar reader refuses several solutions
        CHECK_THROWS_AS(read_sol(scratch().file(name)), InputError);
    }
    // a single scalar written by write_sol reads back as one scalar solution
    write_sol({1.5, 2.5}, scratch().file("one.sol"));
    const Solutions one = read_solutions(scratch().file("one.sol"));
    REQUIRE(one.solutions.size() == 1);
    CHECK(one.solutions[0].type == SolType::Scalar);
    CHECK(one.solutions[0].values == std::vector<double>{1.5, 2.5});
}

TEST_CASE("a bad multi-solution .sol is refused naming the file and the line")
{
    auto message = [](const std::string& name, const std::string& text, int expected) {
        const std::string path = scratch().file(name);
        std::ofstream(path) << text;
        try
        {
            read_solutions(path, expected);
        }
        catch (const InputError& e)
        {
            return std::string(e.what());
        }
        FAIL("no InputError for " << name);
        return std::string();
    };
    auto contains = [](const std::string& text, const std::string& part) {
        CAPTURE(text);
        CHECK(text.find(part) != std::string::npos);
    };
    const std::string head = "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n";
    const std::string count = message("count.sol", head + "2\n2 1 2\n1 1 2 3\n1 1 2 3\nEnd\n", 3);
    contains(count, "count.sol:4:");
    contains(count, "has 2 values but the mesh has 3 vertices");
    const std::string nan = message("nan.sol", head + "2\n2 1 2\n1 1 2 3\n1 nan 2 3\nEnd\n", 2);
    contains(nan, "nan.sol:7:");
    const std::string type = message("type.sol", head + "2\n2 1 4\n1 1\n1 1\nEnd\n", 2);
    contains(type, "type.sol:5:");
    contains(type, "unknown solution type 4");
    const std::string cut = message("cut.sol", head + "2\n2 1 2\n1 1 2 3\n1 1\n", 2);
    contains(cut, "cut.sol:");
}

TEST_CASE(".vtu point data: carried fields after size, with their component counts")
{
    const TetMesh mesh = fixtures::box_mesh(2);
    const int nv = mesh.num_vertices();
    WriteOptions options;
    options.point_fields.push_back({"field1", 1, std::vector<double>(nv, 1.5)});
    options.point_fields.push_back({"field2", 3, std::vector<double>(3 * nv, -2.0)});
    const std::string path = scratch().file("fields.vtu");
    write_mesh(mesh, path, options);
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    CHECK(text.find("<PointData>") != std::string::npos);
    CHECK(text.find("Name=\"field1\" format=\"appended\" offset=\"0\"") != std::string::npos);
    // the second array starts after the first's 8-byte size and its nv doubles
    CHECK(text.find("Name=\"field2\" NumberOfComponents=\"3\" format=\"appended\" offset=\"" +
                    std::to_string(8 + 8 * nv) + "\"") != std::string::npos);
    options.point_fields[1].values.pop_back();
    CHECK_THROWS_AS(write_mesh(mesh, scratch().file("bad.vtu"), options), InputError);
    CHECK(!std::ifstream(scratch().file("bad.vtu")).good());
}

// Bad input: every malformed file gives a typed exception whose message names the file and
// the line (text formats), the byte (binary formats) or the element; randomly truncated and
// corrupted copies of valid files never crash, hang or throw anything else.

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>

#include "common/errors.h"
#include "common/sol_io.h"
#include "fixtures.h"
#include "volume/check/check.h"
#include "volume/io/tet_io.h"

using namespace hdimesh;
namespace fs = std::filesystem;

namespace
{

/// A scratch directory per test binary run, removed at exit.
const fixtures::ScratchDir& scratch()
{
    static const fixtures::ScratchDir dir("hdimesh_bad_input_test");
    return dir;
}

std::string write_text(const std::string& name, const std::string& text)
{
    const std::string path = scratch().file(name);
    // a fresh file rather than a truncated one: ext4 flushes truncated-and-rewritten files to
    // disk on close, which made the fuzz loop wait on the disk rather than compute
    std::error_code ignored;
    fs::remove(path, ignored);
    std::ofstream out(path, std::ios::binary);
    out << text;
    return path;
}

std::string read_bytes(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

/// The InputError message of reading `text` as file `name`; fails the test if nothing throws.
std::string input_error(const std::string& name, const std::string& text)
{
    const std::string path = write_text(name, text);
    try
    {
        read_mesh(path);
    }
    catch (const InputError& e)
    {
        return e.what();
    }
    FAIL("no InputError for " << name);
    return "";
}

/// Checks the message names the file and the expected location and cause.
void check_message(const std::string& message, const std::string& name, const std::string& where,
                   const std::string& cause)
{
    INFO(message);
    CHECK(message.find(scratch().file(name) + where) == 0);
    CHECK(message.find(cause) != std::string::npos);
}

const std::string kHeader = "MeshVersionFormatted 2\nDimension 3\n";  // lines 1-2
// lines 3-8: the unit tet's vertices
const std::string kVertices = "Vertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n";

}  // namespace

TEST_CASE("Medit: empty, blank and missing files")
{
    check_message(input_error("empty.mesh", ""), "empty.mesh", ": ", "empty file");
    check_message(input_error("blank.mesh", "\n  # only a comment\n"), "blank.mesh", ":",
                  "no Medit keyword");
    CHECK_THROWS_AS(read_mesh(scratch().file("does_not_exist.mesh")), IoError);
    CHECK_THROWS_AS(read_mesh(scratch().file("unknown.xyz")), InputError);
}

TEST_CASE("Medit: truncated file and missing End")
{
    // cut in the middle of the 3rd vertex (line 7); the comment keeps the count plausible
    check_message(
        input_error("cut.mesh",
                    kHeader + "Vertices\n4\n0 0 0 0\n1 0 0 0\n0 1 # cut here, and a long comment"),
        "cut.mesh", ":7:", "unexpected end of file");
    // without it, the count alone shows the file cannot hold the announced vertices
    check_message(input_error("cut2.mesh", kHeader + "Vertices\n4\n0 0 0 0\n1 0 0 0\n0 1"),
                  "cut2.mesh", ":4:", "truncated");
    check_message(input_error("noend.mesh", kHeader + kVertices + "Tetrahedra\n1\n1 2 3 4 1\n"),
                  "noend.mesh", ":", "missing End");
}

TEST_CASE("Medit: wrong counts")
{
    // count 5 but 4 vertices: the 5th x is the next keyword (line 9)
    check_message(
        input_error("more.mesh", kHeader + "Vertices\n5\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
                                           "Tetrahedra\n1\n1 2 3 4 1\nEnd\n"),
        "more.mesh", ":9:", "expected a number");
    // count 3 but 4 vertices: the 4th vertex's first number is read as a keyword (line 8)
    check_message(
        input_error("fewer.mesh", kHeader + "Vertices\n3\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n"
                                            "Tetrahedra\n1\n1 2 3 4 1\nEnd\n"),
        "fewer.mesh", ":8:", "unknown keyword '0'");
    // a count no file of this size could hold
    check_message(
        input_error("huge.mesh", kHeader + "Vertices\n999999999999999999\n0 0 0 0\nEnd\n"),
        "huge.mesh", ":4:", "exceeds");
    check_message(input_error("negative.mesh", kHeader + "Vertices\n-4\nEnd\n"), "negative.mesh",
                  ":4:", "negative count");
}

TEST_CASE("Medit: indices out of range")
{
    check_message(
        input_error("range.mesh", kHeader + kVertices + "Tetrahedra\n1\n1 2 3 5 1\nEnd\n"),
        "range.mesh", ":11:", "out of range [1, 4]");
    check_message(input_error("zero.mesh", kHeader + kVertices + "Tetrahedra\n1\n0 1 2 3 1\nEnd\n"),
                  "zero.mesh", ":11:", "out of range");
    // elements before vertices: checked once everything is read, naming the element
    check_message(
        input_error("late.mesh", kHeader + "Tetrahedra\n1\n1 2 3 9 1\n" + kVertices + "End\n"),
        "late.mesh", ": tetrahedron 1:", "vertex 9 out of range [1, 4]");
    check_message(input_error("ridge.mesh",
                              kHeader + kVertices +
                                  "Tetrahedra\n1\n1 2 3 4 1\nEdges\n1\n1 2 0\nRidges\n1\n2\nEnd\n"),
                  "ridge.mesh", ":17:", "out of range [1, 1]");
    check_message(input_error("corner.mesh", kHeader + kVertices +
                                                 "Corners\n1\n7\nTetrahedra\n1\n1 2 3 4 1\nEnd\n"),
                  "corner.mesh", ":11:", "out of range [1, 4]");
    check_message(input_error("reqtet.mesh", kHeader + kVertices +
                                                 "Tetrahedra\n1\n1 2 3 4 1\n"
                                                 "RequiredTetrahedra\n1\n2\nEnd\n"),
                  "reqtet.mesh", ":14:", "out of range [1, 1]");
}

TEST_CASE("Medit: NaN, infinite and malformed coordinates")
{
    for (const char* bad :
         {"nan", "inf", "-inf", "1e999", "1e31", "-2e300", "0x1p3", "1.0.0", "abc"})
    {
        CAPTURE(bad);
        const std::string text =
            kHeader + "Vertices\n4\n0 0 0 0\n1 " + bad + " 0 0\n0 1 0 0\n0 0 1 0\nEnd\n";
        const std::string message = input_error("nan.mesh", text);
        check_message(message, "nan.mesh", ":6:", "");
    }
}

TEST_CASE("Medit: unknown keywords and unsupported dimension")
{
    check_message(
        input_error("typo.mesh", kHeader + kVertices + "Tetrahedron\n1\n1 2 3 4 1\nEnd\n"),
        "typo.mesh", ":9:", "unknown keyword 'Tetrahedron'");
    // element kinds a tet mesh cannot hold: an error when present, harmless when empty
    check_message(
        input_error("quads.mesh", kHeader + kVertices + "Quadrilaterals\n1\n1 2 3 4 1\nEnd\n"),
        "quads.mesh", ":10:", "Quadrilaterals are not supported");
    CHECK(read_mesh(write_text(
                        "noquads.mesh",
                        kHeader + kVertices + "Quadrilaterals\n0\nTetrahedra\n1\n1 2 3 4 1\nEnd\n"))
              .num_tet_slots() == 1);
    check_message(input_error("dim2.mesh", "MeshVersionFormatted 2\nDimension 2\nEnd\n"),
                  "dim2.mesh", ":2:", "Dimension 3");
    check_message(input_error("twice.mesh", kHeader + kVertices + kVertices + "End\n"),
                  "twice.mesh", ":9:", "second Vertices");
}

/*
  Zero and negative volumes, named by element:

      3                 a flat tet (all four vertices in z = 0) has volume 0;
      |                 listing the unit tet as (0,2,1,3) turns it inside out.
      0----2
     /
    1
*/
TEST_CASE("Medit: zero and negative volume tets are rejected by element")
{
    check_message(input_error("negative.mesh",
                              kHeader + kVertices + "Tetrahedra\n2\n1 2 3 4 1\n1 3 2 4 1\nEnd\n"),
                  "negative.mesh", ": tetrahedron 2:", "negative volume");
    check_message(
        input_error("flat.mesh", kHeader + "Vertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n1 1 0 0\n"
                                           "Tetrahedra\n1\n1 2 3 4 1\nEnd\n"),
        "flat.mesh", ": tetrahedron 1:", "zero volume");
    check_message(
        input_error("repeated.mesh", kHeader + kVertices + "Tetrahedra\n1\n1 2 2 4 1\nEnd\n"),
        "repeated.mesh", ": tetrahedron 1:", "zero volume");
}

/*
  Three tets on the face (0,1,2): no valid tet mesh shares a face three times.
*/
TEST_CASE("a face shared by three tets is rejected; an open boundary is reported by the checker")
{
    const std::string three =
        kHeader +
        "Vertices\n6\n0 0 0 0\n1 0 0 0\n0 1 0 0\n0 0 1 0\n0.2 0.2 2 0\n0.3 0.1 3 0\n"
        "Tetrahedra\n3\n1 2 3 4 1\n1 2 3 5 1\n1 2 3 6 1\nEnd\n";
    check_message(input_error("three.mesh", three), "three.mesh", ": ", "more than two");

    // the unit tet with one boundary triangle missing reads fine, and the checker objects
    const std::string open =
        kHeader + kVertices +
        "Tetrahedra\n1\n1 2 3 4 1\nTriangles\n3\n2 3 4 1\n1 4 3 1\n1 2 4 1\nEnd\n";
    const TetMesh mesh = read_mesh(write_text("open.mesh", open));
    const auto violations = check_mesh(mesh);
    bool open_edge = false, missing = false;
    for (const auto& v : violations)
    {
        open_edge |= v.kind == "open_boundary_edge";
        missing |= v.kind == "missing_boundary_triangle";
    }
    CHECK(open_edge);
    CHECK(missing);
}

TEST_CASE("Medit binary: bad magic, version, keyword, truncation")
{
    TetMesh tet = fixtures::single_tet();
    write_mesh(tet, scratch().file("good.meshb"));
    const std::string good = read_bytes(scratch().file("good.meshb"));
    check_message(
        input_error("magic.meshb", std::string("\x07\0\0\0\x02\0\0\0", 8) + good.substr(8)),
        "magic.meshb", ": byte 4:", "not a Medit binary file");
    check_message(
        input_error("version.meshb", std::string("\x01\0\0\0\x09\0\0\0", 8) + good.substr(8)),
        "version.meshb", ": byte 8:", "version 9 out of range");
    check_message(input_error("short.meshb", good.substr(0, good.size() / 2)), "short.meshb",
                  ": byte ", "truncated");
    std::string unknown = good;
    unknown[8] = 99;  // the Dimension keyword code becomes 99
    check_message(input_error("unknown.meshb", unknown), "unknown.meshb", ": byte ",
                  "unsupported keyword code 99");
    check_message(input_error("noend.meshb", good.substr(0, good.size() - 8)), "noend.meshb",
                  ": byte ", "missing End");
}

TEST_CASE("Gmsh: structure errors name the line")
{
    const std::string nodes =
        "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n";  // lines 4-10
    const std::string format = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
    check_message(input_error("nofmt.msh", nodes), "nofmt.msh", ":1:", "expected $MeshFormat");
    check_message(input_error("v3.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n"), "v3.msh",
                  ":2:", "unsupported Gmsh format version '3.0'");
    check_message(
        input_error("count.msh",
                    format + "$Nodes\n5\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n"),
        "count.msh", ":10:", "expected an integer");
    check_message(input_error("undefined.msh",
                              format + nodes + "$Elements\n1\n1 4 2 1 1 1 2 3 7\n$EndElements\n"),
                  "undefined.msh", ":13:", "element 1: node 7 is not in $Nodes");
    check_message(
        input_error("hex.msh",
                    format + nodes + "$Elements\n1\n1 5 2 1 1 1 2 3 4 1 2 3 4\n$EndElements\n"),
        "hex.msh", ":13:", "8-node hexahedron");
    check_message(input_error("dup.msh", format + "$Nodes\n2\n1 0 0 0\n1 1 0 0\n$EndNodes\n"),
                  "dup.msh", ":", "node tag 1 defined twice");
    check_message(input_error("noendsec.msh", format + "$Comments\nnever closed\n"), "noendsec.msh",
                  ":", "has no $EndComments");
    check_message(
        input_error("neg.msh", format + nodes + "$Elements\n1\n1 4 2 1 1 1 3 2 4\n$EndElements\n"),
        "neg.msh", ": tetrahedron 1:", "negative volume");
    check_message(input_error("nannode.msh", format + "$Nodes\n1\n1 0 nan 0\n$EndNodes\n"),
                  "nannode.msh", ":6:", "not finite");
}

TEST_CASE("Gmsh binary: truncation and corrupted block counts")
{
    WriteOptions options;
    options.gmsh_binary = true;
    write_mesh(fixtures::box_mesh(2), scratch().file("good.msh"), options);
    const std::string good = read_bytes(scratch().file("good.msh"));
    check_message(input_error("short.msh", good.substr(0, good.size() / 2)), "short.msh", ":", "");
    // the node count of the node block header: a huge value must not be allocated
    std::string huge = good;
    const std::size_t nodes_at = huge.find("$Nodes\n") + 7;
    for (int k = 0; k < 8; ++k) huge[nodes_at + 8 + k] = '\x7f';
    check_message(input_error("huge.msh", huge), "huge.msh", ": byte ", "exceeds");
}

TEST_CASE(".sol: wrong count, unsupported types, truncation")
{
    auto sol_error = [](const std::string& name, const std::string& text, int expected) {
        const std::string path = write_text(name, text);
        try
        {
            read_sol(path, expected);
        }
        catch (const InputError& e)
        {
            return std::string(e.what());
        }
        FAIL("no InputError for " << name);
        return std::string();
    };
    const std::string head = "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n";
    check_message(sol_error("count.sol", head + "2\n1 1\n0.5\n0.5\nEnd\n", 3), "count.sol",
                  ":4:", "has 2 values but the mesh has 3 vertices");
    check_message(sol_error("tensor.sol", head + "2\n1 3\n1 0 0 1 0 1\nEnd\n", -1), "tensor.sol",
                  ":5:", "only scalar");
    check_message(sol_error("cut.sol", head + "3\n1 1\n0.5\n0.5\n", -1), "cut.sol", ":",
                  "unexpected end");
    check_message(sol_error("inf.sol", head + "1\n1 1\ninf\nEnd\n", -1), "inf.sol",
                  ":6:", "not finite");
}

TEST_CASE(".sol as a size field: a value that is not positive names the file and the vertex")
{
    // three sizes, the second zero: adapt --sol and surfremesh --sol read it the same way
    const std::string path = write_text(
        "zero.sol",
        "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n3\n1 1\n0.5\n0\n0.5\nEnd\n");
    CHECK(read_sol(path, 3).size() == 3);
    try
    {
        read_sol_sizes(path, 3);
        FAIL("no InputError");
    }
    catch (const InputError& e)
    {
        check_message(e.what(), "zero.sol", ": ", "size at vertex 2 is not positive");
    }
}

namespace
{

/// Reads a damaged copy: success or a typed error are fine, anything else fails the test.
/// Returns whether it threw.
bool read_damaged(const std::string& path)
{
    try
    {
        read_mesh(path);
        return false;
    }
    catch (const InputError&)
    {
        return true;
    }
    catch (const IoError&)
    {
        return true;
    }
}

}  // namespace

TEST_CASE("fuzz: truncated and byte-corrupted copies of valid files never crash")
{
    const TetMesh sphere = read_mesh(fixtures::data_path("sphere480.mesh"));
    struct Variant
    {
        const char* name;
        WriteOptions options;
    };
    const Variant variants[] = {
        {"fuzz.mesh", {}},
        {"fuzz.meshb", {}},
        {"fuzz22.msh", {{}, "2.2", false, {}}},
        {"fuzz22b.msh", {{}, "2.2", true, {}}},
        {"fuzz41.msh", {{}, "4.1", false, {}}},
        {"fuzz41b.msh", {{}, "4.1", true, {}}},
    };
    const char interesting[] = {'0', '9', '-', '.', 'e', ' ', '\n', '$', '#', '\0', '\x7f', '\xff'};
    for (const Variant& variant : variants)
    {
        CAPTURE(std::string(variant.name));
        const std::string source = scratch().file(std::string("source_") + variant.name);
        write_mesh(sphere, source, variant.options);
        const std::string good = read_bytes(source);
        const std::string damaged = scratch().file(variant.name);
        std::mt19937 rng(12345);
        for (int seed = 0; seed < 150; ++seed)
        {
            CAPTURE(seed);
            // truncation anywhere before the closing keyword must be detected
            const std::size_t cut =
                std::uniform_int_distribution<std::size_t>(0, good.size() - 2)(rng);
            write_text(variant.name, good.substr(0, cut));
            CHECK(read_damaged(damaged));

            // 1-8 bytes replaced by digits, signs, separators, section marks or binary junk
            std::string corrupt = good;
            const int hits = std::uniform_int_distribution<int>(1, 8)(rng);
            for (int h = 0; h < hits; ++h)
            {
                const std::size_t at =
                    std::uniform_int_distribution<std::size_t>(0, good.size() - 1)(rng);
                const int pick = std::uniform_int_distribution<int>(0, sizeof(interesting))(rng);
                corrupt[at] =
                    pick < static_cast<int>(sizeof(interesting))
                        ? interesting[pick]
                        : static_cast<char>(std::uniform_int_distribution<int>(0, 255)(rng));
            }
            write_text(variant.name, corrupt);
            read_damaged(damaged);  // either outcome is fine; crashing or another exception is not
        }
    }
}

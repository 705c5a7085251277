// meshconvert: converts a tet mesh between formats, refs kept (parse -> read -> check -> write).
#include <iostream>

#include "cli.h"
#include "common/errors.h"
#include "common/sol_io.h"
#include "volume/check/boundary_repair.h"
#include "volume/check/check.h"
#include "volume/io/tet_io.h"

using namespace hdimesh;
using namespace hdimesh::volume;

int main(int argc, char** argv)
{
    return cli::run("meshconvert", [&] {
        std::string input, output, msh_version = "4.1", sol_path;
        bool binary = false, no_check = false, verbose = false, strict = false;
        cli::CommandLine cl(
            "meshconvert",
            "Converts a tetrahedral mesh between formats (by extension), keeping\n"
            "refs: .mesh .meshb .msh (2.2/4.1, ASCII/binary) in, and .vtu out too.");
        cl.positional("IN", &input, "input mesh (.mesh .meshb .msh)");
        cl.positional("OUT", &output, "output mesh (.mesh .meshb .msh .vtu)");
        cl.option("--msh-version", &msh_version, "Gmsh version to write: 2.2 or 4.1 (default)");
        cl.flags({
            {"--binary", &binary, "write .msh in binary"},
            {"--no-check", &no_check, "write even if the mesh checker finds violations"},
            {"--verbose", &verbose, "print the counts read"},
            {"--strict", &strict,
             "refuse triangles that are not the tets' boundary (TetGen's interior and inward "
             "ones, missing ones) instead of mending them"},
        });
        cl.option("--sol", &sol_path,
                  "a .sol/.solb on the input's vertices, written as .vtu point data \"size\"");
        cl.parse(argc, argv);
        if (msh_version != "2.2" && msh_version != "4.1")
            throw InputError("--msh-version expects 2.2 or 4.1, got '" + msh_version + "'");

        TetMesh mesh = read_mesh(input);
        BoundaryRepairOptions repair;
        repair.add_interfaces = false;  // a conversion adds no surface the file did not have
        if (!strict && mesh.num_live_tets() > 0)
            for (const std::string& line : repair_boundary(mesh, repair).lines())
                std::cerr << "meshconvert: " << input << ": " << line << "\n";
        if (verbose)
            std::cout << input << ": " << mesh.num_vertices() << " vertices, "
                      << mesh.num_live_tets() << " tetrahedra, " << mesh.triangles.size()
                      << " triangles, " << mesh.edges.size() << " edges\n";
        // the checker's invariants are about tets: a surface-only mesh converts unchecked
        if (!no_check && mesh.num_live_tets() > 0)
            if (const auto violations = check_mesh(mesh); !violations.empty())
                throw InputError(input +
                                 ": the mesh is not valid (not written; --no-check to force):\n" +
                                 format_violations(violations));

        WriteOptions options;
        options.gmsh_version = msh_version;
        options.gmsh_binary = binary;
        if (!sol_path.empty()) options.vertex_sizes = read_sol(sol_path, mesh.num_vertices());
        write_mesh(mesh, output, options);
        return 0;
    });
}

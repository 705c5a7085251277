#include "common/sol_io.h"

#include <climits>
#include <cstdint>
#include <string>

#include "common/atomic_file.h"
#include "common/buffer_io.h"
#include "common/errors.h"
#include "common/medit_reader.h"

namespace hdimesh
{

namespace
{

using io::BinaryReader;
using io::TextReader;
using io::TextWriter;
namespace gmf = medit::gmf;

std::string count_mismatch(std::size_t n, int expected_vertices)
{
    return "SolAtVertices has " + std::to_string(n) + " values but the mesh has " +
           std::to_string(expected_vertices) + " vertices";
}

bool wrong_count(std::size_t n, int expected_vertices)
{
    return expected_vertices >= 0 && n != static_cast<std::size_t>(expected_vertices);
}

std::vector<double> read_sol_ascii(const std::string& path, const std::string& data,
                                   int expected_vertices)
{
    TextReader in(path, data, '#');
    std::vector<double> values;
    bool seen_solution = false;
    medit::read_ascii_keywords(in, medit::EndKeyword::Required, "solution file",
                               [&](std::string_view keyword) {
                                   if (keyword != "SolAtVertices") return false;
                                   if (seen_solution) in.fail("second SolAtVertices section");
                                   seen_solution = true;
                                   const std::size_t n = in.count("SolAtVertices count", 2);
                                   if (wrong_count(n, expected_vertices))
                                       in.fail(count_mismatch(n, expected_vertices));
                                   if (in.integer("number of solution types") != 1)
                                       in.fail("only one solution per vertex is supported");
                                   if (in.integer("solution type") != 1)
                                       in.fail("only scalar solutions (type 1) are supported");
                                   values.resize(n);
                                   for (double& v : values) v = in.real("solution value");
                                   return true;
                               });
    if (!seen_solution) io::throw_input(path, "no SolAtVertices section");
    return values;
}

std::vector<double> read_solb(const std::string& path, const std::string& data,
                              int expected_vertices)
{
    BinaryReader in(path, data, 0, false);
    medit::BinaryFile file(in);
    std::vector<double> values;
    bool seen_solution = false;
    for (;;)
    {
        const int code = file.keyword().code;
        if (code == gmf::kEnd) break;
        if (code == gmf::kDimension)
            file.dimension();
        else if (code == gmf::kSolAtVertices)
        {
            if (seen_solution) in.fail("second SolAtVertices section");
            seen_solution = true;
            const long long n = file.integer("count", 0, INT_MAX);
            if (in.get<std::int32_t>("number of solution types") != 1)
                in.fail("only one solution per vertex is supported");
            if (in.get<std::int32_t>("solution type") != 1)
                in.fail("only scalar solutions (type 1) are supported");
            if (wrong_count(static_cast<std::size_t>(n), expected_vertices))
                in.fail(count_mismatch(static_cast<std::size_t>(n), expected_vertices));
            in.require(static_cast<unsigned long long>(n), file.real_bytes(), "SolAtVertices");
            values.resize(n);
            for (double& v : values) v = file.real("solution value");
        }
        else
        {
            in.fail("unsupported keyword code " + std::to_string(code) + " in a solution file");
        }
    }
    if (!seen_solution) io::throw_input(path, "no SolAtVertices section");
    return values;
}

/// ".sol" or ".solb"; InputError for any other extension.
std::string sol_extension(const std::string& path)
{
    const std::string ext = io::lower_extension(path);
    if (ext != ".sol" && ext != ".solb")
        throw InputError(path + ": unknown solution format '" + ext + "' (expected .sol or .solb)");
    return ext;
}

}  // namespace

std::vector<double> read_sol(const std::string& path, int expected_vertices)
{
    const std::string ext = sol_extension(path);
    const std::string data = io::load_file(path);
    if (data.empty()) throw InputError(path + ": empty file");
    return ext == ".solb" ? read_solb(path, data, expected_vertices)
                          : read_sol_ascii(path, data, expected_vertices);
}

std::vector<double> read_sol_sizes(const std::string& path, int expected_vertices)
{
    std::vector<double> sizes = read_sol(path, expected_vertices);
    for (std::size_t v = 0; v < sizes.size(); ++v)
        if (!(sizes[v] > 0))
            throw InputError(path + ": size at vertex " + std::to_string(v + 1) +
                             " is not positive");
    return sizes;
}

void write_sol(const std::vector<double>& values, const std::string& path)
{
    const std::string ext = sol_extension(path);
    if (values.size() > static_cast<std::size_t>(INT_MAX))
        throw InputError(path + ": too many values for a solution file");
    write_file_atomically(path, [&](std::ostream& out) {
        TextWriter w(out);
        if (ext == ".sol")
        {
            w.text("MeshVersionFormatted 2\n\nDimension 3\n\nSolAtVertices\n")
                .integer(static_cast<long long>(values.size()))
                .text("\n1 1\n");
            for (double v : values) w.real(v).character('\n');
            w.text("\nEnd\n");
        }
        else
        {
            // version 2: int32 positions, float64 values
            w.raw(std::int32_t{1}).raw(std::int32_t{2});
            // each block: code, absolute position of the next block, payload
            const std::size_t after_dimension = w.offset() + 4 + 4 + 4;
            w.raw(std::int32_t{gmf::kDimension}).raw(static_cast<std::int32_t>(after_dimension));
            w.raw(std::int32_t{3});
            const std::size_t next = w.offset() + 4 + 4 + 4 + 8 + 8 * values.size();
            w.raw(std::int32_t{gmf::kSolAtVertices}).raw(static_cast<std::int32_t>(next));
            w.raw(static_cast<std::int32_t>(values.size()))
                .raw(std::int32_t{1})
                .raw(std::int32_t{1});
            w.bytes(values.data(), values.size() * sizeof(double));
            w.raw(std::int32_t{gmf::kEnd}).raw(std::int32_t{0});
        }
        w.flush();
    });
}

}  // namespace hdimesh

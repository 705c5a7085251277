// Medit solution files with one scalar per vertex (SolAtVertices, type 1), the usual way to
// hand a size field to Mmg-like tools: .sol (ASCII) and .solb (libMeshb binary, same layout
// as .meshb; see medit_io.cpp for the version table).

#include <climits>
#include <cstdint>
#include <string>

#include "common/atomic_file.h"
#include "volume/io_detail.h"

namespace hdimesh::volume
{

namespace
{

using io_detail::BinaryReader;
using io_detail::TextReader;
using io_detail::TextWriter;
namespace gmf = io_detail::gmf;

void check_count(const std::string& path, std::size_t n, int expected_vertices)
{
    if (expected_vertices >= 0 && n != static_cast<std::size_t>(expected_vertices))
        io_detail::throw_input(path, "SolAtVertices has " + std::to_string(n) +
                                         " values but the mesh has " +
                                         std::to_string(expected_vertices) + " vertices");
}

std::vector<double> read_sol_ascii(const std::string& path, const std::string& data,
                                   int expected_vertices)
{
    TextReader in(path, data, '#');
    std::vector<double> values;
    bool seen_solution = false, seen_end = false;
    while (!in.at_end())
    {
        const std::string_view keyword = in.token("keyword");
        if (keyword == "End")
        {
            seen_end = true;
            break;
        }
        if (keyword == "MeshVersionFormatted")
            in.integer_in("MeshVersionFormatted", 1, 4);
        else if (keyword == "Dimension")
        {
            if (in.integer("Dimension") != 3) in.fail("only Dimension 3 is supported");
        }
        else if (keyword == "SolAtVertices")
        {
            if (seen_solution) in.fail("second SolAtVertices section");
            seen_solution = true;
            const std::size_t n = in.count("SolAtVertices count", 2);
            if (in.integer("number of solution types") != 1)
                in.fail("only one solution per vertex is supported");
            if (in.integer("solution type") != 1)
                in.fail("only scalar solutions (type 1) are supported");
            check_count(path, n, expected_vertices);
            values.resize(n);
            for (double& v : values) v = in.real("solution value");
        }
        else
        {
            in.fail("unknown keyword '" + std::string(keyword.substr(0, 60)) + "' in a solution file");
        }
    }
    if (!seen_end)
    {
        in.set_position(in.position(), in.current_line());
        in.fail("missing End keyword (truncated file?)");
    }
    if (!seen_solution) io_detail::throw_input(path, "no SolAtVertices section");
    return values;
}

std::vector<double> read_solb(const std::string& path, const std::string& data, int expected_vertices)
{
    BinaryReader in(path, data, 0, false);
    const std::int32_t magic = in.get<std::int32_t>("magic number");
    if (magic != 1)
    {
        if (BinaryReader::byte_swapped(magic) != 1)
            in.fail("not a Medit binary file (magic number " + std::to_string(magic) + ")");
        in.set_swap(true);
    }
    const int version = static_cast<int>(in.integer_in<std::int32_t>("version", 1, 4));
    std::vector<double> values;
    bool seen_solution = false;
    for (;;)
    {
        if (in.position() >= in.size()) in.fail("missing End keyword (truncated file?)");
        const int code = in.get<std::int32_t>("keyword code");
        if (version >= 3) in.integer_in<std::int64_t>("next keyword position", 0, LLONG_MAX);
        else in.integer_in<std::int32_t>("next keyword position", 0, INT_MAX);
        if (code == gmf::kEnd) break;
        if (code == gmf::kDimension)
        {
            if (in.get<std::int32_t>("dimension") != 3) in.fail("only dimension 3 is supported");
        }
        else if (code == gmf::kSolAtVertices)
        {
            if (seen_solution) in.fail("second SolAtVertices section");
            seen_solution = true;
            const long long n = version == 4 ? in.integer_in<std::int64_t>("count", 0, INT_MAX)
                                             : in.integer_in<std::int32_t>("count", 0, INT_MAX);
            if (in.get<std::int32_t>("number of solution types") != 1)
                in.fail("only one solution per vertex is supported");
            if (in.get<std::int32_t>("solution type") != 1)
                in.fail("only scalar solutions (type 1) are supported");
            check_count(path, static_cast<std::size_t>(n), expected_vertices);
            in.require(static_cast<unsigned long long>(n), version == 1 ? 4 : 8, "SolAtVertices");
            values.resize(n);
            for (double& v : values)
                v = version == 1 ? in.real<float>("solution value") : in.real<double>("solution value");
        }
        else
        {
            in.fail("unsupported keyword code " + std::to_string(code) + " in a solution file");
        }
    }
    if (!seen_solution) io_detail::throw_input(path, "no SolAtVertices section");
    return values;
}

}  // namespace

std::vector<double> read_sol(const std::string& path, int expected_vertices)
{
    const std::string ext = io_detail::lower_extension(path);
    if (ext != ".sol" && ext != ".solb")
        throw InputError(path + ": unknown solution format '" + ext + "' (expected .sol or .solb)");
    const std::string data = io_detail::load_file(path);
    if (data.empty()) throw InputError(path + ": empty file");
    return ext == ".solb" ? read_solb(path, data, expected_vertices)
                          : read_sol_ascii(path, data, expected_vertices);
}

void write_sol(const std::vector<double>& values, const std::string& path)
{
    const std::string ext = io_detail::lower_extension(path);
    if (ext != ".sol" && ext != ".solb")
        throw InputError(path + ": unknown solution format '" + ext + "' (expected .sol or .solb)");
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
            w.raw(static_cast<std::int32_t>(values.size())).raw(std::int32_t{1}).raw(std::int32_t{1});
            w.bytes(values.data(), values.size() * sizeof(double));
            w.raw(std::int32_t{gmf::kEnd}).raw(std::int32_t{0});
        }
        w.flush();
    });
}

}  // namespace hdimesh::volume

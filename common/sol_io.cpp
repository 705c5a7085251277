#include "common/sol_io.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <string>

#include "common/atomic_file.h"
#include "common/buffer_io.h"
#include "common/errors.h"
#include "common/medit_reader.h"
#include "common/metric.h"

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

/// "unknown solution type" unless code is 1, 2 or 3.
bool known_type(long long code) { return code >= 1 && code <= 3; }

std::string type_message(long long code)
{
    return "unknown solution type " + std::to_string(code) +
           " (1 scalar, 2 vector, 3 symmetric tensor)";
}

/// The solutions' arrays sized for n vertices.
void allocate(Solutions& s, std::size_t n)
{
    s.num_vertices = static_cast<int>(n);
    for (Solution& solution : s.solutions)
        solution.values.resize(n * static_cast<std::size_t>(sol_components(solution.type)));
}

/// Types above this many per vertex are refused: a corrupted count must not allocate.
constexpr long long kMaxSolutionsPerVertex = 1000;

/// scalar_only: read_sol's single scalar, with its messages.
Solutions read_sol_ascii(const std::string& path, const std::string& data, int expected_vertices,
                         bool scalar_only)
{
    TextReader in(path, data, '#');
    Solutions result;
    bool seen_solution = false;
    medit::read_ascii_keywords(
        in, medit::EndKeyword::Required, "solution file", [&](std::string_view keyword) {
            if (keyword != "SolAtVertices") return false;
            if (seen_solution) in.fail("second SolAtVertices section");
            seen_solution = true;
            const std::size_t n = in.count("SolAtVertices count", 2);
            if (wrong_count(n, expected_vertices)) in.fail(count_mismatch(n, expected_vertices));
            const long long types = in.integer("number of solution types");
            if (scalar_only && types != 1) in.fail("only one solution per vertex is supported");
            if (types < 1 || types > kMaxSolutionsPerVertex)
                in.fail("number of solution types " + std::to_string(types) + " outside [1, " +
                        std::to_string(kMaxSolutionsPerVertex) + "]");
            std::size_t per_vertex = 0;
            for (long long k = 0; k < types; ++k)
            {
                const long long code = in.integer("solution type");
                if (scalar_only && code != 1)
                    in.fail("only scalar solutions (type 1) are supported");
                if (!known_type(code)) in.fail(type_message(code));
                result.solutions.push_back({static_cast<SolType>(code), {}});
                per_vertex += sol_components(static_cast<SolType>(code));
            }
            // each value takes two characters at least: a corrupted count must not allocate
            if (n * per_vertex > (data.size() - std::min(data.size(), in.position())) / 2)
                in.fail(std::to_string(n) + " vertices x " + std::to_string(per_vertex) +
                        " values do not fit in the rest of the file (truncated?)");
            allocate(result, n);
            for (std::size_t v = 0; v < n; ++v)
                for (Solution& solution : result.solutions)
                {
                    const std::size_t k = sol_components(solution.type);
                    for (std::size_t c = 0; c < k; ++c)
                        solution.values[v * k + c] = in.real("solution value");
                }
            return true;
        });
    if (!seen_solution) io::throw_input(path, "no SolAtVertices section");
    return result;
}

Solutions read_solb(const std::string& path, const std::string& data, int expected_vertices,
                    bool scalar_only)
{
    BinaryReader in(path, data, 0, false);
    medit::BinaryFile file(in);
    Solutions result;
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
            const std::int32_t types = in.get<std::int32_t>("number of solution types");
            if (scalar_only && types != 1) in.fail("only one solution per vertex is supported");
            if (types < 1 || types > kMaxSolutionsPerVertex)
                in.fail("number of solution types " + std::to_string(types) + " outside [1, " +
                        std::to_string(kMaxSolutionsPerVertex) + "]");
            std::size_t per_vertex = 0;
            for (std::int32_t k = 0; k < types; ++k)
            {
                const std::int32_t type = in.get<std::int32_t>("solution type");
                if (scalar_only && type != 1)
                    in.fail("only scalar solutions (type 1) are supported");
                if (!known_type(type)) in.fail(type_message(type));
                result.solutions.push_back({static_cast<SolType>(type), {}});
                per_vertex += sol_components(static_cast<SolType>(type));
            }
            if (wrong_count(static_cast<std::size_t>(n), expected_vertices))
                in.fail(count_mismatch(static_cast<std::size_t>(n), expected_vertices));
            in.require(static_cast<unsigned long long>(n) * per_vertex, file.real_bytes(),
                       "SolAtVertices");
            allocate(result, static_cast<std::size_t>(n));
            for (long long v = 0; v < n; ++v)
                for (Solution& solution : result.solutions)
                {
                    const std::size_t k = sol_components(solution.type);
                    for (std::size_t c = 0; c < k; ++c)
                    {
                        const double value = file.real("solution value");
                        if (!std::isfinite(value))
                            in.fail("solution value at vertex " + std::to_string(v + 1) +
                                    " is not finite");
                        solution.values[v * k + c] = value;
                    }
                }
        }
        else
        {
            in.fail("unsupported keyword code " + std::to_string(code) + " in a solution file");
        }
    }
    if (!seen_solution) io::throw_input(path, "no SolAtVertices section");
    return result;
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

int sol_components(SolType type)
{
    switch (type)
    {
        case SolType::Scalar: return 1;
        case SolType::Vector: return 3;
        case SolType::Tensor: return 6;
    }
    return 1;
}

namespace
{

Solutions read_any(const std::string& path, int expected_vertices, bool scalar_only)
{
    const std::string ext = sol_extension(path);
    const std::string data = io::load_file(path);
    if (data.empty()) throw InputError(path + ": empty file");
    return ext == ".solb" ? read_solb(path, data, expected_vertices, scalar_only)
                          : read_sol_ascii(path, data, expected_vertices, scalar_only);
}

}  // namespace

std::vector<double> read_sol(const std::string& path, int expected_vertices)
{
    return std::move(read_any(path, expected_vertices, true).solutions.front().values);
}

Solutions read_solutions(const std::string& path, int expected_vertices)
{
    return read_any(path, expected_vertices, false);
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

SolSizing read_sol_sizing(const std::string& path, int expected_vertices)
{
    Solutions file = read_solutions(path, expected_vertices);
    if (file.solutions.size() != 1)
        throw InputError(path + ": " + std::to_string(file.solutions.size()) +
                         " solutions, a size field is one (a scalar size or a tensor metric)");
    Solution& one = file.solutions[0];
    SolSizing sizing;
    if (one.type == SolType::Scalar)
    {
        for (std::size_t v = 0; v < one.values.size(); ++v)
            if (!(one.values[v] > 0))
                throw InputError(path + ": size at vertex " + std::to_string(v + 1) +
                                 " is not positive");
        sizing.sizes = std::move(one.values);
        return sizing;
    }
    if (one.type != SolType::Tensor)
        throw InputError(path +
                         ": a vector solution (type 2) is no size field: give sizes "
                         "(type 1) or metrics (type 3)");
    for (std::size_t v = 0; 6 * v < one.values.size(); ++v)
    {
        const std::string problem = metric_problem(metric_from_medit(&one.values[6 * v]));
        if (!problem.empty())
            throw InputError(path + ": the metric at vertex " + std::to_string(v + 1) + " is " +
                             problem);
    }
    sizing.metrics = std::move(one.values);
    return sizing;
}

void write_sol(const std::vector<double>& values, const std::string& path)
{
    if (values.size() > static_cast<std::size_t>(INT_MAX))
        throw InputError(path + ": too many values for a solution file");
    Solutions one;
    one.num_vertices = static_cast<int>(values.size());
    one.solutions.push_back({SolType::Scalar, values});
    write_solutions(one, path);
}

void write_solutions(const Solutions& solutions, const std::string& path)
{
    const std::string ext = sol_extension(path);
    if (solutions.solutions.empty()) throw InputError(path + ": no solution to write");
    const std::size_t n = static_cast<std::size_t>(std::max(solutions.num_vertices, 0));
    std::size_t per_vertex = 0;
    for (std::size_t k = 0; k < solutions.solutions.size(); ++k)
    {
        const Solution& solution = solutions.solutions[k];
        const std::size_t components = sol_components(solution.type);
        if (solution.values.size() != n * components)
            throw InputError(path + ": solution " + std::to_string(k + 1) + " has " +
                             std::to_string(solution.values.size()) + " values, not " +
                             std::to_string(n) + " vertices x " + std::to_string(components));
        per_vertex += components;
    }
    // (int32 block positions: version 2)
    if (8.0 * n * per_vertex > double(INT_MAX) - 1024)
        throw InputError(path + ": too many values for a solution file");
    write_file_atomically(path, [&](std::ostream& out) {
        TextWriter w(out);
        if (ext == ".sol")
        {
            w.text("MeshVersionFormatted 2\n\nDimension 3\n\nSolAtVertices\n")
                .integer(static_cast<long long>(n))
                .character('\n')
                .integer(static_cast<long long>(solutions.solutions.size()));
            for (const Solution& solution : solutions.solutions)
                w.character(' ').integer(static_cast<long long>(solution.type));
            w.character('\n');
            for (std::size_t v = 0; v < n; ++v)
            {
                bool first = true;
                for (const Solution& solution : solutions.solutions)
                {
                    const std::size_t k = sol_components(solution.type);
                    for (std::size_t c = 0; c < k; ++c)
                    {
                        if (!first) w.character(' ');
                        first = false;
                        w.real(solution.values[v * k + c]);
                    }
                }
                w.character('\n');
            }
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
            const std::size_t types = solutions.solutions.size();
            const std::size_t next = w.offset() + 4 + 4 + 4 + 4 + 4 * types + 8 * n * per_vertex;
            w.raw(std::int32_t{gmf::kSolAtVertices}).raw(static_cast<std::int32_t>(next));
            w.raw(static_cast<std::int32_t>(n)).raw(static_cast<std::int32_t>(types));
            for (const Solution& solution : solutions.solutions)
                w.raw(static_cast<std::int32_t>(solution.type));
            if (types == 1)
                w.bytes(solutions.solutions[0].values.data(), 8 * n * per_vertex);
            else
                for (std::size_t v = 0; v < n; ++v)
                    for (const Solution& solution : solutions.solutions)
                    {
                        const std::size_t k = sol_components(solution.type);
                        w.bytes(solution.values.data() + v * k, 8 * k);
                    }
            w.raw(std::int32_t{gmf::kEnd}).raw(std::int32_t{0});
        }
        w.flush();
    });
}

}  // namespace hdimesh

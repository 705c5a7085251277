#include "cli.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <iostream>
#include <sstream>

#include "common/errors.h"
#include "common/sol_io.h"
#include "volume/size_fields.h"
#include "volume/tet_io.h"
#include "volume/tet_tables.h"

namespace hdimesh::cli
{

namespace
{

/// Thrown for a malformed command line so run() can answer with exit code 2.
class UsageError : public InputError
{
public:
    using InputError::InputError;
};

double parse_double(const std::string& flag, const std::string& text)
{
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(value))
        throw UsageError(flag + " expects a number, got '" + text + "'");
    return value;
}

int parse_int(const std::string& flag, const std::string& text)
{
    char* end = nullptr;
    const long value = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0') throw UsageError(flag + " expects an integer, got '" + text + "'");
    return static_cast<int>(value);
}

}  // namespace

CommandLine::CommandLine(std::string program, std::string summary)
    : program_(std::move(program)), summary_(std::move(summary))
{
}

void CommandLine::positional(const std::string& name, std::string* target,
                             const std::string& help, bool required)
{
    positionals_.push_back({name, help, name, [target](const std::string& v) { *target = v; }});
    positional_required_.push_back(required);
}

void CommandLine::flag(const std::string& name, bool* target, const std::string& help)
{
    options_.push_back({name, help, "", [target](const std::string&) { *target = true; }});
}

void CommandLine::option(const std::string& name, double* target, const std::string& help,
                         bool* was_set)
{
    options_.push_back(
        {name, help, "X", [name, target](const std::string& v) { *target = parse_double(name, v); },
         was_set});
}

void CommandLine::option(const std::string& name, int* target, const std::string& help,
                         bool* was_set)
{
    options_.push_back(
        {name, help, "N", [name, target](const std::string& v) { *target = parse_int(name, v); },
         was_set});
}

void CommandLine::option(const std::string& name, std::string* target, const std::string& help,
                         bool* was_set)
{
    options_.push_back(
        {name, help, "S", [target](const std::string& v) { *target = v; }, was_set});
}

void CommandLine::parse(int argc, char** argv)
{
    std::size_t next_positional = 0;
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "-h" || arg == "--help")
        {
            std::cout << help();
            std::exit(0);
        }
        if (arg.size() > 1 && arg[0] == '-' && !std::isdigit(static_cast<unsigned char>(arg[1])))
        {
            const Entry* entry = nullptr;
            for (const auto& o : options_)
                if (o.name == arg) entry = &o;
            if (!entry) throw UsageError("unknown option '" + arg + "' (see --help)");
            std::string value;
            if (!entry->value_name.empty())
            {
                if (i + 1 >= argc) throw UsageError(arg + " expects a value");
                value = argv[++i];
            }
            entry->set(value);
            if (entry->was_set) *entry->was_set = true;
            continue;
        }
        if (next_positional >= positionals_.size())
            throw UsageError("unexpected argument '" + arg + "' (see --help)");
        positionals_[next_positional++].set(arg);
    }
    for (std::size_t k = next_positional; k < positionals_.size(); ++k)
        if (positional_required_[k])
            throw UsageError("missing argument " + positionals_[k].name + " (see --help)");
}

std::string CommandLine::help() const
{
    std::ostringstream out;
    out << "usage: " << program_;
    for (std::size_t k = 0; k < positionals_.size(); ++k)
        out << (positional_required_[k] ? " " : " [") << positionals_[k].name
            << (positional_required_[k] ? "" : "]");
    out << " [options]\n" << summary_ << "\n\n";
    for (const auto& p : positionals_) out << "  " << p.name << "\n      " << p.help << "\n";
    for (const auto& o : options_)
        out << "  " << o.name << (o.value_name.empty() ? "" : " " + o.value_name) << "\n      "
            << o.help << "\n";
    return out.str();
}

int run(const char* program, const std::function<int()>& body)
{
    try
    {
        return body();
    }
    catch (const UsageError& e)
    {
        std::cerr << program << ": error: " << e.what() << "\n";
        return 2;
    }
    catch (const std::exception& e)
    {
        std::cerr << program << ": error: " << e.what() << "\n";
        return 1;
    }
}

}  // namespace hdimesh::cli

// ---------------------------------------------------------------------------------------------
// Size-field flags

namespace hdimesh::cli
{

namespace
{

/// The pointwise minimum of two fields (gradation only shrinks sizes).
class MinimumSize : public SizeField
{
public:
    MinimumSize(std::shared_ptr<const SizeField> a, std::shared_ptr<const SizeField> b)
        : a_(std::move(a)), b_(std::move(b))
    {
    }
    double size(const Vec3& p) const override { return std::min(a_->size(p), b_->size(p)); }

private:
    std::shared_ptr<const SizeField> a_, b_;
};

/// Mean length of the tet edges at each vertex (each edge counted once per tet: good enough
/// for a size, and O(n) without an edge table).
std::vector<double> mean_incident_edge_length(const TetMesh& mesh)
{
    std::vector<double> sum(mesh.num_vertices(), 0.0);
    std::vector<int> count(mesh.num_vertices(), 0);
    for (int t = 0; t < mesh.num_tet_slots(); ++t)
    {
        if (mesh.is_dead(t)) continue;
        for (const auto& e : tet::kEdgeVertices)
        {
            const int a = mesh.tets[t][e[0]], b = mesh.tets[t][e[1]];
            const double length = (mesh.points[a] - mesh.points[b]).norm();
            sum[a] += length;
            sum[b] += length;
            ++count[a];
            ++count[b];
        }
    }
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (count[v] > 0) sum[v] /= count[v];
    return sum;
}

}  // namespace

void SizeFlags::add_to(CommandLine& cli, bool with_bounds)
{
    cli.option("--hsiz", &hsiz, "constant size", &hsiz_set);
    cli.option("--sol", &sol, "sizes at the input mesh's vertices (Medit .sol, SolAtVertices)");
    cli.option("--bench-field", &bench_field,
               "the paper's three-cylinder field, case A, B, C, D or E");
    if (!with_bounds) return;
    cli.option("--hmin", &hmin, "smallest size allowed");
    cli.option("--hmax", &hmax, "largest size allowed");
    cli.option("--hgrad", &hgrad, "gradation: size ratio bound between neighbours (e.g. 1.3)");
}

std::shared_ptr<const SizeField> SizeFlags::make(const TetMesh& input) const
{
    const int given = int(hsiz_set) + int(!sol.empty()) + int(!bench_field.empty());
    if (given > 1) throw UsageError("give only one of --hsiz, --sol and --bench-field");
    if (hsiz_set && !(hsiz > 0)) throw UsageError("--hsiz must be positive");
    if (hmin < 0 || hmax < 0) throw UsageError("--hmin and --hmax must be positive");
    if (hmin > 0 && hmax > 0 && hmin > hmax) throw UsageError("--hmin is larger than --hmax");
    if (hgrad != 0 && !(hgrad > 1)) throw UsageError("--hgrad must be larger than 1");
    if (bench_field.size() > 1) throw UsageError("--bench-field expects one letter A-E");

    std::shared_ptr<const SizeField> field;
    bool at_vertices = false;  // the field is already a graded-able background over input
    std::vector<double> vertex_sizes;
    if (hsiz_set)
    {
        field = std::make_shared<ConstantSize>(hsiz);
    }
    else if (!bench_field.empty())
    {
        field = std::make_shared<BenchmarkSize>(benchmark_case(bench_field[0]));
    }
    else
    {
        if (!sol.empty())
            vertex_sizes = read_sol_sizes(sol, input.num_vertices());
        else
        {
            vertex_sizes = mean_incident_edge_length(input);
            for (std::size_t v = 0; v < vertex_sizes.size(); ++v)
                if (!(vertex_sizes[v] > 0))
                    throw InputError("input mesh: size at vertex " + std::to_string(v + 1) +
                                     " is not positive");
        }
        at_vertices = true;
    }

    if (hgrad > 0)
    {
        if (!at_vertices) vertex_sizes = sample_vertex_sizes(input, *field);
        grade_vertex_sizes(input, vertex_sizes, hgrad);
    }
    if (at_vertices || hgrad > 0)
    {
        auto background = std::make_shared<BackgroundMeshSize>(input, vertex_sizes);
        field = field ? std::shared_ptr<const SizeField>(
                            std::make_shared<MinimumSize>(field, background))
                      : background;
    }
    if (hmin > 0 || hmax > 0)
        field = std::make_shared<ClampedSize>(
            field, hmin, hmax > 0 ? hmax : std::numeric_limits<double>::infinity());
    return field;
}

}  // namespace hdimesh::cli

#include "cli.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <new>
#include <sstream>
#include <stdexcept>

namespace hdimesh::cli
{

namespace
{

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
    if (text.empty() || *end != '\0')
        throw UsageError(flag + " expects an integer, got '" + text + "'");
    return static_cast<int>(value);
}

bool is_integer(const std::string& text)
{
    std::size_t k = text.size() > 1 && text[0] == '-' ? 1 : 0;
    if (k == text.size()) return false;
    for (; k < text.size(); ++k)
        if (!std::isdigit(static_cast<unsigned char>(text[k]))) return false;
    return true;
}

bool file_exists(const std::string& path) { return std::ifstream(path).good(); }

/// Mmg's extension of a file name (MMG5_Get_filenameExt): from the last '.', unless there is
/// none, it starts the name, it is before the last '/', or it is ".o"; empty otherwise.
std::string mmg_extension(const std::string& name)
{
    const std::size_t dot = name.rfind('.');
    const std::size_t slash = name.rfind('/');
    if (dot == std::string::npos || dot == 0 || (slash != std::string::npos && slash > dot) ||
        name.compare(dot, std::string::npos, ".o") == 0)
        return "";
    return name.substr(dot);
}

/// The extension Mmg writes for an input of extension `ext`: its own for a mesh format it
/// writes, else Medit's.
std::string mmg_mesh_format(const std::string& ext)
{
    for (const char* known : {".meshb", ".mesh", ".mshb", ".msh", ".vtu", ".vtp", ".vtk"})
        if (ext == known) return ext;
    return ".mesh";
}

int memory_limit_mb = 0;  // -m, for run()'s message

// GCC says __SANITIZE_ADDRESS__, Clang __has_feature(address_sanitizer)
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define HDIMESH_CLANG_ASAN 1
#endif
#endif
#ifndef HDIMESH_CLANG_ASAN
#define HDIMESH_CLANG_ASAN 0
#endif

}  // namespace

CommandLine::CommandLine(std::string program, std::string summary)
    : program_(std::move(program)), summary_(std::move(summary))
{
}

void CommandLine::positional(const std::string& name, std::string* target, const std::string& help,
                             bool required)
{
    positionals_.push_back({name, help, name, [target](const std::string& v) { *target = v; }});
    positional_required_.push_back(required);
}

void CommandLine::flag(const std::string& name, bool* target, const std::string& help)
{
    options_.push_back({name, help, "", [target](const std::string&) { *target = true; }});
}

void CommandLine::always_on(const std::string& name, const std::string& help)
{
    options_.push_back({name, help, "", [](const std::string&) {}});
}

void CommandLine::flags(const std::vector<Flag>& table)
{
    for (const Flag& f : table) flag(f.name, f.target, f.help);
}

void CommandLine::option(const std::string& name, double* target, const std::string& help,
                         bool* was_set)
{
    options_.push_back({name, help, "X",
                        [name, target](const std::string& v) { *target = parse_double(name, v); },
                        was_set});
}

void CommandLine::option(const std::string& name, int* target, const std::string& help,
                         bool* was_set)
{
    options_.push_back({name, help, "N",
                        [name, target](const std::string& v) { *target = parse_int(name, v); },
                        was_set});
}

void CommandLine::option(const std::string& name, std::string* target, const std::string& help,
                         bool* was_set)
{
    options_.push_back({name, help, "S", [target](const std::string& v) { *target = v; }, was_set});
}

void CommandLine::verbosity(const std::string& name, int* target, int most, const std::string& help)
{
    Entry entry{name, help, "[N]", [name, target, most](const std::string& v) {
                    if (!v.empty()) *target = std::clamp(parse_int(name, v), 0, most);
                }};
    entry.optional_value = true;
    options_.push_back(std::move(entry));
}

CommandLine::Entry* CommandLine::find(const std::string& name)
{
    for (auto* list : {&options_, &positionals_})
        for (Entry& e : *list)
            if (e.name == name || std::count(e.aliases.begin(), e.aliases.end(), name) > 0)
                return &e;
    return nullptr;
}

void CommandLine::alias(const std::string& name, const std::string& existing)
{
    Entry* entry = find(existing);
    if (!entry) throw std::logic_error("alias of an unregistered option " + existing);
    if (entry >= positionals_.data() && entry < positionals_.data() + positionals_.size())
    {
        // an option that fills a positional: its own entry, so the positional knows it was set
        const int index = static_cast<int>(entry - positionals_.data());
        Entry option{name, entry->help, entry->name, entry->set};
        option.positional = index;
        options_.push_back(std::move(option));
        entry = &positionals_[index];
    }
    entry->aliases.push_back(name);
}

void CommandLine::refuse(const std::string& name, const std::string& what, const std::string& why)
{
    refused_.push_back({name, what, why});
}

void CommandLine::parse(int argc, char** argv)
{
    std::vector<bool> positional_set(positionals_.size(), false);
    std::vector<std::string> bare;  // positional arguments, placed once every option is read
    for (int i = 1; i < argc; ++i)
    {
        const std::string arg = argv[i];
        if (arg == "-h" || arg == "--help" || arg == "-?")
        {
            std::cout << help();
            std::exit(0);
        }
        if (arg.size() > 1 && arg[0] == '-' && !std::isdigit(static_cast<unsigned char>(arg[1])))
        {
            for (const Refused& r : refused_)
                if (r.name == arg)
                    throw UsageError(arg + " (" + r.what +
                                     ") is an Mmg option hdimesh does not support" +
                                     (r.why.empty() ? "" : ": " + r.why));
            const Entry* entry = nullptr;
            for (const auto& o : options_)
                if (o.name == arg ||
                    (o.positional < 0 && std::count(o.aliases.begin(), o.aliases.end(), arg) > 0))
                    entry = &o;
            if (!entry) throw UsageError("unknown option '" + arg + "' (see --help)");
            std::string value;
            if (entry->optional_value)
            {
                if (i + 1 < argc && is_integer(argv[i + 1])) value = argv[++i];
            }
            else if (!entry->value_name.empty())
            {
                if (i + 1 >= argc) throw UsageError(arg + " expects a value");
                value = argv[++i];
            }
            entry->set(value);
            if (entry->was_set) *entry->was_set = true;
            if (entry->positional >= 0) positional_set[entry->positional] = true;
            continue;
        }
        bare.push_back(arg);
    }
    std::size_t next_positional = 0;
    for (const std::string& arg : bare)
    {
        while (next_positional < positionals_.size() && positional_set[next_positional])
            ++next_positional;
        if (next_positional >= positionals_.size())
            throw UsageError("unexpected argument '" + arg + "' (see --help)");
        positionals_[next_positional].set(arg);
        positional_set[next_positional++] = true;
    }
    for (std::size_t k = 0; k < positionals_.size(); ++k)
        if (positional_required_[k] && !positional_set[k])
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
    // every spelling of an entry on its line: "--hsiz X | -hsiz X"
    auto spellings = [](const Entry& e, bool with_value) {
        const std::string value = with_value && !e.value_name.empty() ? " " + e.value_name : "";
        std::string line = e.name + value;
        for (const std::string& a : e.aliases) line += " | " + a + value;
        return line;
    };
    for (const auto& p : positionals_)
    {
        std::string line = p.name;
        for (const std::string& a : p.aliases) line += " | " + a + " " + p.name;
        out << "  " << line << "\n      " << p.help << "\n";
    }
    for (const auto& o : options_)
        if (o.positional < 0) out << "  " << spellings(o, true) << "\n      " << o.help << "\n";
    if (!refused_.empty())
    {
        out << "\nMmg options without a counterpart here (each is an error, never ignored):\n";
        for (const Refused& r : refused_)
            out << "  " << r.name << "  " << r.what << (r.why.empty() ? "" : ": " + r.why) << "\n";
    }
    return out.str();
}

MessageSink print_messages()
{
    const bool terminal = isatty(STDERR_FILENO);
    return [terminal](MessageKind kind, const std::string& text) {
        if (kind == MessageKind::Report)
            std::cout << text << std::flush;
        else if (kind == MessageKind::Trace)
            std::cerr << text << std::flush;
        else if (terminal)
            std::cerr << '\r' << text << std::flush;
    };
}

int run(const char* program, const std::function<int()>& body)
{
    try
    {
        return body();
    }
    catch (const std::bad_alloc&)
    {
        std::cerr << program << ": error: out of memory"
                  << (memory_limit_mb > 0 ? ": the run exceeded the -m limit of " +
                                                std::to_string(memory_limit_mb) + " MB"
                                          : std::string())
                  << " (nothing written)\n";
        return 1;
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

void SizeOptions::add_to(CommandLine& cli, bool with_bounds)
{
    cli.option("--hsiz", &hsiz, "constant size", &hsiz_set);
    cli.option("--sol", &sol,
               "sizes or a metric at the input's vertices: Medit .sol/.solb (SolAtVertices, a "
               "scalar or, for the tet tools, a tensor m11 m12 m22 m13 m23 m33), or a .msh's one "
               "$NodeData (1 or 9 components)",
               &sol_set);
    if (!with_bounds) return;
    cli.option("--hmin", &hmin, "smallest size allowed");
    cli.option("--hmax", &hmax, "largest size allowed", &hmax_set);
    cli.option("--hgrad", &hgrad,
               "gradation: size ratio bound between neighbours (e.g. 1.3; -1: none, as Mmg)",
               &hgrad_set);
}

void SizeOptions::add_mmg_aliases(CommandLine& cli, bool with_bounds)
{
    cli.alias("-hsiz", "--hsiz");
    cli.alias("-sol", "--sol");
    cli.alias("-met", "--sol");
    if (!with_bounds) return;
    cli.alias("-hmin", "--hmin");
    cli.alias("-hmax", "--hmax");
    cli.alias("-hgrad", "--hgrad");
}

void refuse_mmg_options(CommandLine& cli, MmgTool tool)
{
    const bool volume = tool == MmgTool::mmg3d;
    if (!volume) cli.refuse("-A", "anisotropic metric", "surfremesh adapts to sizes only");
    cli.refuse("-ls", "level-set discretization");
    cli.refuse("-lssurf", "level-set discretization of the boundary");
    cli.refuse("-isoref", "reference of the level-set boundary");
    cli.refuse("-rmc", "removal of small level-set components");
    if (volume) cli.refuse("-lag", "Lagrangian mesh displacement");
    if (!volume) cli.refuse("-keep-ref", "keep domain references in level-set mode");
    if (volume) cli.refuse("-opnbdy", "keep internal triangles between domains of one ref");
    if (volume) cli.refuse("-nofem", "a mesh not fit for finite elements");
    if (volume) cli.refuse("-optimLES", "skewness improvement for LES");
    if (volume) cli.refuse("-octree", "points per octree cell");
    cli.refuse("-rn", "SCOTCH renumbering");
    cli.refuse("-nsd", "save only one subdomain");
    cli.refuse("-xreg", "vertex regularization");
    cli.always_on("-nreg",
                  "Mmg's normal regularization: always on here (the HDI model refits each node "
                  "normal from its neighbours)");
    cli.refuse("-nosizreq", "no sizes imposed at required vertices");
    cli.refuse("-hgradreq", "gradation from required entities");
    cli.refuse("-d", "debug mode");
    cli.refuse("-val", "print the default parameter values");
    cli.refuse("-default", "save a default parameter file");
    cli.refuse("-f", "parameter file");
}

void add_memory_limit(CommandLine& cli, int* megabytes, bool* was_set)
{
    cli.option("-m", megabytes,
               "memory limit in MB: the process's address space is capped (RLIMIT_AS); a run "
               "that needs more stops with an error and writes nothing",
               was_set);
}

void add_mmg_files(CommandLine& cli, std::string* input, const std::string& input_help,
                   std::string* output, const std::string& output_help)
{
    cli.positional("IN", input, input_help);
    cli.positional("OUT", output, output_help, false);
    cli.alias("-in", "IN");
    cli.alias("-o", "OUT");
    cli.alias("-out", "OUT");
}

std::string mmg_input_name(const std::string& input)
{
    if (!mmg_extension(input).empty()) return input;
    return file_exists(input + ".meshb") ? input + ".meshb" : input + ".mesh";
}

std::string mmg_output_name(const std::string& output, const std::string& input)
{
    if (!output.empty())
    {
        const std::size_t dot = output.rfind('.');
        if (dot != std::string::npos && dot != 0) return output;
        return output + mmg_mesh_format(mmg_extension(input));
    }
    const std::string ext = mmg_extension(input);
    return input.substr(0, input.size() - ext.size()) + ".o" + mmg_mesh_format(ext);
}

std::string mmg_default_sol(const std::string& input)
{
    const std::string ext = mmg_extension(input);
    const bool medit = ext.compare(0, 5, ".mesh") == 0;  // Mmg cuts only a Medit extension
    const std::string stem = medit ? input.substr(0, input.size() - ext.size()) : input;
    for (const char* suffix : {".solb", ".sol"})
        if (file_exists(stem + suffix)) return stem + suffix;
    return "";
}

void refuse_mmg_parameter_file(const std::string& input, const std::string& suffix)
{
    const std::string ext = mmg_extension(input);
    for (const std::string& path :
         {input.substr(0, input.size() - ext.size()) + suffix, "DEFAULT" + suffix})
        if (file_exists(path))
            throw UsageError(path +
                             ": an Mmg parameter file, which hdimesh does not read (local "
                             "parameters per ref); move it away to run without it");
}

void limit_memory_mb(int megabytes)
{
    if (megabytes <= 0) throw UsageError("-m expects a positive number of MB");
#if defined(__SANITIZE_ADDRESS__) || HDIMESH_CLANG_ASAN
    throw UsageError(
        "-m cannot be enforced in a sanitizer build (its shadow memory is reserved "
        "up front)");
#else
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) != 0) throw Error("-m: cannot read the memory limit");
    const rlim_t bytes = static_cast<rlim_t>(megabytes) * 1024 * 1024;
    if (limit.rlim_max != RLIM_INFINITY && bytes > limit.rlim_max)
        throw UsageError("-m " + std::to_string(megabytes) + " is above this process's hard limit");
    limit.rlim_cur = bytes;
    if (setrlimit(RLIMIT_AS, &limit) != 0) throw Error("-m: cannot set the memory limit");
    memory_limit_mb = megabytes;
#endif
}

}  // namespace hdimesh::cli

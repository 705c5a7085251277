#include "cli.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>

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

void SizeOptions::add_to(CommandLine& cli, bool with_bounds)
{
    cli.option("--hsiz", &hsiz, "constant size", &hsiz_set);
    cli.option("--sol", &sol, "sizes at the input's vertices (Medit .sol/.solb, SolAtVertices)",
               &sol_set);
    if (!with_bounds) return;
    cli.option("--hmin", &hmin, "smallest size allowed");
    cli.option("--hmax", &hmax, "largest size allowed", &hmax_set);
    cli.option("--hgrad", &hgrad, "gradation: size ratio bound between neighbours (e.g. 1.3)",
               &hgrad_set);
}

}  // namespace hdimesh::cli

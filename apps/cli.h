#pragma once
// A tiny command-line parser shared by the apps: one table of flag -> variable -> help text,
// Mmg-style "--key value" options, and one error line + non-zero exit on any failure.

#include <functional>
#include <string>
#include <vector>

#include "common/errors.h"

namespace hdimesh::cli
{

/// A malformed command line: run() answers it with exit code 2.
class UsageError : public InputError
{
public:
    using InputError::InputError;
};

class CommandLine
{
public:
    CommandLine(std::string program, std::string summary);

    /// A required or optional positional argument, filled in order.
    void positional(const std::string& name, std::string* target, const std::string& help,
                    bool required = true);
    /// A flag without value ("--check").
    void flag(const std::string& name, bool* target, const std::string& help);
    struct Flag
    {
        std::string name;
        bool* target;
        std::string help;
    };
    /// A tool's switches as one table.
    void flags(const std::vector<Flag>& table);
    /// Options with one value ("--hmin 0.01"). `was_set`, if given, tells whether it appeared.
    void option(const std::string& name, double* target, const std::string& help,
                bool* was_set = nullptr);
    void option(const std::string& name, int* target, const std::string& help,
                bool* was_set = nullptr);
    void option(const std::string& name, std::string* target, const std::string& help,
                bool* was_set = nullptr);

    /// Parses argv; prints help and exits 0 on -h/--help; throws hdimesh::InputError on a bad
    /// command line (unknown flag, missing value, value not a number, missing positional).
    void parse(int argc, char** argv);
    std::string help() const;

private:
    struct Entry
    {
        std::string name;
        std::string help;
        std::string value_name;  // empty for flags
        std::function<void(const std::string&)> set;
        bool* was_set = nullptr;
    };
    std::string program_, summary_;
    std::vector<Entry> options_;
    std::vector<Entry> positionals_;
    std::vector<bool> positional_required_;
};

/// Runs an app body: any exception becomes one line "program: error: message" on stderr and
/// exit code 1 (2 for a bad command line).
int run(const char* program, const std::function<int()>& body);

/// The Mmg size flags every tool shares: --hsiz, --sol and, when with_bounds, --hmin, --hmax,
/// --hgrad. Each tool checks and applies them its own way; 0 means not given.
struct SizeOptions
{
    double hsiz = 0;  ///< --hsiz: constant size
    std::string sol;  ///< --sol: sizes at the input's vertices (Medit .sol/.solb)
    double hmin = 0, hmax = 0, hgrad = 0;
    bool hsiz_set = false, sol_set = false, hmax_set = false, hgrad_set = false;

    void add_to(CommandLine& cli, bool with_bounds);
};

}  // namespace hdimesh::cli

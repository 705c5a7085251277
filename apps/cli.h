#pragma once
// A tiny command-line parser shared by the apps: one table of flag -> variable -> help text,
// Mmg-style "--key value" options, and one error line + non-zero exit on any failure. Mmg's own
// spellings ("-hsiz", "-in", "-out") are aliases of ours, so mmg3d/mmgs scripts run unchanged;
// the Mmg options we lack are refused by name, never ignored.

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "common/errors.h"
#include "common/messages.h"

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
    /// A flag naming what the tool always does (Mmg's -nreg): accepted, and said so in --help.
    void always_on(const std::string& name, const std::string& help);
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
    /// Verbosity "-v [N]" as Mmg parses it: the value is optional (taken when the next argument
    /// is an integer, "-1" included) and clamped to 0..most (Mmg's -1..10 onto ours).
    void verbosity(const std::string& name, int* target, int most, const std::string& help);
    /// A second name for an option, flag or positional registered already ("-hsiz" for
    /// "--hsiz", "-in" for IN); --help shows both. A positional set through its alias is skipped
    /// by the bare arguments, which go to the next one (Mmg: "-in X.mesh Y.mesh" writes Y.mesh).
    void alias(const std::string& name, const std::string& existing);
    /// An option of Mmg's that this tool lacks: naming it is one error line "NAME (WHAT) is an
    /// Mmg option hdimesh does not support[: WHY]" and exit code 2.
    void refuse(const std::string& name, const std::string& what, const std::string& why = "");

    /// Parses argv; prints help and exits 0 on -h/--help; throws hdimesh::InputError on a bad
    /// command line (unknown flag, missing value, value not a number, missing positional).
    void parse(int argc, char** argv);
    std::string help() const;

private:
    struct Entry
    {
        Entry(std::string n, std::string h, std::string v,
              std::function<void(const std::string&)> s, bool* w = nullptr)
            : name(std::move(n)), help(std::move(h)), value_name(std::move(v)), set(std::move(s)),
              was_set(w)
        {
        }
        std::string name;
        std::string help;
        std::string value_name;  // empty for flags
        std::function<void(const std::string&)> set;
        bool* was_set = nullptr;
        std::vector<std::string> aliases;
        bool optional_value = false;  // the value is taken only when the next arg is an integer
        int positional = -1;          // >= 0: an alias of that positional
    };
    struct Refused
    {
        std::string name, what, why;
    };
    Entry* find(const std::string& name);
    std::string program_, summary_;
    std::vector<Entry> options_;
    std::vector<Entry> positionals_;
    std::vector<bool> positional_required_;
    std::vector<Refused> refused_;
};

/// Which Mmg program's command line a tool stands in for.
enum class MmgTool
{
    mmg3d,  ///< adapt
    mmgs,   ///< surfremesh
};

/// Registers the options of `tool` that hdimesh has no counterpart for (level sets, Lagrangian
/// motion, anisotropy, parameter files, ...), each refused with its meaning (CommandLine::refuse).
void refuse_mmg_options(CommandLine& cli, MmgTool tool);

/// Mmg's "-m N": the memory limit in MB (limit_memory_mb applies it once parsed).
void add_memory_limit(CommandLine& cli, int* megabytes, bool* was_set);

/// IN and an optional OUT, positional, with Mmg's spellings: -in IN, -o OUT, -out OUT.
void add_mmg_files(CommandLine& cli, std::string* input, const std::string& input_help,
                   std::string* output, const std::string& output_help);

/// Mmg's input name: one without an extension (no '.' in its last path component, or only ".o")
/// is X.meshb if that exists, else X.mesh; any other name is kept.
std::string mmg_input_name(const std::string& input);

/// Mmg's output name. Given: kept, unless it has no '.' (or only a leading one), which gets the
/// input's extension (.mesh when the input's is not a mesh format). Not given: the input less
/// its extension plus ".o.mesh" (".o.meshb", ".o.msh", ".o.mshb", ".o.vtu", ".o.vtp", ".o.vtk"
/// for those inputs), beside the input.
std::string mmg_output_name(const std::string& output, const std::string& input);

/// The sizes Mmg reads when no -sol/-met is given: X.solb, else X.sol, beside the input (X: the
/// input less a ".mesh"/".meshb" extension, else the whole name). Empty when neither exists.
std::string mmg_default_sol(const std::string& input);

/// Mmg reads a parameter file X.mmg3d / X.mmgs beside the input (or DEFAULT.mmg3d in the
/// working directory) when there is one; we have no such file, so finding one is an error
/// rather than a silently different run. `suffix` is ".mmg3d" or ".mmgs".
void refuse_mmg_parameter_file(const std::string& input, const std::string& suffix);

/// "-m N": caps the process's address space at N MB (setrlimit RLIMIT_AS), so that an allocation
/// beyond it fails; run() then reports "... exceeded the -m limit of N MB" and no output is
/// written. Registered by the tools as an option; refused in a sanitizer build, whose shadow
/// memory is reserved up front.
void limit_memory_mb(int megabytes);

/// The apps' sink for the library's messages: Report lines to stdout, Trace lines to stderr,
/// Progress lines to stderr as a '\r' status line when it is a terminal (dropped otherwise).
MessageSink print_messages();

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
    /// Mmg's spellings of the same: -hsiz, -sol and -met (both --sol), -hmin, -hmax, -hgrad.
    void add_mmg_aliases(CommandLine& cli, bool with_bounds);
};

}  // namespace hdimesh::cli

#pragma once
// A tiny command-line parser shared by the apps: one table of flag -> variable -> help text,
// Mmg-style "--key value" options, and one error line + non-zero exit on any failure.

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "volume/size_field.h"
#include "volume/tet_mesh.h"

namespace hdimesh::cli
{

class CommandLine
{
public:
    CommandLine(std::string program, std::string summary);

    /// A required or optional positional argument, filled in order.
    void positional(const std::string& name, std::string* target, const std::string& help,
                    bool required = true);
    /// A flag without value ("--check").
    void flag(const std::string& name, bool* target, const std::string& help);
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

/// The size-field flags shared by adapt and meshstat (Mmg names).
struct SizeFlags
{
    double hsiz = 0;          ///< --hsiz: constant size
    std::string sol;          ///< --sol: sizes at the input mesh's vertices (Medit .sol)
    std::string bench_field;  ///< --bench-field: the paper's cases A-E
    double hmin = 0, hmax = 0, hgrad = 0;  ///< 0: not set
    bool hsiz_set = false;

    /// Registers --hsiz, --sol, --bench-field and, when with_bounds, --hmin/--hmax/--hgrad.
    void add_to(CommandLine& cli, bool with_bounds);
    bool any() const { return hsiz_set || !sol.empty() || !bench_field.empty(); }
    /// The field they describe over `input` (the mesh the .sol belongs to). With no size flag:
    /// the input's own sizes (mean length of the edges at each vertex, linear in each tet), so
    /// --optim keeps the sizes. --hmin/--hmax clamp; --hgrad bounds the size ratio between
    /// neighbouring vertices (Mmg's H-correction) on the input mesh's vertices: for a .sol the
    /// corrected values are the field, for an analytic field the field becomes
    /// min(analytic, graded samples), so it keeps its own resolution and gradation only ever
    /// shrinks sizes. Throws InputError on conflicting or invalid flags.
    std::shared_ptr<const SizeField> make(const TetMesh& input) const;
};

}  // namespace hdimesh::cli

// meshstat: the quality report of any tet mesh and the mesh checker's verdict
// (parse -> read -> report + check -> print).
#include <iostream>
#include <string>

#include "common/errors.h"
#include "size_flags.h"
#include "volume/check/check.h"
#include "volume/check/quality_report.h"
#include "volume/io/tet_io.h"

using namespace hdimesh;
using namespace hdimesh::volume;

namespace
{

/// The report's JSON object with the checker's verdict appended, so one object says it all.
std::string json_with_check(const QualityReport& report,
                            const std::vector<MeshViolation>& violations)
{
    std::string json = quality_report_json(report);
    const auto close = json.rfind('}');
    json.erase(close);
    while (!json.empty() && (json.back() == '\n' || json.back() == ' ')) json.pop_back();
    json += ",\n  \"violations\": " + std::to_string(violations.size());
    json += ",\n  \"clean\": " + std::string(violations.empty() ? "true" : "false") + "\n}\n";
    return json;
}

}  // namespace

int main(int argc, char** argv)
{
    return cli::run("meshstat", [&] {
        std::string input, svg_path, stats_path;
        bool json = false;
        cli::SizeFlags size;
        cli::CommandLine cl(
            "meshstat",
            "Prints the quality report of a tet mesh (counts, Qe, dihedral angles,\n"
            "Qt of every edge against a size field when one is given) and the\n"
            "mesh checker's verdict. Exit code 0 when the mesh is clean, 1 when\n"
            "the checker finds violations or the mesh cannot be read.");
        cl.positional("IN", &input, "tet mesh (.mesh .meshb .msh)");
        size.add_to(cl, true);
        cl.flag("--json", &json, "print the report as one JSON object instead of a table");
        cl.option("--svg", &svg_path, "draw the Qe and L/hth histograms into FILE.svg");
        cl.option("--stats", &stats_path, "write the report as JSON into FILE.json");
        cl.parse(argc, argv);

        const TetMesh mesh = read_mesh(input);
        // no size flag: shape statistics only (no size is better than an invented one)
        const std::shared_ptr<const SizeField> field = size.any() ? size.make(mesh) : nullptr;
        const QualityReport report = compute_quality_report(mesh, field.get());
        // as strict as the independent checker: a vertex no tet uses is reported too
        CheckOptions check_options;
        check_options.report_unused_vertices = true;
        const std::vector<MeshViolation> violations = check_mesh(mesh, check_options);

        if (json)
        {
            std::cout << json_with_check(report, violations);
        }
        else
        {
            std::cout << "mesh " << input << "\n" << format_quality_table(report);
            std::cout << "check: " << (violations.empty() ? "clean\n" : "")
                      << (violations.empty() ? "" : format_violations(violations));
        }
        if (!svg_path.empty()) write_quality_svg(report, svg_path);
        if (!stats_path.empty()) write_quality_json(report, stats_path);
        if (!violations.empty() && json) std::cerr << format_violations(violations);
        return violations.empty() ? 0 : 1;
    });
}

#pragma once
// The quality report of method.md §1 for any tet mesh: counts, shape (Qe of tets and boundary
// triangles, dihedral angles), size conformity of every edge against a size field (Qt, L/hth),
// printed as a table, written as JSON, drawn as an SVG of the two histograms.

#include <array>
#include <limits>
#include <string>

#include "common/size_field.h"
#include "volume/mesh/tet_mesh.h"

namespace hdimesh::volume
{

/// Bin edges of the L/hth histogram (the same as ../shared/tools/meshstat.py): too short below
/// 0.66, too long above 1/0.66 = 1.515.
inline constexpr std::array<double, 9> kLengthRatioBinEdges = {
    0.0, 0.5, 0.66, 0.8, 1.0, 1.25, 1.515, 2.0, std::numeric_limits<double>::infinity()};

struct QualityReport
{
    // counts
    int vertices = 0;              ///< vertices used by live tets
    int tets = 0;                  ///< live tets
    int boundary_triangles = 0;    ///< faces used by exactly one live tet (the true boundary)
    int declared_triangles = 0;    ///< mesh.triangles (boundary + interfaces as stored)
    long edges = 0;                ///< unique edges of live tets
    double volume = 0.0;           ///< sum of signed tet volumes
    double enclosed_volume = 0.0;  ///< volume enclosed by the boundary faces (divergence theorem)

    // shape
    double min_qe = 0.0, mean_qe = 0.0;
    /// Qe in tenths: bin k holds k/10 <= Qe < (k+1)/10 with the edges computed as k*0.1 like
    /// numpy.histogram; Qe = 1 goes to bin 9, a negative Qe (inverted tet) to bin 0.
    std::array<int, 10> qe_histogram{};
    double percent_qe_ge_05 = 0.0, percent_qe_lt_02 = 0.0;
    /// Tets below QualityReportOptions::floor, and among them those forced: with an edge on a
    /// sharp boundary ridge, a vertex at a sharp boundary corner, or a face on a poor kept
    /// triangle (no tet there can be good).
    double qe_floor = 0.3;
    int below_floor = 0, forced_below_floor = 0;
    double min_dihedral_deg = 0.0, max_dihedral_deg = 0.0;
    double min_boundary_triangle_qe = 0.0, mean_boundary_triangle_qe = 0.0;
    double min_edge_length = 0.0, max_edge_length = 0.0;

    // size (valid when has_size); hth = field at the edge midpoint (size_field.h)
    bool has_size = false;
    double percent_qt_ge_066 = 0.0, percent_too_long = 0.0, percent_too_short = 0.0;
    double min_qt = 0.0, mean_qt = 0.0;
    double min_length_ratio = 0.0, mean_length_ratio = 0.0, max_length_ratio = 0.0;  ///< L/hth
    std::array<long, 8> length_ratio_histogram{};  ///< bins of kLengthRatioBinEdges
    double percent_unit_length = 0.0;  ///< edges with 1/√2 <= L/hth <= √2 (Mmg's band)
    // in a metric (valid when anisotropic): Qe of each tet in the metric at its centroid (as
    // the operators judge shapes), and Mmg's quality with the mean of its vertices' metrics
    bool anisotropic = false;
    double min_metric_qe = 0.0, mean_metric_qe = 0.0;
    double min_mmg_quality = 0.0, mean_mmg_quality = 0.0;
};

struct QualityReportOptions
{
    double floor = 0.3;  ///< Qe below which tets are counted, and told forced or not
    /// A boundary edge where the solid's interior dihedral angle is below this is a sharp
    /// ridge: a tet on it has that dihedral angle or less.
    double sharp_ridge_deg = 60.0;
    /// A boundary vertex where the solid's solid angle is below this is a sharp corner: a
    /// regular tet's vertex (3 acos(1/3) - pi), so no tet there is near regular.
    double sharp_corner_steradians = 0.5513;
    /// The boundary triangles were kept from the input (--keep-surface): a tet on one with
    /// triangle Qe below the floor is forced.
    bool kept_surface = false;
};

/// Computes the report in O(n) (unique edges by per-vertex buckets); field may be nullptr
/// (no size statistics). Dead tets are ignored.
QualityReport compute_quality_report(const TetMesh& mesh, const SizeField* field,
                                     const QualityReportOptions& options = {});

/// Aligned two-column table for terminals, one measure per line.
std::string format_quality_table(const QualityReport& report);

/// One JSON object with the fields of QualityReport under the same names.
std::string quality_report_json(const QualityReport& report);

/// Writes the JSON of the report to path (temporary file + rename). Throws IoError.
void write_quality_json(const QualityReport& report, const std::string& path);

/// Draws the Qe and L/hth histograms side by side as an SVG (temporary file + rename).
/// Throws IoError naming the path.
void write_quality_svg(const QualityReport& report, const std::string& path);

/// Bin of a Qe value in QualityReport::qe_histogram.
int qe_histogram_bin(double qe);

/// Bin of an L/hth value in QualityReport::length_ratio_histogram.
int length_ratio_histogram_bin(double ratio);

/// The six dihedral angles of a tet in degrees, at edges e0..e5 (tet_tables.h); 0 for a
/// degenerate face.
std::array<double, 6> dihedral_angles_deg(const Vec3& a, const Vec3& b, const Vec3& c,
                                          const Vec3& d);

/// The cosine of the smallest dihedral angle of a tet (the largest of the six cosines, as
/// dihedral_angles_deg measures them before acos), or 1 (an angle of 0) for a degenerate face.
/// acos of it, in degrees, is the least of dihedral_angles_deg: one acos instead of six.
double smallest_dihedral_cosine(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d);

/// A dihedral cosine as dihedral_angles_deg turns it into degrees.
double dihedral_cosine_to_deg(double cosine);

}  // namespace hdimesh::volume

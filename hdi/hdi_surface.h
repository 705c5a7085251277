#pragma once
// The HDI (Hermite Diffuse Interpolation) surface model: a meshfree, moving-least-squares
// surface through the nodes and node normals of an input triangle surface (paper §4, method.md §5).
//
// For a point X: the n nearest admissible input nodes (on X's side of every ridge, with a normal
// agreeing with the local one), a window radius from the n-th distance, weights w(d/rho), the
// diffuse origin xd (eq. 5), the plane through xd whose normal is the eigenvector of the smallest
// eigenvalue of P^T W P (eqs. 6-8), and a quadratic Monge patch over that plane (eq. 4) fitted by
// weighted least squares to the nodes' heights and, as Hermite rows, their normals' slopes
// (6 x 6 normal equations in window-scaled coordinates, pivoted LDL^T; a plane when they are
// ill-conditioned). X is moved onto the patch along the plane normal, and the fit is redone at the
// new point until the move is below tolerance * rho, or is predicted to be at the next fit from
// the contraction rate of the last two moves (saves a third fit on most projections). Node
// normals: face-averaged per smooth side, then refined by a positions-only quadratic fit (see
// HdiOptions::refine_normals). Feature lines (ridges, open boundaries) get a 1-D diffuse fit
// (a quadratic in the tangent parameter) of their polyline; corners never move.

#include <memory>
#include <vector>

#include "hdi/features.h"
#include "hdi/point_cloud.h"
#include "hdi/weights.h"

namespace hdimesh::hdi
{

struct HdiOptions
{
    using Weight = WeightFunction;
    /// n: input nodes per fit (the paper: 10-20; at most 256). Fewer keep the window small,
    /// where a quadratic patch fits a curved surface best.
    int neighbours = 12;
    Weight weight = Weight::Interpolating;  ///< w(s), s = d / rho
    double window_factor = 1.1;             ///< rho = window_factor * distance to the n-th node
    double normal_agreement = 0.5;  ///< thin parts: drop nodes whose normal . local normal is below
    int max_iterations = 5;         ///< fits per projection
    double tolerance = 1e-6;        ///< converged when the move is below tolerance * rho
    int ridge_neighbours = 6;       ///< polyline nodes per 1-D fit of a feature line (2-64)
    NormalWeighting normal_weighting = NormalWeighting::Angle;  ///< node normals from the triangles
    /// Re-estimates each node normal (per smooth side) from a positions-only quadratic fit of its
    /// neighbours: face-averaged normals are first-order only, which caps the order near 2.
    /// Normals given to the constructor are trusted as they are.
    bool refine_normals = true;
};

enum class ProjectionStatus
{
    Ok,              ///< converged on the quadratic fit
    LinearFallback,  ///< converged, but the quadratic system was ill-conditioned: a plane was used
    NotConverged,    ///< max_iterations reached; the last point is returned (still on a fit)
    Failed           ///< no usable fit (too few admissible nodes, no feature line): point = input
};

struct Projection
{
    Vec3 point = Vec3::Zero();
    Vec3 normal = Vec3::Zero();   ///< unit, oriented like the input's normals; for a feature line,
                                  ///< the mean of its sides' normals at the nearest line node
    Vec3 tangent = Vec3::Zero();  ///< feature lines only: unit tangent of the fitted curve
    /// Principal curvatures at the point, k1 >= k2, signed positive where the surface bends away
    /// from its normal (a sphere of radius R with outward normals: k1 = k2 = 1/R).
    /// Feature lines: k1 = the curve's curvature, k2 = 0.
    double k1 = 0;
    double k2 = 0;
    ProjectionStatus status = ProjectionStatus::Failed;
};

/// The diffuse plane of the fit at a point: where George's nodal shifting moves a surface vertex
/// before it is projected back (paper §5).
struct DiffusePlane
{
    Vec3 origin = Vec3::Zero();  ///< the diffuse origin xd (eq. 5)
    Vec3 normal = Vec3::Zero();  ///< unit, oriented like the input's normals
    Vec3 e1 = Vec3::Zero();      ///< e1, e2, normal: a right-handed orthonormal frame
    Vec3 e2 = Vec3::Zero();
    double window_radius = 0;  ///< rho
    bool ok = false;           ///< false when no fit exists there (then the rest is zero)
};

/// Thread-safe for const queries (each thread keeps its own scratch). Copies share the model.
class HdiSurface
{
public:
    /// Builds the model from a triangle surface: node normals from the triangles
    /// (options.normal_weighting), one normal per smooth side at a ridge node. `features` are used
    /// as given (detect_features() or read from the input; empty for none); the surface's
    /// open-boundary edges are always added, and every vertex where feature lines branch or end
    /// becomes a corner. Throws InputError for bad indices or options.
    HdiSurface(std::vector<Vec3> points, std::vector<Triangle3> triangles,
               const FeatureSet& features, const HdiOptions& options = {});

    /// Same, with the node normals given (one per point). A given normal replaces the computed one
    /// at every node with a single smooth side. With no triangles at all the points are a pure
    /// point cloud: every point is a node with its given normal.
    HdiSurface(std::vector<Vec3> points, std::vector<Vec3> normals,
               std::vector<Triangle3> triangles, const FeatureSet& features,
               const HdiOptions& options = {});

    /// Projects onto the smooth surface, using only nodes on x's side of any ridge.
    Projection project(const Vec3& x) const;

    /// Projects onto the 1-D diffuse fit of the nearest ridge or boundary polyline (a point past
    /// the end of a line stops at its end node). Failed when the model has no feature line.
    Projection project_to_ridge(const Vec3& x) const;

    /// The plane of the (first) fit at x, with x's side of the ridges chosen as in project().
    DiffusePlane diffuse_plane(const Vec3& x) const;

    bool is_corner(int input_vertex) const;
    const FeatureSet& features() const;
    const std::vector<FeatureChain>& feature_lines() const;
    const std::vector<Vec3>& points() const;
    const std::vector<Triangle3>& triangles() const;
    const HdiOptions& options() const;
    /// Bounding-box diagonal of the input nodes (the model's length scale).
    double scale() const;

    struct Model;  // the built model; defined in hdi_surface.cpp

private:
    std::shared_ptr<const Model> model_;
};

}  // namespace hdimesh::hdi

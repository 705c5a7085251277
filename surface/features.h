#pragma once
// Feature detection on an input surface: ridges (chains of sharp edges long enough to matter,
// not isolated creases of scan noise), corners (where curves meet, end or turn sharply) and open
// boundary curves. Writes the vertex class and the curve ids of vertices and edges.

#include <cstddef>

#include "surface/surface_mesh.h"

namespace hdimesh::surface
{

struct FeatureOptions
{
    bool detect_ridges = true;
    double ridge_angle_deg = 45.0;       // an edge is sharp when its face normals differ by more
    /// Creases between this angle and ridge_angle_deg are kept as ridges too when they form a
    /// long chain (2·min_ridge_length): a 37° crease cut by chords
    /// strays h·sin(18°)/2 from the model. ≥ ridge_angle_deg: off.
    double crease_angle_deg = 30.0;
    double corner_turn_angle_deg = 50.0; // a curve vertex whose curve turns by more is a corner
    double boundary_corner_turn_angle_deg = 75.0;  // the same on an open boundary (scans zig-zag)
    /// An interior vertex away from kept curves whose angle defect (360° minus its angle sum)
    /// exceeds this is a spike kept as an isolated corner (≥ 360: off), if its angle sum is at
    /// least cone_min_angle_sum_deg: remeshing would cut its tip off (cheburashka's spikes, the
    /// knobs of rocker-arm; 0.85·h away from the output before). fandisk has no such vertex.
    double cone_defect_deg = 60.0;
    double cone_min_angle_sum_deg = 150.0;
    /// A boundary corner found only by a turn is dropped when another corner (a junction, an
    /// end, a sharper turn) is closer than this (remesh_surface sets half the target size; 0:
    /// keep all). Ridge turns are always kept: they are the corners of machined parts.
    double min_corner_spacing = 0.0;
    /// A ridge chain is kept when at least this fraction of the bbox diagonal long (twice that for
    /// a crease-only chain), or when both its ends are ends of kept chains; the rest is noise.
    double min_ridge_length = 0.05;
};

struct FeatureSummary
{
    std::size_t ridge_edges = 0, boundary_edges = 0;
    std::size_t ridge_vertices = 0, boundary_vertices = 0, corners = 0;
    std::size_t curves = 0;
    std::size_t dropped_ridge_chains = 0;  // sharp chains discarded as noise
};

/// Classifies every vertex and edge of `mesh` (properties of surface_mesh.h). Curves are
/// numbered 0..curves-1; a curve runs between corners or is a closed loop.
FeatureSummary detect_features(SurfaceMesh& mesh, const FeatureOptions& options = {});

}  // namespace hdimesh::surface

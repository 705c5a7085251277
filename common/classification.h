#pragma once
// One classification of what an entity lies on (Omega_h's "class_dim" and "class_id"), shared
// by the tet mesh and the surface mesh. Each mesh keeps its own compact vertex class and maps
// it to and from this through one function each; no operator changes an entity's class.

#include <cstdint>

namespace hdimesh
{

/// The dimension of the model entity a mesh entity lies on.
enum class Dimension : std::uint8_t
{
    Corner = 0,   ///< a model point: never moves
    Curve = 1,    ///< a feature curve (ridge, open-boundary curve, curve between materials)
    Surface = 2,  ///< a smooth part of a boundary or interface surface
    Volume = 3,   ///< strictly inside a region
};

inline constexpr int kNoModelEntity = -1;

struct Classification
{
    Dimension dimension = Dimension::Volume;
    /// Which curve or surface (or region) of that dimension; kNoModelEntity when unknown.
    int id = kNoModelEntity;
    /// For a curve: it bounds an open surface (one side only) rather than joining two sides.
    bool open_boundary = false;

    friend bool operator==(const Classification& a, const Classification& b)
    {
        return a.dimension == b.dimension && a.id == b.id && a.open_boundary == b.open_boundary;
    }
    friend bool operator!=(const Classification& a, const Classification& b) { return !(a == b); }
};

const char* to_string(Dimension d);

}  // namespace hdimesh

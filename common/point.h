#pragma once
// The one point type of every module: hdi/ and volume/ use it as is, surface/ converts
// OpenMesh's points to and from it in one place (surface/surface_mesh.h).

#include <Eigen/Core>

namespace hdimesh
{

using Vec3 = Eigen::Vector3d;

}  // namespace hdimesh

#pragma once
// Typed exceptions of the surface module (it cannot include volume/errors.h): bad input and
// refused file-system operations. Messages name the file and the line or the element at fault.

#include <stdexcept>

namespace hdimesh::surface
{

/// Input that cannot be used: malformed file, a mesh that cannot be repaired, bad option.
class SurfaceInputError : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

/// The file system refused: cannot open, read, write or rename.
class SurfaceIoError : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

}  // namespace hdimesh::surface

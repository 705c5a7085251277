#pragma once
// Typed exceptions of the hdi module. hdi/ is a leaf (Eigen and FLANN only) and cannot include
// volume/errors.h, so it has its own pair with the same meaning; both derive from
// std::runtime_error, so a caller that catches that catches either.

#include <stdexcept>
#include <string>

namespace hdimesh::hdi
{

/// Input that cannot be used (a triangle naming a missing vertex, a malformed OBJ line, a bad
/// option value). The message names the file and line or the element at fault.
class InputError : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

/// The file system refused (cannot open or read a file).
class IoError : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

}  // namespace hdimesh::hdi

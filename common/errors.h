#pragma once
// The one exception hierarchy of hdimesh, thrown at the library's API boundary.
// "Not legal here" answers are bool/result structs, never exceptions; invariants are asserts.

#include <stdexcept>
#include <string>

namespace hdimesh
{

/// Base of every exception hdimesh throws: catch this to catch them all.
class Error : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

/// Input that cannot be used: malformed file content, invalid mesh, bad option value.
/// The message names the file and the line or the element at fault.
class InputError : public Error
{
public:
    using Error::Error;
};

/// The file system refused: cannot open, read, write or rename.
class IoError : public Error
{
public:
    using Error::Error;
};

/// A mesh whose connectivity an algorithm cannot work with (non-manifold where a manifold is
/// needed, an unclosed cavity); the message names the element.
class TopologyError : public Error
{
public:
    using Error::Error;
};

}  // namespace hdimesh

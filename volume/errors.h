#pragma once
// Typed exceptions thrown at the library's API boundary (bad input, I/O).
// "Not legal here" answers are bool/result structs, never exceptions; invariants are asserts.

#include <stdexcept>
#include <string>

namespace hdimesh
{

/// Input that cannot be used: malformed file content, invalid mesh, bad option value.
/// The message names the file and the line or the element at fault.
class InputError : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

/// The file system refused: cannot open, read, write or rename.
class IoError : public std::runtime_error
{
public:
    using std::runtime_error::runtime_error;
};

}  // namespace hdimesh

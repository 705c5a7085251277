#pragma once
// Every output goes through here, so a crash, a full disk or an exception in the middle of a
// write never leaves a partial file under the final name (an old file there stays intact).

#include <functional>
#include <ostream>
#include <string>

namespace hdimesh
{

/// Calls write(stream) on a temporary file beside path, then renames it to path; on any
/// exception removes the temporary and rethrows. Binary mode. IoError when the temporary
/// cannot be created, written (stream failure after write returns) or renamed.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

}  // namespace hdimesh

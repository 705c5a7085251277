#include "common/atomic_file.h"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <system_error>

#include "common/errors.h"

namespace hdimesh
{

namespace
{

/// A name beside the target that no concurrent writer (thread or process) will pick too.
std::string temporary_name(const std::string& path)
{
    static std::atomic<unsigned> counter{0};
    return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void remove_quietly(const std::string& path)
{
    std::error_code ignored;
    std::filesystem::remove(path, ignored);
}

}  // namespace

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& write)
{
    const std::string temporary = temporary_name(path);
    {
        // a large stream buffer: the writers hand over megabyte chunks anyway
        auto buffer = std::make_unique<char[]>(1 << 20);
        std::ofstream out;
        out.rdbuf()->pubsetbuf(buffer.get(), 1 << 20);
        out.open(temporary, std::ios::binary | std::ios::trunc);
        if (!out)
            throw IoError(path + ": cannot create " + temporary + ": " + std::strerror(errno));
        try
        {
            write(out);
            out.flush();
            if (!out) throw IoError(path + ": write failed: " + std::strerror(errno));
            out.close();
            if (out.fail()) throw IoError(path + ": closing failed: " + std::strerror(errno));
        }
        catch (...)
        {
            out.close();
            remove_quietly(temporary);
            throw;
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error)
    {
        remove_quietly(temporary);
        throw IoError(path + ": cannot rename " + temporary + ": " + error.message());
    }
}

}  // namespace hdimesh

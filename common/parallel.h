#pragma once
// A deterministic parallel for: work is cut into chunks whose bounds depend only on the item
// count (a fixed chunk size), and per-chunk results are combined in chunk order, so a result is
// the same bits for any thread count. std::thread, not OpenMP: GCC's libgomp is not built for
// ThreadSanitizer and reports false races.

#include <algorithm>
#include <condition_variable>
#include <cstddef>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace hdimesh
{

/// Items per chunk: set by the work, never by the thread count.
constexpr std::size_t parallel_chunk_size = 512;

/// A pool of threads, created once per run; the calling thread works too. One thread: every
/// call runs inline, no thread is started.
class Workers
{
public:
    /// \pre threads >= 1
    explicit Workers(int threads = 1);
    ~Workers();
    Workers(const Workers&) = delete;
    Workers& operator=(const Workers&) = delete;

    int threads() const { return threads_; }

    /// Calls task(c) once for each c in [0, chunks), in any order and on any thread, and
    /// returns when all are done. An exception is rethrown on the caller: the lowest chunk's,
    /// so which one a run reports does not depend on the thread count.
    void run(std::size_t chunks, const std::function<void(std::size_t)>& task);

private:
    void work_loop();
    void take_chunks();

    int threads_ = 1;
    std::vector<std::thread> pool_;
    std::mutex mutex_;
    std::condition_variable wake_, done_;
    const std::function<void(std::size_t)>* task_ = nullptr;
    std::size_t chunks_ = 0, next_ = 0, finished_ = 0;
    std::size_t generation_ = 0;
    bool stop_ = false;
    std::size_t failed_chunk_ = 0;
    std::exception_ptr failure_;
};

/// The cores present (std::thread::hardware_concurrency), at least 1.
int default_thread_count();

/// Chunks of count items at chunk items each.
inline std::size_t chunk_count(std::size_t count, std::size_t chunk = parallel_chunk_size)
{
    return (count + chunk - 1) / chunk;
}

/// body(begin, end) over [0, count) cut into chunks of `chunk` items. body must only write
/// what its own items own (e.g. out[i] for i in [begin, end)). workers null: inline.
template <class Body>
void parallel_for(Workers* workers, std::size_t count, Body&& body,
                  std::size_t chunk = parallel_chunk_size)
{
    const std::size_t chunks = chunk_count(count, chunk);
    auto run_chunk = [&](std::size_t c) { body(c * chunk, std::min(count, (c + 1) * chunk)); };
    if (!workers || workers->threads() == 1 || chunks <= 1)
    {
        for (std::size_t c = 0; c < chunks; ++c) run_chunk(c);
        return;
    }
    workers->run(chunks, run_chunk);
}

/// map(begin, end) -> T per chunk, folded left to right in chunk order from init with
/// combine(T, T) -> T: the same bits for any thread count, floating point included.
template <class T, class Map, class Combine>
T parallel_reduce(Workers* workers, std::size_t count, T init, Map&& map, Combine&& combine,
                  std::size_t chunk = parallel_chunk_size)
{
    std::vector<T> partial(chunk_count(count, chunk), init);
    parallel_for(
        workers, partial.size(),
        [&](std::size_t first, std::size_t last) {
            for (std::size_t c = first; c < last; ++c)
                partial[c] = map(c * chunk, std::min(count, (c + 1) * chunk));
        },
        1);
    T result = init;
    for (auto& value : partial) result = combine(result, value);
    return result;
}

}  // namespace hdimesh

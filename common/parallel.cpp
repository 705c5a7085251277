#include "common/parallel.h"

#include <cassert>
#include <exception>

namespace hdimesh
{

int default_thread_count() { return std::max(1u, std::thread::hardware_concurrency()); }

Workers::Workers(int threads) : threads_(std::max(1, threads))
{
    for (int t = 1; t < threads_; ++t) pool_.emplace_back([this] { work_loop(); });
}

Workers::~Workers()
{
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    for (auto& thread : pool_) thread.join();
}

void Workers::take_chunks()
{
    // chunks are claimed under the lock: a few per thousand items, the lock is not the cost
    for (;;)
    {
        std::size_t c;
        const std::function<void(std::size_t)>* task;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (next_ >= chunks_) return;
            c = next_++;
            task = task_;
        }
        std::exception_ptr error;
        try
        {
            (*task)(c);
        }
        catch (...)
        {
            error = std::current_exception();
        }
        std::lock_guard<std::mutex> lock(mutex_);
        if (error && (!failure_ || c < failed_chunk_))
        {
            failure_ = error;
            failed_chunk_ = c;
        }
        if (++finished_ == chunks_) done_.notify_all();
    }
}

void Workers::work_loop()
{
    std::size_t seen = 0;
    for (;;)
    {
        {
            std::unique_lock<std::mutex> lock(mutex_);
            wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
            if (stop_) return;
            seen = generation_;
        }
        take_chunks();
    }
}

void Workers::run(std::size_t chunks, const std::function<void(std::size_t)>& task)
{
    if (chunks == 0) return;
    if (pool_.empty())
    {
        for (std::size_t c = 0; c < chunks; ++c) task(c);
        return;
    }
    {
        std::lock_guard<std::mutex> lock(mutex_);
        assert(!task_ && "Workers::run is not reentrant");
        task_ = &task;
        chunks_ = chunks;
        next_ = finished_ = 0;
        failure_ = nullptr;
        ++generation_;
    }
    wake_.notify_all();
    take_chunks();
    std::exception_ptr failure;
    {
        std::unique_lock<std::mutex> lock(mutex_);
        done_.wait(lock, [&] { return finished_ == chunks_; });
        task_ = nullptr;
        failure = failure_;
        failure_ = nullptr;
    }
    if (failure) std::rethrow_exception(failure);
}

}  // namespace hdimesh

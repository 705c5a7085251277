#pragma once
// Wall and thread-CPU time of a stage: the CPU time of the calling thread is the figure of
// record (the machine may be shared), the wall time is printed beside it.

#include <chrono>

namespace hdimesh
{

/// CPU seconds the calling thread has used since it started.
double thread_cpu_seconds();

/// Wall time since construction (or the last restart()): no system call, so it can time the
/// operators inside a per-element loop.
class WallStopwatch
{
public:
    WallStopwatch() { restart(); }
    void restart() { start_ = Clock::now(); }
    double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

private:
    using Clock = std::chrono::steady_clock;
    Clock::time_point start_;
};

/// A running clock of both times since construction (or the last restart()).
class Stopwatch
{
public:
    Stopwatch() { restart(); }
    void restart()
    {
        wall_.restart();
        cpu_start_ = thread_cpu_seconds();
    }
    double wall_seconds() const { return wall_.seconds(); }
    double cpu_seconds() const { return thread_cpu_seconds() - cpu_start_; }

private:
    WallStopwatch wall_;
    double cpu_start_ = 0.0;
};

/// Adds the wall and CPU time of its own lifetime to two report fields when it goes.
class StageTimer
{
public:
    StageTimer(double& wall, double& cpu) : wall_(wall), cpu_(cpu) {}
    ~StageTimer()
    {
        wall_ += clock_.wall_seconds();
        cpu_ += clock_.cpu_seconds();
    }
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;

private:
    double& wall_;
    double& cpu_;
    Stopwatch clock_;
};

}  // namespace hdimesh

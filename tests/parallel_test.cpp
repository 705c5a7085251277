// The deterministic parallel for (common/parallel.h): chunk bounds set by the item count, results
// combined in chunk order, so 1, 2, 3 and 8 threads give the same bits.

#include "common/parallel.h"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <vector>

using namespace hdimesh;

namespace
{
// a sum whose rounding depends on the order of the additions: equal bits mean equal order
double order_sensitive_sum(Workers& workers, std::size_t count)
{
    return parallel_reduce(
        &workers, count, 0.0,
        [](std::size_t begin, std::size_t end) {
            double sum = 0;
            for (std::size_t i = begin; i < end; ++i) sum += std::sin(double(i)) * 1e-3 + 1e7;
            return sum;
        },
        [](double a, double b) { return a + b; }, 97);
}
}  // namespace

TEST_CASE("parallel_for and parallel_reduce: identical results for 1, 2, 3 and 8 threads")
{
    const std::size_t count = 100003;  // not a multiple of any chunk size
    std::vector<double> reference_items;
    double reference_sum = 0;
    for (int threads : {1, 2, 3, 8})
    {
        Workers workers(threads);
        CHECK(workers.threads() == threads);
        std::vector<double> items(count, -1.0);
        parallel_for(&workers, count, [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) items[i] = std::sqrt(double(i)) / 3.0;
        });
        // the pool is reused: a second and third round on the same workers
        double sum = 0;
        for (int round = 0; round < 3; ++round) sum = order_sensitive_sum(workers, count);
        if (threads == 1)
        {
            reference_items = items;
            reference_sum = sum;
            continue;
        }
        CHECK(std::memcmp(items.data(), reference_items.data(), count * sizeof(double)) == 0);
        CHECK(std::memcmp(&sum, &reference_sum, sizeof(double)) == 0);
    }
}

TEST_CASE("parallel_for: empty, one item, null workers")
{
    Workers workers(3);
    int calls = 0;
    parallel_for(&workers, 0, [&](std::size_t, std::size_t) { ++calls; });
    CHECK(calls == 0);
    parallel_for(nullptr, 1, [&](std::size_t b, std::size_t e) { calls += int(e - b); });
    CHECK(calls == 1);
    CHECK(default_thread_count() >= 1);
}

TEST_CASE("parallel_for: the lowest chunk's exception reaches the caller, for any thread count")
{
    for (int threads : {1, 2, 3, 8})
    {
        Workers workers(threads);
        std::string message;
        try
        {
            parallel_for(
                &workers, 1000,
                [](std::size_t begin, std::size_t) {
                    if (begin >= 300) throw std::runtime_error("chunk " + std::to_string(begin));
                },
                100);
        }
        catch (const std::runtime_error& e)
        {
            message = e.what();
        }
        CHECK(message == "chunk 300");
        // the pool still works after a failure
        std::vector<int> out(10, 0);
        parallel_for(
            &workers, 10,
            [&](std::size_t b, std::size_t e) {
                for (auto i = b; i < e; ++i) out[i] = 1;
            },
            3);
        CHECK(out == std::vector<int>(10, 1));
    }
}

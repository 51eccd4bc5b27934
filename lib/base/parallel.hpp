// A minimal work-sharing loop: `jobs` threads take indices in order until none are left.
// Results go to per-index slots, so output order never depends on scheduling.
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <thread>
#include <vector>

namespace mf {

// Calls fn(i) for every i in [0, n) on min(jobs, n) threads (jobs <= 0: all cores).
// fn must not throw.
template <class F>
void parallel_for(size_t n, int jobs, F&& fn) {
    const size_t hw = std::max(1u, std::thread::hardware_concurrency());
    const size_t threads = std::min<size_t>(jobs > 0 ? static_cast<size_t>(jobs) : hw, std::max<size_t>(1, n));
    std::atomic<size_t> next{0};
    auto worker = [&] {
        for (size_t i = next++; i < n; i = next++) fn(i);
    };
    std::vector<std::thread> pool;
    for (size_t t = 1; t < threads; ++t) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
}

// As parallel_for on two threads, the second joining only while `spare()` holds (a core of the
// batch is idle: the batch's tail, a set alone). It looks every millisecond until every index is
// handed out, so a stage that began while the batch was busy still gets the core freed midway.
// fn must not throw; spare() is called from the second thread.
template <class S, class F>
void parallel_for_spare(size_t n, S&& spare, F&& fn) {
    std::atomic<size_t> next{0};
    auto worker = [&] {
        for (size_t i = next++; i < n; i = next++) fn(i);
    };
    if (n < 2) {
        worker();
        return;
    }
    std::thread helper([&] {
        while (next.load() < n) {
            if (spare()) {
                worker();
                return;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(1));
        }
    });
    worker();
    helper.join();
}

}  // namespace mf

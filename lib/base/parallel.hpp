// A minimal work-sharing loop: `jobs` threads take indices in order until none are left.
// Results go to per-index slots, so output order never depends on scheduling.
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <queue>
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

// As parallel_for, for an fn that may throw: every index still runs, then the exception of the
// lowest index that threw is rethrown (the others are dropped).
template <class F>
void parallel_for_rethrow(size_t n, int jobs, F&& fn) {
    std::vector<std::exception_ptr> failed(n);
    parallel_for(n, jobs, [&](size_t i) {
        try {
            fn(i);
        } catch (...) {
            failed[i] = std::current_exception();
        }
    });
    for (const std::exception_ptr& e : failed)
        if (e) std::rethrow_exception(e);
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

// Tasks posted by one owner thread as it makes them, run largest first by the owner (run()) and
// by one more thread while `spare()` holds (a core of the batch is idle): parallel_for_spare over
// a list that grows while it runs (ingest: a set's outputs of every preset, posted as each
// preset's planes are made, so no preset waits for the one before). The helper sleeps while
// nothing is queued and looks every millisecond while tasks wait and no core is spare. A task
// must not throw; tasks of equal cost run in the order posted.
class SpareTasks {
public:
    explicit SpareTasks(std::function<bool()> spare) : spare_(std::move(spare)) {}
    ~SpareTasks() { run(); }
    SpareTasks(const SpareTasks&) = delete;
    SpareTasks& operator=(const SpareTasks&) = delete;

    void post(uint64_t cost, std::function<void()> task) {
        {
            std::lock_guard lock(mutex_);
            queue_.push(Task{cost, posted_++, std::move(task)});
            if (!helper_.joinable() && spare_) helper_ = std::thread([this] { help(); });
        }
        changed_.notify_all();
    }

    // Runs tasks on this thread until none is queued, then waits for the helper's; every task
    // posted before is done when it returns. Tasks may be posted again afterwards.
    void run() {
        while (take_and_run()) {
        }
        {
            std::unique_lock lock(mutex_);
            changed_.wait(lock, [&] { return running_ == 0; });
            closed_ = true;
        }
        changed_.notify_all();
        if (helper_.joinable()) helper_.join();
        std::lock_guard lock(mutex_);
        closed_ = false;
    }

private:
    struct Task {
        uint64_t cost;
        uint64_t order;
        std::function<void()> fn;
        bool operator<(const Task& o) const { return cost != o.cost ? cost < o.cost : order > o.order; }
    };
    // Takes the largest task and runs it; false when none is queued.
    bool take_and_run() {
        std::function<void()> fn;
        {
            std::lock_guard lock(mutex_);
            if (queue_.empty()) return false;
            fn = std::move(const_cast<Task&>(queue_.top()).fn);  // popped next: its function may go
            queue_.pop();
            ++running_;
        }
        fn();
        {
            std::lock_guard lock(mutex_);
            --running_;
        }
        changed_.notify_all();
        return true;
    }
    void help() {
        std::unique_lock lock(mutex_);
        while (!closed_) {
            if (queue_.empty()) {
                changed_.wait(lock);
                continue;
            }
            lock.unlock();
            const bool spare = spare_();
            if (!spare || !take_and_run()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
            lock.lock();
        }
    }

    std::function<bool()> spare_;
    std::mutex mutex_;
    std::condition_variable changed_;
    std::priority_queue<Task> queue_;
    uint64_t posted_ = 0;
    int running_ = 0;
    bool closed_ = false;
    std::thread helper_;
};

}  // namespace mf

// A byte budget shared by worker threads: caps the decoded pixels in flight, so peak memory
// stays bounded however many sets a batch holds. A request larger than the whole budget is
// granted when nothing else is held (one huge set still runs, alone).
#pragma once
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>

namespace mf {

class MemoryBudget {
public:
    explicit MemoryBudget(uint64_t capacity) : capacity_(capacity) {}

    void acquire(uint64_t bytes) {
        std::unique_lock lock(mutex_);
        const auto fits = [&] { return used_ == 0 || used_ + bytes <= capacity_; };
        if (!fits()) {
            ++waiting_;
            freed_.wait(lock, fits);
            --waiting_;
        }
        used_ += bytes;
    }
    void release(uint64_t bytes) {
        {
            std::lock_guard lock(mutex_);
            used_ -= bytes;
        }
        freed_.notify_all();
    }
    uint64_t capacity() const { return capacity_; }
    // Threads waiting in acquire() now: workers whose cores are idle (ingest lends them to the
    // sets running: process/ingest.cpp).
    int waiting() const { return waiting_.load(); }

private:
    uint64_t capacity_;
    uint64_t used_ = 0;
    std::atomic<int> waiting_{0};
    std::mutex mutex_;
    std::condition_variable freed_;
};

// RAII holder of a share of a budget.
class BudgetLease {
public:
    BudgetLease(MemoryBudget* budget, uint64_t bytes) : budget_(budget), bytes_(bytes) {
        if (budget_) budget_->acquire(bytes_);
    }
    ~BudgetLease() {
        if (budget_) budget_->release(bytes_);
    }
    BudgetLease(const BudgetLease&) = delete;
    BudgetLease& operator=(const BudgetLease&) = delete;

private:
    MemoryBudget* budget_;
    uint64_t bytes_;
};

}  // namespace mf

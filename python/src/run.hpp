// How a call from Python runs the library: the GIL released for the whole run, which goes on a
// thread of its own while the calling thread watches for a stop (a Cancel token, a progress
// callback returning False or raising, Ctrl-C in the interpreter) and asks the library to stop
// the way a signal does (base/interrupt.hpp): the run ends cleanly, as `matforge ingest` does
// on SIGINT (no temporary left, no manifest written).
#pragma once
#include <pybind11/pybind11.h>

#include <atomic>
#include <condition_variable>
#include <csignal>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "base/interrupt.hpp"

namespace mfpy {

namespace py = pybind11;

// The exceptions matforge raises (python/matforge/_errors.py): `kind` names the class, `code`
// the finding code or the kind of failure it carries.
struct Failure : std::exception {
    std::string kind, code, message;
    Failure(std::string k, std::string c, std::string m)
        : kind(std::move(k)), code(std::move(c)), message(std::move(m)) {}
    const char* what() const noexcept override { return message.c_str(); }
};

// matforge.Cancel: a token any thread may set; a run given it stops at its next set (at once
// while the run is going: it asks the library itself; before, the run stops at its start).
class Cancel {
public:
    void cancel() {
        flag_.store(true);
        if (active_.load()) mf::g_stop_signal.store(SIGINT, std::memory_order_relaxed);
    }
    bool cancelled() const { return flag_.load(); }
    void set_active(bool a) {
        active_.store(a);
        if (a && flag_.load()) mf::g_stop_signal.store(SIGINT, std::memory_order_relaxed);
    }

private:
    std::atomic<bool> flag_{false}, active_{false};
};

// One run's watch: why it was asked to stop, and the Python error to raise after it.
class Watch {
public:
    Watch(py::object progress, std::shared_ptr<Cancel> token)
        : progress_(std::move(progress)), token_(std::move(token)) {}
    Watch(const Watch&) = delete;
    Watch& operator=(const Watch&) = delete;
    ~Watch() {
        if (error_) {  // never raised (the run failed first): dropped under the GIL
            py::gil_scoped_acquire gil;
            error_.reset();
        }
    }

    // The library's progress hook (from its worker threads, serialized by the library): the
    // GIL is taken only here. False from the callback cancels; an exception stops the run and
    // is raised when it has ended.
    void report(size_t done, size_t total, const std::string& name) {
        if (progress_.is_none() || stopped()) return;
        py::gil_scoped_acquire gil;
        in_callback() = true;
        try {
            const py::object r = progress_(done, total, name);
            if (r.is(py::bool_(false))) stop();
        } catch (py::error_already_set& e) {
            keep(std::move(e));
        }
        in_callback() = false;
    }

    // The calling thread, about every 50 ms with the GIL: Ctrl-C (Python's own handler marked
    // it; only the main thread runs it), and the token.
    void poll() {
        if (token_ && token_->cancelled()) stop();
        if (PyErr_CheckSignals() != 0) keep(py::error_already_set());
    }

    bool stopped() const { return stopped_.load() || (token_ && token_->cancelled()); }
    Cancel* token() const { return token_.get(); }
    // Raises what stopped the run, if anything did: the Python error (a callback's, or
    // KeyboardInterrupt), else matforge.Cancelled when the library says it ended early.
    void raise_if_stopped(bool ended_early) {
        if (error_) {
            error_->restore();
            error_.reset();
            throw py::error_already_set();
        }
        if (stopped() && ended_early)
            throw Failure("Cancelled", "INTERRUPTED",
                          "cancelled before the end; nothing is torn: run it again to finish");
    }

    // True while a progress callback runs on this thread: matforge cannot be called from there
    // (the run holds the one-run lock).
    static bool& in_callback() {
        thread_local bool inside = false;
        return inside;
    }
    // The one stop flag the library polls is the process's: one run at a time.
    static std::mutex& one_run() {
        static std::mutex m;
        return m;
    }

private:
    void stop() {
        stopped_.store(true);
        mf::g_stop_signal.store(SIGINT, std::memory_order_relaxed);
    }
    void keep(py::error_already_set&& e) {
        if (!error_) error_ = std::make_unique<py::error_already_set>(std::move(e));
        stop();
    }

    py::object progress_;
    std::shared_ptr<Cancel> token_;
    std::unique_ptr<py::error_already_set> error_;
    std::atomic<bool> stopped_{false};
};

// Runs `work` (library calls only, no Python) with the GIL released, on a thread of its own,
// `watch` polled meanwhile; called with the GIL held. Library exceptions come back as they were.
template <class Work>
void run_watched(Watch& watch, Work&& work) {
    if (Watch::in_callback())
        throw Failure("UsageError", "usage", "matforge cannot be called from a progress callback");
    std::exception_ptr failure;
    {
        py::gil_scoped_release nogil;
        const std::lock_guard run(Watch::one_run());
        mf::g_stop_signal.store(0);
        if (Cancel* token = watch.token()) token->set_active(true);
        std::mutex m;
        std::condition_variable cv;
        bool finished = false;
        std::thread worker([&] {
            try {
                work();
            } catch (...) {
                failure = std::current_exception();
            }
            const std::lock_guard lock(m);
            finished = true;
            cv.notify_all();
        });
        std::unique_lock lock(m);
        while (!cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return finished; })) {
            lock.unlock();
            {
                py::gil_scoped_acquire gil;
                watch.poll();
            }
            lock.lock();
        }
        lock.unlock();
        worker.join();
        if (Cancel* token = watch.token()) token->set_active(false);
        mf::g_stop_signal.store(0);
    }
    if (failure) std::rethrow_exception(failure);
}

}  // namespace mfpy

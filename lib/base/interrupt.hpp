// A request to stop, from a signal: the command's handler stores the signal number (SIGINT,
// SIGTERM) and long loops poll it, so a run ends cleanly (no temporary left, no manifest
// describing files it replaced) instead of dying mid-write. 0 while nothing asked to stop.
#pragma once
#include <atomic>

namespace mf {

// Lock-free (checked by a static_assert), so a signal handler may store to it.
inline std::atomic<int> g_stop_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

inline bool stop_requested() { return g_stop_signal.load(std::memory_order_relaxed) != 0; }

}  // namespace mf

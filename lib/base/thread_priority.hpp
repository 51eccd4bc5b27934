// The calling thread's scheduling weight, lowered for background work that others wait on less
// than it waits on them.
#pragma once

#if defined(__linux__)
#include <sys/resource.h>
#include <unistd.h>

#include <cerrno>
#endif

namespace mf {

// Raises the calling thread's nice value by `steps` (Linux schedules threads as tasks, each with
// its own nice value; raising it needs no privilege). A thread at nice 5 weighs about a third of
// one at 0 (the kernel's weight table: 335 against 1024), so threads at 0 that wake up get a core
// at once. Does nothing elsewhere, or when the value cannot be read or set.
inline void lower_this_thread_priority(int steps) {
#if defined(__linux__)
    const auto tid = static_cast<id_t>(::gettid());
    errno = 0;
    const int now = ::getpriority(PRIO_PROCESS, tid);
    if (now == -1 && errno != 0) return;
    ::setpriority(PRIO_PROCESS, tid, now + steps);
#else
    (void)steps;
#endif
}

}  // namespace mf

// Wall-clock seconds on the steady clock, for the timings a command reports about itself
// (`preview --timings`, render::Renderer::host_times): never for a decision or an output.
#pragma once
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>

#if defined(__linux__)
#include <unistd.h>
#endif

namespace mf {

class Stopwatch {
public:
    // Seconds since construction (or the last lap), and starts the next lap.
    double lap() {
        const auto now = std::chrono::steady_clock::now();
        const double s = std::chrono::duration<double>(now - last_).count();
        last_ = now;
        return s;
    }
    // Seconds since construction (or the last lap); the lap goes on.
    double elapsed() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - last_).count(); }

private:
    std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// Seconds since this process was started (exec: the dynamic loader's work included), to within
// the kernel's clock tick (10 ms): /proc/self/stat's start time against CLOCK_BOOTTIME, its
// clock. -1 where that is not known (not Linux, /proc not mounted).
inline double seconds_since_process_start() {
#if defined(__linux__)
    std::FILE* f = std::fopen("/proc/self/stat", "r");
    if (!f) return -1.0;
    char buf[1024];
    const size_t n = std::fread(buf, 1, sizeof buf - 1, f);
    std::fclose(f);
    buf[n] = '\0';
    // Field 22 (starttime), counted after the command name's closing parenthesis (the name may
    // hold spaces and parentheses of its own).
    const char* p = nullptr;
    for (const char* c = buf; *c; ++c)
        if (*c == ')') p = c;
    if (!p) return -1.0;
    // Fields 3 (state) to 22, each after one space: the 20th is starttime, in clock ticks.
    for (int field = 3; field <= 22 && p; ++field) p = std::strchr(p + 1, ' ');
    if (!p) return -1.0;
    char* end = nullptr;
    const unsigned long long ticks = std::strtoull(p + 1, &end, 10);
    if (end == p + 1) return -1.0;
    timespec now{};
    const long hz = ::sysconf(_SC_CLK_TCK);
    if (hz <= 0 || ::clock_gettime(CLOCK_BOOTTIME, &now) != 0) return -1.0;
    return static_cast<double>(now.tv_sec) + static_cast<double>(now.tv_nsec) * 1e-9 -
           static_cast<double>(ticks) / static_cast<double>(hz);
#else
    return -1.0;
#endif
}

}  // namespace mf

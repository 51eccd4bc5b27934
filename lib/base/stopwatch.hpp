// Wall-clock seconds on the steady clock, for the timings a command reports about itself
// (`preview --timings`, render::Renderer::host_times): never for a decision or an output.
#pragma once
#include <chrono>

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

}  // namespace mf

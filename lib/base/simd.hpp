// Fixed-width lanes for the statistics loops (validate/): GCC/Clang vector types, SSE on x86-64,
// NEON on ARM. A loop written in these lanes computes the same figures on every machine: the
// lane count is fixed here, not by the compiler or the CPU, and double sums are added lane by
// lane, then the lanes in order (Sum4::total), so no figure depends on how a loop is compiled.
// No fused multiply-add is asked for (x86-64's baseline has none).
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#if defined(__SSE__)
#include <immintrin.h>
#endif

namespace mf::simd {

using F4 = float __attribute__((vector_size(16)));
using I4 = int32_t __attribute__((vector_size(16)));  // what comparing F4s gives: -1 true, 0 false
using D2 = double __attribute__((vector_size(16)));

inline F4 sqrt4(F4 v) {
#if defined(__SSE__)
    return _mm_sqrt_ps(v);  // correctly rounded, as std::sqrt is
#else
    for (int l = 0; l < 4; ++l) v[l] = std::sqrt(v[l]);
    return v;
#endif
}
inline F4 abs4(F4 v) { return std::bit_cast<F4>(std::bit_cast<I4>(v) & 0x7fffffff); }
// std::max(a, b) lane by lane: (a < b) ? b : a (a NaN b gives a).
inline F4 max4(F4 a, F4 b) { return a < b ? b : a; }
// v where mask is true, else +0.
inline F4 keep(F4 v, I4 mask) { return std::bit_cast<F4>(std::bit_cast<I4>(v) & mask); }
inline I4 finite4(F4 v) { return v - v == F4{}; }  // Inf - Inf and NaN - NaN are NaN
inline F4 load4(const float* p) {
    F4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}
inline D2 low2d(F4 v) { return __builtin_convertvector(__builtin_shufflevector(v, v, 0, 1), D2); }
inline D2 high2d(F4 v) { return __builtin_convertvector(__builtin_shufflevector(v, v, 2, 3), D2); }

// A double sum of four float lanes.
struct Sum4 {
    D2 lo{}, hi{};
    void add(F4 v) {
        lo += low2d(v);
        hi += high2d(v);
    }
    void add_squares(F4 v) {  // each lane's square, in double
        const D2 l = low2d(v), h = high2d(v);
        lo += l * l;
        hi += h * h;
    }
    double total() const { return lo[0] + lo[1] + hi[0] + hi[1]; }
};

// How many lanes a sum of comparison masks counted (each true lane added -1).
inline long long count(I4 masks) { return -(static_cast<long long>(masks[0]) + masks[1] + masks[2] + masks[3]); }

}  // namespace mf::simd

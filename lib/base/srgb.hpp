// The exact sRGB transfer functions of IEC 61966-2-1:1999 (the oracle for every approximation).
#pragma once
#include <cmath>

namespace mf {

// Decoding: encoded value in [0,1] -> linear light. Linear segment below 0.04045 (IEC 61966-2-1
// §5.2; the 0.04045/12.92 pair is the standard's, not the 0.03928 of older drafts).
// Values outside [0,1] extend the curve symmetrically; NaN passes through.
template <class T>
T srgb_to_linear(T v) {
    const T a = std::abs(v);
    const T r = a <= T(0.04045) ? a / T(12.92) : std::pow((a + T(0.055)) / T(1.055), T(2.4));
    return std::copysign(r, v);
}

// Encoding: linear light -> encoded value (inverse of the above).
template <class T>
T linear_to_srgb(T v) {
    const T a = std::abs(v);
    const T r = a <= T(0.0031308) ? a * T(12.92) : T(1.055) * std::pow(a, T(1) / T(2.4)) - T(0.055);
    return std::copysign(r, v);
}

}  // namespace mf

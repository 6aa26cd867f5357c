#pragma once
// Uniforms that a choice leaves over: once a uniform u in [0, 1) has picked a share of [0, 1),
// what lies within the share, stretched back onto [0, 1), is a fresh uniform. Rounding can carry
// it to 1, which every draw after it must not see.

#include <algorithm>

namespace tracer {

/// The largest double below one.
inline constexpr double kBelowOne = 0x1.fffffffffffffp-1;

/// u kept below one.
inline double below_one(double u) { return std::min(u, kBelowOne); }
/// u as a float below one.
inline float below_one_float(double u) { return std::min(float(u), 0x1.fffffep-1f); }

}  // namespace tracer

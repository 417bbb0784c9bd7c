#pragma once
// Tests that compare two paths through the same arithmetic bit for bit (a sweep against the single-ray tracer,
// a guided walk against a plain one) are built a second time with multiply-adds fused: test_*_fused.cpp defines
// SSS_TEST_FUSED and includes the test, and the build compiles it at -O3 with -ffp-contract=fast (-mfma on
// x86). A compiler may then fuse the same expression differently where it is inlined into different code, so
// the two paths agree only to rounding: such a test compares to a tolerance there, while every hit found by one
// path must still be found by the other. On an x86 processor without FMA the fused build skips itself (exit
// code 77, which CTest and Meson count as skipped) before any test runs.

#include <cmath>
#include <cstdlib>
#include <limits>

#include "sss/core/types.hpp"

namespace sss_test {

#ifdef SSS_TEST_FUSED
inline constexpr bool fused = true;
#else
inline constexpr bool fused = false;
#endif

// How many units in the last place two paths may differ by in a fused build, relative to the quantity's scale.
inline constexpr double fused_ulps = 64;

// a == b where nothing is fused; otherwise |a - b| <= fused_ulps epsilons of `scale` (in the type of a and b).
template <class T> bool same_to_rounding(T a, T b, double scale) {
    if constexpr (!fused) return a == b;
    return std::abs(double(a) - double(b)) <= fused_ulps * double(std::numeric_limits<T>::epsilon()) * scale;
}

// The same for each component of a vector, with one scale for all three.
template <class T> bool same_to_rounding(const sss::vec3<T>& a, const sss::vec3<T>& b, double scale) {
    return same_to_rounding(a.x, b.x, scale) && same_to_rounding(a.y, b.y, scale) &&
           same_to_rounding(a.z, b.z, scale);
}

} // namespace sss_test

#if defined(SSS_TEST_FUSED) && (defined(__GNUC__) || defined(__clang__)) && (defined(__x86_64__) || defined(__i386__))
namespace {
[[maybe_unused]] const bool sss_test_fma_checked = [] {
    __builtin_cpu_init();
    if (!__builtin_cpu_supports("fma")) std::exit(77);
    return true;
}();
} // namespace
#endif

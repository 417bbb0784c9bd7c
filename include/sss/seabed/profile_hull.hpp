#pragma once
/// \file
/// Two tools over a seabed profile (s_m[i], z_m[i]) sampled along a line, used to rest rigid targets on a
/// seabed (seabed/targets.hpp):
/// - `disc_rest_heights`: where the centre of a disc of radius r resting on the profile lies (the profile
///   dilated by the disc): c_i = max over |s_j - s_i| <= r of z_j + sqrt(r^2 - (s_j - s_i)^2);
/// - `taut_string`: the string pulled taut over a profile from its first to its last sample, i.e. its upper
///   convex hull, which follows the profile over crests and bridges every hollow in a straight line. From
///   each support the string goes to the sample within reach `max_span_m` that it meets at the steepest
///   upward (least downward) slope, the farthest of equals; with unlimited reach this is the gift-wrapping
///   construction of the upper hull (Jarvis, 1973, Information Processing Letters 2(1) 18-21), computed in
///   linear time by the monotone chain (Andrew, 1979, Information Processing Letters 9(5) 216-219). With a
///   finite reach a hollow wider than the reach is not bridged whole: the string comes down into it.
///   Every chord lies on or above every sample it passes (each sample within reach has a lower slope).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <vector>

#include "sss/core/types.hpp"

namespace sss::seabed {

/// Lowest heights (m) of the centre of a disc of radius r resting on the profile (s_m[i], z_m[i]), at each s_m[i]
/// (see the file comment). s_m ascending.
template <Real T>
[[nodiscard]] std::vector<T> disc_rest_heights(std::span<const T> s_m, std::span<const T> z_m, T radius_m) {
    std::vector<T> c(s_m.size());
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 0; i < s_m.size(); ++i) {
        while (s_m[i] - s_m[lo] > radius_m) ++lo;
        while (hi + 1 < s_m.size() && s_m[hi + 1] - s_m[i] <= radius_m) ++hi;
        T best = -std::numeric_limits<T>::infinity();
        for (std::size_t j = lo; j <= hi; ++j) {
            const T d = s_m[j] - s_m[i];
            best = std::max(best, z_m[j] + std::sqrt(std::max(T(0), radius_m * radius_m - d * d)));
        }
        c[i] = best;
    }
    return c;
}

/// Indices of the supports of the taut string over the profile (s_m[i], z_m[i]) (see the file comment):
/// ascending, first 0, last size - 1; no support is collinear with its neighbours. s_m strictly ascending.
template <Real T>
[[nodiscard]] std::vector<std::size_t> taut_string(std::span<const T> s_m, std::span<const T> z_m,
                                                   T max_span_m = std::numeric_limits<T>::infinity()) {
    const std::size_t n = s_m.size();
    std::vector<std::size_t> v;
    if (n == 0) return v;
    // > 0 when b lies below the chord from a to c, 0 on it, < 0 above it.
    auto turn = [&](std::size_t a, std::size_t b, std::size_t c) {
        return (double(s_m[b]) - double(s_m[a])) * (double(z_m[c]) - double(z_m[a])) -
               (double(z_m[b]) - double(z_m[a])) * (double(s_m[c]) - double(s_m[a]));
    };
    auto not_above = [&](std::size_t a, std::size_t b, std::size_t c) { return turn(a, b, c) >= 0.0; };
    if (!(s_m[n - 1] - s_m[0] > max_span_m)) { // unlimited reach: the upper hull by the monotone chain
        for (std::size_t i = 0; i < n; ++i) {
            while (v.size() >= 2 && not_above(v[v.size() - 2], v.back(), i)) v.pop_back();
            v.push_back(i);
        }
        return v;
    }
    v.push_back(0);
    std::size_t i = 0;
    while (i + 1 < n) {
        std::size_t best = i + 1;
        for (std::size_t j = i + 2; j < n && s_m[j] - s_m[i] <= max_span_m; ++j)
            if (not_above(i, best, j)) best = j; // j at least as steep as best: take the farther
        // A support exactly collinear with its neighbours is dropped when the chord stays within reach.
        if (v.size() >= 2 && turn(v[v.size() - 2], v.back(), best) == 0.0 && s_m[best] - s_m[v[v.size() - 2]] <= max_span_m)
            v.back() = best;
        else
            v.push_back(best);
        i = best;
    }
    return v;
}

} // namespace sss::seabed

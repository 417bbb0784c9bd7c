#pragma once
/// \file
/// Internal to beam/directivity.hpp: the inverses of sinc x and of the uniform array factor on their main lobe,
/// by which the lobe widths are found. Not part of the API.

#include <cmath>
#include <cstddef>
#include <limits>

#include "sss/beam/sinc.hpp"
#include "sss/core/constants.hpp"
#include "sss/core/types.hpp"

namespace sss::beam::detail {
/// The x in (0, pi) where sinc(x) = level, for a level in (0, 1): Newton from a bisection bracket.
template <Real T> [[nodiscard]] inline T sinc_inverse(T level) noexcept {
    T lo = 0, hi = pi_v<T>;
    for (int i = 0; i < 200 && hi - lo > T(4) * std::numeric_limits<T>::epsilon() * hi; ++i) {
        const T mid = (lo + hi) / T(2);
        (sinc(mid) > level ? lo : hi) = mid;
    }
    return (lo + hi) / T(2);
}
/// The delta in (0, pi/N) where sin(N delta)/(N sin delta) = level, level in (0, 1): bisection.
template <Real T> [[nodiscard]] inline T array_factor_inverse(std::size_t count, T level) noexcept {
    const T n = static_cast<T>(count);
    T lo = 0, hi = pi_v<T> / n;
    for (int i = 0; i < 200 && hi - lo > T(4) * std::numeric_limits<T>::epsilon() * hi; ++i) {
        const T mid = (lo + hi) / T(2);
        (sinc(n * mid) / sinc(mid) > level ? lo : hi) = mid;
    }
    return (lo + hi) / T(2);
}
/// 2 asin(s), or pi (the whole front half-space) when s >= 1.
template <Real T> [[nodiscard]] inline T full_width_from_sine(T s) noexcept {
    return s >= T(1) ? pi_v<T> : T(2) * std::asin(s);
}
} // namespace sss::beam::detail

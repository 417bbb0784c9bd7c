#pragma once
/// \file
/// sin(x)/x, the pattern of the uniform line aperture, accurate near x = 0, and the argument of its first
/// sidelobe. Part of beam/directivity.hpp, which includes it.

#include <cmath>

#include "sss/core/types.hpp"

namespace sss::beam {

/// First positive root of tan x = x: the argument of the first sidelobe of sin x / x.
template <Real T> inline constexpr T sinc_first_sidelobe_x_v = T(4.493409457909064175307880927276L);

/// sin(x)/x, exact 1 at x = 0 and accurate near it (Taylor series below |x| = 1e-2, where the series to x^6
/// has a relative error under 1e-17).
template <Real T> [[nodiscard]] inline T sinc(T x) noexcept {
    const T ax = std::abs(x);
    if (ax < T(1e-2)) {
        const T x2 = x * x;
        return T(1) - x2 / T(6) * (T(1) - x2 / T(20) * (T(1) - x2 / T(42)));
    }
    return std::sin(x) / x;
}

} // namespace sss::beam

#pragma once
/// \file
/// The ideal fan beam: uniform response inside an along-track width and a vertical width centred on a
/// depression (tilt) angle, nothing outside; the same fan on port and starboard.

#include <algorithm>

#include "sss/beam/concept.hpp"
#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"

namespace sss::beam {

template <Real T> struct ideal_fan_params {
    T along_width_deg = T(1);     ///< full along-track width (deg), in (0, 180)
    T vertical_width_deg = T(50); ///< full width in the tilted across-track plane (deg), in (0, 180]
    T depression_deg = T(20);     ///< depression of the fan's axis below horizontal (deg), in [-90, 90]
};

template <Real T> class ideal_fan {
public:
    using value_type = T;

    /// Parts of the fan beyond the vertical (depression above 90 deg) belong to the other side and are dropped.
    /// Default parameters (non-explicit, so `{}` builds one).
    ideal_fan() : ideal_fan(ideal_fan_params<T>{}) {}

    explicit ideal_fan(const ideal_fan_params<T>& p) : p_(p) {
        sss::require_finite(p.along_width_deg, "ideal_fan.along_width_deg");
        sss::require(p.along_width_deg > T(0) && p.along_width_deg < T(180), "ideal_fan.along_width_deg",
                        "must lie in (0, 180) degrees");
        sss::require_finite(p.vertical_width_deg, "ideal_fan.vertical_width_deg");
        sss::require(p.vertical_width_deg > T(0) && p.vertical_width_deg <= T(180), "ideal_fan.vertical_width_deg",
                        "must lie in (0, 180] degrees");
        sss::require_in_range(p.depression_deg, T(-90), T(90), "ideal_fan.depression_deg");
        const T half_along = deg_to_rad(p.along_width_deg) / T(2);
        const T lo = deg_to_rad(p.depression_deg - p.vertical_width_deg / T(2));
        const T hi = deg_to_rad(p.depression_deg + p.vertical_width_deg / T(2));
        extent_ = beam_extent<T>{-half_along, half_along, std::max(lo, -half_pi_v<T>), std::min(hi, half_pi_v<T>)};
    }

    [[nodiscard]] const ideal_fan_params<T>& params() const noexcept { return p_; }
    [[nodiscard]] beam_extent<T> extent(side) const noexcept { return extent_; }

    [[nodiscard]] T weight(side, T along_rad, T depression_rad) const noexcept {
        const bool inside = along_rad >= extent_.along_min_rad && along_rad <= extent_.along_max_rad &&
                            depression_rad >= extent_.depression_min_rad && depression_rad <= extent_.depression_max_rad;
        return inside ? T(1) : T(0);
    }

private:
    ideal_fan_params<T> p_;
    beam_extent<T> extent_{};
};

static_assert(Beam<ideal_fan<float>> && Beam<ideal_fan<double>>);

} // namespace sss::beam

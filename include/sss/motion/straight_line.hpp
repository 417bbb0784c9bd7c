#pragma once
/// \file
/// A towfish running a straight line at constant speed, heading and altitude, level.

#include <cmath>
#include <cstddef>

#include <string>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/motion/concept.hpp"
#include "sss/motion/detail/nominal_track.hpp"

namespace sss::motion {

template <Real T> struct straight_line_params {
    vec2<T> start_m{T(0), T(0)}; ///< world (x east, y north) position of ping 0 (m)
    T heading_deg = T(0);        ///< course, clockwise from north (deg)
    T speed_mps = T(2);          ///< speed over ground (m/s), >= 0
    T altitude_m = T(10);        ///< world z of the towfish (m): its altitude above a flat seabed at z = 0; > 0
    T ping_interval_s = T(0.1);  ///< time between pings (s), > 0
};

template <Real T> class straight_line {
public:
    using value_type = T;

    /// Default parameters (non-explicit, so `{}` builds one).
    straight_line() : straight_line(straight_line_params<T>{}) {}

    explicit straight_line(const straight_line_params<T>& p) : p_(p) {
        detail::validate_nominal_track(p, "straight_line");
        yaw_rad_ = deg_to_rad(p.heading_deg);
        rotation_ = body_to_world_rotation(T(0), T(0), yaw_rad_);
    }

    [[nodiscard]] const straight_line_params<T>& params() const noexcept { return p_; }

    [[nodiscard]] sss::pose<T> pose_at(std::size_t ping) const noexcept {
        const T t = static_cast<T>(ping) * p_.ping_interval_s;
        const T d = p_.speed_mps * t;
        const vec3<T> position{p_.start_m.x + d * std::sin(yaw_rad_), p_.start_m.y + d * std::cos(yaw_rad_), p_.altitude_m};
        return sss::pose<T>{t, position, T(0), T(0), yaw_rad_, rotation_};
    }

private:
    straight_line_params<T> p_;
    T yaw_rad_{};
    mat3<T> rotation_{T(1)};
};

static_assert(Motion<straight_line<float>> && Motion<straight_line<double>>);

} // namespace sss::motion

#pragma once
/// \file
/// A towfish on a nominal path (a straight line or a constant-rate turn) with sinusoidal yaw, sway, pitch,
/// heave and roll oscillations. Every pose is in closed form, so any ping can be evaluated on its own.
///
/// Nominal path, at time t = ping * ping_interval_s, speed V, initial heading psi0, signed turn rate omega
/// (rad/s, positive turning to starboard, i.e. clockwise seen from above; 0 on a straight line):
///     psi(t) = psi0 + omega t,
///     p(t)   = start + V t sinc(omega t / 2) (sin(psi0 + omega t / 2), cos(psi0 + omega t / 2))   (x east, y north),
/// the chord of the arc of radius R = V / |omega| (a straight line as omega -> 0), at world z = altitude.
///
/// Oscillations: each channel is a sin(2 pi t / period + phase) (see `oscillation`), all independent:
/// - sway s(t) (m) along the nominal horizontal starboard direction (cos psi, -sin psi, 0);
/// - heave h(t) (m) added to z (positive up);
/// - yaw, pitch, roll (deg) added to psi(t), 0 and 0.
/// Optionally the towfish points along the track the sway and heave make it follow (it does not crab):
/// - `yaw_follows_sway` adds the track angle atan2(ds/dt, V - omega s). The horizontal velocity of the
///   swayed position is (V - omega s) along psi plus ds/dt to starboard: at lateral offset s a point on the
///   turn lies on radius R - s (starboard turn) or R + s (port turn), so it moves at V (R -+ s) / R.
/// - `pitch_follows_heave` adds the climb angle atan2(dh/dt, |horizontal velocity|).

#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/motion/concept.hpp"
#include "sss/motion/straight_line.hpp"

namespace sss::motion {

/// A sinusoid a sin(2 pi t / period + phase).
template <Real T> struct oscillation {
    T amplitude = T(0); ///< peak value (deg for angles, m for offsets); 0: none
    T period_s = T(1);  ///< period (s), > 0
    T phase_deg = T(0); ///< phase at t = 0 (deg)
};

/// The value of an oscillation at time `t_s` (s), in its amplitude's unit.
template <Real T> [[nodiscard]] inline double oscillation_value(const oscillation<T>& o, double t_s) noexcept {
    const double w = two_pi_v<double> / static_cast<double>(o.period_s);
    return static_cast<double>(o.amplitude) * std::sin(w * t_s + deg_to_rad(static_cast<double>(o.phase_deg)));
}

/// The time derivative of an oscillation at `t_s` (unit of the amplitude per second).
template <Real T> [[nodiscard]] inline double oscillation_rate(const oscillation<T>& o, double t_s) noexcept {
    const double w = two_pi_v<double> / static_cast<double>(o.period_s);
    return static_cast<double>(o.amplitude) * w * std::cos(w * t_s + deg_to_rad(static_cast<double>(o.phase_deg)));
}

/// A turn at constant rate: give either its radius or its rate.
template <Real T> struct constant_turn {
    side toward = side::starboard; ///< the side the towfish turns to
    T radius_m = T(0);             ///< radius of the nominal path (m), > 0; or 0 to use rate_deg_s
    T rate_deg_s = T(0);           ///< turn rate (deg/s), > 0, given when radius_m is 0 (not both)
};

template <Real T> struct perturbed_params {
    vec2<T> start_m{T(0), T(0)}; ///< world (x east, y north) position of ping 0 on the nominal path (m)
    T heading_deg = T(0);        ///< nominal heading at ping 0, clockwise from north (deg)
    T speed_mps = T(2);          ///< nominal speed (m/s), >= 0
    T altitude_m = T(10);        ///< nominal world z (m), > 0
    T ping_interval_s = T(0.1);  ///< time between pings (s), > 0
    std::optional<constant_turn<T>> turn{}; ///< empty: a straight line
    oscillation<T> yaw_deg{};    ///< yaw oscillation (deg)
    oscillation<T> sway_m{};     ///< sway oscillation (m), positive to starboard
    oscillation<T> pitch_deg{};  ///< pitch oscillation (deg), |amplitude| < 90
    oscillation<T> heave_m{};    ///< heave oscillation (m), positive up
    oscillation<T> roll_deg{};   ///< roll oscillation (deg), |amplitude| < 90
    bool yaw_follows_sway = false;    ///< add the track angle of the swaying path to the yaw
    bool pitch_follows_heave = false; ///< add the climb angle of the heaving path to the pitch
};

template <Real T> class perturbed {
public:
    using value_type = T;

    /// Default parameters (non-explicit, so `{}` builds one).
    perturbed() : perturbed(perturbed_params<T>{}) {}

    explicit perturbed(const perturbed_params<T>& p) : p_(p) {
        detail::validate_nominal_track(p, "perturbed");
        check(p.yaw_deg, "perturbed.yaw_deg");
        check(p.sway_m, "perturbed.sway_m");
        check(p.pitch_deg, "perturbed.pitch_deg");
        check(p.heave_m, "perturbed.heave_m");
        check(p.roll_deg, "perturbed.roll_deg");
        sss::require(std::abs(p.pitch_deg.amplitude) < T(90), "perturbed.pitch_deg.amplitude", "must be < 90 deg");
        sss::require(std::abs(p.roll_deg.amplitude) < T(90), "perturbed.roll_deg.amplitude", "must be < 90 deg");
        if (p.turn) {
            const constant_turn<T>& c = *p.turn;
            const double sign = c.toward == side::starboard ? 1.0 : -1.0;
            sss::require(c.radius_m == T(0) || c.rate_deg_s == T(0), "perturbed.turn.rate_deg_s",
                         "a turn takes radius_m or rate_deg_s, not both (the radius would win)");
            if (c.radius_m != T(0)) {
                sss::require_positive(c.radius_m, "perturbed.turn.radius_m");
                omega_ = sign * static_cast<double>(p.speed_mps) / static_cast<double>(c.radius_m);
            } else {
                sss::require_positive(c.rate_deg_s, "perturbed.turn.rate_deg_s");
                omega_ = sign * deg_to_rad(static_cast<double>(c.rate_deg_s));
            }
        }
        // The towfish stays above z = 0 (as the motion concept asks) however it heaves.
        sss::require(std::abs(static_cast<double>(p.heave_m.amplitude)) < static_cast<double>(p.altitude_m),
                     "perturbed.heave_m.amplitude", "must be smaller than altitude_m: the towfish would heave to z <= 0");
        if (p.yaw_follows_sway || p.pitch_follows_heave) {
            // Pointing along the track needs a track: the swayed path's forward speed V - omega s stays positive
            // (a sway beyond the turn's radius would reverse it and turn the heading round).
            const double v = static_cast<double>(p.speed_mps);
            const double slowest = v - std::abs(omega_) * std::abs(static_cast<double>(p.sway_m.amplitude));
            sss::require(slowest > 0.0, p.yaw_follows_sway ? "perturbed.yaw_follows_sway" : "perturbed.pitch_follows_heave",
                         "needs a forward speed: speed_mps > 0 and, in a turn, |sway_m.amplitude| below the turn's radius");
            if (p.pitch_follows_heave) {
                // The climb angle at most atan(max |dh/dt| / slowest) on top of the pitch oscillation stays short of 90.
                const double climb = std::atan2(2.0 * pi_v<double> * std::abs(static_cast<double>(p.heave_m.amplitude)) /
                                                    static_cast<double>(p.heave_m.period_s),
                                                slowest);
                sss::require(std::abs(static_cast<double>(p.pitch_deg.amplitude)) + climb * 180.0 / pi_v<double> < 90.0,
                             "perturbed.pitch_follows_heave",
                             "with pitch_deg.amplitude the climb of the heave (heave_m amplitude and period against the "
                             "speed) would pitch the towfish 90 deg or more");
            }
        }
    }

    [[nodiscard]] const perturbed_params<T>& params() const noexcept { return p_; }
    /// Signed nominal turn rate (rad/s), positive to starboard; 0 on a straight line.
    [[nodiscard]] T turn_rate_rad_s() const noexcept { return static_cast<T>(omega_); }
    /// Radius of the nominal path (m): V / |omega|; infinite on a straight line (or at rest).
    [[nodiscard]] T turn_radius_m() const noexcept {
        return omega_ == 0.0 ? std::numeric_limits<T>::infinity()
                             : static_cast<T>(static_cast<double>(p_.speed_mps) / std::abs(omega_));
    }

    /// The pose on the nominal path, without the oscillations.
    [[nodiscard]] sss::pose<T> nominal_pose_at(std::size_t ping) const noexcept {
        const double t = time_of(ping);
        const nominal n = nominal_at(t);
        return make_pose(static_cast<T>(t), vec3<T>{static_cast<T>(n.x), static_cast<T>(n.y), p_.altitude_m}, T(0), T(0),
                         static_cast<T>(n.psi));
    }

    [[nodiscard]] sss::pose<T> pose_at(std::size_t ping) const noexcept {
        const double t = time_of(ping);
        const nominal n = nominal_at(t);
        const double s = oscillation_value(p_.sway_m, t);
        const double h = oscillation_value(p_.heave_m, t);
        const double x = n.x + s * std::cos(n.psi), y = n.y - s * std::sin(n.psi);
        const double z = static_cast<double>(p_.altitude_m) + h;
        double yaw = n.psi + deg_to_rad(oscillation_value(p_.yaw_deg, t));
        double pitch = deg_to_rad(oscillation_value(p_.pitch_deg, t));
        const double roll = deg_to_rad(oscillation_value(p_.roll_deg, t));
        // Horizontal velocity of the swayed position: forward (along psi) and to starboard.
        const double forward = static_cast<double>(p_.speed_mps) - omega_ * s;
        const double starboard = oscillation_rate(p_.sway_m, t);
        if (p_.yaw_follows_sway) yaw += std::atan2(starboard, forward);
        if (p_.pitch_follows_heave) pitch += std::atan2(oscillation_rate(p_.heave_m, t), std::hypot(forward, starboard));
        return make_pose(static_cast<T>(t), vec3<T>{static_cast<T>(x), static_cast<T>(y), static_cast<T>(z)},
                         static_cast<T>(roll), static_cast<T>(pitch), static_cast<T>(yaw));
    }

private:
    struct nominal {
        double x, y, psi;
    };

    static void check(const oscillation<T>& o, const std::string& name) {
        sss::require_finite(o.amplitude, name + ".amplitude");
        sss::require_positive(o.period_s, name + ".period_s");
        sss::require_finite(o.phase_deg, name + ".phase_deg");
    }

    [[nodiscard]] double time_of(std::size_t ping) const noexcept {
        return static_cast<double>(ping) * static_cast<double>(p_.ping_interval_s);
    }

    [[nodiscard]] static double sinc(double x) noexcept {
        if (std::abs(x) < 1e-4) return 1.0 - x * x / 6.0;
        return std::sin(x) / x;
    }

    [[nodiscard]] nominal nominal_at(double t) const noexcept {
        const double psi0 = deg_to_rad(static_cast<double>(p_.heading_deg));
        const double half = 0.5 * omega_ * t;
        const double chord = static_cast<double>(p_.speed_mps) * t * sinc(half);
        const double dir = psi0 + half;
        return nominal{static_cast<double>(p_.start_m.x) + chord * std::sin(dir),
                       static_cast<double>(p_.start_m.y) + chord * std::cos(dir), psi0 + 2.0 * half};
    }

    perturbed_params<T> p_;
    double omega_ = 0.0;
};

static_assert(Motion<perturbed<float>> && Motion<perturbed<double>>);

} // namespace sss::motion

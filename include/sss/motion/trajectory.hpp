#pragma once
/// \file
/// A towfish following a sampled trajectory: positions (and optionally attitude, heave and sway) at given
/// times or ping numbers, interpolated to every ping.
///
/// Samples. Each sample has a key, either a time (s) or a ping number, strictly increasing, and a world
/// position (x east, y north, z up, m). Optional per-sample channels, each given for all samples or none:
/// - roll, pitch, yaw (rad, the conventions of core/pose.hpp);
/// - heave_m: a vertical offset added to the world z of the interpolated position (positive up);
/// - sway_m: a lateral offset along the horizontal starboard direction of the heading,
///   (cos yaw, -sin yaw, 0) in world ENU (positive to starboard). Heave and sway displace the towfish
///   without entering the derived orientation.
///
/// Derived orientation. Where yaw or pitch is not given it comes from the velocity v = dp/dkey of the sampled
/// positions (the same three-point derivative the cubic interpolation uses, below): yaw = atan2(v_east,
/// v_north), pitch = atan2(v_up, |v_horizontal|) (the climb angle). Where the horizontal velocity vanishes the
/// yaw of the nearest sample with a defined one is kept (0 if none). Roll, when not given, is 0, or, with
/// `roll_from_turn`, the bank angle of a coordinated turn, atan(V r / g): V the horizontal speed (m/s), r the
/// yaw rate (rad/s, positive turning to starboard, so a starboard turn rolls starboard down), g = 9.80665 m/s^2.
///
/// Interpolation (`interpolation`): every channel (x, y, z, the angles unwrapped to continuous series so the
/// shortest arc is taken between samples, heave, sway, and time when keyed by ping) is interpolated over the
/// key by the same rule:
/// - linear: piecewise linear;
/// - cubic (default): piecewise cubic Hermite whose slope at each sample is that of the parabola through the
///   sample and its two neighbours (one-sided parabola at the ends; the chord with two samples). It passes
///   through the samples, is C1, and reproduces quadratics exactly. The time's slopes are limited so that it
///   increases between samples as at them (Fritsch & Carlson 1980), where a gap in the record would make the
///   cubic run backwards.
/// Output angles: yaw in [0, 2 pi), pitch and roll within 90 degrees of level, as the samples are (each taken
/// modulo 2 pi): where a cubic between samples near 90 degrees overshoots (samples 0, 89, 89, 0 degrees reach 100),
/// the angle is held just short of 90 degrees.
///
/// Pings. Keyed by time: ping i is at time t0 + i * ping_interval_s, t0 = `ping_zero_at` (default the first
/// sample's time). Keyed by ping: ping i is the sample key k0 + i, k0 = `ping_zero_at` (default the first
/// sample's ping number). `pose.time_s` is the time since ping 0 (s): i * ping_interval_s when keyed by time or
/// when keyed by ping without times; the interpolated time minus that of ping 0 otherwise. Keys are held in
/// double so that absolute times (e.g. seconds since 1970) keep their resolution. `pose_at` throws
/// invalid_parameter("ping") for pings beyond the last sample (see `ping_count()`).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/motion/concept.hpp"

namespace sss::motion {

/// How a trajectory is interpolated between its samples.
enum class interpolation : unsigned char { linear, cubic };

/// Sampled trajectory. Exactly one of `time_s` and `ping` may be empty; when `ping` is given it is the key
/// and `time_s` (optional) gives the time of each sample. Every other vector but `position_m` may be empty.
template <Real T> struct trajectory_samples {
    std::vector<double> time_s{};      ///< sample times (s), strictly increasing
    std::vector<double> ping{};        ///< sample ping numbers, strictly increasing (then the key)
    std::vector<vec3<T>> position_m{}; ///< world position (m): x east, y north, z up
    std::vector<T> roll_rad{};         ///< roll, starboard down positive (rad), within pi/2 of level (modulo 2 pi)
    std::vector<T> pitch_rad{};        ///< pitch, bow up positive (rad), within pi/2 of level (modulo 2 pi)
    std::vector<T> yaw_rad{};          ///< heading, clockwise from north (rad)
    std::vector<T> heave_m{};          ///< vertical offset added to z (m), positive up
    std::vector<T> sway_m{};           ///< offset along the horizontal starboard direction (m)
};

template <Real T> struct trajectory_params {
    T ping_interval_s = T(0.1);        ///< time between pings (s), > 0
    /// Key of ping 0: a time (s) when keyed by time, a ping number when keyed by ping; NaN: the first sample's.
    double ping_zero_at = std::numeric_limits<double>::quiet_NaN();
    interpolation method = interpolation::cubic;
    bool roll_from_turn = false;       ///< without a roll channel: coordinated-turn bank angle instead of 0
};

template <Real T> class trajectory {
public:
    using value_type = T;

    /// Standard gravity (m/s^2), for the coordinated-turn roll.
    static constexpr double gravity_mps2 = 9.80665;

    explicit trajectory(const trajectory_samples<T>& s, const trajectory_params<T>& p = {}) : p_(p) {
        sss::require_positive(p.ping_interval_s, "trajectory.ping_interval_s");
        by_ping_ = !s.ping.empty();
        const std::vector<double>& key = by_ping_ ? s.ping : s.time_s;
        const std::size_t n = key.size();
        sss::require(n >= 2, by_ping_ ? "trajectory.ping" : "trajectory.time_s",
                             "needs at least 2 samples (with either time_s or ping given)");
        check_increasing(key, by_ping_ ? "trajectory.ping" : "trajectory.time_s");
        require_size(s.position_m.size(), n, "trajectory.position_m");
        for (std::size_t i = 0; i < n; ++i) {
            const vec3<T>& q = s.position_m[i];
            sss::require(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z), "trajectory.position_m",
                                 [&] { return "sample " + std::to_string(i) + " is not finite"; });
        }
        has_time_ = by_ping_ && !s.time_s.empty();
        if (has_time_) {
            require_size(s.time_s.size(), n, "trajectory.time_s");
            check_increasing(s.time_s, "trajectory.time_s");
        }
        require_channel(s.roll_rad, n, "trajectory.roll_rad");
        require_channel(s.pitch_rad, n, "trajectory.pitch_rad");
        require_near_level(s.roll_rad, "trajectory.roll_rad");
        require_near_level(s.pitch_rad, "trajectory.pitch_rad");
        require_channel(s.yaw_rad, n, "trajectory.yaw_rad");
        require_channel(s.heave_m, n, "trajectory.heave_m");
        require_channel(s.sway_m, n, "trajectory.sway_m");

        key_ = key;
        k0_ = std::isnan(p.ping_zero_at) ? key.front() : p.ping_zero_at;
        sss::require(std::isfinite(k0_) && k0_ >= key.front() && k0_ <= key.back(), "trajectory.ping_zero_at",
                             "must lie within the samples' keys");
        const double step = by_ping_ ? 1.0 : static_cast<double>(p.ping_interval_s);
        const double span = (key.back() - k0_) / step;
        // 2^53 pings: beyond it ping numbers are no longer exact in double (and the count would overflow).
        sss::require(span < 9007199254740992.0, by_ping_ ? "trajectory.ping" : "trajectory.time_s",
                             "the samples span more than 2^53 pings");
        // Keyed by ping the count is exact. Keyed by time, two epsilons of T (relative) absorb the rounding of an
        // interval given in T (0.1f lies 1.5e-8 above 0.1: 10 s of samples still hold ping 100) and of the division;
        // an absolute tolerance would add pings beyond the samples to long surveys (up to 2^22 pings in float, 2^51
        // in double, the last ping's key lies within a fraction of an interval of the samples' end).
        const double tolerance = by_ping_ ? 0.0 : 2.0 * static_cast<double>(std::numeric_limits<T>::epsilon());
        count_ = static_cast<std::size_t>(std::floor(span * (1.0 + tolerance))) + 1;

        // Position channels and their slopes (d/dkey).
        for (int c = 0; c < 3; ++c) {
            std::vector<double> v(n);
            for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<double>(s.position_m[i][c]);
            pos_[c] = make_channel(std::move(v), "trajectory.position_m");
        }
        // Yaw and pitch: given (unwrapped) or from the direction of travel.
        std::vector<double> yaw(n), pitch(n);
        if (!s.yaw_rad.empty() || !s.pitch_rad.empty()) {
            for (std::size_t i = 0; i < n; ++i) {
                if (!s.yaw_rad.empty()) yaw[i] = static_cast<double>(s.yaw_rad[i]);
                if (!s.pitch_rad.empty()) pitch[i] = static_cast<double>(s.pitch_rad[i]);
            }
        }
        if (s.yaw_rad.empty() || s.pitch_rad.empty()) {
            std::vector<double> derived_yaw(n), derived_pitch(n);
            derive_orientation(derived_yaw, derived_pitch);
            if (s.yaw_rad.empty()) yaw = derived_yaw;
            if (s.pitch_rad.empty()) pitch = derived_pitch;
        }
        yaw_ = make_channel(unwrap(std::move(yaw)), "trajectory.yaw_rad");
        pitch_ = make_channel(wrapped(std::move(pitch)), "trajectory.pitch_rad");

        // Sample times, for the ping times and the turn rate.
        std::vector<double> t(n);
        for (std::size_t i = 0; i < n; ++i)
            t[i] = by_ping_ ? (has_time_ ? s.time_s[i] : key[i] * static_cast<double>(p.ping_interval_s)) : key[i];
        if (has_time_) {
            time_ = make_channel(t, "trajectory.time_s");
            limit_to_increasing(time_);
        }

        std::vector<double> roll(n, 0.0);
        if (!s.roll_rad.empty()) {
            for (std::size_t i = 0; i < n; ++i) roll[i] = static_cast<double>(s.roll_rad[i]);
        } else if (p.roll_from_turn) {
            const std::vector<double> r = slopes(t, yaw_.value);
            const std::vector<double> vx = slopes(t, pos_[0].value), vy = slopes(t, pos_[1].value);
            for (std::size_t i = 0; i < n; ++i) roll[i] = std::atan(std::hypot(vx[i], vy[i]) * r[i] / gravity_mps2);
        }
        roll_ = make_channel(wrapped(std::move(roll)), "trajectory.roll_rad");
        if (!s.heave_m.empty()) heave_ = make_channel(to_double(s.heave_m), "trajectory.heave_m");
        if (!s.sway_m.empty()) sway_ = make_channel(to_double(s.sway_m), "trajectory.sway_m");
        if (has_time_) t0_ = eval(time_, k0_);
        else t0_ = by_ping_ ? k0_ * static_cast<double>(p.ping_interval_s) : k0_;
    }

    [[nodiscard]] const trajectory_params<T>& params() const noexcept { return p_; }
    /// Number of pings whose key lies within the samples: pings 0 .. ping_count() - 1 are valid.
    [[nodiscard]] std::size_t ping_count() const noexcept { return count_; }
    /// True when the samples are keyed by ping number, false when by time.
    [[nodiscard]] bool keyed_by_ping() const noexcept { return by_ping_; }
    /// Absolute time of ping 0 (s), in the samples' time base (ping_zero_at * ping_interval_s when keyed by
    /// ping without times).
    [[nodiscard]] double start_time_s() const noexcept { return t0_; }

    /// Ping `ping`'s time since ping 0 (s) in double, as pose_at gives it in T (which, in float, rounds it to
    /// milliseconds after a few hours).
    [[nodiscard]] double time_since_ping0_s(std::size_t ping) const {
        if (ping >= count_)
            throw invalid_parameter("ping", "ping " + std::to_string(ping) + " lies beyond the trajectory's " +
                                                std::to_string(count_) + " pings");
        if (!has_time_) return static_cast<double>(ping) * static_cast<double>(p_.ping_interval_s);
        return eval(time_, locate(std::min(k0_ + static_cast<double>(ping), key_.back()))) - t0_;
    }

    [[nodiscard]] sss::pose<T> pose_at(std::size_t ping) const {
        if (ping >= count_)
            throw invalid_parameter("ping", "ping " + std::to_string(ping) + " lies beyond the trajectory's " +
                                                std::to_string(count_) + " pings");
        const double step = by_ping_ ? 1.0 : static_cast<double>(p_.ping_interval_s);
        const locus k = locate(std::min(k0_ + static_cast<double>(ping) * step, key_.back()));
        const double t = has_time_ ? eval(time_, k) - t0_ : static_cast<double>(ping) * static_cast<double>(p_.ping_interval_s);
        const double yaw = eval(yaw_, k);
        double x = eval(pos_[0], k), y = eval(pos_[1], k), z = eval(pos_[2], k);
        if (!heave_.value.empty()) z += eval(heave_, k);
        if (!sway_.value.empty()) {
            const double sw = eval(sway_, k);
            x += sw * std::cos(yaw);
            y -= sw * std::sin(yaw);
        }
        const vec3<T> position{static_cast<T>(x), static_cast<T>(y), static_cast<T>(z)};
        // The heading in [0, 2 pi) in T too: a yaw just below 2 pi rounds up to it in float.
        const T heading = static_cast<T>(wrap_two_pi(yaw));
        return make_pose(static_cast<T>(t), position, static_cast<T>(held_near_level(eval(roll_, k))),
                         static_cast<T>(held_near_level(eval(pitch_, k))),
                         heading >= static_cast<T>(2.0 * pi_v<double>) ? T(0) : heading);
    }

private:
    struct channel {
        std::vector<double> value{};
        std::vector<double> slope{}; ///< d value / d key at each sample
    };

    static void require_size(std::size_t got, std::size_t n, const char* name) {
        sss::require(got == n, name,
                             [&] { return "must hold one value per sample (" + std::to_string(n) + "), got " + std::to_string(got); });
    }
    template <class V> static void require_channel(const std::vector<V>& v, std::size_t n, const char* name) {
        if (v.empty()) return;
        require_size(v.size(), n, name);
        for (std::size_t i = 0; i < n; ++i)
            sss::require(std::isfinite(v[i]), name, [&] { return "sample " + std::to_string(i) + " is not finite"; });
    }
    /// Roll and pitch within 90 degrees of level once wrapped to [-pi, pi] (as perturbed's amplitudes): past that the
    /// towfish flies on its side or nose down and its heading loses its meaning.
    template <class V> static void require_near_level(const std::vector<V>& v, const char* name) {
        for (std::size_t i = 0; i < v.size(); ++i)
            sss::require(std::abs(std::remainder(static_cast<double>(v[i]), 2.0 * pi_v<double>)) < 0.5 * pi_v<double>,
                         name, [&] { return "sample " + std::to_string(i) + " is 90 deg or more from level"; });
    }
    static void check_increasing(const std::vector<double>& k, const char* name) {
        for (std::size_t i = 0; i < k.size(); ++i) {
            sss::require(std::isfinite(k[i]), name, [&] { return "sample " + std::to_string(i) + " is not finite"; });
            if (i > 0)
                sss::require(k[i] > k[i - 1], name,
                                     [&] { return "must be strictly increasing; sample " + std::to_string(i) + " is not"; });
        }
    }
    static std::vector<double> to_double(const std::vector<T>& v) { return std::vector<double>(v.begin(), v.end()); }

    [[nodiscard]] static double wrap_pi(double a) noexcept {
        const double w = std::remainder(a, 2.0 * pi_v<double>);
        return w <= -pi_v<double> ? w + 2.0 * pi_v<double> : w;
    }
    /// An interpolated roll or pitch (its channel's samples wrapped to within 90 degrees of level: `wrapped`) held
    /// within 90 degrees of level (file comment): at least 1e-6 rad short of it, which float too keeps below 90 degrees
    /// (pi/2 in float rounds up). An overshoot of any size stays on its own side.
    [[nodiscard]] static double held_near_level(double a) noexcept {
        constexpr double limit = 0.5 * pi_v<double> - 1e-6;
        return std::clamp(a, -limit, limit);
    }
    /// Roll or pitch samples each wrapped to (-pi, pi]: within 90 degrees of level (require_near_level, or derived
    /// so), neighbours then differ by less than pi, so the shortest arc between them is the plain difference.
    [[nodiscard]] static std::vector<double> wrapped(std::vector<double> a) {
        for (double& x : a) x = wrap_pi(x);
        return a;
    }
    [[nodiscard]] static double wrap_two_pi(double a) noexcept {
        double w = std::fmod(a, 2.0 * pi_v<double>);
        if (w < 0.0) w += 2.0 * pi_v<double>;
        return w >= 2.0 * pi_v<double> ? 0.0 : w;
    }
    /// A continuous angle series: each step taken as the shortest arc.
    [[nodiscard]] static std::vector<double> unwrap(std::vector<double> a) {
        for (std::size_t i = 1; i < a.size(); ++i) a[i] = a[i - 1] + wrap_pi(a[i] - a[i - 1]);
        return a;
    }

    /// Slopes at the samples of the parabola through each sample and its neighbours (one-sided at the ends).
    [[nodiscard]] static std::vector<double> slopes(const std::vector<double>& k, const std::vector<double>& f) {
        const std::size_t n = f.size();
        std::vector<double> m(n);
        if (n == 2) {
            m[0] = m[1] = (f[1] - f[0]) / (k[1] - k[0]);
            return m;
        }
        for (std::size_t i = 1; i + 1 < n; ++i) {
            const double h0 = k[i] - k[i - 1], h1 = k[i + 1] - k[i];
            const double d0 = (f[i] - f[i - 1]) / h0, d1 = (f[i + 1] - f[i]) / h1;
            m[i] = (h1 * d0 + h0 * d1) / (h0 + h1);
        }
        {
            const double h0 = k[1] - k[0], h1 = k[2] - k[1];
            const double d0 = (f[1] - f[0]) / h0, d1 = (f[2] - f[1]) / h1;
            m[0] = (d0 * (2.0 * h0 + h1) - d1 * h0) / (h0 + h1);
        }
        {
            const double h1 = k[n - 1] - k[n - 2], h0 = k[n - 2] - k[n - 3];
            const double d1 = (f[n - 1] - f[n - 2]) / h1, d0 = (f[n - 2] - f[n - 3]) / h0;
            m[n - 1] = (d1 * (2.0 * h1 + h0) - d0 * h1) / (h0 + h1);
        }
        return m;
    }

    /// Slopes of an increasing channel (the sample times) limited to [0, 3 min(d_left, d_right)], d the secants beside
    /// each sample, so that the cubic between samples increases too (Fritsch & Carlson, SIAM J. Numer. Anal. 17(2),
    /// 1980): the parabola's slope overshoots where the samples' spacing in time jumps (a gap in a record), and the
    /// interpolated time would run backwards.
    void limit_to_increasing(channel& c) const {
        const std::size_t n = c.value.size();
        for (std::size_t i = 0; i < n; ++i) {
            double bound = std::numeric_limits<double>::infinity();
            if (i > 0) bound = std::min(bound, 3.0 * (c.value[i] - c.value[i - 1]) / (key_[i] - key_[i - 1]));
            if (i + 1 < n) bound = std::min(bound, 3.0 * (c.value[i + 1] - c.value[i]) / (key_[i + 1] - key_[i]));
            c.slope[i] = std::clamp(c.slope[i], 0.0, bound);
        }
    }

    /// The largest magnitude of a sample value (m, rad or s): beyond it interpolation could overflow.
    static constexpr double max_sample_value = 1e12;

    /// A channel of values over the keys; throws invalid_parameter(name) for a value beyond max_sample_value or a
    /// slope that is not finite (values that change by more than a double can hold between close keys).
    [[nodiscard]] channel make_channel(std::vector<double> v, const char* name) const {
        channel c;
        for (std::size_t i = 0; i < v.size(); ++i)
            if (!(std::abs(v[i]) <= max_sample_value))
                throw invalid_parameter(name, "sample " + std::to_string(i) + " exceeds 1e12 in magnitude");
        c.slope = slopes(key_, v);
        for (std::size_t i = 0; i < c.slope.size(); ++i)
            if (!std::isfinite(c.slope[i]))
                throw invalid_parameter(name, "changes faster than a double can hold near sample " + std::to_string(i) +
                                                  " (keys too close for the change in value)");
        c.value = std::move(v);
        return c;
    }

    void derive_orientation(std::vector<double>& yaw, std::vector<double>& pitch) const {
        const std::size_t n = key_.size();
        std::vector<bool> defined(n, false);
        for (std::size_t i = 0; i < n; ++i) {
            const double vx = pos_[0].slope[i], vy = pos_[1].slope[i], vz = pos_[2].slope[i];
            const double horizontal = std::hypot(vx, vy);
            const double speed = std::hypot(horizontal, vz);
            defined[i] = horizontal > 1e-12 * std::max(speed, 1e-300);
            yaw[i] = defined[i] ? std::atan2(vx, vy) : 0.0;
            pitch[i] = speed > 0.0 ? std::atan2(vz, horizontal) : 0.0;
        }
        // Fill undefined headings from the nearest defined one (forward, then backward).
        for (std::size_t i = 1; i < n; ++i)
            if (!defined[i] && defined[i - 1]) { yaw[i] = yaw[i - 1]; defined[i] = true; }
        for (std::size_t i = n - 1; i-- > 0;)
            if (!defined[i] && defined[i + 1]) { yaw[i] = yaw[i + 1]; defined[i] = true; }
    }

    /// Where a key falls: segment [key_i, key_i+1], fraction s in [0, 1] and length h.
    struct locus {
        std::size_t i;
        double s, h;
    };
    [[nodiscard]] locus locate(double k) const noexcept {
        const auto it = std::upper_bound(key_.begin(), key_.end(), k);
        const std::size_t i = std::clamp<std::size_t>(static_cast<std::size_t>(it - key_.begin()), 1, key_.size() - 1) - 1;
        const double h = key_[i + 1] - key_[i];
        return locus{i, (k - key_[i]) / h, h};
    }

    /// A channel at a located key.
    [[nodiscard]] double eval(const channel& c, const locus& at) const noexcept {
        const std::size_t i = at.i;
        const double s = at.s, h = at.h;
        if (p_.method == interpolation::linear) return c.value[i] + s * (c.value[i + 1] - c.value[i]);
        const double s2 = s * s, s3 = s2 * s;
        const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0, h10 = s3 - 2.0 * s2 + s;
        const double h01 = -2.0 * s3 + 3.0 * s2, h11 = s3 - s2;
        return h00 * c.value[i] + h10 * h * c.slope[i] + h01 * c.value[i + 1] + h11 * h * c.slope[i + 1];
    }
    [[nodiscard]] double eval(const channel& c, double k) const noexcept { return eval(c, locate(k)); }

    trajectory_params<T> p_;
    bool by_ping_ = false;
    bool has_time_ = false;
    std::vector<double> key_{};
    double k0_ = 0.0;
    double t0_ = 0.0;
    std::size_t count_ = 0;
    channel pos_[3]{};
    channel yaw_{}, pitch_{}, roll_{}, heave_{}, sway_{}, time_{};
};

static_assert(Motion<trajectory<float>> && Motion<trajectory<double>>);

} // namespace sss::motion

#pragma once
/// \file
/// A planar transducer array on each side of the towfish: N elements along track by M elements across
/// (in the vertical plane), rectangular elements, optional amplitude shading per axis, separate transmit and
/// receive arrays allowed. Its two-way weight is the far-field transmit power pattern times the receive power
/// pattern, each normalised to 1 on the array axis.
///
/// Geometry. The array face lies in a plane containing the body x axis; its outward normal points out of the
/// side, tilted down by the depression angle tau: n = (0, s cos tau, sin tau) in body FRD (s = +1 starboard,
/// -1 port). Its along axis is p = (1, 0, 0) and its vertical axis q = (0, -s sin tau, cos tau) (positive
/// towards larger depression). A launch direction (along a, depression e) has, in the array's own frame, the
/// direction cosines
///     u = sin a,   v = cos a sin(e - tau),   w = cos a cos(e - tau)   (w along the normal),
/// the same on both sides. The array is baffled: nothing is radiated or heard where w <= 0.
///
/// Pattern (amplitude, one way; Kinsler et al., 2000, "Fundamentals of Acoustics",
/// 4th ed., ch. 8): E(u, v) = A(u) B(v) with, per axis, A(u) = sinc(pi a u / lambda) AF_N(u): the element
/// (a rectangular piston of side a) times the array factor of N elements at pitch d (uniform:
/// sin(N pi d u / lambda) / (N sin(pi d u / lambda)); shaded: the normalised weighted sum). lambda = c / f.
/// Two-way weight W = |E_tx|^2 |E_rx|^2, which separates as W_u(u) W_v(v).
///
/// Extent. The extent holds every direction whose two-way level is at or above `threshold_db` (t). Because
/// W = W_u(u) W_v(v) with both factors at most 1 (non-negative shading) and even in their argument, W >= t
/// needs W_u(u) >= t, which bounds |a| <= asin U, and W_v(v) >= t / W_u(u), which bounds |v| and so, with
/// cos a, |sin(e - tau)|. Each axis is scanned densely (32 points per null spacing) with every sampled local
/// maximum refined (golden section) and the outermost crossing bisected, so a sidelobe or grating-lobe peak
/// falling between samples is not missed. Depressions are clamped to [-pi/2, pi/2].

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sss/beam/concept.hpp"
#include "sss/beam/directivity.hpp"
#include "sss/core/constants.hpp"
#include "sss/core/decibel.hpp"
#include "sss/core/error.hpp"

namespace sss::beam {

/// One axis of a planar array.
template <Real T> struct array_axis {
    std::size_t count = 1;    ///< number of elements along this axis, >= 1
    T element_m = T(0.5);     ///< element length along this axis (m), > 0
    T pitch_m = T(0);         ///< centre-to-centre spacing (m), >= element_m when count > 1 (ignored when 1)
    std::vector<T> shading{}; ///< amplitude weight per element (count of them, >= 0, not all 0); empty: uniform
};

/// The element layout of one array (transmit or receive).
template <Real T> struct array_layout {
    array_axis<T> along{.count = 1, .element_m = T(0.5)};      ///< along-track axis (body x)
    array_axis<T> vertical{.count = 1, .element_m = T(0.02)};  ///< axis in the tilted across-track plane
};

template <Real T> struct planar_array_params {
    T frequency_hz = T(100000);        ///< acoustic frequency (Hz), > 0
    T sound_speed_mps = T(1500);       ///< sound speed at the transducer (m/s), > 0
    T depression_deg = T(20);          ///< tilt of the array normal below horizontal (deg), in [-90, 90]
    array_layout<T> transmit{};        ///< transmitting array
    std::optional<array_layout<T>> receive{}; ///< receiving array; empty: the transmitting array receives
    T threshold_db = T(-30);           ///< two-way level bounding the extent (dB), < 0
};

template <Real T> class planar_array {
public:
    using value_type = T;

    /// Default parameters (non-explicit, so `{}` builds one).
    planar_array() : planar_array(planar_array_params<T>{}) {}

    explicit planar_array(const planar_array_params<T>& p) : p_(p) {
        sss::require_positive(p.frequency_hz, "planar_array.frequency_hz");
        sss::require_positive(p.sound_speed_mps, "planar_array.sound_speed_mps");
        sss::require_in_range(p.depression_deg, T(-90), T(90), "planar_array.depression_deg");
        sss::require_finite(p.threshold_db, "planar_array.threshold_db");
        sss::require(p.threshold_db < T(0), "planar_array.threshold_db", "must be < 0 dB");
        validate(p.transmit.along, "planar_array.transmit.along");
        validate(p.transmit.vertical, "planar_array.transmit.vertical");
        if (p.receive) {
            validate(p.receive->along, "planar_array.receive.along");
            validate(p.receive->vertical, "planar_array.receive.vertical");
        }
        wavelength_m_ = p.sound_speed_mps / p.frequency_hz;
        tilt_rad_ = deg_to_rad(p.depression_deg);
        tx_along_ = make_axis(p.transmit.along);
        tx_vertical_ = make_axis(p.transmit.vertical);
        rx_along_ = p.receive ? make_axis(p.receive->along) : tx_along_;
        rx_vertical_ = p.receive ? make_axis(p.receive->vertical) : tx_vertical_;
        compute_extent();
    }

    [[nodiscard]] const planar_array_params<T>& params() const noexcept { return p_; }
    [[nodiscard]] T wavelength_m() const noexcept { return wavelength_m_; }
    [[nodiscard]] beam_extent<T> extent(side) const noexcept { return extent_; }

    /// (u, v, w): direction cosines of a launch direction against the array's along axis, vertical axis and
    /// normal (see the file comment). Independent of the side.
    [[nodiscard]] vec3<T> direction_cosines(T along_rad, T depression_rad) const noexcept {
        const T ca = std::cos(along_rad);
        const T rel = depression_rad - tilt_rad_;
        return vec3<T>{std::sin(along_rad), ca * std::sin(rel), ca * std::cos(rel)};
    }

    /// One-way transmit intensity pattern |E_tx|^2 (1 on the array axis, 0 behind the baffle).
    [[nodiscard]] T transmit_power(T along_rad, T depression_rad) const noexcept {
        return one_way(tx_along_, tx_vertical_, direction_cosines(along_rad, depression_rad));
    }
    /// One-way receive intensity pattern |E_rx|^2 (1 on the array axis, 0 behind the baffle).
    [[nodiscard]] T receive_power(T along_rad, T depression_rad) const noexcept {
        return one_way(rx_along_, rx_vertical_, direction_cosines(along_rad, depression_rad));
    }

    /// Two-way intensity weight: transmit_power x receive_power inside the extent, 0 outside.
    [[nodiscard]] T weight(side, T along_rad, T depression_rad) const noexcept {
        if (!(along_rad >= extent_.along_min_rad && along_rad <= extent_.along_max_rad &&
              depression_rad >= extent_.depression_min_rad && depression_rad <= extent_.depression_max_rad))
            return T(0);
        const vec3<T> c = direction_cosines(along_rad, depression_rad);
        if (c.z <= T(0)) return T(0);
        const T tx = tx_along_.amplitude(c.x) * tx_vertical_.amplitude(c.y);
        if (!p_.receive) return (tx * tx) * (tx * tx); // the same array transmits and receives
        const T rx = rx_along_.amplitude(c.x) * rx_vertical_.amplitude(c.y);
        return (tx * tx) * (rx * rx);
    }

    /// Along-track angular step (rad) that resolves the pattern: a third of the null spacing lambda / L of the
    /// longer along-track aperture L (transmit or receive), so that ray columns sample every lobe.
    [[nodiscard]] T along_resolution_rad(side) const noexcept {
        auto length = [](const array_axis<T>& a) { return T(a.count - 1) * a.pitch_m + a.element_m; };
        T L = length(p_.transmit.along);
        if (p_.receive) L = std::max(L, length(p_.receive->along));
        return wavelength_m_ / L / T(3);
    }

private:
    /// An axis ready to evaluate: element size, pitch and shading, with lambda folded in.
    struct axis_model {
        T element_m{};
        T pitch_m{};
        T wavelength_m{};
        std::size_t count = 1;
        std::vector<T> shading{}; ///< empty when uniform
        [[nodiscard]] T amplitude(T u) const noexcept {
            const T element = line_aperture(element_m, wavelength_m, u);
            if (count <= 1) return element;
            const T af = shading.empty() ? array_factor(count, pitch_m, wavelength_m, u)
                                         : array_factor(std::span<const T>(shading), pitch_m, wavelength_m, u);
            return element * af;
        }
        /// Smallest spacing of pattern nulls in u: a lobe is at least this wide.
        [[nodiscard]] T lobe_spacing_u() const noexcept {
            T s = wavelength_m / element_m;
            if (count > 1) s = std::min(s, wavelength_m / (static_cast<T>(count) * pitch_m));
            return s;
        }
    };

    static void validate(const array_axis<T>& a, const std::string& name) {
        sss::require(a.count >= 1, name + ".count", "must be at least 1");
        sss::require_positive(a.element_m, name + ".element_m");
        if (a.count > 1) {
            sss::require_positive(a.pitch_m, name + ".pitch_m");
            sss::require(a.pitch_m >= a.element_m, name + ".pitch_m",
                            "must be at least element_m (elements cannot overlap)");
        }
        if (!a.shading.empty()) {
            sss::require(a.shading.size() == a.count, name + ".shading",
                            [&] { return "must hold one weight per element (" + std::to_string(a.count) + "), got " +
                                std::to_string(a.shading.size()); });
            T sum = 0;
            for (T w : a.shading) {
                sss::require(std::isfinite(w) && w >= T(0), name + ".shading", "weights must be finite and >= 0");
                sum += w;
            }
            sss::require(sum > T(0), name + ".shading", "weights must not all be 0");
        }
    }

    [[nodiscard]] axis_model make_axis(const array_axis<T>& a) const {
        axis_model m{a.element_m, a.pitch_m, wavelength_m_, a.count, {}};
        const bool uniform = std::all_of(a.shading.begin(), a.shading.end(), [&](T w) { return w == a.shading.front(); });
        if (!uniform) m.shading = a.shading;
        return m;
    }

    [[nodiscard]] static T one_way(const axis_model& along, const axis_model& vertical, const vec3<T>& c) noexcept {
        if (c.z <= T(0)) return T(0);
        const T e = along.amplitude(c.x) * vertical.amplitude(c.y);
        return e * e;
    }

    /// The two-way power of one axis, W(x) = (A_tx(x) A_rx(x))^2 for x in [0, 1], tabulated on a grid fine
    /// against its lobes (32 points per null spacing), with, for each grid interval, an upper value `top` (the
    /// larger end sample, or the golden-section-refined peak of a lobe whose sampled maximum falls next to
    /// it) and a point `where` inside the interval at which that value is reached.
    struct axis_profile {
        const axis_model* tx{};
        const axis_model* rx{};
        std::size_t n = 0;
        T h{};
        std::vector<T> sample{};
        std::vector<T> top{};
        std::vector<T> where{};

        axis_profile(const axis_model& t, const axis_model& r) : tx(&t), rx(&r) {
            const T spacing = std::min(t.lobe_spacing_u(), r.lobe_spacing_u());
            const T target = std::min(spacing / T(32), T(1) / T(64));
            n = std::min<std::size_t>(static_cast<std::size_t>(std::ceil(T(1) / target)), std::size_t{1} << 20);
            h = T(1) / static_cast<T>(n);
            sample.resize(n + 1);
            for (std::size_t i = 0; i <= n; ++i) sample[i] = power(x_at(i));
            top.resize(n);
            where.resize(n);
            for (std::size_t j = 0; j < n; ++j) {
                const bool right = sample[j + 1] > sample[j];
                top[j] = right ? sample[j + 1] : sample[j];
                where[j] = right ? x_at(j + 1) : x_at(j);
            }
            for (std::size_t i = 1; i <= n; ++i) {
                const bool peak = sample[i] >= sample[i - 1] && (i == n || sample[i] >= sample[i + 1]);
                if (!peak) continue;
                const T xp = golden_max(x_at(i - 1), x_at(std::min(i + 1, n)));
                const T wp = power(xp);
                const std::size_t j = std::min(static_cast<std::size_t>(xp / h), n - 1);
                if (wp > top[j]) { top[j] = wp; where[j] = xp; }
            }
        }

        [[nodiscard]] T x_at(std::size_t i) const noexcept { return i == n ? T(1) : static_cast<T>(i) * h; }
        [[nodiscard]] T power(T x) const noexcept {
            const T a = tx->amplitude(x) * rx->amplitude(x);
            return a * a;
        }

        [[nodiscard]] T golden_max(T lo, T hi) const noexcept {
            const T r = T(0.6180339887498948482);
            T x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
            T f1 = power(x1), f2 = power(x2);
            for (int k = 0; k < 100 && hi - lo > T(4) * std::numeric_limits<T>::epsilon(); ++k) {
                if (f1 < f2) {
                    lo = x1; x1 = x2; f1 = f2; x2 = lo + r * (hi - lo); f2 = power(x2);
                } else {
                    hi = x2; x2 = x1; f2 = f1; x1 = hi - r * (hi - lo); f1 = power(x1);
                }
            }
            return f1 > f2 ? x1 : x2;
        }

        /// Bisects [lo, hi], W(lo) >= level > W(hi), for the crossing; returns the outer end.
        [[nodiscard]] T crossing(T lo, T hi, T level) const noexcept {
            for (int k = 0; k < 100 && hi - lo > T(4) * std::numeric_limits<T>::epsilon(); ++k) {
                const T mid = (lo + hi) / T(2);
                (power(mid) >= level ? lo : hi) = mid;
            }
            return hi;
        }

        /// The largest x in [0, cap] where W reaches `level` (<= 1), on the outer side of the crossing
        /// (0 when only x = 0 does).
        [[nodiscard]] T outermost(T level, T cap = T(1)) const noexcept {
            if (power(cap) >= level) return cap;
            std::size_t j = std::min(static_cast<std::size_t>(cap / h), n - 1);
            if (cap < x_at(j + 1)) {
                // The interval holding the cap: its tabulated peak may lie beyond the cap, so search [x_j, cap].
                T xp = golden_max(x_at(j), cap);
                if (power(x_at(j)) > power(xp)) xp = x_at(j);
                if (power(xp) >= level) return crossing(xp, cap, level);
            } else {
                ++j;
            }
            while (j-- > 0) {
                // W(where) >= level > W(x_{j+1}) (the intervals further out stayed below the level).
                if (top[j] >= level) return crossing(where[j], x_at(j + 1), level);
            }
            return T(0); // not reached: W(0) = 1 >= level
        }
    };

    /// |a| <= asin U with U the outermost u where W_u reaches the threshold t. For the depression, a direction
    /// with u in grid interval j needs W_v(v) >= t / top_u[j]; with v = cos a sin(e - tau), and e - tau held in
    /// [-pi/2, pi/2] by the baffle and in [-pi/2 - tau, pi/2 - tau] by |e| <= pi/2, |sin(e - tau)| on each side
    /// is at most V / sqrt(1 - u_{j+1}^2), V the outermost v up to that side's limit where W_v reaches
    /// t / top_u[j]. The bound is the largest of these over the intervals where top_u[j] >= t.
    void compute_extent() {
        const T level = db_to_power(p_.threshold_db);
        const axis_profile along(tx_along_, rx_along_);
        const axis_profile vertical(tx_vertical_, rx_vertical_);
        const T u_max = along.outermost(level);
        const T cap_down = std::cos(std::max(T(0), tilt_rad_)); // sin of the largest reachable e - tau
        const T cap_up = std::cos(std::min(T(0), tilt_rad_));   // sin of the largest reachable tau - e
        T sin_down = 0, sin_up = 0;
        for (std::size_t j = 0; j < along.n; ++j) {
            if (along.top[j] < level) continue;
            const T needed = std::min(T(1), level / along.top[j]);
            const T u_end = along.x_at(j + 1);
            const T c = std::sqrt(std::max(T(0), T(1) - u_end * u_end));
            const auto ratio = [&](T v) { return c > v ? v / c : T(1); };
            sin_down = std::max(sin_down, ratio(vertical.outermost(needed, cap_down)));
            sin_up = std::max(sin_up, ratio(vertical.outermost(needed, cap_up)));
            if (sin_down >= T(1) && sin_up >= T(1)) break;
        }
        const auto angle = [](T s) { return s >= T(1) ? half_pi_v<T> : std::asin(s); };
        const T along_rad = angle(u_max);
        extent_ = beam_extent<T>{-along_rad, along_rad, std::max(tilt_rad_ - angle(sin_up), -half_pi_v<T>),
                                 std::min(tilt_rad_ + angle(sin_down), half_pi_v<T>)};
    }

    planar_array_params<T> p_;
    T wavelength_m_{};
    T tilt_rad_{};
    axis_model tx_along_{}, tx_vertical_{}, rx_along_{}, rx_vertical_{};
    beam_extent<T> extent_{};
};

static_assert(Beam<planar_array<float>> && Beam<planar_array<double>>);

} // namespace sss::beam

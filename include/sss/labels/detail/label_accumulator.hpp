#pragma once
/// \file
/// Internal to labels/ground_truth.hpp: echo energy per sample, kept apart by where it came from.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "sss/core/detail/force_inline.hpp"
#include "sss/receiver/pulse.hpp"

namespace sss::detail {

/// How the receiver shows an echo (receiver/time_sampler.hpp): power arriving at t shows at t - d + tau, d the clock's
/// delay (pulse::filter_delay_s) and tau spread as the pulse's power envelope p over [w0, w1]: a burst's whole length;
/// a compressed chirp's main lobe, its peak +-1/B (its sidelobes, 13 dB down and falling, are not what an image shows
/// as the echo). C(y) is the envelope's energy before y and G(y) its integral, both over the window's energy:
/// power spread evenly over arrivals [t0, t1] shows before x a share (G(x + d - t0) - G(x + d - t1)) / (t1 - t0).
/// C is tabulated at 1024 steps of the window (exact for a burst, whose C is known in closed form at the steps, and
/// linear between them for a rectangular one) and taken as linear between them; G is its exact integral.
class echo_smear {
public:
    explicit echo_smear(const pulse& p) {
        const bool chirp = p.shape == pulse_shape::lfm;
        d_ = p.filter_delay_s();
        w0_ = chirp ? std::max(0.0, p.length_s - 1.0 / p.bandwidth_hz) : 0.0;
        w1_ = chirp ? std::min(p.duration_s(), p.length_s + 1.0 / p.bandwidth_hz) : p.duration_s();
        step_ = (w1_ - w0_) / double(steps);
        c_.assign(steps + 1, 0.0);
        if (chirp) { // 4-point Gauss-Legendre over each step
            static constexpr double gx[4] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
            static constexpr double gw[4] = {0.1739274225844904, 0.3260725774155096, 0.3260725774155096, 0.1739274225844904};
            for (std::size_t i = 0; i < steps; ++i) {
                double piece = 0.0;
                for (std::size_t g = 0; g < 4; ++g) piece += gw[g] * p.power(w0_ + (double(i) + gx[g]) * step_);
                c_[i + 1] = c_[i] + piece * step_;
            }
        } else {
            for (std::size_t i = 0; i <= steps; ++i) c_[i] = p.cumulative(w0_ + double(i) * step_);
        }
        const double energy = c_.back();
        g_.assign(steps + 1, 0.0);
        if (!(step_ > 0.0) || !std::isfinite(1.0 / step_) || !(energy > 0.0) || !std::isfinite(energy)) {
            // A pulse too short to hold: shown at arrival (inverse_step() stays 0).
            w1_ = w0_;
            std::fill(c_.begin(), c_.end(), 0.0);
            return;
        }
        for (double& c : c_) c /= energy;
        for (std::size_t i = 0; i < steps; ++i) g_[i + 1] = g_[i] + 0.5 * step_ * (c_[i] + c_[i + 1]);
        inv_step_ = 1.0 / step_;
    }

    /// The clock's delay d and the window [w0, w1] (s).
    [[nodiscard]] double delay_s() const noexcept { return d_; }
    [[nodiscard]] double window_begin_s() const noexcept { return w0_; }
    [[nodiscard]] double window_end_s() const noexcept { return w1_; }

    /// The share of the envelope's energy before y (s after the echo's arrival, on the receiver's clock plus d).
    [[nodiscard]] double energy_before(double y) const noexcept {
        if (!(y > w0_)) return 0.0;
        if (!(y < w1_)) return 1.0;
        const double x = (y - w0_) / step_;
        const auto i = std::min<std::size_t>(static_cast<std::size_t>(x), steps - 1);
        return c_[i] + (x - double(i)) * (c_[i + 1] - c_[i]);
    }
    /// Its integral from w0 to y (s).
    [[nodiscard]] double energy_integral(double y) const noexcept {
        if (inv_step_ == 0.0) return y > w0_ ? y - w0_ : 0.0; // no window: all of the energy at w0
        return integral_at_step((y - w0_) * inv_step_);
    }
    /// The same integral at x = (y - w0) / step, the table's own coordinate (label_accumulator::spread steps in it).
    [[nodiscard]] SSS_FORCE_INLINE double integral_at_step(double x) const noexcept {
        if (!(x > 0.0)) return 0.0;
        if (!(x < double(steps))) return g_[steps] + (x - double(steps)) * step_;
        const auto i = std::min<std::size_t>(static_cast<std::size_t>(x), steps - 1);
        const double f = x - double(i);
        return g_[i] + step_ * f * (c_[i] + 0.5 * f * (c_[i + 1] - c_[i]));
    }
    /// 1 / the table's step (1/s; 0 for a pulse too short to hold).
    [[nodiscard]] double inverse_step() const noexcept { return inv_step_; }

private:
    static constexpr std::size_t steps = 1024;
    double d_ = 0.0, w0_ = 0.0, w1_ = 0.0, step_ = 0.0, inv_step_ = 0.0;
    std::vector<double> c_, g_;
};

/// Energy per sample, kept apart by source.
struct label_accumulator {
    std::size_t n = 0;
    double dt = 1.0;
    std::vector<double> seabed, bare;           ///< seabed echo in the scene; the bare seabed's echo
    std::vector<double> seabed_best;            ///< largest single seabed contribution, with its ids:
    std::vector<std::uint32_t> seabed_region, seabed_material;
    std::vector<double> bare_best;
    std::vector<std::uint32_t> bare_region, bare_material;
    std::vector<std::uint32_t> ids;             ///< objects met on this line
    std::vector<std::uint32_t> classes;         ///< their class ids
    std::vector<std::vector<double>> echo, blocked, best_echo;
    std::vector<std::vector<std::uint32_t>> echo_material;
    double first_bare_s = std::numeric_limits<double>::infinity();   ///< the bare seabed's first echo (s)
    double last_bare_s = -std::numeric_limits<double>::infinity();   ///< the bare seabed's last direct echo (s)
    double first_seabed_s = std::numeric_limits<double>::infinity(); ///< the scene's first seabed echo (s)
    double last_seabed_s = -std::numeric_limits<double>::infinity(); ///< the scene's last direct seabed echo (s)
    bool met_object = false; ///< some ray of the scene's pass met an object (with or without echo power)

    const echo_smear* smear = nullptr; ///< how the receiver shows an echo (none: at its arrival alone)

    explicit label_accumulator(std::size_t samples, double dt_s, const echo_smear* shown = nullptr)
        : n(samples), dt(dt_s), seabed(samples), bare(samples), seabed_best(samples), seabed_region(samples),
          seabed_material(samples), bare_best(samples), bare_region(samples), bare_material(samples), smear(shown) {}

    std::size_t slot(std::uint32_t id, std::uint32_t cls) {
        for (std::size_t i = 0; i < ids.size(); ++i)
            if (ids[i] == id) return i;
        ids.push_back(id);
        classes.push_back(cls);
        echo.emplace_back(n, 0.0);
        blocked.emplace_back(n, 0.0);
        best_echo.emplace_back(n, 0.0);
        echo_material.emplace_back(n, 0u);
        return ids.size() - 1;
    }

    /// Adds the share w to total[k]; true when w is the largest single share at k yet (then kept in best[k]), for
    /// the caller to record its ids.
    static bool add(std::vector<double>& total, std::vector<double>& best, std::size_t k, double w) {
        total[k] += w;
        if (!(w > best[k])) return false;
        best[k] = w;
        return true;
    }

    /// Calls f(k, share) for every sample k that power arriving evenly over [t0, t1] (s) shows in, share: the fraction
    /// of it there, as the receiver shows it (`smear`; without: the fraction of the span in k).
    template <class F> void spread(double t0, double t1, F&& f) const {
        if (t1 < t0) std::swap(t0, t1);
        if (smear != nullptr) {
            const double d = smear->delay_s();
            const double a = (t0 - d + smear->window_begin_s()) / dt, b = (t1 - d + smear->window_end_s()) / dt;
            if (!(a < double(n)) || !(b >= 0.0)) return;
            const double width = t1 - t0;
            const bool point = !(width > 1e-6 * dt);
            const double t_mid = 0.5 * (t0 + t1);
            const double shown_from = point ? t_mid - d + smear->window_begin_s() : t0 - d + smear->window_begin_s();
            const double shown_to = point ? t_mid - d + smear->window_end_s() : t1 - d + smear->window_end_s();
            // G(x + d - t) in the table's coordinate, (x - (t - d + w0)) / step: the difference first, so that it
            // stays finite for any pulse the table holds.
            const double inv = smear->inverse_step(), from1 = t1 - d + smear->window_begin_s(),
                         per_width = point ? 0.0 : 1.0 / width;
            // The share shown before x (s): none up to where the echo shows from, all of it past where it ends.
            const auto before = [&](double x) {
                if (x <= shown_from) return 0.0;
                if (x > shown_to) return 1.0;
                if (point) return smear->energy_before(x + d - t_mid);
                if (inv == 0.0) return std::clamp((x - shown_from) * per_width, 0.0, 1.0); // no window: as it arrives
                return std::clamp((smear->integral_at_step((x - shown_from) * inv) -
                                   smear->integral_at_step((x - from1) * inv)) * per_width, 0.0, 1.0);
            };
            // One sample more than b reaches: the rounding of b must not cut off the last share.
            const auto k0 = static_cast<std::size_t>(std::max(0.0, a));
            const std::size_t k1 = b + 1.0 < double(n) ? static_cast<std::size_t>(std::max(0.0, b)) + 1 : n - 1;
            double lo = before(double(k0) * dt);
            for (std::size_t k = k0; k <= k1; ++k) {
                const double hi = before(double(k + 1) * dt);
                if (hi > lo) f(k, hi - lo);
                lo = hi;
            }
            return;
        }
        const double a = t0 / dt, b = t1 / dt;
        if (!(a < double(n)) || !(b >= 0.0)) return;
        if (b - a <= 0.0) {
            f(static_cast<std::size_t>(a), 1.0);
            return;
        }
        const auto k0 = static_cast<std::size_t>(std::max(0.0, a));
        const std::size_t k1 = std::min(n - 1, static_cast<std::size_t>(b));
        for (std::size_t k = k0; k <= k1; ++k) {
            const double lo = std::max(a, double(k)), hi = std::min(b, double(k + 1));
            if (hi > lo) f(k, (hi - lo) / (b - a));
        }
    }
};

} // namespace sss::detail

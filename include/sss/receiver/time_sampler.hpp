#pragma once
/// \file
/// Resampling echoes into uniform time samples without distorting the signal.
///
/// Echo energy arrives as spans (a ray tube's power spread evenly over the delays between two adjacent rays)
/// and points (an isolated ray). The sampler keeps, per sub-bin j of width h = dt/q (q sub-bins per sample),
/// the exact zeroth and first moments of the echo-power density, M0_j = int rho ds and M1_j = int rho u ds
/// (u in [0, 1) the position within the sub-bin). Within each sub-bin the density is taken as the linear
/// function with those moments (its slope limited so that it never goes negative), and its convolution with the
/// pulse's power envelope p, averaged over each output sample, is applied exactly through precomputed kernels:
///
///     y_k = sum_{D, r}  M0_{q(k-D)+r} K0[D][r] + (M1 - M0/2)_{q(k-D)+r} K1[D][r],
///     K0[D][r] = int_0^1 v(x) du,  K1[D][r] = 12 int_0^1 v(x) (u - 1/2) du,  x = (r + u)/q,
///     v(x) = (1/dt) int_D^{D+1} p((y - x) dt) dt dy   (the share of an echo at delay (k - D + x) dt in sample k).
///
/// y_k is the mean received power over sample k. The result is exact for any density when the pulse lasts a
/// whole number of samples (the share is then linear within each sub-bin, and no slope is limited), and for
/// densities linear within each sub-bin otherwise. Energy is conserved exactly (the slope terms carry none):
/// sum_k y_k dt = (sum of deposits) x (pulse energy), up to echoes whose pulse runs past either end of the line.
/// Accumulation is in double for every scalar type.
///
/// The line runs on the receiver's clock: sample k covers [k dt, (k + 1) dt) after the transmission less the
/// pulse's filter delay d (pulse::filter_delay_s: a compressed chirp's T, so that an echo peaks at its arrival).
/// Deposits are kept at their delay less d, from -d on, so that an echo arriving within d of the transmission
/// still lands its envelope's part after time 0; echoes up to (samples) dt + d reach the line.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "sss/core/detail/gauss_legendre.hpp"
#include "sss/core/error.hpp"
#include "sss/receiver/pulse.hpp"

namespace sss {

class time_sampler {
public:
    /// Sub-bins per output sample.
    static constexpr std::size_t sub_bins = 8;

    /// \param samples   number of output samples (the line covers [0, samples dt))
    /// \param dt_s      sample interval (s)
    /// \param p         transmitted pulse
    time_sampler(std::size_t samples, double dt_s, const pulse& p) : n_(samples), dt_(dt_s), inv_h_(double(sub_bins) / dt_s) {
        sss::require_positive(dt_s, "time_sampler.dt_s");
        p.validate();
        delay_s_ = p.filter_delay_s();
        // The delay in samples, rounded up, and one more where there is one: an echo at time 0 is kept whatever
        // the rounding of delay / dt.
        lead_ = delay_s_ > 0.0 ? static_cast<std::size_t>(std::ceil(delay_s_ / dt_s)) + 1 : 0;
        lead_bins_ = static_cast<double>(lead_ * sub_bins);
        m0_.assign((n_ + lead_) * sub_bins, 0.0);
        m1_.assign((n_ + lead_) * sub_bins, 0.0);
        build_kernels(p);
    }

    [[nodiscard]] std::size_t size() const noexcept { return n_; }
    [[nodiscard]] double dt_s() const noexcept { return dt_; }
    /// The receiver's clock's delay (s): pulse::filter_delay_s. Echoes arriving up to size() dt_s() + this reach
    /// the line.
    [[nodiscard]] double delay_s() const noexcept { return delay_s_; }
    /// Kernel taps, [D * sub_bins + r].
    [[nodiscard]] const std::vector<double>& kernel0() const noexcept { return k0_; }
    [[nodiscard]] const std::vector<double>& kernel1() const noexcept { return k1_; }

    /// Forget all deposits.
    void clear() noexcept {
        std::fill(m0_.begin(), m0_.end(), 0.0);
        std::fill(m1_.begin(), m1_.end(), 0.0);
    }

    /// Echo power `power` arriving at a single delay t_s (s).
    void add_point(double t_s, double power) noexcept {
        if (!(t_s >= 0.0)) return;
        const double x = (t_s - delay_s_) * inv_h_ + lead_bins_;
        if (!(x >= 0.0 && x < static_cast<double>(m0_.size()))) return;
        const auto j = static_cast<std::size_t>(x);
        m0_[j] += power;
        m1_[j] += power * (x - static_cast<double>(j));
    }

    /// Echo power `power` spread evenly over the delays between t0_s and t1_s (either order).
    void add_span(double t0_s, double t1_s, double power) noexcept {
        const double t_lo = std::min(t0_s, t1_s), t_hi = std::max(t0_s, t1_s);
        double a = t_lo * inv_h_;
        const double b = t_hi * inv_h_;
        const double width = b - a;
        if (!(width > 1e-9)) {
            add_point(0.5 * (t0_s + t1_s), power);
            return;
        }
        const double density = power / width; // power per sub-bin of delay
        // Into the bins: delays less the clock's delay, from -lead_ samples; delays before 0 are dropped.
        a = (std::max(t_lo, 0.0) - delay_s_) * inv_h_ + lead_bins_;
        const double b_bins = (t_hi - delay_s_) * inv_h_ + lead_bins_;
        const auto bins = static_cast<double>(m0_.size());
        if (!(a < bins) || !(b_bins > 0.0) || !(t_hi > 0.0)) return;
        a = std::max(a, 0.0);
        const double end = std::min(b_bins, bins);
        auto j = static_cast<std::size_t>(a);
        while (a < end && j < m0_.size()) {
            const double bin_end = std::min(static_cast<double>(j + 1), end);
            const double share = density * (bin_end - a);
            m0_[j] += share;
            m1_[j] += share * (0.5 * (a + bin_end) - static_cast<double>(j));
            a = bin_end;
            ++j;
        }
    }

    /// Writes the mean received power of each sample into `out` (resized to size()).
    template <class T> void render(std::vector<T>& out) const {
        out.assign(n_, T(0));
        const std::size_t taps = k0_.size() / sub_bins;
        for (std::size_t k = 0; k < n_; ++k) {
            double y = 0.0;
            const std::size_t kk = k + lead_; // the sample's place among the bins, which start lead_ samples early
            const std::size_t dmax = std::min(taps - 1, kk);
            for (std::size_t d = 0; d <= dmax; ++d) {
                const std::size_t base = (kk - d) * sub_bins;
                for (std::size_t r = 0; r < sub_bins; ++r) {
                    const double m0 = m0_[base + r];
                    double slope = m1_[base + r] - 0.5 * m0;
                    // Keep the linear density non-negative (mean position within [1/3, 2/3] of the sub-bin).
                    if (!exact_) slope = std::clamp(slope, -m0 / 6.0, m0 / 6.0);
                    y += m0 * k0_[d * sub_bins + r] + slope * k1_[d * sub_bins + r];
                }
            }
            out[k] = static_cast<T>(std::max(y, 0.0)); // only rounding can make y negative
        }
    }

private:
    void build_kernels(const pulse& p) {
        const double tau = p.duration_s() / dt_; // pulse length in samples
        // A compressed chirp's cumulative energy has no closed form: tabulated once, 64 steps per 1/B, and
        // interpolated linearly (its derivative, the envelope, is smooth at that scale).
        std::vector<double> table;
        double step = 0.0;
        if (p.shape == pulse_shape::lfm) {
            step = 1.0 / (64.0 * p.bandwidth_hz);
            const auto steps = static_cast<std::size_t>(std::ceil(p.duration_s() / step));
            step = p.duration_s() / double(steps);
            table.resize(steps + 1, 0.0);
            for (std::size_t i = 0; i < steps; ++i) {
                double piece = 0.0;
                for (std::size_t g = 0; g < 4; ++g) piece += gl4_w[g] * p.power((double(i) + gl4_x[g]) * step);
                table[i + 1] = table[i] + piece * step;
            }
        }
        const auto cumulative = [&](double t) {
            if (table.empty()) return p.cumulative(t);
            const double x = std::clamp(t / step, 0.0, double(table.size() - 1));
            const auto i = std::min(static_cast<std::size_t>(x), table.size() - 2);
            return table[i] + (x - double(i)) * (table[i + 1] - table[i]);
        };
        exact_ = std::abs(tau * double(sub_bins) - std::round(tau * double(sub_bins))) < 1e-9;
        const auto taps = static_cast<std::size_t>(std::ceil(tau)) + 2;
        k0_.assign(taps * sub_bins, 0.0);
        k1_.assign(taps * sub_bins, 0.0);
        // 8-point Gauss-Legendre on [0, 1].
        const auto& gx = sss::detail::gauss_legendre8_x;
        const auto& gw = sss::detail::gauss_legendre8_w;
        const double q = double(sub_bins);
        for (std::size_t d = 0; d < taps; ++d) {
            for (std::size_t r = 0; r < sub_bins; ++r) {
                const double dd = static_cast<double>(d), rr = static_cast<double>(r);
                // v(x) = [C((d + 1 - x) dt) - C((d - x) dt)] / dt, C the envelope's cumulative energy, x = (r + u)/q.
                auto v = [&](double u) {
                    const double x = (rr + u) / q;
                    return (cumulative((dd + 1.0 - x) * dt_) - cumulative((dd - x) * dt_)) / dt_;
                };
                // v has kinks where its arguments reach 0 or the pulse end: integrate piecewise between them.
                std::array<double, 6> cuts{0.0, 1.0, q * dd - rr, q * (dd + 1.0) - rr, q * (dd - tau) - rr,
                                           q * (dd + 1.0 - tau) - rr};
                std::sort(cuts.begin(), cuts.end());
                double s0 = 0.0, s1 = 0.0;
                double lo = 0.0;
                for (double c : cuts) {
                    const double hi = std::clamp(c, 0.0, 1.0);
                    if (hi <= lo) continue;
                    for (std::size_t g = 0; g < gx.size(); ++g) {
                        const double u = lo + (hi - lo) * gx[g];
                        const double w = (hi - lo) * gw[g] * v(u);
                        s0 += w;
                        s1 += w * (u - 0.5);
                    }
                    lo = hi;
                }
                k0_[d * sub_bins + r] = s0;
                k1_[d * sub_bins + r] = 12.0 * s1;
            }
        }
    }

    // 4-point Gauss-Legendre on [0, 1].
    static constexpr std::array<double, 4> gl4_x{0.0694318442029737, 0.3300094782075719, 0.6699905217924281, 0.9305681557970263};
    static constexpr std::array<double, 4> gl4_w{0.1739274225844904, 0.3260725774155096, 0.3260725774155096, 0.1739274225844904};

    std::size_t n_;
    double dt_;
    double inv_h_;
    double delay_s_ = 0.0;   // the clock's delay: deposits are kept at their delay less this
    std::size_t lead_ = 0;   // samples of bins before time 0 (the delay, rounded up, and one)
    double lead_bins_ = 0.0; // lead_ in sub-bins
    bool exact_ = true;
    std::vector<double> m0_, m1_;
    std::vector<double> k0_, k1_;
};

} // namespace sss

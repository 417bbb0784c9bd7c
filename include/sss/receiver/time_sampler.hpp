#pragma once
/// \file
/// Resampling echoes into uniform time samples without distorting the signal.
///
/// Echo energy arrives as spans (a ray tube's power spread evenly over the delays between two adjacent rays)
/// and points (an isolated ray). The sampler keeps, per sample bin j of width dt, the exact zeroth and first
/// moments of the echo-power density over the bin, M0_j = int rho ds and M1_j = int rho u ds (u in [0, 1) the
/// position within the bin). Within each bin the density is taken as the linear function with those moments,
/// and its convolution with the pulse's power envelope p, averaged over each output bin, is applied exactly
/// through two precomputed kernels:
///
///     y_k = sum_d  M0_{k-d} K0_d + (M1_{k-d} - M0_{k-d}/2) K1_d,
///     K0_d = int_0^1 v_d(u) du,  K1_d = 12 int_0^1 v_d(u) (u - 1/2) du,  v_d(u) = int_d^{d+1} p((x - u) dt) dx.
///
/// y_k is the mean received power over sample k. The result is exact for any density whenever the pulse
/// lasts a whole number of samples (the overlap is then linear in u), and for densities linear within each bin
/// otherwise; energy is conserved exactly: sum_k y_k dt = (sum of deposits) x (pulse energy), up to echoes whose
/// pulse runs past the last sample. Accumulation is in double for every scalar type.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/receiver/pulse.hpp"

namespace sss {

class time_sampler {
public:
    /// \param samples   number of output samples (the line covers [0, samples dt))
    /// \param dt_s      sample interval (s)
    /// \param p         transmitted pulse
    time_sampler(std::size_t samples, double dt_s, const pulse& p)
        : n_(samples), dt_(dt_s), inv_dt_(1.0 / dt_s), m0_(samples, 0.0), m1_(samples, 0.0) {
        sss::detail::require_positive(dt_s, "time_sampler.dt_s");
        p.validate();
        build_kernels(p);
    }

    [[nodiscard]] std::size_t size() const noexcept { return n_; }
    [[nodiscard]] double dt_s() const noexcept { return dt_; }
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
        const double x = t_s * inv_dt_;
        if (!(x < static_cast<double>(n_))) return;
        const auto j = static_cast<std::size_t>(x);
        m0_[j] += power;
        m1_[j] += power * (x - static_cast<double>(j));
    }

    /// Echo power `power` spread evenly over the delays between t0_s and t1_s (either order).
    void add_span(double t0_s, double t1_s, double power) noexcept {
        double a = std::min(t0_s, t1_s) * inv_dt_;
        double b = std::max(t0_s, t1_s) * inv_dt_;
        const double width = b - a;
        if (!(width > 1e-9)) {
            add_point(0.5 * (t0_s + t1_s), power);
            return;
        }
        if (!(a < static_cast<double>(n_)) || !(b > 0.0)) return;
        const double density = power / width; // power per bin-width of delay
        a = std::max(a, 0.0);
        const double end = std::min(b, static_cast<double>(n_));
        auto j = static_cast<std::size_t>(a);
        while (a < end && j < n_) {
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
        const std::size_t taps = k0_.size();
        for (std::size_t k = 0; k < n_; ++k) {
            double y = 0.0;
            const std::size_t dmax = std::min(taps - 1, k);
            for (std::size_t d = 0; d <= dmax; ++d) {
                const std::size_t j = k - d;
                y += m0_[j] * k0_[d] + (m1_[j] - 0.5 * m0_[j]) * k1_[d];
            }
            out[k] = static_cast<T>(std::max(y, 0.0));
        }
    }

private:
    void build_kernels(const pulse& p) {
        const double tau = p.length_s * inv_dt_; // pulse length in samples
        const auto taps = static_cast<std::size_t>(std::ceil(tau)) + 2;
        k0_.assign(taps, 0.0);
        k1_.assign(taps, 0.0);
        // 8-point Gauss-Legendre on [0, 1].
        static constexpr std::array<double, 8> gx{0.0198550717512319, 0.1016667612931866, 0.2372337950418355,
                                                   0.4082826787521751, 0.5917173212478249, 0.7627662049581645,
                                                   0.8983332387068134, 0.9801449282487681};
        static constexpr std::array<double, 8> gw{0.0506142681451881, 0.1111905172266872, 0.1568533229389436,
                                                   0.1813418916891810, 0.1813418916891810, 0.1568533229389436,
                                                   0.1111905172266872, 0.0506142681451881};
        for (std::size_t d = 0; d < taps; ++d) {
            const double dd = static_cast<double>(d);
            // v_d(u) = [C((d + 1 - u) dt) - C((d - u) dt)] / dt with C the envelope's cumulative energy.
            auto v = [&](double u) { return (p.cumulative((dd + 1.0 - u) * dt_) - p.cumulative((dd - u) * dt_)) * inv_dt_; };
            // v_d has kinks where its arguments reach 0 or the pulse end: integrate piecewise between them.
            std::array<double, 6> cuts{0.0, 1.0, dd, dd + 1.0, dd - tau, dd + 1.0 - tau};
            std::sort(cuts.begin(), cuts.end());
            double s0 = 0.0, s1 = 0.0;
            double lo = 0.0;
            for (double c : cuts) {
                const double hi = std::clamp(c, 0.0, 1.0);
                if (hi <= lo) continue;
                for (std::size_t q = 0; q < gx.size(); ++q) {
                    const double u = lo + (hi - lo) * gx[q];
                    const double w = (hi - lo) * gw[q] * v(u);
                    s0 += w;
                    s1 += w * (u - 0.5);
                }
                lo = hi;
            }
            k0_[d] = s0;
            k1_[d] = 12.0 * s1;
        }
    }

    std::size_t n_;
    double dt_;
    double inv_dt_;
    std::vector<double> m0_, m1_;
    std::vector<double> k0_, k1_;
};

} // namespace sss

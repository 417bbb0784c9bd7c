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
/// The sum runs over every sample the pulse spans: for a long pulse (a chirp of milliseconds spans thousands of samples)
/// that is (taps x sub_bins) products per output sample, and the line is instead convolved in the Fourier domain:
/// the deposits' two sequences (M0 and the slopes) as one complex sequence, one transform forward, the kernels'
/// spectra (computed once, shared by copies of the sampler), one transform back, read every sub_bins-th value
/// (Oppenheim & Schafer, "Discrete-Time Signal Processing", 3rd ed., 2010, sec. 8.7: linear convolution by the DFT).
/// Its rounding is relative to the line's largest values (about 1e-16 of them), so a sample more than 90 dB below
/// them is summed directly; a sample with no deposit within the pulse's reach is exactly 0 either way, as the direct
/// sum makes it. render() takes the cheaper of the two (render_method), which for the default pulses (a few samples)
/// is the direct sum.
///
/// The line runs on the receiver's clock: sample k covers [k dt, (k + 1) dt) after the transmission less the
/// pulse's filter delay d (pulse::filter_delay_s: a compressed chirp's T, so that an echo peaks at its arrival).
/// Deposits are kept at their delay less d, from -d on, so that an echo arriving within d of the transmission
/// still lands its envelope's part after time 0; echoes up to (samples) dt + d reach the line.

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <limits>
#include <memory>
#include <vector>

#include "sss/core/detail/gauss_legendre.hpp"
#include "sss/core/error.hpp"
#include "sss/receiver/pulse.hpp"
#include "sss/seabed/fft.hpp"

namespace sss {

/// How time_sampler::render convolves the line with the pulse: the cheaper of the two (automatic), the direct sum
/// over the pulse's taps, or through the discrete Fourier transform.
enum class render_method : unsigned char { automatic, direct, fourier };

namespace detail {

/// A time sampler's kernels as spectra, for the Fourier path of time_sampler::render: the transform plan of the
/// convolution's length and the transforms of the two kernels, each sample's sub-bins in reverse order (so that the
/// line's value at sample k is the convolution at sub-bin (k + 1) sub_bins - 1).
struct sampler_spectra {
    seabed::fft_plan plan;
    std::vector<std::complex<double>> k0, k1;
    std::size_t taps = 0;   ///< taps the convolution reaches (at most the line's bins, in samples)
    std::size_t first = 0;  ///< the kernels' first and last non-zero values (reversed index): a sample's value
    std::size_t last = 0;   ///< depends on the bins (k + 1) q - 1 - [last, first] alone
};

} // namespace detail

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
        lead_ = lead_of(dt_s, p);
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

    /// Writes the mean received power of each sample into `out` (resized to size()), by `method` (render_method).
    template <class T> void render(std::vector<T>& out, render_method method = render_method::automatic) const {
        if (method == render_method::fourier || (method == render_method::automatic && fourier_pays_)) {
            render_fourier(out);
            return;
        }
        out.assign(n_, T(0));
        for (std::size_t k = 0; k < n_; ++k) out[k] = static_cast<T>(direct_sample(k));
    }

    /// The memory a sampler for `samples` samples at dt_s with pulse p holds (bytes, roughly): its sub-bins' two
    /// moments, its kernels, and where render() takes the Fourier path the kernels' spectra (shared by copies of the
    /// sampler: `shared`); and what each render() takes on top (`per_render`: the Fourier path's transform).
    struct memory {
        double per_copy = 0;   ///< the moments and kernels: every copy of the sampler (one per ping in flight)
        double shared = 0;     ///< the spectra and their transform plan, shared by copies
        double per_render = 0; ///< a render's transform buffer
    };
    [[nodiscard]] static memory memory_bytes(std::size_t samples, double dt_s, const pulse& p) noexcept {
        // Beyond any memory (and beyond size_t's range for the transform's length): unbounded.
        const double bins = double(samples) + (p.filter_delay_s() + p.duration_s()) / dt_s + 3.0;
        if (!(bins < 0x1p56)) {
            constexpr double inf = std::numeric_limits<double>::infinity();
            return {.per_copy = inf, .shared = inf, .per_render = inf};
        }
        const std::size_t lead = lead_of(dt_s, p), taps = taps_of(dt_s, p);
        const double length = double(fourier_length(samples, lead, taps));
        const double complex_bytes = double(sizeof(std::complex<double>));
        return {.per_copy = 2.0 * double(sizeof(double)) * (double(samples + lead) + double(taps)) * double(sub_bins),
                // two spectra, the plan's twiddles in both directions and its bit reversal table
                .shared = (4.0 * complex_bytes + double(sizeof(std::size_t))) * length,
                .per_render = complex_bytes * length};
    }

    /// Whether render() takes the Fourier path by default: where its cost, about 5 N log2 N for the two transforms of
    /// N values (the line's sub-bins and the kernel's, padded to a power of two), is below the direct sum's
    /// 2 x taps x sub-bins products per sample.
    [[nodiscard]] bool renders_by_fourier() const noexcept { return fourier_pays_; }

private:
    /// Sample k by the direct sum over the taps (the file comment's y_k).
    [[nodiscard]] double direct_sample(std::size_t k) const noexcept {
        const std::size_t taps = k0_.size() / sub_bins;
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
        return std::max(y, 0.0); // only rounding can make y negative
    }

    [[nodiscard]] std::shared_ptr<const detail::sampler_spectra> make_spectra() const {
        const std::size_t taps = std::min(k0_.size() / sub_bins, n_ + lead_);
        const std::size_t length = transform_length(n_, lead_, k0_.size() / sub_bins);
        auto sp = std::make_shared<detail::sampler_spectra>(detail::sampler_spectra{
            .plan = seabed::fft_plan(length), .k0 = {}, .k1 = {}, .taps = taps});
        sp->k0.assign(length, 0.0);
        sp->k1.assign(length, 0.0);
        for (std::size_t d = 0; d < taps; ++d)
            for (std::size_t r = 0; r < sub_bins; ++r) {
                sp->k0[d * sub_bins + (sub_bins - 1 - r)] = k0_[d * sub_bins + r];
                sp->k1[d * sub_bins + (sub_bins - 1 - r)] = k1_[d * sub_bins + r];
            }
        std::size_t first = length, last = 0;
        for (std::size_t z = 0; z < taps * sub_bins; ++z)
            if (sp->k0[z] != 0.0 || sp->k1[z] != 0.0) {
                first = std::min(first, z);
                last = z;
            }
        sp->first = first;
        sp->last = last;
        sp->plan.execute(std::span(sp->k0), seabed::fft_direction::forward);
        sp->plan.execute(std::span(sp->k1), seabed::fft_direction::forward);
        return sp;
    }
    /// The delay in samples, rounded up, and one more where there is one: an echo at time 0 is kept whatever the
    /// rounding of delay / dt.
    [[nodiscard]] static std::size_t lead_of(double dt_s, const pulse& p) noexcept {
        const double delay_s = p.filter_delay_s();
        return delay_s > 0.0 ? static_cast<std::size_t>(std::ceil(delay_s / dt_s)) + 1 : 0;
    }
    /// The kernels' taps: the pulse's length in samples, rounded up, and two (an echo spans one sample more).
    [[nodiscard]] static std::size_t taps_of(double dt_s, const pulse& p) noexcept {
        return static_cast<std::size_t>(std::ceil(p.duration_s() / dt_s)) + 2;
    }
    /// The length of the Fourier path's transforms: the line's bins and the kernel's reach (at most the line: a
    /// sample's sum stops at the line's first bin), without wrapping, to a power of two.
    [[nodiscard]] static std::size_t transform_length(std::size_t samples, std::size_t lead, std::size_t taps) noexcept {
        return seabed::next_power_of_two((samples + lead + std::min(taps, samples + lead)) * sub_bins);
    }
    /// The transform length of the Fourier path for `samples` samples, `lead` of them before time 0, and `taps`
    /// taps, or 0 where the direct sum costs less (renders_by_fourier).
    [[nodiscard]] static std::size_t fourier_length(std::size_t samples, std::size_t lead, std::size_t taps) noexcept {
        const std::size_t reach = std::min(taps, samples + lead);
        const std::size_t length = transform_length(samples, lead, taps);
        const double direct = 2.0 * double(samples) * double(reach) * double(sub_bins);
        return 5.0 * double(length) * std::log2(double(length)) < direct ? length : 0;
    }
    [[nodiscard]] bool fourier_cheaper() const noexcept { return fourier_length(n_, lead_, k0_.size() / sub_bins) != 0; }

    /// render() through the transforms (see the file comment). y_k = (A * K0r + S * K1r)[(kk + 1) q - 1], A the
    /// M0 sequence, S the slopes, K0r, K1r the kernels with each sample's sub-bins reversed, kk = k + lead_.
    template <class T> void render_fourier(std::vector<T>& out) const {
        using complex = std::complex<double>;
        // The spectra made in the constructor where the Fourier path pays; for a sampler that would not choose it
        // (render_method::fourier, as a test compares the two), made for this call.
        const std::shared_ptr<const detail::sampler_spectra> own = spectra_ ? spectra_ : make_spectra();
        const detail::sampler_spectra& sp = *own;
        const std::size_t length = sp.plan.size(), bins = m0_.size();
        std::vector<complex> z(length, complex(0.0, 0.0));
        for (std::size_t j = 0; j < bins; ++j) {
            const double m0 = m0_[j];
            double slope = m1_[j] - 0.5 * m0;
            if (!exact_) slope = std::clamp(slope, -m0 / 6.0, m0 / 6.0);
            z[j] = complex(m0, slope);
        }
        sp.plan.execute(std::span(z), seabed::fft_direction::forward);
        // The transforms of A and S from that of A + i S (both real): A^_k = (Z_k + conj Z_{N-k}) / 2,
        // S^_k = (Z_k - conj Z_{N-k}) / 2i; then Y = A^ K0^ + S^ K1^, a pair (k, N - k) at a time, in place.
        const std::size_t mask = length - 1;
        for (std::size_t k = 0; k <= length / 2; ++k) {
            const std::size_t m = (length - k) & mask;
            const complex zk = z[k], zm = z[m];
            auto y = [&](complex a, complex b, std::size_t i) {
                const complex fa = 0.5 * (a + std::conj(b));
                const complex fs = complex(0.0, -0.5) * (a - std::conj(b));
                return fa * sp.k0[i] + fs * sp.k1[i];
            };
            z[k] = y(zk, zm, k);
            if (m != k) z[m] = y(zm, zk, m);
        }
        sp.plan.execute(std::span(z), seabed::fft_direction::backward);
        // Read every sub_bins-th value, at (kk + 1) q - 1. A sample with no deposit where the kernels reach, bins
        // (kk + 1) q - 1 - [last, first], is exactly 0, as the direct sum gives it (a sliding count of deposits).
        out.assign(n_, T(0));
        if (sp.first > sp.last) return; // kernels of zeros
        const double scale = 1.0 / static_cast<double>(length);
        std::vector<double> y(n_, 0.0);
        std::vector<bool> reached(n_, false);
        double top = 0.0;
        std::size_t lo = 0, hi = 0, held = 0; // bins [lo, hi) counted, `held` of them with a deposit
        for (std::size_t k = 0; k < n_; ++k) {
            const std::size_t at = (k + lead_ + 1) * sub_bins - 1;
            const std::size_t end = at >= sp.first ? std::min(at - sp.first + 1, bins) : 0;
            const std::size_t begin = at >= sp.last ? at - sp.last : 0;
            for (; hi < end; ++hi) held += m0_[hi] != 0.0 || m1_[hi] != 0.0;
            for (; lo < std::min(begin, hi); ++lo) held -= m0_[lo] != 0.0 || m1_[lo] != 0.0;
            if (held == 0) continue;
            reached[k] = true;
            y[k] = std::max(z[at].real() * scale, 0.0);
            top = std::max(top, y[k]);
        }
        // The transforms' rounding is about 1e-16 of the line's largest values, whatever a sample's own level: a
        // sample far below them (more than 90 dB: after time-varied gain the far range of a long line can be) is
        // summed directly instead, so that every sample keeps its own relative accuracy (1e-6 or better).
        const double floor = fourier_floor * top;
        for (std::size_t k = 0; k < n_; ++k) {
            if (reached[k] && y[k] < floor) y[k] = direct_sample(k);
            out[k] = static_cast<T>(y[k]);
        }
    }
    /// Below this fraction of the line's largest value, render_fourier sums a sample directly.
    static constexpr double fourier_floor = 1e-9;

    void build_kernels(const pulse& p) {
        const double tau = p.duration_s() / dt_; // pulse length in samples (taps_of)
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
        const std::size_t taps = taps_of(dt_, p);
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
        fourier_pays_ = fourier_cheaper();
        if (fourier_pays_) spectra_ = make_spectra();
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
    bool fourier_pays_ = false;
    std::shared_ptr<const detail::sampler_spectra> spectra_; // where fourier_pays_: immutable, shared by copies
};

} // namespace sss

#pragma once
/// \file
/// Speckle that belongs to the seabed: Rayleigh (fully developed) and K-distributed, on top of the mean power.
///
/// A resolution cell holds many scatterers whose echoes add with random phases, so the received complex
/// amplitude is circular Gaussian and the intensity exponential about its mean (Goodman, "Speckle Phenomena in
/// Optics", 2007). Here the scatterers are complex Gaussian amplitudes a_c of unit power fixed to a lattice on
/// the seabed (cells keyed by seed, lattice index and survey epoch through a counter-based hash: no generator
/// state), and the field of sample k of a ping is the linear filter
///
///     z_k = sum_c h(u_c) w(t_k - t_c) a_c,    E|z_k|^2 = sum_c h(u_c)^2 w(t_k - t_c)^2,
///
/// with t_c the cell's two-way time (flat seabed at the towfish's altitude), w the pulse's amplitude envelope
/// (sqrt of its power envelope; for a compressed chirp its signed autocorrelation, main lobe and 8 sidelobes
/// each side) and h the two-way along-track co-array of a transducer of length L: the
/// triangle h(u) = max(0, 1 - 2|u|/L) of the transmit and receive apertures' phase-centre positions. Then
///
/// - across track, samples dt apart share the cells of both their pulse windows: intensity correlation
///   |rho_a(dt)|^2, rho_a the pulse's normalised amplitude autocorrelation (rectangular CW: 1 - |dt|/tau);
/// - along track, pings d apart see the same cells through apertures shifted by d: field correlation is the
///   normalised overlap of the co-array with its shifted copy, with u = 2d/L,
///       rho(d) = 1 - 3u^2/2 + 3u^3/4 (u <= 1),  (2 - u)^3/4 (1 <= u <= 2),  0 beyond (d >= L)
///   (the translated-aperture principle of the van Cittert-Zernike theorem, as used for synthetic aperture sonar
///   micronavigation: Bellettini & Pinto, IEEE J. Oceanic Eng. 27(4), 2002);
/// - the same ground seen again from the same place gives the same speckle, whatever the ping's index, thread
///   or pass; `survey_time_s` moves the scatterers slowly: each cell's amplitude is cos(theta) a_e + sin(theta)
///   a_(e+1), e and theta = (pi/2) (t / T + phi - e) from the survey time t over `decorrelation_time_s` T and
///   the cell's own phase phi (uniform in [0, 1), keyed by the cell): continuous in time, of unit power, and
///   over the cells its field correlation between times t and t + s T depends on s alone (`drift_correlation`),
///       rho(s) = (1 - s/2) cos(pi s / 2) + sin(pi s / 2) / pi  (0 <= s <= 2),  0 beyond;
///   with one phase for every cell it would hold only on average over where in an epoch t lies.
///
/// The received intensity is mean_k tex_k |z_k|^2 / E|z_k|^2: its expectation is the ray tracer's mean power
/// exactly. With a K shape nu, tex is a Gamma(nu) texture of unit mean attached to the seabed in square
/// patches (Jakeman & Pusey, IEEE Trans. Antennas Propag. 24, 1976; Abraham & Lyons, IEEE J. Oceanic Eng. 27(4),
/// 2002): intensity K-distributed with E[I^2]/E[I]^2 = 2 (1 + 1/nu); nu may differ per material (the simulator tells
/// a stage that asks which material's echo dominates each sample: coarse, patchy beds spikier than fine ones). With a scatterer density the shape follows
/// the resolution cell: nu = density x (range x along-track beam width) x (ground extent of the pulse's counting
/// extent `counting_extent_s`: a burst's length, 18/35 of it for Hann, about 1.5/B for a chirp).
///
/// The lattice is world-fixed in a frame turned to the nearest of 64 headings (5.625 degrees apart): a pass on
/// the same heading sees the same cells; another aspect sees other speckle, as a real seabed does. Along track it
/// is spaced L/3 (the overlap above is then met to within 0.003 on average over the pings' places), across
/// track c tau_res / (2 cells_per_pulse), tau_res the pulse's range resolution time (its length; 1/B for a chirp).
/// Cells within a pulse window are summed by prefix sums for a rectangular pulse (cost per sample independent of
/// the window), one by one otherwise. Samples with mean power but no seabed cell in their window (an object in
/// the water column, before the first return) take cells of a lattice of their own (other keys) at the towfish's
/// depth and the sample's range, summed in the same way: they correlate along track and across it as the seabed's
/// speckle does, and belong to a place (another line across track sees other cells).

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/detail/gauss_legendre.hpp"
#include "sss/core/error.hpp"
#include "sss/receiver/detail/counter_random.hpp"
#include "sss/receiver/line_stage.hpp"
#include "sss/receiver/pulse.hpp"

namespace sss {

struct speckle_params {
    double transducer_length_m = 0.5;        ///< along-track length L of the transducer (m), at least 1 mm
    double k_shape = 0.0;                    ///< K-distribution shape nu (> 0); 0: Rayleigh (nu infinite)
    std::vector<double> k_shape_by_material{};///< nu per material id (0: Rayleigh; ids beyond: the last);
                                              ///< empty: k_shape for every material
    double scatterer_density_per_m2 = 0.0;   ///< > 0 (at most 10^12): nu from the cell's area instead (scatterers per m^2)
    double along_beamwidth_rad = 0.0;        ///< along-track beam width for that area (rad); in (0, pi] with a density
    double texture_patch_m = 1.0;            ///< side of the square seabed patches one texture value covers (m)
    double survey_time_s = 0.0;              ///< time of the survey (s): speckle drifts as it grows (below 2^62 decorrelation times)
    double decorrelation_time_s = 0.0;       ///< time over which the scatterers renew (s); 0: never
    double cells_per_pulse = 4.0;            ///< seabed cells per pulse length across track, 2-64

    void validate() const {
        sss::require_positive(transducer_length_m, "speckle.transducer_length_m");
        // The lattice is spaced L/3 along track from the world's origin: below a millimetre its cells' indices run
        // out of a double's integers within a survey's extent.
        sss::require(transducer_length_m >= 1e-3, "speckle.transducer_length_m",
                     "must be at least 1 mm (sidescan transducers are 0.1 to 2 m long)");
        sss::require_non_negative(k_shape, "speckle.k_shape");
        for (std::size_t i = 0; i < k_shape_by_material.size(); ++i)
            sss::require_non_negative(k_shape_by_material[i], "speckle.k_shape_by_material[" + std::to_string(i) + "]");
        sss::require_in_range(scatterer_density_per_m2, 0.0, 1e12, "speckle.scatterer_density_per_m2");
        if (scatterer_density_per_m2 > 0.0) {
            sss::require_positive(along_beamwidth_rad, "speckle.along_beamwidth_rad");
            sss::require(along_beamwidth_rad <= pi_v<double>, "speckle.along_beamwidth_rad", "must be at most pi rad");
        }
        sss::require_positive(texture_patch_m, "speckle.texture_patch_m");
        sss::require_finite(survey_time_s, "speckle.survey_time_s");
        sss::require_non_negative(decorrelation_time_s, "speckle.decorrelation_time_s");
        // The survey's epoch (survey time over decorrelation time) is counted in a 64-bit integer.
        sss::require(!(decorrelation_time_s > 0.0) || std::abs(survey_time_s / decorrelation_time_s) < 0x1p62,
                     "speckle.survey_time_s", "over speckle.decorrelation_time_s must be below 2^62 (epochs)");
        sss::require_in_range(cells_per_pulse, 2.0, 64.0, "speckle.cells_per_pulse");
    }
};

/// Normalised overlap of the two-way co-array of a transducer of length L with its copy shifted by d: the
/// ping-to-ping field correlation of speckle (see the file comment). Zero for d >= L.
[[nodiscard]] inline double coarray_overlap(double d_m, double length_m) noexcept {
    const double u = 2.0 * std::abs(d_m) / length_m;
    if (u <= 1.0) return 1.0 - 1.5 * u * u + 0.75 * u * u * u;
    if (u <= 2.0) return (2.0 - u) * (2.0 - u) * (2.0 - u) / 4.0;
    return 0.0;
}

/// Field correlation of the seabed's speckle between survey times s decorrelation times apart (see the file
/// comment): (1 - s/2) cos(pi s / 2) + sin(pi s / 2) / pi for |s| <= 2, 0 beyond. Intensities correlate as its square.
[[nodiscard]] inline double drift_correlation(double s) noexcept {
    const double a = std::abs(s);
    if (!(a < 2.0)) return 0.0;
    const double x = 0.5 * pi_v<double> * a;
    return (1.0 - 0.5 * a) * std::cos(x) + std::sin(x) / pi_v<double>;
}

/// The scatterer-counting extent of a pulse's power envelope p over [lo_s, hi_s] (s):
///
///     t_N = (int p dt)^2 / int p^2 dt,
///
/// the span whose scatterers one sample's intensity counts. With a Poisson number of scatterers of density n in the
/// cell, E[I^2] / E[I]^2 - 2 falls as 1 / (n t_N) when each is weighted by p (Jakeman, J. Phys. A 13, 1980): t_N is
/// the length of a rectangular burst, 18/35 of a Hann burst's and about 1.5/B for a compressed chirp.
[[nodiscard]] inline double counting_extent_s(const pulse& p, double lo_s, double hi_s) noexcept {
    if (!(hi_s > lo_s)) return 0.0;
    if (p.shape == pulse_shape::rectangular) return hi_s - lo_s;
    // 8-point Gauss-Legendre over pieces of a sixteenth of a burst or a quarter of a chirp's sidelobe.
    const auto& gx = sss::detail::gauss_legendre8_x;
    const auto& gw = sss::detail::gauss_legendre8_w;
    const double piece = p.shape == pulse_shape::lfm ? 0.25 / p.bandwidth_hz : p.length_s / 16.0;
    double s1 = 0.0, s2 = 0.0;
    for (double lo = lo_s; lo < hi_s; lo += piece) {
        const double hi = std::min(hi_s, lo + piece);
        for (std::size_t g = 0; g < gx.size(); ++g) {
            const double v = p.power(lo + (hi - lo) * gx[g]);
            s1 += (hi - lo) * gw[g] * v;
            s2 += (hi - lo) * gw[g] * v * v;
        }
    }
    return s2 > 0.0 ? s1 * s1 / s2 : 0.0;
}

/// The seabed's speckle field for one line at a time.
class seabed_speckle {
public:
    seabed_speckle() : seabed_speckle(speckle_params{}) {}
    /// Speckle of the given statistics; another seed, other speckle.
    explicit seabed_speckle(const speckle_params& p, std::uint64_t seed = 1) : p_(p), seed_(seed) { p_.validate(); }

    [[nodiscard]] const speckle_params& params() const noexcept { return p_; }
    [[nodiscard]] std::uint64_t seed() const noexcept { return seed_; }

    /// Complex amplitudes out[k] with E|out[k]|^2 = mean[k] (the expectation over seeds), for the line `ctx` names.
    template <Real T>
    void amplitudes(const std::vector<T>& mean, const line_context<T>& ctx, std::vector<std::complex<double>>& out) const {
        const std::size_t n = mean.size();
        out.assign(n, {0.0, 0.0});
        if (n == 0) return;
        const auto& table = sss::detail::half_normal_table();
        const double c = ctx.c_mps, dt = ctx.dt_s, tau = ctx.pulse.duration_s();
        const double delay = ctx.pulse.filter_delay_s(); // sample k holds the envelope at its time plus this
        const double H = std::max(double(ctx.altitude_m), 1e-3);
        const double L = p_.transducer_length_m;
        const double s_a = L / 3.0;
        const double s_c = c * ctx.pulse.resolution_s() / (2.0 * p_.cells_per_pulse);
        // A compressed chirp's window: its main lobe and 8 sidelobes each side (the rest holds < 1% of its energy).
        const bool chirp = ctx.pulse.shape == pulse_shape::lfm;
        const double lag_lo = chirp ? std::max(0.0, ctx.pulse.length_s - 8.0 / ctx.pulse.bandwidth_hz) : 0.0;
        const double lag_hi = chirp ? std::min(tau, ctx.pulse.length_s + 8.0 / ctx.pulse.bandwidth_hz) : tau;
        // The resolution cell's share of the window, for the K shape from a scatterer density: the pulse's counting
        // extent over the window (its whole length for a rectangular burst, less for a tapered one, about 1.5/B for
        // a chirp, whose window holds sidelobes too).
        const bool density_shape = p_.scatterer_density_per_m2 > 0.0;
        const double resolution_share = density_shape ? counting_extent_s(ctx.pulse, lag_lo, lag_hi) / (lag_hi - lag_lo) : 1.0;
        // The lattice frame: the nearest of 64 headings. delta: the ping's heading from it.
        const double step = 2.0 * pi_v<double> / 64.0;
        const double yaw = double(ctx.pose.yaw_rad);
        const double bin = std::round(yaw / step);
        const double yb = bin * step, delta = yaw - yb;
        const std::uint64_t heading_key = static_cast<std::uint64_t>(static_cast<std::int64_t>(bin) & 63);
        const double fx = std::sin(yb), fy = std::cos(yb);  // along track
        const double nx = std::cos(yb), ny = -std::sin(yb); // starboard
        const double px = double(ctx.pose.position.x), py = double(ctx.pose.position.y);
        const double a_p = px * fx + py * fy, c_p = px * nx + py * ny;
        const double sigma = ctx.line_side == side::starboard ? 1.0 : -1.0;
        const double cd = std::cos(delta), sd = std::sin(delta);
        // Bin-frame coordinates of the ground point at along offset u and ground range g on this side.
        const double along_per_g = -sigma * sd, cross_per_u = sd, cross_per_g = sigma * cd;

        // The survey's drift (file comment): whole epochs and the fraction of one; each cell adds its own phase.
        const bool drifting = p_.decorrelation_time_s > 0.0;
        std::int64_t epoch0 = 0;
        double epoch_frac = 0.0;
        if (drifting) {
            const double e = p_.survey_time_s / p_.decorrelation_time_s;
            const double fl = std::floor(e);
            epoch0 = static_cast<std::int64_t>(fl);
            epoch_frac = e - fl;
        }
        const std::uint64_t base = sss::detail::mix(sss::detail::mix(seed_, 0x5bec1eULL), heading_key);

        // Points: rows along track at the lattice's cell centres within the co-array, columns across at its cell
        // centres from nadir out, at horizontal distance g0 + m dg on this side.
        const double r_max = 0.5 * c * (dt * double(n) + delay);
        const double dg = s_c / cd;
        const double i_first = sigma > 0 ? std::ceil(c_p / s_c - 0.5) : std::floor(c_p / s_c - 0.5);
        const double g0 = sigma * ((i_first + 0.5) * s_c - c_p) / cd;
        const auto points_to = [&](double g) { return static_cast<std::size_t>(std::max(0.0, std::ceil((g - g0) / dg))) + 1; };
        const double j_lo = std::ceil((a_p - 0.5 * L * cd) / s_a - 0.5), j_hi = std::floor((a_p + 0.5 * L * cd) / s_a - 0.5);
        const auto index_in = [&](double g, std::size_t points) { // first point index at or beyond distance g
            return static_cast<std::size_t>(std::clamp(std::ceil((g - g0) / dg), 0.0, double(points)));
        };
        // The rows: at most four (the co-array is L cos(delta) long, the rows L/3 apart), counted in an integer.
        struct lattice_row {
            std::int64_t j;
            double u, h;
        };
        std::array<lattice_row, 8> rows{};
        std::size_t row_count = 0;
        double row_power = 0.0; // sum over rows of h^2
        {
            const double count = j_hi - j_lo + 1.0;
            const std::int64_t span = count > 0.0 ? static_cast<std::int64_t>(std::min(count, 8.0)) : 0;
            for (std::int64_t k = 0; k < span; ++k) {
                const double j = j_lo + static_cast<double>(k);
                const double u = ((j + 0.5) * s_a - a_p) / cd;
                const double h = std::max(0.0, 1.0 - 2.0 * std::abs(u) / L);
                if (h <= 0.0) continue;
                row_power += h * h;
                rows[row_count++] = {static_cast<std::int64_t>(j), u, h};
            }
        }
        // bb[m] for m in [from, to): the sum over rows of h times the cell under point m, cells keyed from key_base
        // (the seabed's, or the water column's). A cell holds one unit complex Gaussian; while the survey drifts,
        // cos(theta) a_e + sin(theta) a_(e+1) with its own phase in the epoch (a uniform offset keyed by the cell),
        // so that the correlation over a lag of survey time is the same wherever in an epoch it starts.
        const auto fill = [&](std::vector<std::complex<double>>& bb, std::size_t from, std::size_t to, std::uint64_t key_base) {
            const auto epoch_key = [&](std::int64_t e) { return sss::detail::mix(key_base, sss::detail::key_word(e)); };
            const std::uint64_t base_e0 = epoch_key(drifting ? epoch0 : 0);
            const std::uint64_t base_e1 = drifting ? epoch_key(epoch0 + 1) : 0, base_e2 = drifting ? epoch_key(epoch0 + 2) : 0;
            const std::uint64_t phase_base = sss::detail::mix(key_base, 0x9a5e0ffULL);
            for (std::size_t r = 0; r < row_count; ++r) {
                const auto [j, u, h] = rows[r];
                // The point's bin-frame coordinates in cells, stepped along the row; each cell's hash is one mix of
                // its row's key (kept while the row index stays) and its column index.
                const double xa0 = (a_p + u * cd + g0 * along_per_g) / s_a, dxa = dg * along_per_g / s_a;
                const double xc0 = (c_p + u * cross_per_u + g0 * cross_per_g) / s_c, dxc = dg * cross_per_g / s_c;
                std::int64_t row = sss::detail::floor_to_int(xa0 + double(from) * dxa);
                std::uint64_t k0 = 0, k1 = 0, k2 = 0, kp = 0;
                const auto row_keys = [&] {
                    k0 = sss::detail::mix(base_e0, sss::detail::key_word(row));
                    if (drifting) {
                        k1 = sss::detail::mix(base_e1, sss::detail::key_word(row));
                        k2 = sss::detail::mix(base_e2, sss::detail::key_word(row));
                        kp = sss::detail::mix(phase_base, sss::detail::key_word(row));
                    }
                };
                row_keys();
                for (std::size_t m = from; m < to; ++m) {
                    const double fm = double(m);
                    const std::int64_t cj = sss::detail::floor_to_int(xa0 + fm * dxa);
                    const std::int64_t ci = sss::detail::floor_to_int(xc0 + fm * dxc);
                    if (cj != row) {
                        row = cj;
                        row_keys();
                    }
                    const std::uint64_t col = sss::detail::key_word(ci);
                    if (!drifting) {
                        const std::complex<float> a = sss::detail::complex_gaussian(sss::detail::mix_fast(k0, col), table);
                        bb[m] = {bb[m].real() + h * double(a.real()), bb[m].imag() + h * double(a.imag())};
                        continue;
                    }
                    double e = epoch_frac + sss::detail::uniform_open(sss::detail::mix_fast(kp, col));
                    const bool later = e >= 1.0; // the cell's phase carries it into the next epoch
                    if (later) e -= 1.0;
                    const double theta = 0.5 * pi_v<double> * e;
                    const std::complex<float> a = sss::detail::complex_gaussian(sss::detail::mix_fast(later ? k1 : k0, col), table);
                    const std::complex<float> a2 = sss::detail::complex_gaussian(sss::detail::mix_fast(later ? k2 : k1, col), table);
                    const double wn = std::cos(theta), wx = std::sin(theta);
                    const double re = wn * double(a.real()) + wx * double(a2.real());
                    const double im = wn * double(a.imag()) + wx * double(a2.imag());
                    bb[m] = {bb[m].real() + h * re, bb[m].imag() + h * im};
                }
            }
        };
        const bool rect = ctx.pulse.shape == pulse_shape::rectangular;
        const auto prefix_sums = [&](std::vector<std::complex<double>>& bb) { // bb[m] becomes the sum of points [0, m)
            std::complex<double> acc{0.0, 0.0};
            for (auto& v : bb) {
                const std::complex<double> x = v;
                v = acc;
                acc += x;
            }
            bb.push_back(acc);
        };
        // Ground range of the delays a sample's window holds: sample k sees scatterers at two-way times
        // [t_k - lag_hi, t_k - lag_lo], t_k its centre on the envelope's clock (the receiver's, plus its delay).
        const auto window = [&](std::size_t k, double& g_lo, double& g_hi, double& r_lo, double& r_hi) {
            const double t_k = (double(k) + 0.5) * dt + delay;
            r_hi = std::max(0.0, 0.5 * c * (t_k - lag_lo));
            r_lo = std::max(0.0, 0.5 * c * (t_k - lag_hi));
            g_hi = std::sqrt(std::max(0.0, r_hi * r_hi - H * H));
            g_lo = std::sqrt(std::max(0.0, r_lo * r_lo - H * H));
        };
        // The field of sample k from points [m_lo, m_hi) of bb at distance g with two-way time 2 sqrt(g^2 + h^2) / c,
        // and its expected power.
        const auto field = [&](const std::vector<std::complex<double>>& bb, std::size_t k, std::size_t m_lo, std::size_t m_hi,
                               double height, std::complex<double>& z, double& power) {
            z = {0.0, 0.0};
            power = 0.0;
            if (!(m_hi > m_lo) || !(row_power > 0.0)) return;
            if (rect) {
                z = bb[m_hi] - bb[m_lo];
                power = row_power * double(m_hi - m_lo);
                return;
            }
            const double t_k = (double(k) + 0.5) * dt + delay;
            for (std::size_t m = m_lo; m < m_hi; ++m) {
                const double g = g0 + double(m) * dg;
                const double w = ctx.pulse.amplitude(t_k - 2.0 * std::sqrt(g * g + height * height) / c);
                z += w * bb[m];
                power += w * w;
            }
            power *= row_power;
        };

        // The seabed's points, out to the line's last range; only those some sample with echo power sees get cells.
        const std::size_t points = points_to(std::sqrt(std::max(0.0, r_max * r_max - H * H)));
        std::vector<std::complex<double>> b(points, {0.0, 0.0});
        {
            std::size_t k0 = 0, k1 = n;
            while (k0 < n && !(double(mean[k0]) > 0.0)) ++k0;
            while (k1 > k0 && !(double(mean[k1 - 1]) > 0.0)) --k1;
            if (k0 < k1) {
                double gl = 0, gh = 0, rl = 0, rh = 0;
                window(k0, gl, gh, rl, rh);
                const std::size_t m_begin = index_in(gl, points);
                window(k1 - 1, gl, gh, rl, rh);
                fill(b, m_begin, index_in(gh, points), base);
            }
        }
        if (rect) prefix_sums(b);

        const std::uint64_t texture_base = sss::detail::mix(sss::detail::mix(seed_, 0x7e4757eULL), heading_key);
        const bool by_material = !p_.k_shape_by_material.empty() && ctx.materials.size() == n;
        const bool textured = p_.k_shape > 0.0 || p_.scatterer_density_per_m2 > 0.0 ||
                              std::any_of(p_.k_shape_by_material.begin(), p_.k_shape_by_material.end(), [](double v) { return v > 0.0; });
        std::int64_t last_pj = 0, last_pi = 0;
        double last_nu = -1.0, last_tex = 1.0;
        const auto finish = [&](std::size_t k, std::complex<double> z, double power, double g_lo, double g_hi, double r_lo,
                                double r_hi) {
            double tex = 1.0;
            if (textured) {
                const double g_mid = 0.5 * (g_lo + g_hi);
                double nu = p_.k_shape;
                if (by_material)
                    nu = p_.k_shape_by_material[std::min<std::size_t>(ctx.materials[k], p_.k_shape_by_material.size() - 1)];
                if (p_.scatterer_density_per_m2 > 0.0)
                    nu = std::max(1e-3, p_.scatterer_density_per_m2 * (0.5 * (r_lo + r_hi) * p_.along_beamwidth_rad) *
                                            std::max((g_hi - g_lo) * resolution_share, s_c));
                const auto pj = static_cast<std::int64_t>(std::floor((a_p + g_mid * along_per_g) / p_.texture_patch_m));
                const auto pi = static_cast<std::int64_t>(std::floor((c_p + g_mid * cross_per_g) / p_.texture_patch_m));
                if (!(nu > 0.0)) {
                    last_nu = -1.0; // Rayleigh here: no texture
                } else if (nu != last_nu || pj != last_pj || pi != last_pi) {
                    last_tex = sss::detail::gamma_unit_mean(
                        nu, sss::detail::mix(sss::detail::mix(texture_base, sss::detail::key_word(pj)), sss::detail::key_word(pi)));
                    last_nu = nu;
                    last_pj = pj;
                    last_pi = pi;
                }
                tex = nu > 0.0 ? last_tex : 1.0;
            }
            out[k] = z * std::sqrt(double(mean[k]) * tex / power);
        };
        std::vector<std::size_t> water; // samples whose window holds no seabed cell
        for (std::size_t k = 0; k < n; ++k) {
            if (!(double(mean[k]) > 0.0)) continue;
            double g_lo = 0, g_hi = 0, r_lo = 0, r_hi = 0;
            window(k, g_lo, g_hi, r_lo, r_hi);
            const std::size_t m_lo = index_in(g_lo, points), m_hi = index_in(g_hi, points);
            std::complex<double> z;
            double power = 0.0;
            if (rect && m_hi > m_lo && row_power > 0.0) { // the common case, inline
                z = b[m_hi] - b[m_lo];
                power = row_power * double(m_hi - m_lo);
            } else {
                field(b, k, m_lo, m_hi, H, z, power);
            }
            if (power > 0.0) finish(k, z, power, g_lo, g_hi, r_lo, r_hi);
            else water.push_back(k);
        }
        if (water.empty()) return;

        // No seabed cell in the window (an object in the water column, before the first return): scatterers on a
        // lattice of their own (other keys), at the towfish's depth and the sample's range, summed over the
        // co-array's rows and the pulse's window as the seabed's are, so that they correlate along track as the
        // co-array's overlap says, across track as the pulse's envelope does, and belong to a place across track.
        const std::size_t points_w = points_to(r_max);
        std::vector<std::complex<double>> bw(points_w, {0.0, 0.0});
        {
            double gl = 0, gh = 0, rl = 0, rh = 0;
            window(water.front(), gl, gh, rl, rh);
            const std::size_t m_begin = index_in(rl, points_w);
            window(water.back(), gl, gh, rl, rh);
            fill(bw, m_begin, index_in(rh, points_w), sss::detail::mix(base, 0xfa11bac4ULL));
        }
        if (rect) prefix_sums(bw);
        for (const std::size_t k : water) {
            double g_lo = 0, g_hi = 0, r_lo = 0, r_hi = 0;
            window(k, g_lo, g_hi, r_lo, r_hi);
            std::complex<double> z;
            double power = 0.0;
            field(bw, k, index_in(r_lo, points_w), index_in(r_hi, points_w), 0.0, z, power);
            if (!(power > 0.0)) { // no row within the co-array, or a window that holds no point: one Gaussian
                z = std::complex<double>(sss::detail::complex_gaussian(
                    sss::detail::mix(sss::detail::mix(base, 0xfa11bac5ULL), (std::uint64_t(k) << 1) | (sigma > 0 ? 1U : 0U)), table));
                power = 1.0;
            }
            finish(k, z, power, g_lo, g_hi, r_lo, r_hi);
        }
    }

private:
    speckle_params p_;
    std::uint64_t seed_ = 1;
};

} // namespace sss

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
///   or pass; `survey_time_s` moves the scatterers slowly: within an epoch of `decorrelation_time_s` the field is
///   cos(theta) a_e + sin(theta) a_(e+1), theta = (pi/2) (t / T - e), continuous in time and of unit power.
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
/// the water column) get a Gaussian per lattice row and sample, summed over the co-array's rows: they correlate along
/// track as the seabed's speckle does, and are independent from sample to sample.

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

/// The scatterer-counting extent of a pulse's power envelope p over [lo_s, hi_s] (s):
///
///     t_N = (int p dt)^2 / int p^2 dt,
///
/// the span whose scatterers one sample's intensity counts. With a Poisson number of scatterers of density n in the
/// cell, <I^2>/<I>^2 - 2 falls as 1 / (n t_N) when each is weighted by p (Jakeman, J. Phys. A 13, 1980): t_N is
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

        // Survey epoch and the weights of its two scatterer sets.
        std::int64_t epoch = 0;
        double w_now = 1.0, w_next = 0.0;
        if (p_.decorrelation_time_s > 0.0) {
            const double e = p_.survey_time_s / p_.decorrelation_time_s;
            const double fl = std::floor(e);
            epoch = static_cast<std::int64_t>(fl);
            const double theta = 0.5 * pi_v<double> * (e - fl);
            w_now = std::cos(theta);
            w_next = std::sin(theta);
        }
        const std::uint64_t base = sss::detail::mix(sss::detail::mix(seed_, 0x5bec1eULL), heading_key);
        const std::uint64_t base_now = sss::detail::mix(base, sss::detail::key_word(epoch));
        const std::uint64_t base_next = sss::detail::mix(base, sss::detail::key_word(epoch + 1));

        // Ground points: rows along track at the lattice's cell centres within the co-array, columns across at
        // its cell centres from nadir out to the line's last range.
        const double r_max = 0.5 * c * (dt * double(n) + delay);
        const double g_max = std::sqrt(std::max(0.0, r_max * r_max - H * H));
        const double dg = s_c / cd;
        const double i_first = sigma > 0 ? std::ceil(c_p / s_c - 0.5) : std::floor(c_p / s_c - 0.5);
        const double g0 = sigma * ((i_first + 0.5) * s_c - c_p) / cd;
        const auto points = static_cast<std::size_t>(std::max(0.0, std::ceil((g_max - g0) / dg))) + 1;
        const double j_lo = std::ceil((a_p - 0.5 * L * cd) / s_a - 0.5), j_hi = std::floor((a_p + 0.5 * L * cd) / s_a - 0.5);
        std::vector<std::complex<double>> b(points, {0.0, 0.0});
        const auto index_of = [&](double g) { // first point index at or beyond ground range g
            return static_cast<std::size_t>(std::clamp(std::ceil((g - g0) / dg), 0.0, double(points)));
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
        // Only the points some sample with echo power can see need their cells.
        std::size_t m_begin = points, m_end = 0;
        {
            std::size_t k0 = 0, k1 = n;
            while (k0 < n && !(double(mean[k0]) > 0.0)) ++k0;
            while (k1 > k0 && !(double(mean[k1 - 1]) > 0.0)) --k1;
            if (k0 < k1) {
                double gl = 0, gh = 0, rl = 0, rh = 0;
                window(k0, gl, gh, rl, rh);
                m_begin = index_of(gl);
                window(k1 - 1, gl, gh, rl, rh);
                m_end = index_of(gh);
            }
        }
        double row_power = 0.0; // sum over rows of h^2
        // The rows: at most four (the co-array is L cos(delta) long, the rows L/3 apart), counted in an integer.
        const double row_count = j_hi - j_lo + 1.0;
        const std::int64_t rows = row_count > 0.0 ? static_cast<std::int64_t>(std::min(row_count, 8.0)) : 0;
        std::array<std::pair<std::int64_t, double>, 8> row_weights{}; // each row's index and h, for the fallback below
        std::size_t weighted_rows = 0;
        for (std::int64_t k = 0; k < rows; ++k) {
            const double j = j_lo + static_cast<double>(k);
            const double u = ((j + 0.5) * s_a - a_p) / cd;
            const double h = std::max(0.0, 1.0 - 2.0 * std::abs(u) / L);
            if (h <= 0.0) continue;
            row_power += h * h;
            row_weights[weighted_rows++] = {static_cast<std::int64_t>(j), h};
            // The point's bin-frame coordinates in cells, stepped along the row; each cell's hash is one mix of
            // its row's key (kept while the row index stays) and its column index.
            const double xa0 = (a_p + u * cd + g0 * along_per_g) / s_a, dxa = dg * along_per_g / s_a;
            const double xc0 = (c_p + u * cross_per_u + g0 * cross_per_g) / s_c, dxc = dg * cross_per_g / s_c;
            std::int64_t row = sss::detail::floor_to_int(xa0 + double(m_begin) * dxa);
            std::uint64_t row_now = sss::detail::mix(base_now, sss::detail::key_word(row));
            std::uint64_t row_next = sss::detail::mix(base_next, sss::detail::key_word(row));
            for (std::size_t m = m_begin; m < m_end; ++m) {
                const double fm = double(m);
                const std::int64_t cj = sss::detail::floor_to_int(xa0 + fm * dxa);
                const std::int64_t ci = sss::detail::floor_to_int(xc0 + fm * dxc);
                if (cj != row) {
                    row = cj;
                    row_now = sss::detail::mix(base_now, sss::detail::key_word(row));
                    row_next = sss::detail::mix(base_next, sss::detail::key_word(row));
                }
                const std::complex<float> a = sss::detail::complex_gaussian(sss::detail::mix_fast(row_now, sss::detail::key_word(ci)), table);
                double re = double(a.real()), im = double(a.imag());
                if (w_next != 0.0) {
                    const std::complex<float> a2 = sss::detail::complex_gaussian(sss::detail::mix_fast(row_next, sss::detail::key_word(ci)), table);
                    re = w_now * re + w_next * double(a2.real());
                    im = w_now * im + w_next * double(a2.imag());
                }
                b[m] = {b[m].real() + h * re, b[m].imag() + h * im};
            }
        }
        const bool rect = ctx.pulse.shape == pulse_shape::rectangular;
        if (rect) { // prefix sums: b[m] becomes the sum of points [0, m)
            std::complex<double> acc{0.0, 0.0};
            for (std::size_t m = 0; m < points; ++m) {
                const std::complex<double> v = b[m];
                b[m] = acc;
                acc += v;
            }
            b.push_back(acc);
        }
        const std::uint64_t texture_base = sss::detail::mix(sss::detail::mix(seed_, 0x7e4757eULL), heading_key);
        const bool by_material = !p_.k_shape_by_material.empty() && ctx.materials.size() == n;
        const bool textured = p_.k_shape > 0.0 || p_.scatterer_density_per_m2 > 0.0 ||
                              std::any_of(p_.k_shape_by_material.begin(), p_.k_shape_by_material.end(), [](double v) { return v > 0.0; });
        std::int64_t last_pj = 0, last_pi = 0;
        double last_nu = -1.0, last_tex = 1.0;
        for (std::size_t k = 0; k < n; ++k) {
            const double y = double(mean[k]);
            if (!(y > 0.0)) continue;
            const double t_k = (double(k) + 0.5) * dt + delay;
            double g_lo = 0, g_hi = 0, r_lo = 0, r_hi = 0;
            window(k, g_lo, g_hi, r_lo, r_hi);
            const std::size_t m_lo = index_of(g_lo), m_hi = index_of(g_hi);
            std::complex<double> z{0.0, 0.0};
            double power = 0.0;
            if (m_hi > m_lo && row_power > 0.0) {
                if (rect) {
                    z = b[m_hi] - b[m_lo];
                    power = row_power * double(m_hi - m_lo);
                } else {
                    for (std::size_t m = m_lo; m < m_hi; ++m) {
                        const double g = g0 + double(m) * dg;
                        const double w = ctx.pulse.amplitude(t_k - 2.0 * std::sqrt(g * g + H * H) / c);
                        z += w * b[m];
                        power += w * w;
                    }
                    power *= row_power;
                }
            }
            if (!(power > 0.0)) {
                // No seabed cell in the window (an object in the water column): a Gaussian per lattice row, keyed by
                // the row, the sample and the side, summed over the co-array's rows as the seabed's cells are, so
                // that pings correlate along track as the co-array's overlap says (and drift with the survey time).
                const std::uint64_t side_sample = (std::uint64_t(k) << 1) | (sigma > 0 ? 1U : 0U);
                const auto row_gaussian = [&](std::uint64_t epoch_base, std::int64_t row) {
                    return std::complex<double>(sss::detail::complex_gaussian(
                        sss::detail::mix(sss::detail::mix(sss::detail::mix(epoch_base, 0xfa11bac4ULL),
                                                          sss::detail::key_word(row)),
                                         side_sample),
                        table));
                };
                z = {0.0, 0.0};
                for (std::size_t r = 0; r < weighted_rows; ++r) {
                    const auto [row, h] = row_weights[r];
                    std::complex<double> g = row_gaussian(base_now, row);
                    if (w_next != 0.0) g = w_now * g + w_next * row_gaussian(base_next, row);
                    z += h * g;
                }
                power = row_power;
                if (!(power > 0.0)) { // no row within the co-array (it cannot happen for a transducer of length > 0)
                    z = row_gaussian(base_now, static_cast<std::int64_t>(std::floor(a_p / s_a)));
                    power = 1.0;
                }
            }
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
            out[k] = z * std::sqrt(y * tex / power);
        }
    }

private:
    speckle_params p_;
    std::uint64_t seed_ = 1;
};

} // namespace sss

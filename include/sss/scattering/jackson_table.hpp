#pragma once
/// \file
/// A lookup table of the APL-UW backscattering cross section over grazing angle, for one sediment at one
/// frequency and water sound speed, so that a hot loop pays a square root, one interpolation and an exp
/// instead of the full model (TR 9407 Section IV; see jackson_terms.hpp).
///
/// Layout. The nodes are uniform in x = sqrt(theta / (pi/2)) (theta_j = (pi/2) (j/N)^2, j = 0..N), which
/// packs them towards grazing incidence, where sigma falls like a power of theta, and keeps them at most
/// (pi/2)(2/N) apart near normal incidence. The table holds ln sigma at the nodes and interpolates it
/// linearly in x (a power law theta^n is exactly linear in ln sigma against ln x, and nearly so against x
/// once x >> 1/N). The first cell [0, theta_1] (theta_1 = 90 deg / N^2 <= 0.0014 deg) interpolates sigma
/// itself linearly from 0 at theta = 0.
///
/// Accuracy. Construction starts from N = 256 and doubles N until linear interpolation misses the direct
/// model by at most `tolerance_db` at every cell midpoint from 0.05 deg on (the midpoint is where the
/// interpolation error of a smooth function peaks), or until N reaches `max_intervals`. Below 0.05 deg
/// sigma behaves like theta^n (n about 1 to 3) and cell j misses it by about n / (4 j^2) nepers whatever N
/// is (0.12 n nepers, about 0.5 n dB, in cell 1, which lies below 0.006 deg); no accuracy is promised
/// there, only a finite, non-negative, continuous value. The midpoint evaluations become the nodes of
/// the next level, so building costs about 2N direct evaluations (under a microsecond each). The achieved
/// midpoint error is kept (`midpoint_error_db()`); with the default 0.01 dB the error anywhere in
/// [0.1, 90] deg stays far below 0.05 dB for every TR 9407 sediment from 10 kHz to 1 MHz.
///
/// Bistatic evaluation is not tabulated: it needs a 3-D table (theta_i, theta_s, phi) with a sharp specular
/// Kirchhoff lobe, megabytes per sediment at this accuracy, and the sidescan hot path is monostatic.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/scattering/jackson_terms.hpp"

namespace sss::scattering {

template <Real T> class jackson_backscatter_table {
public:
    using value_type = T;

    /// Tabulates jackson_backscatter(c, theta) (evaluated in double). tolerance_db > 0 (dB, at cell
    /// midpoints); max_intervals >= 256 caps N (memory: (N + 1) values of T).
    explicit jackson_backscatter_table(const jackson_coefficients<double>& c, double tolerance_db = 0.01,
                                       std::size_t max_intervals = std::size_t(1) << 16) {
        sss::require_positive(tolerance_db, "jackson_backscatter_table.tolerance_db");
        sss::require(max_intervals >= 256, "jackson_backscatter_table.max_intervals", "must be >= 256");
        build(c, tolerance_db, max_intervals);
    }

    /// Tabulates the model for a sediment, frequency f_hz (Hz) and water sound speed c_water_mps (m/s).
    /// Throws invalid_parameter as make_jackson_coefficients does.
    jackson_backscatter_table(const sediment_params<T>& p, T f_hz, T c_water_mps, double tolerance_db = 0.01)
        : jackson_backscatter_table(make_jackson_coefficients(to_double(p), double(f_hz), double(c_water_mps)), tolerance_db) {}

    /// sigma (linear) at grazing angle graze_rad (clamped to [0, pi/2]; NaN gives 0).
    [[nodiscard]] T operator()(T graze_rad) const noexcept {
        if (!(graze_rad > T(0))) return T(0);
        const T g = std::min(graze_rad, half_pi_v<T>);
        const T u = std::sqrt(g * (T(1) / half_pi_v<T>)) * n_;
        std::size_t j = static_cast<std::size_t>(u);
        if (j >= intervals_) j = intervals_ - 1;
        const T t = u - T(j);
        if (j == 0) return first_sigma_ * t;
        const T a = log_sigma_[j];
        return std::exp(a + t * (log_sigma_[j + 1] - a));
    }

    /// Number of intervals N.
    [[nodiscard]] std::size_t intervals() const noexcept { return intervals_; }
    /// Grazing angle (deg) from which the construction checks its cell midpoints.
    static constexpr double check_from_deg = 0.05;
    /// Largest |table - direct| found at the cell midpoints from check_from_deg on, final level (dB).
    [[nodiscard]] double midpoint_error_db() const noexcept { return midpoint_error_db_; }

private:
    void build(const jackson_coefficients<double>& c, double tolerance_db, std::size_t max_intervals) {
        const auto log_sigma_at = [&](double x) { // x = sqrt(theta / (pi/2)) in [0, 1]
            const double s = jackson_backscatter(c, half_pi_v<double> * x * x);
            return std::log(std::max(s, 1e-300));
        };
        std::size_t n = 256;
        std::vector<double> nodes(n + 1);
        for (std::size_t j = 0; j <= n; ++j) nodes[j] = log_sigma_at(double(j) / double(n));
        const double db_per_neper = 10.0 / ln10_v<double>;
        const double check_from_rad = deg_to_rad(check_from_deg);
        double worst = 0.0;
        for (;;) {
            std::vector<double> mids(n);
            worst = 0.0;
            for (std::size_t j = 0; j < n; ++j) {
                mids[j] = log_sigma_at((double(j) + 0.5) / double(n));
                const double theta_j = half_pi_v<double> * double(j * j) / double(n * n);
                if (theta_j >= check_from_rad)
                    worst = std::max(worst, std::abs(mids[j] - 0.5 * (nodes[j] + nodes[j + 1])) * db_per_neper);
            }
            if (worst <= tolerance_db || 2 * n > max_intervals) break;
            std::vector<double> finer(2 * n + 1);
            for (std::size_t j = 0; j < n; ++j) {
                finer[2 * j] = nodes[j];
                finer[2 * j + 1] = mids[j];
            }
            finer[2 * n] = nodes[n];
            nodes.swap(finer);
            n *= 2;
        }
        intervals_ = n;
        n_ = T(n);
        midpoint_error_db_ = worst;
        log_sigma_.resize(n + 1);
        for (std::size_t j = 0; j <= n; ++j) log_sigma_[j] = T(nodes[j]);
        first_sigma_ = T(std::exp(nodes[1]));
    }

    std::vector<T> log_sigma_; // ln sigma at theta_j = (pi/2)(j/N)^2; entry 0 unused
    std::size_t intervals_ = 0;
    T n_ = T(0);
    T first_sigma_ = T(0);     // sigma at theta_1
    double midpoint_error_db_ = 0.0;
};

} // namespace sss::scattering

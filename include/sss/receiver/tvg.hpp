#pragma once
/// \file
/// Time-varied gain and the per-range mean normalisation of processing software.
///
/// A sidescan's receiver raises its gain with time so that the seabed looks alike at every range:
///
///     G(r) = N log10 r + 2 alpha r / 1000 + G0   (dB; r in m, alpha in dB/km),
///
/// N = 30 for seabed returns (two-way spherical spreading 40 log r less the footprint's growth 10 log r),
/// N = 40 for point targets, N = 20 in many older systems (Urick, "Principles of Underwater Sound", 3rd ed.,
/// 1983, ch. 8; Blondel, "The Handbook of Sidescan Sonar", 2009, ch. 4). The gain multiplies power by 10^(G/10).
/// Processing software often flattens the remaining trend empirically instead: each range bin divided by its
/// mean over many pings (`normalise_range_mean`; also called beam-pattern or angle-varying gain correction).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/receiver/image.hpp"
#include "sss/receiver/line_stage.hpp"

namespace sss {

struct tvg_params {
    double spreading_n = 30.0;        ///< N of N log10 r (dB per decade of range), -60 to 60
    double absorption_db_per_km = 0.0;///< alpha, one-way (dB/km), 0 to 1000
    double gain_db = 0.0;             ///< G0 (dB), -300 to 300
    double min_range_m = 1.0;         ///< ranges below this get the gain at this range (m), > 0

    void validate() const {
        // Spherical spreading is N = 40, seawater's absorption at 1 MHz about 300 dB/km. Over a long enough line the
        // gain still passes any number's range: process holds such samples at the largest value (file comment).
        sss::require_in_range(spreading_n, -60.0, 60.0, "tvg.spreading_n");
        sss::require_in_range(absorption_db_per_km, 0.0, 1000.0, "tvg.absorption_db_per_km");
        sss::require_in_range(gain_db, -300.0, 300.0, "tvg.gain_db");
        sss::require_positive(min_range_m, "tvg.min_range_m");
    }
};

/// G(r) = N log10 r + 2 alpha r / 1000 + G0 (dB) at slant range r (m).
[[nodiscard]] inline double tvg_gain_db(const tvg_params& p, double range_m) noexcept {
    const double r = std::max(range_m, p.min_range_m);
    return p.spreading_n * std::log10(r) + 2.0 * p.absorption_db_per_km * r / 1000.0 + p.gain_db;
}

/// The time-varied gain as a line stage: sample k (two-way time (k + 1/2) dt, range c t / 2) times 10^(G/10). A sample
/// the gain would lift beyond T's largest value (far out at a high absorption) is held there, as a receiver
/// saturates; zero stays zero whatever the gain.
class tvg {
public:
    tvg() = default;
    explicit tvg(const tvg_params& p) : p_(p) { p_.validate(); }
    [[nodiscard]] const tvg_params& params() const noexcept { return p_; }

    template <Real T> void process(std::vector<T>& line, const line_context<T>& ctx) const {
        const double top = double(std::numeric_limits<T>::max());
        for (std::size_t k = 0; k < line.size(); ++k) {
            const double v = double(line[k]);
            if (v == 0.0 || !std::isfinite(v)) continue;
            const double r = 0.5 * ctx.c_mps * (double(k) + 0.5) * ctx.dt_s;
            const double g_db = tvg_gain_db(p_, r);
            double out = std::abs(v) * std::pow(10.0, g_db / 10.0);
            if (!(out < top)) { // the gain alone may pass double's range: in decibels, 10 log10 |v| + G
                const double level_db = 10.0 * std::log10(std::abs(v)) + g_db;
                out = level_db >= 10.0 * std::log10(top) ? top : std::pow(10.0, level_db / 10.0);
            }
            line[k] = static_cast<T>(std::copysign(std::min(out, top), v));
        }
    }

private:
    tvg_params p_{};
};

/// Divides every column of a waterfall (one range on one side) by its mean over the pings; columns whose mean is
/// zero (the water column of a noiseless record) or not finite are left as they are.
template <Real T> void normalise_range_mean(waterfall<T>& w) {
    const std::size_t width = w.width();
    std::vector<double> mean(width, 0.0);
    for (std::size_t i = 0; i < w.pings; ++i)
        for (std::size_t c = 0; c < width; ++c) mean[c] += double(w.values[i * width + c]);
    for (std::size_t c = 0; c < width; ++c) {
        if (!(mean[c] > 0.0) || !std::isfinite(mean[c])) continue; // (a column holding infinity or NaN, too)
        const double scale = double(w.pings) / mean[c];
        for (std::size_t i = 0; i < w.pings; ++i) w.values[i * width + c] = static_cast<T>(double(w.values[i * width + c]) * scale);
    }
}

} // namespace sss

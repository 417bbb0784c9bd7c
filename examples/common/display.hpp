#pragma once
// Display gain for the examples: like a sidescan's time-varied gain, take spreading and absorption out of a waterfall
// before mapping it to grey levels: power x r^3 x 10^(2 alpha r / 10^4), r the sample's mid slant range (m).
// (r^3: two-way spherical spreading r^4 times the footprint's growth r; alpha in dB/km.)

#include <cmath>
#include <cstddef>
#include <vector>

#include <sss/receiver/image.hpp>

namespace sss_examples {

template <class T>
[[nodiscard]] std::vector<double> range_compensated(const sss::waterfall<T>& w, double c_mps, double absorption_db_per_km) {
    std::vector<double> gain(w.samples);
    for (std::size_t k = 0; k < w.samples; ++k) {
        const double r = (double(k) + 0.5) * w.dt_s * 0.5 * c_mps;
        gain[k] = r * r * r * std::pow(10.0, 2.0 * absorption_db_per_km * r / 1e4);
    }
    std::vector<double> shown(w.values.size());
    for (std::size_t p = 0; p < w.pings; ++p)
        for (std::size_t c = 0; c < w.width(); ++c) {
            const std::size_t k = c < w.samples ? w.samples - 1 - c : c - w.samples; // port is mirrored
            shown[p * w.width() + c] = double(w.at(p, c)) * gain[k];
        }
    return shown;
}

} // namespace sss_examples

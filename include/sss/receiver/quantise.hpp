#pragma once
/// \file
/// Digitisation: what a sidescan records is gain x amplitude (or intensity), rounded and clipped to 8 or 16 bits
/// unsigned (XTF and most sidescan formats; some record 32-bit floats, which need nothing here). Strong highlights
/// saturate at the clip level, as in real records.

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/core/types.hpp"

namespace sss {

struct quantise_params {
    double gain = 1.0;      ///< counts per unit of amplitude (or of intensity), > 0
    bool amplitude = true;  ///< record sqrt(power) (the usual); false: the power itself

    void validate() const { sss::require_positive(gain, "quantise.gain"); }
};

/// Each value as round(gain x sqrt(value)) (or gain x value), clipped to [0, max of U].
template <std::unsigned_integral U, Real T>
[[nodiscard]] std::vector<U> quantise(std::span<const T> values, const quantise_params& p) {
    p.validate();
    // The largest count, as a double that converts back to U: beyond 53 bits U's maximum itself rounds up to 2^bits,
    // which U cannot hold; 2^bits - 2^(bits - 53) is the largest double below it.
    constexpr U max = std::numeric_limits<U>::max();
    constexpr double top = std::numeric_limits<U>::digits <= 53 ? double(max) : double(U(max - (max >> 53)));
    std::vector<U> out(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double v = std::max(0.0, double(values[i]));
        const double counts = std::round(p.gain * (p.amplitude ? std::sqrt(v) : v));
        out[i] = static_cast<U>(std::isnan(counts) ? 0.0 : std::min(counts, top));
    }
    return out;
}

/// The gain that maps `reference` (a power, e.g. a chosen percentile of a record) to `counts`, for amplitude
/// recording when `amplitude` is true.
[[nodiscard]] inline double quantise_gain(double reference, double counts, bool amplitude = true) {
    sss::require_positive(reference, "quantise_gain.reference");
    sss::require_positive(counts, "quantise_gain.counts");
    return counts / (amplitude ? std::sqrt(reference) : reference);
}

} // namespace sss

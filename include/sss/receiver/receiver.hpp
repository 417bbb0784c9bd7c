#pragma once
/// \file
/// What the receiver records: sample rate, range window, pulse and source level.

#include <cmath>
#include <cstddef>

#include "sss/core/error.hpp"
#include "sss/receiver/pulse.hpp"

namespace sss {

struct receiver_params {
    double sample_rate_hz = 20000.0; ///< samples per second per side (Hz), > 0
    double max_range_m = 50.0;       ///< slant range covered per side (m), > 0: samples = ceil(2 range / c fs)
    sss::pulse pulse{};              ///< transmitted pulse envelope
    double source_level_db = 0.0;    ///< source level (dB re 1 unit at 1 m), -300 to 300; outputs are powers on the same reference

    void validate() const {
        sss::require_positive(sample_rate_hz, "receiver.sample_rate_hz");
        sss::require_positive(max_range_m, "receiver.max_range_m");
        // Levels in dB are powers of ten of a tenth of them: within +-300 dB they stay in range through the chain,
        // in float too (10^38); real source levels are 150 to 250 dB re 1 uPa at 1 m.
        sss::require_in_range(source_level_db, -300.0, 300.0, "receiver.source_level_db");
        pulse.validate();
    }

    /// Samples per line for a reference sound speed c (m/s); saturates at 2^62 (and gives 0 for a count that is not
    /// a number) rather than overflowing the size type.
    [[nodiscard]] std::size_t samples(double c_mps) const noexcept {
        const double n = std::ceil(2.0 * max_range_m / c_mps * sample_rate_hz);
        constexpr double cap = 4611686018427387904.0; // 2^62
        if (!(n >= 0.0)) return 0;
        return n < cap ? static_cast<std::size_t>(n) : static_cast<std::size_t>(cap);
    }
};

} // namespace sss

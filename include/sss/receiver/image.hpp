#pragma once
/// \file
/// Ping lines and the waterfall image they form.

#include <cstddef>
#include <vector>

#include "sss/core/types.hpp"

namespace sss {

/// One ping: the port and starboard lines, sample k covering two-way time [k dt, (k + 1) dt): mean power.
template <Real T> struct ping_lines {
    std::vector<T> port;
    std::vector<T> starboard;
    double dt_s = 0.0; ///< sample interval (s)
};

/// Pings x (2 samples) image, row-major, one row per ping: port on the left mirrored (its far range at
/// column 0, nadir in the middle), starboard on the right (nadir in the middle, far range at the last column).
template <Real T> struct waterfall {
    std::size_t pings = 0;
    std::size_t samples = 0; ///< samples per side; each row has 2 samples values
    double dt_s = 0.0;
    std::vector<T> values;

    [[nodiscard]] std::size_t width() const noexcept { return 2 * samples; }
    [[nodiscard]] T at(std::size_t ping, std::size_t column) const noexcept { return values[ping * width() + column]; }

    /// Stores a ping as row `row`.
    void set_row(std::size_t row, const ping_lines<T>& lines) {
        T* out = values.data() + row * width();
        for (std::size_t k = 0; k < samples; ++k) {
            out[samples - 1 - k] = k < lines.port.size() ? lines.port[k] : T(0);
            out[samples + k] = k < lines.starboard.size() ? lines.starboard[k] : T(0);
        }
    }
};

} // namespace sss

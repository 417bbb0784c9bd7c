#pragma once
/// \file
/// Products of sizes checked before they are used, and the limits on what one parameter may make sss allocate.
///
/// Every product of sizes formed from parameters (grid nx * ny, pings * columns, FFT oversampling) goes through
/// `checked_mul`, so an overflow is an `sss::invalid_parameter` naming the parameter rather than a wrapped
/// size that later reads or writes out of bounds. Buffers whose size a parameter sets are also held to
/// `max_elements`: a request for more is refused by name before anything is allocated (rather than ending in
/// `std::bad_alloc`, or in the operating system killing the process).

#include <cstddef>
#include <limits>
#include <string>
#include <string_view>

#include "sss/core/error.hpp"

namespace sss {

/// The most elements one buffer sized by a parameter may hold: 2^31 (8 GiB of float, 32 GiB of complex<double>).
/// A grid (raster, height field), a waterfall image (pings x columns) or an FFT's oversampled grid larger than
/// this is refused by name.
inline constexpr std::size_t max_elements = std::size_t(1) << 31;

/// a * b; throws invalid_parameter(name) when the product overflows std::size_t.
[[nodiscard]] inline std::size_t checked_mul(std::size_t a, std::size_t b, std::string_view name) {
    if (b != 0 && a > std::numeric_limits<std::size_t>::max() / b)
        throw invalid_parameter(name, std::to_string(a) + " x " + std::to_string(b) + " overflows the size type");
    return a * b;
}

/// a * b for the element count of a buffer; throws invalid_parameter(name) when it overflows or exceeds `limit`.
[[nodiscard]] inline std::size_t checked_elements(std::size_t a, std::size_t b, std::string_view name,
                                                  std::size_t limit = max_elements) {
    const std::size_t n = checked_mul(a, b, name);
    if (n > limit)
        throw invalid_parameter(name, std::to_string(a) + " x " + std::to_string(b) + " = " + std::to_string(n) +
                                          " elements exceed the limit of " + std::to_string(limit));
    return n;
}

} // namespace sss

#pragma once
/// \file
/// Greyscale PNG images, 8 or 16 bits, with no dependency, and the display mapping of a waterfall to grey.
///
/// Optional: no core header includes it. The encoder is the library's own (io/detail/deflate.hpp): the PNG
/// specification (W3C, 2003, "Portable Network Graphics (PNG) Specification, Second Edition", ISO/IEC 15948)
/// stores rows (filter byte 0, then the samples, 16-bit big-endian) in a zlib stream (Deutsch & Gailly, 1996,
/// RFC 1950) of deflate data (Deutsch, 1996, RFC 1951); here one block with deflate's fixed Huffman codes and
/// greedy LZ77 matching; every chunk ends with its CRC-32 (the PNG specification's Annex D). Chosen over libpng
/// so that any consumer of the library writes images with no dependency. On the products example the waterfall
/// comes out 1.27 times the size zlib (level 6) makes of it, the label images 65 to 120 times smaller than their
/// raw samples (1.8 to 3.6 times zlib's size).
///
/// Display mapping (`to_grey_db`): the level 10 log10(v) of each value over the window
/// [top_db - dynamic_range_db, top_db] goes linearly to [0, max grey] (255 or 65535); top_db is the peak's level
/// unless given (the finite values' peak). Zeros, negatives and NaN map to 0, +infinity to the max grey.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/io/detail/bytes.hpp"
#include "sss/io/detail/deflate.hpp"
#include "sss/io/detail/png_encode.hpp"

namespace sss::io {

namespace detail {
/// The image's size and pixel count, checked before `path` is written, with the file named in the message.
inline void check_png_image(const std::string& path, std::size_t width, std::size_t height, std::size_t pixels) {
    if (!(width >= 1 && height >= 1 && width <= 0x7fffffffu && height <= 0x7fffffffu))
        sss::require(false, "png size", "width and height must lie in [1, 2^31 - 1], got " + std::to_string(width) +
                                            " x " + std::to_string(height) + " for '" + path + "'");
    if (pixels != width * height)
        sss::require(false, "png samples", "must hold width x height = " + std::to_string(width * height) +
                                               " values, got " + std::to_string(pixels) + " for '" + path + "'");
}
} // namespace detail

/// Writes an 8-bit greyscale PNG: `height` rows of `width` values, top row first (through a temporary renamed
/// when complete: a failure leaves no file).
inline void write_png_grey8(const std::string& path, std::size_t width, std::size_t height, std::span<const std::uint8_t> pixels) {
    detail::check_png_image(path, width, height, pixels.size());
    const auto bytes = sss::detail::encode_png_grey<std::uint8_t>(width, height, pixels);
    sss::detail::write_file_atomically(path, bytes.data(), bytes.size());
}

/// Writes a 16-bit greyscale PNG (as write_png_grey8).
inline void write_png_grey16(const std::string& path, std::size_t width, std::size_t height, std::span<const std::uint16_t> pixels) {
    detail::check_png_image(path, width, height, pixels.size());
    const auto bytes = sss::detail::encode_png_grey<std::uint16_t>(width, height, pixels);
    sss::detail::write_file_atomically(path, bytes.data(), bytes.size());
}

/// The display window of `to_grey_db`.
struct display_params {
    double dynamic_range_db = 40.0; ///< width of the window (dB), > 0
    double top_db = std::numeric_limits<double>::quiet_NaN(); ///< level shown white (dB re the values' unit); NaN: the peak's level
};

/// Grey levels 0..max(U) of linear values on a decibel window (see the file comment). U: std::uint8_t or
/// std::uint16_t.
template <class U, class V> [[nodiscard]] std::vector<U> to_grey_db(std::span<const V> values, const display_params& p = {}) {
    sss::require_positive(p.dynamic_range_db, "display_params.dynamic_range_db");
    double top = p.top_db;
    if (std::isnan(top)) {
        double peak = 0.0;
        for (const V v : values)
            if (std::isfinite(double(v))) peak = std::max(peak, double(v));
        top = peak > 0.0 ? 10.0 * std::log10(peak) : 0.0;
    }
    sss::require_finite(top, "display_params.top_db");
    const double floor_db = top - p.dynamic_range_db, grey = double(static_cast<U>(~U(0)));
    std::vector<U> out(values.size(), U(0));
    for (std::size_t i = 0; i < values.size(); ++i) {
        const double v = double(values[i]);
        if (!(v > 0.0)) continue;
        if (std::isinf(v)) { // beyond any level: white
            out[i] = static_cast<U>(~U(0));
            continue;
        }
        const double f = std::clamp((10.0 * std::log10(v) - floor_db) / p.dynamic_range_db, 0.0, 1.0);
        out[i] = static_cast<U>(std::lround(f * grey));
    }
    return out;
}

} // namespace sss::io

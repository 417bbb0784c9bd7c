#pragma once
/// \file
/// Grayscale PNG output for the examples (libpng), and the mapping of linear intensities to 8-bit
/// gray over a decibel window. Not part of the library: the examples' own helper.
///
/// Files are written to a temporary file of their own (`path + ".tmp-"` and 16 hexadecimal digits, created
/// exclusively, as the library's writers do) and renamed onto `path` once complete, so a reader never sees a
/// half-written image and two writers of one path never share a temporary. Failures throw std::runtime_error
/// naming the file.

#include <png.h>

#include <sss/io/detail/atomic_file.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csetjmp>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace sss_examples {

namespace detail {

    /// Writes `height` rows of `width` gray samples (bit_depth 8 or 16, 16-bit rows big-endian)
    /// to an open file. Returns false on any libpng error; `message` then holds libpng's text.
    /// Only plain C data lives in this function: libpng reports errors by longjmp back into it.
    inline bool write_png_rows(std::FILE* file, png_uint_32 width, png_uint_32 height, int bit_depth,
                               png_bytep* rows, char (&message)[256]) noexcept {
        message[0] = '\0';
        png_structp png = png_create_write_struct(
            PNG_LIBPNG_VER_STRING, message,
            [](png_structp p, png_const_charp text) {
                auto* out = static_cast<char*>(png_get_error_ptr(p));
                std::snprintf(out, 256, "%s", text);
                png_longjmp(p, 1);
            },
            nullptr);
        if (png == nullptr) {
            std::snprintf(message, sizeof message, "cannot create the libpng write structure");
            return false;
        }
        png_infop info = png_create_info_struct(png);
        if (info == nullptr) {
            png_destroy_write_struct(&png, nullptr);
            std::snprintf(message, sizeof message, "cannot create the libpng info structure");
            return false;
        }
        if (setjmp(png_jmpbuf(png))) {
            png_destroy_write_struct(&png, &info);
            return false;
        }
        png_init_io(png, file);
        png_set_IHDR(png, info, width, height, bit_depth, PNG_COLOR_TYPE_GRAY, PNG_INTERLACE_NONE,
                     PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
        png_write_info(png, info);
        png_write_image(png, rows);
        png_write_end(png, nullptr);
        png_destroy_write_struct(&png, &info);
        return true;
    }

    /// Writes `bytes` (rows of `row_bytes` bytes, top row first) as a gray PNG of the given bit depth.
    inline void write_png_gray(const std::string& path, std::size_t width, std::size_t height,
                               int bit_depth, std::vector<std::uint8_t>& bytes) {
        constexpr std::size_t max_side = 0x7fffffffu; // the PNG limit on width and height
        if (width == 0 || height == 0 || width > max_side || height > max_side) {
            throw std::invalid_argument("write_png: image size " + std::to_string(width) + " x " +
                                        std::to_string(height) + " is not writable as PNG (" + path +
                                        ")");
        }
        const std::size_t row_bytes = width * static_cast<std::size_t>(bit_depth / 8);
        std::vector<png_bytep> rows(height);
        for (std::size_t y = 0; y < height; ++y) {
            rows[y] = bytes.data() + y * row_bytes;
        }

        const std::string tmp = path + ".tmp-" + sss::detail::temporary_suffix();
        std::FILE* file = std::fopen(tmp.c_str(), "wbx");
        if (file == nullptr) {
            throw std::runtime_error("write_png: cannot open '" + tmp + "' for writing: " +
                                     std::strerror(errno));
        }
        char message[256];
        const bool written = write_png_rows(file, static_cast<png_uint_32>(width),
                                            static_cast<png_uint_32>(height), bit_depth, rows.data(),
                                            message);
        const bool closed = std::fclose(file) == 0;
        if (!written || !closed) {
            std::remove(tmp.c_str());
            throw std::runtime_error("write_png: cannot write '" + tmp + "': " +
                                     (written ? std::string("error closing the file")
                                              : std::string(message)));
        }
        if (std::rename(tmp.c_str(), path.c_str()) != 0) {
            const std::string why = std::strerror(errno);
            std::remove(tmp.c_str());
            throw std::runtime_error("write_png: cannot rename '" + tmp + "' to '" + path + "': " + why);
        }
    }

    inline void require_pixel_count(const std::string& path, std::size_t width, std::size_t height,
                                    std::size_t count) {
        if (height != 0 && width > std::numeric_limits<std::size_t>::max() / height) {
            throw std::invalid_argument("write_png: width x height overflows (" + path + ")");
        }
        if (count != width * height) {
            throw std::invalid_argument("write_png: pixels has " + std::to_string(count) +
                                        " values, width x height = " + std::to_string(width) + " x " +
                                        std::to_string(height) + " (" + path + ")");
        }
    }

} // namespace detail

/// Writes an 8-bit grayscale PNG. `pixels` holds `height` rows of `width` values, top row first.
inline void write_png_gray8(const std::string& path, std::size_t width, std::size_t height,
                            const std::vector<std::uint8_t>& pixels) {
    detail::require_pixel_count(path, width, height, pixels.size());
    std::vector<std::uint8_t> bytes(pixels);
    detail::write_png_gray(path, width, height, 8, bytes);
}

/// Writes a 16-bit grayscale PNG. `pixels` holds `height` rows of `width` values, top row first.
inline void write_png_gray16(const std::string& path, std::size_t width, std::size_t height,
                             const std::vector<std::uint16_t>& pixels) {
    detail::require_pixel_count(path, width, height, pixels.size());
    std::vector<std::uint8_t> bytes(2 * pixels.size());
    for (std::size_t i = 0; i < pixels.size(); ++i) { // PNG stores 16-bit samples big-endian
        bytes[2 * i] = static_cast<std::uint8_t>(pixels[i] >> 8);
        bytes[2 * i + 1] = static_cast<std::uint8_t>(pixels[i] & 0xffu);
    }
    detail::write_png_gray(path, width, height, 16, bytes);
}

/// Maps linear intensities to 8-bit gray on a decibel scale: 10 log10(value) over the window
/// [peak - dynamic_range_db, peak] (dB) goes linearly to 0..255, where peak is the largest value's
/// level. Values at or below the window's floor, zeros, negatives and NaN map to 0.
/// \param values           linear intensities (any unit: only ratios to the peak matter)
/// \param dynamic_range_db width of the displayed window (dB), > 0
template <class T>
[[nodiscard]] std::vector<std::uint8_t> to_gray8_db(const std::vector<T>& values, double dynamic_range_db) {
    if (!(dynamic_range_db > 0.0) || !std::isfinite(dynamic_range_db)) {
        throw std::invalid_argument("to_gray8_db: dynamic_range_db must be finite and > 0, got " +
                                    std::to_string(dynamic_range_db));
    }
    double peak = 0.0;
    for (const T v : values) {
        const auto d = static_cast<double>(v);
        if (std::isfinite(d) && d > peak) {
            peak = d;
        }
    }
    std::vector<std::uint8_t> gray(values.size(), std::uint8_t{0});
    if (!(peak > 0.0)) {
        return gray;
    }
    const double floor_db = 10.0 * std::log10(peak) - dynamic_range_db;
    for (std::size_t i = 0; i < values.size(); ++i) {
        const auto d = static_cast<double>(values[i]);
        if (!(d > 0.0)) {
            continue;
        }
        const double fraction = std::clamp((10.0 * std::log10(d) - floor_db) / dynamic_range_db, 0.0, 1.0);
        gray[i] = static_cast<std::uint8_t>(std::lround(fraction * 255.0));
    }
    return gray;
}

} // namespace sss_examples

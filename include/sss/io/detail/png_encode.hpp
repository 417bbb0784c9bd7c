#pragma once
/// \file
/// Internal to io/png.hpp: the PNG encoder (chunks, their CRC-32, the greyscale image). Not part of the API.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/io/detail/deflate.hpp"

namespace sss::detail {

/// CRC-32 (polynomial 0xEDB88320, reflected) as PNG and zlib's gzip use it; `crc` continues a running value.
[[nodiscard]] inline std::uint32_t png_crc32(std::span<const std::uint8_t> bytes, std::uint32_t crc = 0) noexcept {
    static const std::array<std::uint32_t, 256> table = [] {
        std::array<std::uint32_t, 256> t{};
        for (std::uint32_t n = 0; n < 256; ++n) {
            std::uint32_t c = n;
            for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
            t[n] = c;
        }
        return t;
    }();
    crc = ~crc;
    for (const std::uint8_t b : bytes) crc = table[(crc ^ b) & 0xffu] ^ (crc >> 8);
    return ~crc;
}

inline void png_put_be32(std::vector<std::uint8_t>& out, std::uint32_t v) {
    for (int s = 24; s >= 0; s -= 8) out.push_back(static_cast<std::uint8_t>(v >> s));
}

inline void png_chunk(std::vector<std::uint8_t>& out, const char (&type)[5], std::span<const std::uint8_t> data) {
    sss::require(data.size() < (std::size_t(1) << 31), "png chunk", "must hold fewer than 2^31 bytes");
    png_put_be32(out, static_cast<std::uint32_t>(data.size()));
    const std::size_t start = out.size();
    out.insert(out.end(), type, type + 4);
    out.insert(out.end(), data.begin(), data.end());
    png_put_be32(out, png_crc32(std::span<const std::uint8_t>(out.data() + start, out.size() - start)));
}

/// A greyscale PNG of `height` rows of `width` samples of `bit_depth` 8 or 16 (`samples`: one value per pixel).
template <class U>
[[nodiscard]] std::vector<std::uint8_t> encode_png_grey(std::size_t width, std::size_t height, std::span<const U> samples) {
    constexpr int bit_depth = 8 * int(sizeof(U));
    sss::require(width >= 1 && height >= 1 && width <= 0x7fffffffu && height <= 0x7fffffffu, "png size",
                         "width and height must lie in [1, 2^31 - 1]");
    sss::require(samples.size() == width * height, "png samples", "must hold width x height values");
    const std::size_t row_bytes = 1 + width * sizeof(U);
    std::vector<std::uint8_t> raw(row_bytes * height);
    for (std::size_t y = 0; y < height; ++y) {
        std::uint8_t* r = raw.data() + y * row_bytes;
        r[0] = 0; // filter: none
        for (std::size_t x = 0; x < width; ++x) {
            const U v = samples[y * width + x];
            if constexpr (sizeof(U) == 1) r[1 + x] = v;
            else {
                r[1 + 2 * x] = static_cast<std::uint8_t>(v >> 8);
                r[2 + 2 * x] = static_cast<std::uint8_t>(v & 0xffu);
            }
        }
    }
    const std::vector<std::uint8_t> z = zlib_compress(raw);
    std::vector<std::uint8_t> out{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    std::vector<std::uint8_t> ihdr;
    png_put_be32(ihdr, static_cast<std::uint32_t>(width));
    png_put_be32(ihdr, static_cast<std::uint32_t>(height));
    ihdr.insert(ihdr.end(), {static_cast<std::uint8_t>(bit_depth), 0, 0, 0, 0}); // grey, deflate, filter 0, no interlace
    png_chunk(out, "IHDR", ihdr);
    // The zlib stream in IDAT chunks of at most 1 MiB: a chunk's length must stay below 2^31 (PNG, section 5.3), and a
    // speckled image of 2^31 pixels compresses to more than that.
    constexpr std::size_t idat_bytes = std::size_t(1) << 20;
    for (std::size_t at = 0; at < z.size(); at += idat_bytes)
        png_chunk(out, "IDAT", std::span<const std::uint8_t>(z.data() + at, std::min(idat_bytes, z.size() - at)));
    png_chunk(out, "IEND", {});
    return out;
}

} // namespace sss::detail

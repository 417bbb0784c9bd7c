#pragma once
/// \file
/// Internal to io/xtf.hpp: the sizes of XTF's headers, the file's units, the CHANINFO entry, the Weight of
/// integer samples and the error of a malformed file. Not part of the API.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "sss/core/error.hpp"
#include "sss/io/detail/bytes.hpp"
#include "sss/io/xtf_file.hpp"

namespace sss::detail {

inline constexpr double knots_per_mps = 3600.0 / 1852.0;

inline constexpr std::size_t xtf_file_header_bytes = 1024, xtf_ping_header_bytes = 256, xtf_chan_header_bytes = 64;

/// Throws the file_error of a malformed XTF file at byte `offset`.
[[noreturn]] inline void xtf_fail(const std::string& name, std::size_t offset, const std::string& why) {
    throw file_error(name, 0, offset == 0 ? why + " (at byte 0)" : why, offset);
}

[[nodiscard]] inline std::size_t xtf_bytes_per_sample(io::xtf_sample_format f) noexcept {
    return f == io::xtf_sample_format::u8 ? 1 : f == io::xtf_sample_format::u16 ? 2 : 4;
}

inline void xtf_put_chaninfo(std::uint8_t* c, std::uint8_t type, const io::xtf_channel_info& ch, io::xtf_sample_format f,
                             std::string_view name) {
    put_le<std::uint8_t>(c, 0, type);
    put_le<std::uint16_t>(c, 2, 1); // slant range
    put_le<std::uint16_t>(c, 4, f == io::xtf_sample_format::f32 ? 0 : 1);
    put_le<std::uint16_t>(c, 6, static_cast<std::uint16_t>(xtf_bytes_per_sample(f)));
    put_chars(c, 12, name, 16);
    put_le<float>(c, 28, 5.0f);
    put_le<float>(c, 32, static_cast<float>(ch.frequency_khz));
    put_le<float>(c, 36, static_cast<float>(ch.horizontal_beam_angle_deg));
    put_le<float>(c, 40, static_cast<float>(ch.tilt_deg));
    put_le<float>(c, 44, static_cast<float>(ch.beam_width_deg));
    put_le<std::uint8_t>(c, 74, f == io::xtf_sample_format::u8 ? 8 : f == io::xtf_sample_format::u16 ? 3 : 5);
}

/// The Weight N for integer samples: the largest with peak x 2^N <= the format's largest count.
[[nodiscard]] inline int xtf_weight(const io::xtf_file& f) {
    if (f.header.format == io::xtf_sample_format::f32) return 0;
    double peak = 0.0;
    for (const auto& p : f.pings) {
        for (float v : p.port) peak = std::max(peak, double(v));
        for (float v : p.starboard) peak = std::max(peak, double(v));
    }
    if (!(peak > 0.0)) return 0;
    const double top = f.header.format == io::xtf_sample_format::u8 ? 255.0 : 65535.0;
    return std::clamp(static_cast<int>(std::floor(std::log2(top / peak))), -32768, 32767);
}

} // namespace sss::detail

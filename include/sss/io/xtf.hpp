#pragma once
/// \file
/// XTF (eXtended Triton Format) files of two-channel sidescan: writer and reader, no dependency.
///
/// Layout, from Triton Imaging's "eXtended Triton Format (XTF)" specification (Rev. 41): little-endian,
/// byte-packed, zero-filled. A 1024-byte XTFFILEHEADER (128-byte CHANINFO entries from byte 256; it grows in
/// 1024-byte steps past 6 channels), then one packet per ping: a 256-byte XTFPINGHEADER (magic 0xFACE, header
/// type 0 = sonar, NumBytesThisRecord = the whole packet), then per channel a 64-byte XTFPINGCHANHEADER and its
/// samples: port (channel 0) stored far-to-near, starboard (channel 1) near-to-far, so port then starboard
/// concatenated is the usual waterfall line. The writer pads each packet to a multiple of 64 bytes (as Isis does).
///
/// Conventions written (and assumed by the reader):
/// - SoundVelocity holds half the sound speed (750 m/s for 1500), Isis's convention; the reader doubles values
///   below 1000 m/s and takes larger ones as the full speed (some writers store 1500).
/// - Time: Year ... HSeconds (UTC, 1/100 s) and JulianDay (day of the year, 1 = 1 January).
/// - ThisFileName: the file's own name (xtf_header::file_name, else the written path's last component);
///   ProcessingFlags 4 in each channel header when the samples carry TVG (xtf_header::tvg_applied), else 0.
/// - SensorSpeed in knots (1852 m per hour); heading (in [0, 360)), pitch (nose up positive), roll (starboard down positive)
///   in degrees; SensorXcoordinate / SensorYcoordinate: easting / northing (m) when NavUnits is 0, longitude /
///   latitude (deg) when it is 3: from the world's x and y as UTM easting and northing in a given zone (io/utm.hpp), or
///   as a local plane about a geodetic origin (io/geodetic.hpp).
/// - Sample formats: unsigned 8-bit (SampleFormat 8, UniPolar 1), unsigned 16-bit (SampleFormat 3, UniPolar 1),
///   IEEE float (SampleFormat 5). Integer samples hold value x 2^Weight rounded (Weight, XTFPINGCHANHEADER
///   byte 58, one value per file chosen so the largest sample nearly fills the range): the reader returns
///   count x 2^-Weight, so a round trip is exact to within half of 2^-Weight.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/core/pose.hpp"
#include "sss/io/detail/bytes.hpp"
#include "sss/io/detail/civil_date.hpp"
#include "sss/io/detail/xtf_layout.hpp"
#include "sss/io/geodetic.hpp"
#include "sss/io/utm.hpp"
#include "sss/io/xtf_file.hpp"
#include "sss/receiver/image.hpp"

namespace sss::io {

/// A heading (deg) in [0, 360) as a float holds it: any number of turns either way removed, and a heading that
/// rounds to 360 in float (-1e-12 deg) written as 0.
[[nodiscard]] inline double heading_in_circle_deg(double deg) noexcept {
    double h = std::fmod(deg, 360.0);
    if (h < 0.0) h += 360.0;
    return static_cast<float>(h) >= 360.0f || h == 0.0 ? 0.0 : h; // -0 as 0 too
}

/// How a render becomes an XTF file.
struct xtf_render_params {
    double start_unix_s = 0.0;               ///< UTC time of row 0 (s since 1970)
    double ping_interval_s = 0.1;            ///< (s), > 0: row i at start + i interval where no times are known
    /// Each row's time since row 0 (s), in double; empty: the poses' time_s (in T) where they increase.
    std::vector<double> row_times_s{};
    std::uint32_t first_ping_number = 1;     ///< PingNumber of ping 0
    double sound_speed_mps = 1500.0;         ///< the render's reference sound speed (m/s), > 0
    geodetic_origin origin{};                ///< latitude/longitude of world (0, 0), for NavUnits 3
    /// For NavUnits 3: the world's x and y are UTM easting and northing (m) in this zone, converted exactly
    /// (io/utm.hpp); `origin` is then unused. Without it, x and y are metres east and north of `origin`.
    std::optional<utm_zone> utm{};
    xtf_header header{};
};

/// An XTF file from a waterfall and the poses of its pings (`poses[i]` for row i). `altitude_m[i]`, when
/// given, is the towfish's height above the seabed at ping i; otherwise the pose's z (a flat seabed at z = 0).
/// Each ping's time is start_unix_s plus its time since row 0: row_times_s, or its pose's time_s less row 0's
/// where those increase strictly (a trajectory's own times, when it has them), or i ping_interval_s. Its speed is
/// the distance between neighbouring poses over their time difference, SecondsPerPing their time difference per
/// ping, and FixedVSOP the distance per ping; heave is 0.
template <Real T>
[[nodiscard]] xtf_file make_xtf(const waterfall<T>& w, std::span<const pose<T>> poses, const xtf_render_params& p,
                                std::span<const double> altitude_m = {}) {
    sss::require(poses.size() == w.pings, "poses", "must hold one pose per ping (" + std::to_string(w.pings) + ")");
    sss::require(altitude_m.empty() || altitude_m.size() == w.pings, "altitude_m", "must be empty or one per ping");
    sss::require_positive(p.ping_interval_s, "xtf_render_params.ping_interval_s");
    sss::require_positive(p.sound_speed_mps, "xtf_render_params.sound_speed_mps");
    sss::require_finite(p.start_unix_s, "xtf_render_params.start_unix_s");
    sss::require(w.pings == 0 || w.pings - 1 <= std::numeric_limits<std::uint32_t>::max() - p.first_ping_number,
                 "xtf_render_params.first_ping_number", [&] {
                     return "leaves no room for " + std::to_string(w.pings) + " pings: PingNumber (32 bits) would wrap past " +
                            std::to_string(std::numeric_limits<std::uint32_t>::max());
                 });
    sss::require(p.row_times_s.empty() || p.row_times_s.size() == w.pings, "xtf_render_params.row_times_s",
                 "must be empty or one per ping");
    // Each row's time since row 0.
    std::vector<double> since(w.pings, 0.0);
    bool increasing = true;
    for (std::size_t i = 0; i < w.pings; ++i) {
        since[i] = p.row_times_s.empty() ? double(poses[i].time_s) - double(poses[0].time_s)
                                         : p.row_times_s[i] - p.row_times_s[0];
        if (!std::isfinite(since[i]) || (i > 0 && !(since[i] > since[i - 1]))) increasing = false;
    }
    if (!increasing) {
        sss::require(p.row_times_s.empty(), "xtf_render_params.row_times_s", "must be finite and increase strictly");
        for (std::size_t i = 0; i < w.pings; ++i) since[i] = double(i) * p.ping_interval_s;
    }
    xtf_file f;
    f.header = p.header;
    f.pings.resize(w.pings);
    const double deg = 180.0 / pi_v<double>;
    for (std::size_t i = 0; i < w.pings; ++i) {
        xtf_ping& q = f.pings[i];
        const pose<T>& s = poses[i];
        q.ping_number = p.first_ping_number + static_cast<std::uint32_t>(i);
        q.time_unix_s = p.start_unix_s + since[i];
        const double east = double(s.position.x), north = double(s.position.y);
        if (p.header.nav_units == xtf_nav_units::latitude_longitude) {
            const geodetic_position g = p.utm ? utm_to_geodetic(*p.utm, east, north) : to_geodetic(p.origin, east, north);
            q.x = g.longitude_deg;
            q.y = g.latitude_deg;
        } else {
            q.x = east;
            q.y = north;
        }
        q.altitude_m = altitude_m.empty() ? double(s.position.z) : altitude_m[i];
        const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(i + 1, w.pings - 1);
        const double dt = since[b] - since[a];
        q.seconds_per_ping = p.ping_interval_s;
        if (b > a && dt > 0.0) {
            const auto d = poses[b].position - poses[a].position;
            q.speed_mps = std::hypot(double(d.x), double(d.y)) / dt;
            q.seconds_per_ping = dt / double(b - a);
        }
        // The world's yaw is from its +y; where that is UTM grid north, the file's heading is from true north.
        const double north_bearing_deg = p.utm ? utm_north_grid_bearing_deg(*p.utm, east, north) : 0.0;
        q.heading_deg = heading_in_circle_deg(double(s.yaw_rad) * deg - north_bearing_deg);
        q.pitch_deg = double(s.pitch_rad) * deg;
        q.roll_deg = double(s.roll_rad) * deg;
        q.sound_speed_mps = p.sound_speed_mps;
        q.slant_range_m = double(w.samples) * w.dt_s * 0.5 * p.sound_speed_mps;
        q.port.resize(w.samples);
        q.starboard.resize(w.samples);
        for (std::size_t k = 0; k < w.samples; ++k) {
            q.port[k] = static_cast<float>(w.at(i, w.samples - 1 - k));
            q.starboard[k] = static_cast<float>(w.at(i, w.samples + k));
        }
    }
    return f;
}

/// The bytes of an XTF file (see the file comment). Throws invalid_parameter for samples that are not finite or
/// negative samples in an integer format. A ping's two channels may differ in length (each channel header gives its
/// own NumSamples). ThisFileName is header.file_name (write_xtf fills it in from the path when it is empty).
[[nodiscard]] inline std::vector<std::uint8_t> encode_xtf(const xtf_file& f) {
    using namespace sss::detail;
    const xtf_sample_format fmt = f.header.format;
    const std::size_t bps = xtf_bytes_per_sample(fmt);
    const int weight = xtf_weight(f);
    const double scale = std::ldexp(1.0, weight), top = fmt == xtf_sample_format::u8 ? 255.0 : 65535.0;
    std::size_t total = xtf_file_header_bytes;
    for (const auto& p : f.pings)
        total += (xtf_ping_header_bytes + 2 * xtf_chan_header_bytes + (p.port.size() + p.starboard.size()) * bps + 63) / 64 * 64;
    std::vector<std::uint8_t> out(total, 0);
    std::uint8_t* h = out.data();
    put_le<std::uint8_t>(h, 0, 0x7B);
    put_le<std::uint8_t>(h, 1, 1);
    put_chars(h, 2, f.header.program_name, 8);
    put_chars(h, 10, "223", 8);
    put_chars(h, 18, f.header.sonar_name, 16);
    put_chars(h, 36, f.header.note, 64);
    put_chars(h, 100, f.header.file_name, 64);
    put_le<std::uint16_t>(h, 164, static_cast<std::uint16_t>(f.header.nav_units));
    put_le<std::uint16_t>(h, 166, 2);
    xtf_put_chaninfo(h + 256, 1, f.header.port, fmt, "port");
    xtf_put_chaninfo(h + 256 + 128, 2, f.header.starboard, fmt, "starboard");
    std::size_t at = xtf_file_header_bytes;
    for (std::size_t i = 0; i < f.pings.size(); ++i) {
        const xtf_ping& p = f.pings[i];
        const std::size_t n_port = p.port.size(), n_stbd = p.starboard.size();
        const std::size_t bytes = (xtf_ping_header_bytes + 2 * xtf_chan_header_bytes + (n_port + n_stbd) * bps + 63) / 64 * 64;
        std::uint8_t* q = out.data() + at;
        put_le<std::uint16_t>(q, 0, 0xFACE);
        put_le<std::uint8_t>(q, 2, 0);
        put_le<std::uint16_t>(q, 4, 2);
        put_le<std::uint32_t>(q, 10, static_cast<std::uint32_t>(bytes));
        // Years 1 to 9999, as the header's year field and the civil calendar hold them.
        if (!(p.time_unix_s >= -62135596800.0 && p.time_unix_s < 253402300800.0))
            sss::require(false, "xtf_file.pings[" + std::to_string(i) + "].time_unix_s",
                         "must lie in years 1 to 9999 (-62135596800 to 253402300800 s since 1970), got " +
                             std::to_string(p.time_unix_s));
        const long long cs = std::llround(p.time_unix_s * 100.0);
        const long long days = (cs >= 0 ? cs : cs - 8639999) / 8640000;
        const long long in_day = cs - days * 8640000;
        const civil_date d = civil_from_days(days);
        put_le<std::uint16_t>(q, 14, static_cast<std::uint16_t>(d.year));
        put_le<std::uint8_t>(q, 16, static_cast<std::uint8_t>(d.month));
        put_le<std::uint8_t>(q, 17, static_cast<std::uint8_t>(d.day));
        put_le<std::uint8_t>(q, 18, static_cast<std::uint8_t>(in_day / 360000));
        put_le<std::uint8_t>(q, 19, static_cast<std::uint8_t>(in_day / 6000 % 60));
        put_le<std::uint8_t>(q, 20, static_cast<std::uint8_t>(in_day / 100 % 60));
        put_le<std::uint8_t>(q, 21, static_cast<std::uint8_t>(in_day % 100));
        put_le<std::uint16_t>(q, 22, static_cast<std::uint16_t>(days - days_from_civil(d.year, 1, 1) + 1));
        put_le<std::uint32_t>(q, 28, p.ping_number);
        put_le<float>(q, 32, static_cast<float>(0.5 * p.sound_speed_mps));
        put_le<float>(q, 72, static_cast<float>(p.sound_speed_mps));
        put_le<float>(q, 152, static_cast<float>(p.speed_mps * knots_per_mps));
        put_le<double>(q, 160, p.y);
        put_le<double>(q, 168, p.x);
        put_le<float>(q, 196, static_cast<float>(p.altitude_m));
        put_le<float>(q, 204, static_cast<float>(p.pitch_deg));
        put_le<float>(q, 208, static_cast<float>(p.roll_deg));
        put_le<float>(q, 212, static_cast<float>(p.heading_deg));
        put_le<float>(q, 216, static_cast<float>(p.heave_m));
        std::size_t c = at + xtf_ping_header_bytes;
        for (std::uint16_t ch = 0; ch < 2; ++ch) {
            const std::vector<float>& s = ch == 0 ? p.port : p.starboard;
            std::uint8_t* k = out.data() + c;
            put_le<std::uint16_t>(k, 0, ch);
            put_le<float>(k, 4, static_cast<float>(p.slant_range_m));
            const double ground = std::sqrt(std::max(0.0, p.slant_range_m * p.slant_range_m - p.altitude_m * p.altitude_m));
            put_le<float>(k, 8, static_cast<float>(ground));
            put_le<float>(k, 16, static_cast<float>(2.0 * p.slant_range_m / p.sound_speed_mps));
            put_le<float>(k, 20, static_cast<float>(p.seconds_per_ping));
            put_le<std::uint16_t>(k, 24, f.header.tvg_applied ? 4 : 0); // ProcessingFlags: 4, TVG applied
            const double f_khz = ch == 0 ? f.header.port.frequency_khz : f.header.starboard.frequency_khz;
            put_le<std::uint16_t>(k, 26, static_cast<std::uint16_t>(std::clamp(std::lround(f_khz), 0L, 65535L)));
            put_le<std::uint32_t>(k, 42, static_cast<std::uint32_t>(s.size()));
            put_le<float>(k, 54, static_cast<float>(100.0 * p.speed_mps * p.seconds_per_ping));
            put_le<std::int16_t>(k, 58, static_cast<std::int16_t>(weight));
            c += xtf_chan_header_bytes;
            // A bad sample is named by its ping, side and index: "xtf_file.pings[3].starboard[7]".
            const auto which = [&](std::size_t j) {
                return "xtf_file.pings[" + std::to_string(i) + "]." + (ch == 0 ? "port[" : "starboard[") +
                       std::to_string(ch == 0 ? s.size() - 1 - j : j) + "]";
            };
            for (std::size_t j = 0; j < s.size(); ++j) {
                const float v = s[ch == 0 ? s.size() - 1 - j : j]; // port far-to-near
                if (!std::isfinite(v)) require_finite(v, which(j));
                if (fmt == xtf_sample_format::f32) {
                    put_le<float>(out.data(), c + 4 * j, v);
                    continue;
                }
                if (!(v >= 0.0f)) require(false, which(j), "must be >= 0 for an unsigned sample format");
                const double count = std::min(top, std::round(double(v) * scale));
                if (fmt == xtf_sample_format::u8) put_le<std::uint8_t>(out.data(), c + j, static_cast<std::uint8_t>(count));
                else put_le<std::uint16_t>(out.data(), c + 2 * j, static_cast<std::uint16_t>(count));
            }
            c += s.size() * bps;
        }
        at += bytes;
    }
    return out;
}

/// Writes `f` to `path` (through a temporary renamed when complete: a failure leaves no file).
/// ThisFileName (file header byte 100) holds header.file_name, or when that is empty the path's last component.
inline void write_xtf(const std::string& path, const xtf_file& f) {
    std::vector<std::uint8_t> bytes = encode_xtf(f);
    if (f.header.file_name.empty()) {
        const std::size_t slash = path.find_last_of("/\\");
        sss::detail::put_chars(bytes.data(), 100, slash == std::string::npos ? path : path.substr(slash + 1), 64);
    }
    sss::detail::write_file_atomically(path, bytes.data(), bytes.size());
}

/// Reads the bytes of an XTF file named `name` (for messages): the first port and starboard sidescan channels
/// of every sonar packet; other packets (notes, attitude, navigation, ...) and channels are skipped. Throws
/// file_error with the byte offset of the first fault: a wrong magic number, no sonar channel, a record that
/// runs past the end of the file or is too short for what it holds, an unsupported sample format.
[[nodiscard]] inline xtf_file parse_xtf(std::span<const std::uint8_t> b, const std::string& name) {
    using namespace sss::detail;
    auto fail = [&name](std::size_t offset, const std::string& why) { xtf_fail(name, offset, why); };
    if (b.size() < xtf_file_header_bytes)
        fail(b.size(), "file of " + std::to_string(b.size()) + " bytes is shorter than the 1024-byte XTF file header");
    const std::uint8_t* h = b.data();
    if (h[0] != 0x7B) fail(0, "not an XTF file: FileFormat byte is " + std::to_string(h[0]) + ", expected 123 (0x7B)");
    xtf_file f;
    f.header.program_name = get_chars(h, 2, 8);
    f.header.sonar_name = get_chars(h, 18, 16);
    f.header.note = get_chars(h, 36, 64);
    const auto nav = get_le<std::uint16_t>(h, 164);
    f.header.nav_units = nav == 3 ? xtf_nav_units::latitude_longitude : xtf_nav_units::projected_m;
    const std::size_t n_sonar = get_le<std::uint16_t>(h, 166);
    if (n_sonar == 0) fail(166, "NumberOfSonarChannels is 0: no sidescan channel");
    const std::size_t n_all = n_sonar + get_le<std::uint16_t>(h, 168) + h[170] + h[171] + get_le<std::uint16_t>(h, 172) + h[174];
    const std::size_t header_bytes = std::max<std::size_t>(1, (256 + 128 * n_all + 1023) / 1024) * 1024;
    if (b.size() < header_bytes) fail(b.size(), "file ends inside the file header of " + std::to_string(header_bytes) + " bytes");
    struct chan { std::uint8_t type; std::size_t bps; bool unipolar; std::uint8_t format; };
    std::vector<chan> chans(n_sonar);
    int port = -1, stbd = -1;
    for (std::size_t i = 0; i < n_sonar; ++i) {
        const std::uint8_t* c = h + 256 + 128 * i;
        chans[i] = {c[0], get_le<std::uint16_t>(c, 6), get_le<std::uint16_t>(c, 4) != 0, c[74]};
        xtf_channel_info info{get_le<float>(c, 32), get_le<float>(c, 36), get_le<float>(c, 44), get_le<float>(c, 40)};
        const std::size_t off = 256 + 128 * i;
        if (chans[i].bps != 1 && chans[i].bps != 2 && chans[i].bps != 4)
            fail(off + 6, "channel " + std::to_string(i) + ": BytesPerSample " + std::to_string(chans[i].bps) + " is not 1, 2 or 4");
        if (chans[i].format == 1) fail(off + 74, "channel " + std::to_string(i) + ": IBM float samples are not supported");
        if (c[0] == 1 && port < 0) { port = int(i); f.header.port = info; }
        if (c[0] == 2 && stbd < 0) { stbd = int(i); f.header.starboard = info; }
    }
    if (port < 0 && stbd < 0) fail(256, "no port (type 1) or starboard (type 2) sidescan channel among the sonar channels");
    const chan& ref = chans[std::size_t(port >= 0 ? port : stbd)];
    f.header.format = ref.bps == 1 ? xtf_sample_format::u8 : ref.bps == 2 ? xtf_sample_format::u16 : xtf_sample_format::f32;
    std::size_t at = header_bytes;
    while (at < b.size()) {
        if (b.size() - at < 14) fail(at, "truncated packet: " + std::to_string(b.size() - at) + " bytes left, a packet header needs 14");
        const std::uint8_t* q = b.data() + at;
        const auto magic = get_le<std::uint16_t>(q, 0);
        if (magic != 0xFACE) fail(at, "packet magic number is " + std::to_string(magic) + ", expected 0xFACE (64206)");
        const std::size_t bytes = get_le<std::uint32_t>(q, 10);
        if (bytes < 14) fail(at + 10, "NumBytesThisRecord " + std::to_string(bytes) + " is shorter than a packet header");
        if (bytes > b.size() - at)
            fail(at + 10, "record of " + std::to_string(bytes) + " bytes runs past the end of the file (" +
                              std::to_string(b.size() - at) + " bytes left): truncated packet or wrong record length");
        if (q[2] == 0) {
            if (bytes < xtf_ping_header_bytes) fail(at + 10, "sonar record of " + std::to_string(bytes) + " bytes is shorter than its 256-byte ping header");
            xtf_ping p;
            p.ping_number = get_le<std::uint32_t>(q, 28);
            const long long days = days_from_civil(get_le<std::uint16_t>(q, 14), q[16], q[17]);
            p.time_unix_s = double(days) * 86400.0 + q[18] * 3600.0 + q[19] * 60.0 + q[20] + q[21] / 100.0;
            const double sv = get_le<float>(q, 32);
            p.sound_speed_mps = sv < 1000.0 ? 2.0 * sv : sv;
            p.speed_mps = double(get_le<float>(q, 152)) / knots_per_mps;
            p.y = get_le<double>(q, 160);
            p.x = get_le<double>(q, 168);
            p.altitude_m = get_le<float>(q, 196);
            p.pitch_deg = get_le<float>(q, 204);
            p.roll_deg = get_le<float>(q, 208);
            p.heading_deg = get_le<float>(q, 212);
            p.heave_m = get_le<float>(q, 216);
            const std::size_t n_chans = get_le<std::uint16_t>(q, 4);
            std::size_t c = xtf_ping_header_bytes;
            for (std::size_t k = 0; k < n_chans; ++k) {
                if (bytes - c < xtf_chan_header_bytes) fail(at + c, "channel header overruns its record of " + std::to_string(bytes) + " bytes");
                const std::uint8_t* ch = q + c;
                const std::size_t number = get_le<std::uint16_t>(ch, 0);
                if (number >= n_sonar) fail(at + c, "ChannelNumber " + std::to_string(number) + " names no sonar channel");
                const chan& info = chans[number];
                const std::size_t n = get_le<std::uint32_t>(ch, 42);
                if (n > (bytes - c - xtf_chan_header_bytes) / info.bps)
                    fail(at + c + 42, "NumSamples " + std::to_string(n) + " overruns its record of " + std::to_string(bytes) + " bytes");
                const double unit = std::ldexp(1.0, -get_le<std::int16_t>(ch, 58));
                const std::uint8_t* s = ch + xtf_chan_header_bytes;
                std::vector<float> v(n);
                for (std::size_t j = 0; j < n; ++j) {
                    double x = 0.0;
                    if (info.bps == 1) x = info.unipolar ? double(s[j]) : double(static_cast<std::int8_t>(s[j]));
                    else if (info.bps == 2) x = info.unipolar ? double(get_le<std::uint16_t>(s, 2 * j)) : double(get_le<std::int16_t>(s, 2 * j));
                    else if (info.format == 5 || info.format == 0) x = double(get_le<float>(s, 4 * j));
                    else x = info.unipolar ? double(get_le<std::uint32_t>(s, 4 * j)) : double(get_le<std::int32_t>(s, 4 * j));
                    v[j] = static_cast<float>(info.bps == 4 && (info.format == 5 || info.format == 0) ? x : x * unit);
                    if (!std::isfinite(v[j]))
                        fail(at + c + xtf_chan_header_bytes + j * info.bps,
                             "sample " + std::to_string(j) + " of channel " + std::to_string(number) +
                                 " is not finite (or its Weight scales it out of range)");
                }
                if (int(number) == port || int(number) == stbd) {
                    p.slant_range_m = get_le<float>(ch, 4);
                    p.seconds_per_ping = get_le<float>(ch, 20);
                    p.weight = get_le<std::int16_t>(ch, 58);
                    if ((get_le<std::uint16_t>(ch, 24) & 4u) != 0) f.header.tvg_applied = true;
                }
                if (int(number) == port) p.port.assign(v.rbegin(), v.rend()); // stored far-to-near
                if (int(number) == stbd) p.starboard = std::move(v);
                c += xtf_chan_header_bytes + n * info.bps;
            }
            f.pings.push_back(std::move(p));
        }
        at += bytes;
    }
    return f;
}

/// Reads an XTF file (see parse_xtf).
[[nodiscard]] inline xtf_file read_xtf(const std::string& path) {
    const std::vector<std::uint8_t> bytes = sss::detail::read_file_bytes(path);
    return parse_xtf(bytes, path);
}

} // namespace sss::io

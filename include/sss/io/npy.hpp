#pragma once
/// \file
/// NumPy .npy arrays of a render, and a JSON sidecar that says what the array holds.
///
/// The .npy layout is NumPy's format version 1.0 (Kern, 2007, NumPy Enhancement Proposal 1, "A simple file
/// format for NumPy arrays"): the magic "\x93NUMPY", version bytes 1 0, a little-endian u16 header length, an
/// ASCII Python dict {'descr': '<f4' or '<f8', 'fortran_order': False, 'shape': (pings, 2 samples), }
/// padded with spaces and a newline so that the data start at a multiple of 64 bytes, then the values in C
/// order. `numpy.load(path)` returns the waterfall exactly: row i is ping i, port mirrored on the left (far
/// range in column 0), starboard on the right (receiver/image.hpp).
///
/// The sidecar (`write_render_sidecar`) is a JSON object: the array's file name, shape and dtype, the sample
/// interval (s), the sound speed (m/s), the range of the last sample (m), the column layout, what the values are
/// (`values`; the source level, dB, they are relative to; the receiver's stages applied to them in order, each
/// {stage, parameters}: speckle, noise, a TVG's gain, none for the mean echo power), and the pose of every ping
/// (time_s, x_m, y_m, z_m world metres; heading_deg clockwise from north in [0, 360), pitch_deg nose up, roll_deg
/// starboard down).

#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/core/pose.hpp"
#include "sss/io/detail/bytes.hpp"
#include "sss/io/detail/json.hpp"
#include "sss/receiver/image.hpp"

namespace sss::io {

/// The bytes of a .npy file holding `rows` x `cols` values of `values` (C order).
template <Real T>
[[nodiscard]] std::vector<std::uint8_t> encode_npy(std::span<const T> values, std::size_t rows, std::size_t cols) {
    sss::require(values.size() == rows * cols, "values", "must hold rows x cols values");
    std::string dict = std::string("{'descr': '<") + (sizeof(T) == 4 ? "f4" : "f8") +
                       "', 'fortran_order': False, 'shape': (" + std::to_string(rows) + ", " + std::to_string(cols) + "), }";
    const std::size_t unpadded = 10 + dict.size() + 1;
    dict.append((64 - unpadded % 64) % 64, ' ');
    dict += '\n';
    std::vector<std::uint8_t> out(10 + dict.size() + values.size() * sizeof(T));
    std::memcpy(out.data(), "\x93NUMPY\x01\x00", 8);
    sss::detail::put_le<std::uint16_t>(out.data(), 8, static_cast<std::uint16_t>(dict.size()));
    std::memcpy(out.data() + 10, dict.data(), dict.size());
    const std::size_t at = 10 + dict.size();
    for (std::size_t i = 0; i < values.size(); ++i) sss::detail::put_le<T>(out.data(), at + i * sizeof(T), values[i]);
    return out;
}

/// Writes the waterfall as a .npy array of shape (pings, 2 samples) in its own precision (see the file comment),
/// through a temporary renamed when complete.
template <Real T> void write_npy(const std::string& path, const waterfall<T>& w) {
    const auto bytes = encode_npy<T>(std::span<const T>(w.values), w.pings, w.width());
    sss::detail::write_file_atomically(path, bytes.data(), bytes.size());
}

/// What the sidecar records besides the waterfall itself.
struct render_sidecar_params {
    std::string array_file;          ///< the .npy file it describes (as the sidecar should name it)
    double sound_speed_mps = 1500.0; ///< the render's reference sound speed (m/s)
    double source_level_db = 0.0;    ///< the source level the powers are relative to (receiver_params::source_level_db)
    /// The receiver's line stages applied to the values, in order: (stage, its parameters in words); none: the mean
    /// echo power per sample as the simulator gives it.
    std::vector<std::pair<std::string, std::string>> receiver_stages{};
};

/// The sidecar's JSON text (see the file comment). `poses` holds one pose per ping, or none.
template <Real T>
[[nodiscard]] std::string render_sidecar_json(const waterfall<T>& w, std::span<const pose<T>> poses, const render_sidecar_params& p) {
    sss::require(poses.empty() || poses.size() == w.pings, "poses", "must be empty or hold one pose per ping");
    sss::require_positive(p.sound_speed_mps, "render_sidecar_params.sound_speed_mps");
    const double deg = 180.0 / pi_v<double>;
    sss::detail::json_writer j;
    j.begin_object();
    j.member("array_file", p.array_file).member("dtype", sizeof(T) == 4 ? "<f4" : "<f8");
    j.key("shape").begin_array().value(w.pings).value(w.width()).end_array();
    j.member("samples_per_side", w.samples);
    j.member("sample_interval_s", w.dt_s).member("sound_speed_mps", p.sound_speed_mps);
    j.member("max_range_m", double(w.samples) * w.dt_s * 0.5 * p.sound_speed_mps);
    j.member("columns", "port far-to-near in [0, samples), starboard near-to-far in [samples, 2 samples); sample k "
                        "covers two-way time [k dt, (k + 1) dt)");
    j.member("values", p.receiver_stages.empty()
                           ? "mean received power per sample, relative to the source level reference"
                           : "received power per sample, relative to the source level reference, after the receiver "
                             "stages listed in receiver_stages (in that order)");
    j.member("source_level_db", p.source_level_db);
    j.key("receiver_stages").begin_array();
    for (const auto& [stage, parameters] : p.receiver_stages) {
        j.newline().begin_object();
        j.member("stage", stage).member("parameters", parameters);
        j.end_object();
    }
    j.end_array();
    j.key("poses").begin_array();
    for (const pose<T>& q : poses) {
        j.newline().begin_object();
        j.member("time_s", double(q.time_s)).member("x_m", double(q.position.x)).member("y_m", double(q.position.y));
        double heading = std::fmod(double(q.yaw_rad) * deg, 360.0); // in [0, 360): a turning towfish's yaw grows on
        if (heading < 0.0) heading += 360.0;
        j.member("z_m", double(q.position.z)).member("heading_deg", heading >= 360.0 ? 0.0 : heading);
        j.member("pitch_deg", double(q.pitch_rad) * deg).member("roll_deg", double(q.roll_rad) * deg);
        j.end_object();
    }
    j.end_array().end_object().newline();
    return j.str();
}

/// Writes the sidecar (through a temporary renamed when complete).
template <Real T>
void write_render_sidecar(const std::string& path, const waterfall<T>& w, std::span<const pose<T>> poses, const render_sidecar_params& p) {
    sss::detail::write_file_atomically(path, render_sidecar_json(w, poses, p));
}

} // namespace sss::io

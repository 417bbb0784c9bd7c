#pragma once
/// \file
/// The contents of an XTF (eXtended Triton Format) file of two-channel sidescan as plain data: the file header,
/// its channels' descriptions and the pings. io/xtf.hpp writes and reads them (and includes this header).

#include <cstdint>
#include <string>
#include <vector>

namespace sss::io {

enum class xtf_sample_format : std::uint8_t { u8, u16, f32 };
enum class xtf_nav_units : std::uint16_t { projected_m = 0, latitude_longitude = 3 };

/// One sidescan channel's description (CHANINFO).
struct xtf_channel_info {
    double frequency_khz = 100.0;           ///< centre frequency (kHz)
    double horizontal_beam_angle_deg = 1.0; ///< along-track beam width (deg)
    double beam_width_deg = 50.0;           ///< vertical beam width (deg)
    double tilt_deg = 20.0;                 ///< depression of the beam axis below horizontal (deg)
};

/// What the file header says.
struct xtf_header {
    std::string program_name = "sss";          ///< RecordingProgramName (7 bytes kept, and a zero)
    std::string sonar_name = "sss simulator";  ///< SonarName (15 bytes kept, and a zero)
    std::string note;                          ///< NoteString (63 bytes kept, and a zero)
    /// ThisFileName (63 bytes kept, and a zero); empty: write_xtf writes the last component of the path it writes to
    /// (give the final name here when the file is written under a temporary name and renamed later). The reader
    /// leaves it empty, so that a file read and written elsewhere takes its new name.
    std::string file_name;
    /// The samples carry time-varied gain: ProcessingFlags 4 ("TVG applied") in each channel header, so that a
    /// reader does not apply its own on top.
    bool tvg_applied = false;
    xtf_nav_units nav_units = xtf_nav_units::latitude_longitude;
    xtf_sample_format format = xtf_sample_format::f32;
    xtf_channel_info port{}, starboard{};
};

/// One sonar packet: a ping's navigation, attitude and the two channels' samples.
struct xtf_ping {
    std::uint32_t ping_number = 0;
    double time_unix_s = 0.0;      ///< UTC seconds since 1970-01-01 (kept to 1/100 s)
    double x = 0.0, y = 0.0;       ///< SensorX/Ycoordinate: easting/northing (m) or longitude/latitude (deg)
    double altitude_m = 0.0;       ///< above the seabed (m)
    double speed_mps = 0.0;        ///< (m/s; knots in the file)
    double heading_deg = 0.0;      ///< clockwise from north (deg)
    double pitch_deg = 0.0;        ///< nose up positive (deg)
    double roll_deg = 0.0;         ///< starboard down positive (deg)
    double heave_m = 0.0;          ///< (m)
    double sound_speed_mps = 1500.0; ///< full sound speed (m/s)
    double slant_range_m = 0.0;    ///< range of the last sample (m)
    double seconds_per_ping = 0.0; ///< ping interval (s)
    int weight = 0;                ///< integer samples are count x 2^-weight (set by the writer)
    std::vector<float> port;       ///< port samples, near range first
    std::vector<float> starboard;  ///< starboard samples, near range first
};

struct xtf_file {
    xtf_header header{};
    std::vector<xtf_ping> pings;
};

} // namespace sss::io

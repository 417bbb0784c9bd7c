// XTF files: a render written and read back keeps every field and sample (exactly for float samples, within half a
// quantisation step for 8 and 16 bits); the fixed offsets of the format hold byte for byte; broken files give
// errors naming the byte; a failed write leaves no file; the geodetic mapping has the published lengths of a degree.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <filesystem>
#include <string>
#include <vector>

#include "sss/io/xtf.hpp"
#include "sss/scene/flat_seabed.hpp"
#include "sss/simulator.hpp"
#include "support/temporaries.hpp"

namespace {

using namespace sss;
using io::xtf_file;

struct render {
    waterfall<double> w;
    std::vector<pose<double>> poses;
};

// Six pings over a flat seabed 8 m below a towfish heading 30 deg, 25 m of range at 20 kHz.
render small_render() {
    receiver_params rp;
    rp.max_range_m = 25.0;
    motion::straight_line_params<double> tow{.start_m = {100.0, -50.0}, .heading_deg = 30.0, .speed_mps = 2.0,
                                             .altitude_m = 8.0, .ping_interval_s = 0.2};
    const simulator<scattering::lambertian<double>, propagation::straight<double>, beam::ideal_fan<double>, motion::straight_line<double>>
        sim({}, {}, {}, motion::straight_line<double>(tow), rp, ray_density{.along = 2, .across = 0, .per_sample = 1.0});
    render r;
    r.w = sim.render(scene::flat_seabed<double>(0.0), 0, 6, 1);
    for (std::size_t i = 0; i < 6; ++i) r.poses.push_back(sim.motion().pose_at(i));
    return r;
}

io::xtf_render_params params(io::xtf_sample_format f, io::xtf_nav_units nav) {
    io::xtf_render_params p{.start_unix_s = 1'700'000'000.25, .ping_interval_s = 0.2, .first_ping_number = 41,
                            .sound_speed_mps = 1500.0, .origin = {.latitude_deg = 57.1, .longitude_deg = 11.9}};
    p.header.format = f;
    p.header.nav_units = nav;
    p.header.note = "round trip";
    p.header.port = {.frequency_khz = 410.0, .horizontal_beam_angle_deg = 0.5, .beam_width_deg = 40.0, .tilt_deg = 15.0};
    p.header.starboard = {.frequency_khz = 420.0, .horizontal_beam_angle_deg = 0.6, .beam_width_deg = 45.0, .tilt_deg = 16.0};
    return p;
}

double f32(double x) { return double(static_cast<float>(x)); }

void check_same_header(const io::xtf_header& a, const io::xtf_header& b) {
    CHECK(a.program_name == b.program_name);
    CHECK(a.sonar_name == b.sonar_name);
    CHECK(a.note == b.note);
    CHECK(a.nav_units == b.nav_units);
    CHECK(a.format == b.format);
    for (int s = 0; s < 2; ++s) {
        const auto& x = s == 0 ? a.port : a.starboard;
        const auto& y = s == 0 ? b.port : b.starboard;
        CHECK(y.frequency_khz == f32(x.frequency_khz));
        CHECK(y.horizontal_beam_angle_deg == f32(x.horizontal_beam_angle_deg));
        CHECK(y.beam_width_deg == f32(x.beam_width_deg));
        CHECK(y.tilt_deg == f32(x.tilt_deg));
    }
}

void check_same_navigation(const io::xtf_ping& a, const io::xtf_ping& b) {
    CHECK(b.ping_number == a.ping_number);
    CHECK(std::abs(b.time_unix_s - a.time_unix_s) <= 0.005 + 1e-6); // HSeconds: 1/100 s
    CHECK(b.x == a.x);
    CHECK(b.y == a.y);
    CHECK(b.altitude_m == f32(a.altitude_m));
    CHECK(b.speed_mps == doctest::Approx(a.speed_mps).epsilon(1e-6)); // knots in the file
    CHECK(b.heading_deg == f32(a.heading_deg));
    CHECK(b.pitch_deg == f32(a.pitch_deg));
    CHECK(b.roll_deg == f32(a.roll_deg));
    CHECK(b.heave_m == f32(a.heave_m));
    CHECK(b.sound_speed_mps == f32(a.sound_speed_mps));
    CHECK(b.slant_range_m == f32(a.slant_range_m));
    CHECK(b.seconds_per_ping == f32(a.seconds_per_ping));
}

std::vector<std::uint8_t> bytes_of(const xtf_file& f) { return io::encode_xtf(f); }

/// The file_error of parsing `b`, or a default one at byte 999999 when nothing is thrown.
file_error error_of(const std::vector<std::uint8_t>& b) {
    try {
        (void)io::parse_xtf(b, "broken.xtf");
    } catch (const file_error& e) {
        return e;
    }
    return file_error("(none)", 0, "no error", 999999);
}

} // namespace

TEST_CASE("XTF ping times, SecondsPerPing and FixedVSOP follow the poses' own times, not the nominal interval") {
    // The poses of the render, retimed as a trajectory timed by its own clock would be: 0.5 s apart, then 1 s for the
    // last ping; the nominal interval passed in (0.2 s) is only for a file of one ping.
    render r = small_render();
    const double times[6] = {0.0, 0.5, 1.0, 1.5, 2.0, 3.0};
    for (std::size_t i = 0; i < 6; ++i) r.poses[i].time_s = 10.0 + times[i]; // row 0 at 10 s: only differences count
    const auto p = params(io::xtf_sample_format::f32, io::xtf_nav_units::projected_m);
    const xtf_file f = io::make_xtf<double>(r.w, r.poses, p);
    io::write_xtf("timed.xtf", f);
    const xtf_file g = io::read_xtf("timed.xtf");
    REQUIRE(g.pings.size() == 6u);
    for (std::size_t i = 0; i < 6; ++i)
        CHECK(std::abs(g.pings[i].time_unix_s - (1'700'000'000.25 + times[i])) <= 0.005 + 1e-6); // HSeconds: 1/100 s
    // Ping 2 between pings 1 and 3: 1 s over 2 pings, 0.4 m of track each (2 m/s over 0.2 s each in the render).
    CHECK(g.pings[2].seconds_per_ping == doctest::Approx(0.5));
    CHECK(g.pings[2].speed_mps == doctest::Approx(0.8).epsilon(1e-5));
    const auto bytes = detail::read_file_bytes("timed.xtf");
    // The second ping's starboard channel header: 1024 bytes of file header, a ping record each before it.
    std::size_t at = 1024;
    at += detail::get_le<std::uint32_t>(bytes.data(), at + 10); // NumBytesThisRecord of ping 0
    at += detail::get_le<std::uint32_t>(bytes.data(), at + 10); // of ping 1
    const std::size_t port_channel = at + 256;
    const std::uint32_t port_samples = detail::get_le<std::uint32_t>(bytes.data(), port_channel + 42);
    const std::size_t starboard_channel = port_channel + 64 + 4 * std::size_t(port_samples);
    for (const std::size_t c : {port_channel, starboard_channel}) {
        CHECK(detail::get_le<float>(bytes.data(), c + 20) == doctest::Approx(0.5));        // SecondsPerPing
        CHECK(detail::get_le<float>(bytes.data(), c + 54) == doctest::Approx(40.0).epsilon(1e-5)); // FixedVSOP, cm per ping
    }
    std::filesystem::remove("timed.xtf");
    // Times given in double take the place of the poses' (which in float lose milliseconds after hours).
    auto q = p;
    q.row_times_s = {3600.0, 3600.25, 3600.5, 3600.75, 3601.0, 3601.25};
    const xtf_file h = io::make_xtf<double>(r.w, r.poses, q);
    CHECK(h.pings[5].time_unix_s == 1'700'000'000.25 + 1.25);
    CHECK(h.pings[2].seconds_per_ping == doctest::Approx(0.25).epsilon(1e-12));
    // Poses whose times do not increase (none given): the nominal interval.
    for (auto& pose : r.poses) pose.time_s = 0.0;
    const xtf_file z = io::make_xtf<double>(r.w, r.poses, p);
    CHECK(z.pings[4].time_unix_s == doctest::Approx(1'700'000'000.25 + 4 * 0.2).epsilon(1e-15));
    CHECK(z.pings[4].seconds_per_ping == doctest::Approx(0.2).epsilon(1e-12));
    q.row_times_s[3] = q.row_times_s[2];
    CHECK_THROWS_AS((void)io::make_xtf<double>(r.w, r.poses, q), invalid_parameter);
}

TEST_CASE("An XTF round trip of a render keeps every header field, navigation value and float sample") {
    const render r = small_render();
    const auto p = params(io::xtf_sample_format::f32, io::xtf_nav_units::latitude_longitude);
    const xtf_file f = io::make_xtf<double>(r.w, r.poses, p);
    io::write_xtf("float.xtf", f);
    const xtf_file g = io::read_xtf("float.xtf");
    check_same_header(f.header, g.header);
    CHECK(detail::get_chars(detail::read_file_bytes("float.xtf").data(), 100, 64) == "float.xtf"); // ThisFileName
    CHECK(g.header.file_name.empty()); // not read: a file read and written elsewhere takes its new name
    CHECK(!g.header.tvg_applied);
    io::write_xtf("copied.xtf", g);
    CHECK(detail::get_chars(detail::read_file_bytes("copied.xtf").data(), 100, 64) == "copied.xtf");
    std::filesystem::remove("copied.xtf");
    REQUIRE(g.pings.size() == 6u);
    for (std::size_t i = 0; i < 6; ++i) {
        check_same_navigation(f.pings[i], g.pings[i]);
        REQUIRE(g.pings[i].port.size() == r.w.samples);
        REQUIRE(g.pings[i].starboard.size() == r.w.samples);
        for (std::size_t k = 0; k < r.w.samples; ++k) {
            CHECK(g.pings[i].port[k] == static_cast<float>(r.w.at(i, r.w.samples - 1 - k)));
            CHECK(g.pings[i].starboard[k] == static_cast<float>(r.w.at(i, r.w.samples + k)));
        }
    }
    // What the render put in: ping numbers from the first, times from the start and the interval, the
    // towfish's speed, heading and altitude, the range of the last sample.
    CHECK(g.pings[3].ping_number == 44u);
    CHECK(g.pings[3].time_unix_s == doctest::Approx(1'700'000'000.85).epsilon(1e-12));
    CHECK(g.pings[2].speed_mps == doctest::Approx(2.0).epsilon(1e-5));
    CHECK(g.pings[2].heading_deg == doctest::Approx(30.0).epsilon(1e-5));
    CHECK(g.pings[2].altitude_m == doctest::Approx(8.0));
    CHECK(g.pings[0].slant_range_m == doctest::Approx(double(r.w.samples) * r.w.dt_s * 750.0));
    // Position: ping 5 is 2 m of track further along 30 deg from ping 0, in latitude and longitude.
    double e0 = 0, n0 = 0, e5 = 0, n5 = 0;
    io::from_geodetic(p.origin, {g.pings[0].y, g.pings[0].x}, e0, n0);
    io::from_geodetic(p.origin, {g.pings[5].y, g.pings[5].x}, e5, n5);
    CHECK(e0 == doctest::Approx(100.0).epsilon(1e-9));
    CHECK(n0 == doctest::Approx(-50.0).epsilon(1e-9));
    CHECK(std::hypot(e5 - e0, n5 - n0) == doctest::Approx(2.0).epsilon(1e-6));
    // The far port sample is the first stored, as readers expect: the waterfall's leftmost column.
    const auto raw = bytes_of(f);
    CHECK(detail::get_le<float>(raw.data(), 1024 + 256 + 64) == static_cast<float>(r.w.at(0, 0)));
}

TEST_CASE("8- and 16-bit XTF samples come back within half a quantisation step of 2^-Weight") {
    const render r = small_render();
    double peak = 0;
    for (double v : r.w.values) peak = std::max(peak, v);
    for (const auto fmt : {io::xtf_sample_format::u8, io::xtf_sample_format::u16}) {
        CAPTURE(int(fmt));
        const xtf_file f = io::make_xtf<double>(r.w, r.poses, params(fmt, io::xtf_nav_units::projected_m));
        io::write_xtf("quantised.xtf", f);
        const xtf_file g = io::read_xtf("quantised.xtf");
        check_same_header(f.header, g.header);
        REQUIRE(g.pings.size() == 6u);
        const double step = std::ldexp(1.0, -g.pings[0].weight);
        const double top = fmt == io::xtf_sample_format::u8 ? 255.0 : 65535.0;
        // The weight nearly fills the range: the peak is above half the largest count.
        CHECK(peak / step <= top);
        CHECK(peak / step > top / 2);
        for (std::size_t i = 0; i < 6; ++i) {
            check_same_navigation(f.pings[i], g.pings[i]);
            CHECK(g.pings[i].weight == g.pings[0].weight);
            for (std::size_t k = 0; k < r.w.samples; ++k) {
                CHECK(std::abs(double(g.pings[i].port[k]) - double(f.pings[i].port[k])) <= 0.5 * step * (1 + 1e-6));
                CHECK(std::abs(double(g.pings[i].starboard[k]) - double(f.pings[i].starboard[k])) <= 0.5 * step * (1 + 1e-6));
            }
        }
    }
}

TEST_CASE("XTF bytes sit at the format's fixed offsets and the record lengths sum to the file size") {
    const render r = small_render();
    for (const auto fmt : {io::xtf_sample_format::u8, io::xtf_sample_format::u16, io::xtf_sample_format::f32}) {
        const xtf_file f = io::make_xtf<double>(r.w, r.poses, params(fmt, io::xtf_nav_units::latitude_longitude));
        const auto b = bytes_of(f);
        const std::uint8_t* h = b.data();
        const std::size_t bps = fmt == io::xtf_sample_format::u8 ? 1 : fmt == io::xtf_sample_format::u16 ? 2 : 4;
        CHECK(h[0] == 0x7B);
        CHECK(h[1] == 1);
        CHECK(std::string(reinterpret_cast<const char*>(h + 10)) == "223");
        CHECK(detail::get_le<std::uint16_t>(h, 164) == 3); // NavUnits: latitude/longitude
        CHECK(detail::get_le<std::uint16_t>(h, 166) == 2);  // two sonar channels
        CHECK(detail::get_le<std::uint16_t>(h, 168) == 0);
        CHECK(h[256] == 1);       // port
        CHECK(h[256 + 128] == 2); // starboard
        CHECK(detail::get_le<std::uint16_t>(h, 256 + 6) == bps);
        CHECK(detail::get_le<float>(h, 256 + 32) == 410.0f);
        CHECK(h[256 + 74] == (bps == 1 ? 8 : bps == 2 ? 3 : 5));
        std::size_t at = 1024, packets = 0;
        while (at < b.size()) {
            const std::uint8_t* q = h + at;
            CHECK(q[0] == 0xCE);
            CHECK(q[1] == 0xFA);
            CHECK(q[2] == 0);
            CHECK(detail::get_le<std::uint16_t>(q, 4) == 2);
            const std::uint32_t len = detail::get_le<std::uint32_t>(q, 10);
            CHECK(len % 64 == 0);
            CHECK(len >= 256 + 2 * 64 + 2 * r.w.samples * bps);
            CHECK(len < 256 + 2 * 64 + 2 * r.w.samples * bps + 64);
            CHECK(detail::get_le<std::uint32_t>(q, 28) == 41 + packets);
            CHECK(detail::get_le<float>(q, 32) == 750.0f);
            CHECK(detail::get_le<std::uint16_t>(q, 256) == 0);                                  // port channel header
            CHECK(detail::get_le<std::uint32_t>(q, 256 + 42) == r.w.samples);
            CHECK(detail::get_le<std::uint16_t>(q, 256 + 64 + r.w.samples * bps) == 1);       // starboard's
            CHECK(detail::get_le<std::uint32_t>(q, 256 + 64 + r.w.samples * bps + 42) == r.w.samples);
            at += len;
            ++packets;
        }
        CHECK(at == b.size());
        CHECK(packets == 6u);
    }
}

TEST_CASE("Broken XTF files each give their own error with the byte offset of the fault") {
    const render r = small_render();
    const auto good = bytes_of(io::make_xtf<double>(r.w, r.poses, params(io::xtf_sample_format::u16, io::xtf_nav_units::projected_m)));
    const std::size_t second = 1024 + detail::get_le<std::uint32_t>(good.data(), 1024 + 10);
    SUBCASE("wrong file magic") {
        auto b = good;
        b[0] = 0x7A;
        const auto e = error_of(b);
        CHECK(e.byte_offset() == 0);
        CHECK(std::string(e.what()).find("0x7B") != std::string::npos);
    }
    SUBCASE("a float sample that is not finite") {
        auto b = bytes_of(io::make_xtf<double>(r.w, r.poses, params(io::xtf_sample_format::f32, io::xtf_nav_units::projected_m)));
        const std::size_t sample = 1024 + 256 + 64 + 4 * 3; // the first ping's port channel, fourth sample stored
        detail::put_le<float>(b.data(), sample, std::numeric_limits<float>::quiet_NaN());
        const auto e = error_of(b);
        CHECK(e.byte_offset() == sample);
        CHECK(std::string(e.what()).find("not finite") != std::string::npos);
    }
    SUBCASE("zero channels") {
        auto b = good;
        detail::put_le<std::uint16_t>(b.data(), 166, 0);
        const auto e = error_of(b);
        CHECK(e.byte_offset() == 166);
        CHECK(std::string(e.what()).find("NumberOfSonarChannels") != std::string::npos);
    }
    SUBCASE("truncated packet") {
        auto b = good;
        b.resize(b.size() - 100);
        const auto e = error_of(b);
        CHECK(e.byte_offset() == good.size() - (second - 1024) + 10); // the last record's length field
        CHECK(std::string(e.what()).find("runs past the end") != std::string::npos);
    }
    SUBCASE("record length past the end") {
        auto b = good;
        detail::put_le<std::uint32_t>(b.data(), second + 10, 0x7fffffffu);
        const auto e = error_of(b);
        CHECK(e.byte_offset() == second + 10);
        CHECK(std::string(e.what()).find("2147483647") != std::string::npos);
    }
    SUBCASE("wrong packet magic") {
        auto b = good;
        b[second] = 0;
        const auto e = error_of(b);
        CHECK(e.byte_offset() == second);
        CHECK(std::string(e.what()).find("0xFACE") != std::string::npos);
    }
    SUBCASE("too many samples for the record") {
        auto b = good;
        detail::put_le<std::uint32_t>(b.data(), second + 256 + 42, 1u << 20);
        const auto e = error_of(b);
        CHECK(e.byte_offset() == second + 256 + 42);
        CHECK(std::string(e.what()).find("NumSamples") != std::string::npos);
    }
    SUBCASE("shorter than the file header") {
        const std::vector<std::uint8_t> b(good.begin(), good.begin() + 500);
        const auto e = error_of(b);
        CHECK(e.byte_offset() == 500);
        CHECK(std::string(e.what()).find("1024") != std::string::npos);
    }
    // And every error names the file.
    CHECK(std::string(error_of(std::vector<std::uint8_t>(10)).what()).find("broken.xtf") != std::string::npos);
}

TEST_CASE("An ordinary sidescan file with other packets and channel types reads its port and starboard lines") {
    const render r = small_render();
    auto b = bytes_of(io::make_xtf<double>(r.w, r.poses, params(io::xtf_sample_format::f32, io::xtf_nav_units::projected_m)));
    // A 64-byte notes packet (header type 1) after the file header, as field files carry.
    std::vector<std::uint8_t> note(64, 0);
    detail::put_le<std::uint16_t>(note.data(), 0, 0xFACE);
    note[2] = 1;
    detail::put_le<std::uint32_t>(note.data(), 10, 64);
    b.insert(b.begin() + 1024, note.begin(), note.end());
    const xtf_file g = io::parse_xtf(b, "with_notes.xtf");
    REQUIRE(g.pings.size() == 6u);
    CHECK(g.pings[5].starboard[10] == static_cast<float>(r.w.at(5, r.w.samples + 10)));
    CHECK(g.pings[5].port[10] == static_cast<float>(r.w.at(5, r.w.samples - 11)));
}

TEST_CASE("A failed XTF write leaves no file, not even the temporary") {
    const render r = small_render();
    xtf_file f = io::make_xtf<double>(r.w, r.poses, params(io::xtf_sample_format::u8, io::xtf_nav_units::projected_m));
    CHECK_THROWS_AS(io::write_xtf("no_such_directory/a.xtf", f), file_error);
    CHECK(!std::filesystem::exists("no_such_directory"));
    f.pings[2].starboard[3] = std::nanf("");
    CHECK_THROWS_AS(io::write_xtf("nan.xtf", f), invalid_parameter);
    CHECK(!std::filesystem::exists("nan.xtf"));
    CHECK(sss_test::temporaries_left("nan.xtf") == 0);
}

TEST_CASE("The geodetic mapping has the published lengths of a degree on WGS 84 and inverts exactly") {
    // Metres per degree on WGS 84 from the usual series in the latitude phi: 111132.954 - 559.822 cos 2 phi
    // + 1.175 cos 4 phi of latitude and 111412.84 cos phi - 93.5 cos 3 phi + 0.118 cos 5 phi of longitude:
    // 110574.31 and 111319.46 m at the equator, 111131.78 and 78846.81 m at 45 deg.
    double e = 0, n = 0;
    io::from_geodetic({0.0, 0.0}, {1.0, 1.0}, e, n);
    CHECK(n == doctest::Approx(110574.31).epsilon(1e-6));
    CHECK(e == doctest::Approx(111319.46).epsilon(1e-6));
    io::from_geodetic({45.0, 0.0}, {46.0, 1.0}, e, n);
    CHECK(n == doctest::Approx(111131.78).epsilon(1e-6));
    CHECK(e == doctest::Approx(78846.81).epsilon(1e-6));
    const auto g = io::to_geodetic({57.1, 11.9}, 1234.5, -678.9);
    io::from_geodetic({57.1, 11.9}, g, e, n);
    CHECK(e == doctest::Approx(1234.5).epsilon(1e-12));
    CHECK(n == doctest::Approx(-678.9).epsilon(1e-12));
    // Across the antimeridian: 0.02 deg of longitude at 10 N is about 2.19 km east, not 40,000 km west; the way
    // back gives a longitude in (-180, 180].
    io::from_geodetic({10.0, 179.99}, {10.0, -179.99}, e, n);
    CHECK(e == doctest::Approx(2192.0).epsilon(2e-3));
    CHECK(n == doctest::Approx(0.0).scale(1.0));
    const auto across = io::to_geodetic({10.0, 179.99}, 5000.0, 0.0);
    CHECK(across.longitude_deg < -179.9);
    CHECK(across.longitude_deg > -180.0);
    CHECK_THROWS_AS(io::from_geodetic({10.0, 0.0}, {std::nan(""), 1.0}, e, n), sss::invalid_parameter);
    // 300 km north of 89 N is beyond the pole: refused, not written as latitude 91.7.
    try {
        (void)io::to_geodetic({89.0, 0.0}, 0.0, 300000.0);
        FAIL("no exception");
    } catch (const sss::invalid_parameter& bad) {
        CHECK(bad.parameter() == "north_m");
    }
}

TEST_CASE("Corrupted XTF bytes read as a file or give a file_error, never anything else") {
    const render r = small_render();
    const auto good = bytes_of(io::make_xtf<double>(r.w, r.poses, params(io::xtf_sample_format::u16, io::xtf_nav_units::projected_m)));
    std::uint64_t s = 12345;
    auto next = [&s] { // splitmix64 (Steele, Lea & Flood, 2014)
        std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    };
    std::size_t read = 0, rejected = 0, other = 0;
    for (int trial = 0; trial < 1500; ++trial) {
        auto b = good;
        // A few bytes changed in the headers' range (where the lengths and counts live), sometimes a cut.
        for (int k = 0; k < 3; ++k) {
            const std::size_t packet = 1024 + (next() % 6) * detail::get_le<std::uint32_t>(good.data(), 1024 + 10);
            const std::size_t at = next() % 2 ? next() % 1024 : packet + next() % (256 + 64);
            b[std::min(at, b.size() - 1)] = static_cast<std::uint8_t>(next());
        }
        if (next() % 4 == 0) b.resize(next() % b.size());
        try {
            (void)io::parse_xtf(b, "fuzz.xtf");
            ++read;
        } catch (const file_error&) {
            ++rejected;
        } catch (...) {
            ++other;
        }
    }
    MESSAGE(read << " corrupted files read, " << rejected << " rejected");
    CHECK(other == 0u);
    CHECK(rejected > 100u);
}

TEST_CASE("A ping time the header's calendar cannot hold (before the year 1 or after 9999) is refused by name") {
    const render r = small_render();
    xtf_file f = io::make_xtf<double>(r.w, r.poses, params(io::xtf_sample_format::f32, io::xtf_nav_units::projected_m));
    // The last second of 9999 still encodes, with its date.
    f.pings[0].time_unix_s = 253402300799.0;
    const auto bytes = io::encode_xtf(f);
    const auto back = io::parse_xtf(bytes, "year9999.xtf");
    CHECK(back.pings[0].time_unix_s == doctest::Approx(253402300799.0));
    for (const double t : {253402300800.0, 1e300, -62135596801.0}) {
        f.pings[0].time_unix_s = t;
        try {
            (void)io::encode_xtf(f);
            FAIL("no error for " << t);
        } catch (const invalid_parameter& e) {
            CHECK(e.parameter() == "xtf_file.pings[0].time_unix_s");
        }
    }
}

TEST_CASE("A sample that an XTF file cannot hold is refused naming its ping, side and index") {
    const render r = small_render();
    xtf_file f = io::make_xtf<double>(r.w, r.poses, params(io::xtf_sample_format::u16, io::xtf_nav_units::projected_m));
    f.pings[3].starboard[7] = -1.0f;
    try {
        (void)io::encode_xtf(f);
        FAIL("no error for a negative count");
    } catch (const invalid_parameter& e) {
        CHECK(e.parameter() == "xtf_file.pings[3].starboard[7]");
    }
    f.pings[3].starboard[7] = 0.0f;
    f.pings[2].port[5] = std::numeric_limits<float>::infinity();
    try {
        (void)io::encode_xtf(f);
        FAIL("no error for an infinite sample");
    } catch (const invalid_parameter& e) {
        CHECK(e.parameter() == "xtf_file.pings[2].port[5]");
    }
}

TEST_CASE("ThisFileName holds the final name given for a file written under another, and ProcessingFlags says TVG") {
    const render r = small_render();
    auto p = params(io::xtf_sample_format::f32, io::xtf_nav_units::projected_m);
    p.header.file_name = "line7.xtf";
    p.header.tvg_applied = true;
    io::write_xtf(".line7.xtf.partial-0123", io::make_xtf<double>(r.w, r.poses, p));
    const auto b = detail::read_file_bytes(".line7.xtf.partial-0123");
    CHECK(detail::get_chars(b.data(), 100, 64) == "line7.xtf");
    const std::size_t chan = 1024 + 256, samples = r.w.samples;
    CHECK(detail::get_le<std::uint16_t>(b.data(), chan + 24) == 4);                // port: TVG applied
    CHECK(detail::get_le<std::uint16_t>(b.data(), chan + 64 + 4 * samples + 24) == 4); // starboard
    const xtf_file g = io::read_xtf(".line7.xtf.partial-0123");
    CHECK(g.header.tvg_applied);
    std::filesystem::remove(".line7.xtf.partial-0123");
    // Without TVG the flags are 0.
    p.header.tvg_applied = false;
    const auto c = io::encode_xtf(io::make_xtf<double>(r.w, r.poses, p));
    CHECK(detail::get_le<std::uint16_t>(c.data(), chan + 24) == 0);
}

TEST_CASE("a character field always ends in a zero byte: a longer text is cut short of the field, not inside a character") {
    const render r = small_render();
    auto p = params(io::xtf_sample_format::f32, io::xtf_nav_units::projected_m);
    p.header.file_name = std::string(70, 'a') + ".xtf";
    p.header.program_name = "sss-render";       // 10 bytes for 8
    p.header.sonar_name = std::string(14, 's') + "\xc3\xa9"; // 16 bytes, the last character two of them
    const auto b = io::encode_xtf(io::make_xtf<double>(r.w, r.poses, p));
    CHECK(b[100 + 63] == 0);
    CHECK(detail::get_chars(b.data(), 100, 64) == std::string(63, 'a'));
    CHECK(detail::get_chars(b.data(), 2, 8) == "sss-ren");
    CHECK(detail::get_chars(b.data(), 18, 16) == std::string(14, 's')); // the two-byte character does not fit in 15
    p.header.file_name = std::string(63, 'b');                          // fits exactly
    const auto c = io::encode_xtf(io::make_xtf<double>(r.w, r.poses, p));
    CHECK(detail::get_chars(c.data(), 100, 64) == std::string(63, 'b'));
}

TEST_CASE("SensorHeading lies in [0, 360) however many turns the yaw has made, either way") {
    CHECK(io::heading_in_circle_deg(30.0) == 30.0);
    CHECK(io::heading_in_circle_deg(-18.0) == 342.0);
    CHECK(io::heading_in_circle_deg(-400.0) == 320.0);
    CHECK(io::heading_in_circle_deg(-720.0) == 0.0);
    CHECK(io::heading_in_circle_deg(1090.0) == 10.0);
    CHECK(io::heading_in_circle_deg(-1e-12) == 0.0);       // 360 - 1e-12 is 360 in float: written as 0
    CHECK(io::heading_in_circle_deg(359.9999999) == 0.0);  // likewise
    CHECK(static_cast<float>(io::heading_in_circle_deg(359.99)) == 359.99f);
    render r = small_render();
    for (std::size_t i = 0; i < r.poses.size(); ++i) r.poses[i].yaw_rad = -7.0 + 3.0 * double(i); // -401 deg to 458 deg
    const xtf_file g = io::parse_xtf(io::encode_xtf(io::make_xtf<double>(r.w, r.poses,
                                                                         params(io::xtf_sample_format::f32, io::xtf_nav_units::projected_m))),
                                     "turns.xtf");
    for (std::size_t i = 0; i < g.pings.size(); ++i) {
        const double deg = (-7.0 + 3.0 * double(i)) * 180.0 / 3.14159265358979323846;
        CHECK(g.pings[i].heading_deg >= 0.0);
        CHECK(g.pings[i].heading_deg < 360.0);
        CHECK(g.pings[i].heading_deg == doctest::Approx(deg - 360.0 * std::floor(deg / 360.0)).epsilon(1e-6));
    }
}

TEST_CASE("Ping numbers that would wrap past 32 bits are refused by name; the last one that fits is written") {
    const render r = small_render(); // six pings
    auto p = params(io::xtf_sample_format::f32, io::xtf_nav_units::projected_m);
    p.first_ping_number = 4294967291u; // the sixth is 4294967296
    try {
        (void)io::make_xtf<double>(r.w, r.poses, p);
        FAIL("no error");
    } catch (const invalid_parameter& e) {
        CHECK(std::string(e.what()).find("xtf_render_params.first_ping_number") != std::string::npos);
    }
    p.first_ping_number = 4294967290u;
    const xtf_file f = io::make_xtf<double>(r.w, r.poses, p);
    CHECK(f.pings.back().ping_number == 4294967295u);
}

TEST_CASE("A ping whose channels differ in length is written and read back as it is") {
    xtf_file f;
    f.pings.resize(1);
    f.pings[0].sound_speed_mps = 1500.0;
    f.pings[0].port = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
    f.pings[0].starboard = {0.5f, 1.5f, 2.5f, 3.5f, 4.5f, 5.5f, 6.5f};
    const xtf_file g = io::parse_xtf(io::encode_xtf(f), "uneven.xtf");
    REQUIRE(g.pings.size() == 1u);
    CHECK(g.pings[0].port == f.pings[0].port);
    CHECK(g.pings[0].starboard == f.pings[0].starboard);
}

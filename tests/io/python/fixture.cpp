// Writes the files the Python readers of tests/io/python check, with what they should find in them given
// through a separate path (raw arrays written here with fwrite, and plain "key value" text), so the readers
// share nothing with the library's own reader. Run in a scratch directory; exits non-zero on any failure.
#include <cstdint>
#include <cstdio>
#include <exception>
#include <vector>

#include "sss/io/npy.hpp"
#include "sss/io/png.hpp"
#include "sss/io/xtf.hpp"
#include "sss/scene/flat_seabed.hpp"
#include "sss/simulator.hpp"

namespace {

void write_raw(const char* path, const void* data, std::size_t bytes) {
    std::FILE* f = std::fopen(path, "wb");
    if (f == nullptr || std::fwrite(data, 1, bytes, f) != bytes || std::fclose(f) != 0) throw std::runtime_error(path);
}

} // namespace

int main() try {
    using namespace sss;
    receiver_params rp;
    rp.max_range_m = 30.0;
    motion::straight_line_params<double> tow{.start_m = {250.0, 1200.0}, .heading_deg = 120.0, .speed_mps = 1.5,
                                             .altitude_m = 9.0, .ping_interval_s = 0.25};
    const simulator<scattering::lambertian<double>, propagation::straight<double>, beam::ideal_fan<double>, motion::straight_line<double>>
        sim({}, {}, {}, motion::straight_line<double>(tow), rp, ray_density{.along = 2, .across = 0, .per_sample = 1.0});
    const std::size_t pings = 5;
    const auto w = sim.render(scene::flat_seabed<double>(0.0), 0, pings, 1);
    std::vector<pose<double>> poses;
    for (std::size_t i = 0; i < pings; ++i) poses.push_back(sim.motion().pose_at(i));

    io::xtf_render_params p{.start_unix_s = 1'735'689'599.5, .ping_interval_s = 0.25, .first_ping_number = 7,
                            .sound_speed_mps = 1500.0, .origin = {.latitude_deg = -33.9, .longitude_deg = 151.2}};
    p.header.port = {.frequency_khz = 300.0, .horizontal_beam_angle_deg = 0.8, .beam_width_deg = 50.0, .tilt_deg = 20.0};
    p.header.starboard = p.header.port;
    p.header.format = io::xtf_sample_format::f32;
    io::write_xtf("sss_f32.xtf", io::make_xtf<double>(w, poses, p));
    p.header.format = io::xtf_sample_format::u16;
    p.header.nav_units = io::xtf_nav_units::projected_m;
    io::write_xtf("sss_u16.xtf", io::make_xtf<double>(w, poses, p));
    p.header.format = io::xtf_sample_format::u8;
    io::write_xtf("sss_u8.xtf", io::make_xtf<double>(w, poses, p));

    std::FILE* e = std::fopen("expected.txt", "w");
    if (e == nullptr) throw std::runtime_error("expected.txt");
    std::fprintf(e, "pings %zu\nsamples %zu\nstart_unix_s %.6f\nping_interval_s 0.25\nfirst_ping 7\n", pings, w.samples, p.start_unix_s);
    std::fprintf(e, "sound_speed_mps 1500\nfrequency_khz 300\nbeam_width_deg 50\ntilt_deg 20\nhorizontal_beam_angle_deg 0.8\n");
    std::fprintf(e, "origin_lat_deg -33.9\norigin_lon_deg 151.2\naltitude_m 9\nheading_deg 120\nspeed_mps 1.5\n");
    std::fprintf(e, "dt_s %.17g\n", w.dt_s);
    for (std::size_t i = 0; i < pings; ++i)
        std::fprintf(e, "position %zu %.17g %.17g\n", i, poses[i].position.x, poses[i].position.y);
    std::fclose(e);
    write_raw("waterfall_f64.raw", w.values.data(), w.values.size() * sizeof(double));

    io::write_npy("waterfall.npy", w);
    waterfall<float> wf{w.pings, w.samples, w.dt_s, std::vector<float>(w.values.begin(), w.values.end())};
    io::write_npy("waterfall_f32.npy", wf);
    write_raw("waterfall_f32.raw", wf.values.data(), wf.values.size() * sizeof(float));
    io::write_render_sidecar<double>("waterfall.json", w, poses, {.array_file = "waterfall.npy", .sound_speed_mps = 1500.0});

    const auto grey8 = io::to_grey_db<std::uint8_t>(std::span<const double>(w.values), {.dynamic_range_db = 50.0});
    const auto grey16 = io::to_grey_db<std::uint16_t>(std::span<const double>(w.values), {.dynamic_range_db = 50.0});
    io::write_png_grey8("grey8.png", w.width(), w.pings, grey8);
    io::write_png_grey16("grey16.png", w.width(), w.pings, grey16);
    write_raw("grey8.raw", grey8.data(), grey8.size());
    write_raw("grey16.raw", grey16.data(), grey16.size() * 2);
    // A tall image: more than one stored deflate block (65535 bytes).
    std::vector<std::uint8_t> ramp(300 * 400);
    for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = static_cast<std::uint8_t>(i * 7 % 251);
    io::write_png_grey8("ramp.png", 300, 400, ramp);
    write_raw("ramp.raw", ramp.data(), ramp.size());
    // Incompressible noise (literals only) and long runs of 16-bit values (the longest matches).
    std::vector<std::uint8_t> noise(257 * 131);
    std::uint32_t state = 2463534242u;
    const auto next = [&state] {
        state ^= state << 13, state ^= state >> 17, state ^= state << 5; // xorshift32 (Marsaglia, 2003)
        return static_cast<std::uint8_t>(state >> 24);
    };
    for (auto& v : noise) v = next();
    io::write_png_grey8("noise.png", 257, 131, noise);
    write_raw("noise.raw", noise.data(), noise.size());
    // Noise of 2.1 MB: its zlib stream spans three IDAT chunks of at most 1 MiB.
    std::vector<std::uint8_t> wide(2048 * 1024);
    for (auto& v : wide) v = next();
    io::write_png_grey8("wide.png", 2048, 1024, wide);
    write_raw("wide.raw", wide.data(), wide.size());
    std::vector<std::uint16_t> runs(500 * 40);
    for (std::size_t i = 0; i < runs.size(); ++i) runs[i] = static_cast<std::uint16_t>((i / 1000) * 3001 + (i % 500 > 480 ? 7 : 0));
    io::write_png_grey16("runs.png", 500, 40, runs);
    write_raw("runs.raw", runs.data(), runs.size() * 2);
    return 0;
} catch (const std::exception& x) {
    std::fprintf(stderr, "fixture: %s\n", x.what());
    return 1;
}

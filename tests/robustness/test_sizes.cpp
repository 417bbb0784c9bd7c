// Sizes a user can make huge are refused by name before anything is allocated: products that would overflow
// std::size_t, buffers beyond sss::max_elements, and a towfish that is not above the seabed.

#include <doctest/doctest.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <limits>
#include <string>

#include <sss/sss.hpp>
#include <sss/seabed/fractal.hpp>
#include <sss/seabed/ripples.hpp>
#include <sss/scene/height_field.hpp>

namespace {

// Runs f and returns the name of the parameter its invalid_parameter names ("" if it did not throw one).
template <class F> std::string named(F&& f) {
    try {
        f();
    } catch (const sss::invalid_parameter& e) {
        CHECK(std::string(e.what()).find(e.parameter()) != std::string::npos);
        return e.parameter();
    }
    return {};
}

constexpr std::size_t two_pow_32 = std::size_t(1) << 32;
constexpr std::size_t two_pow_63 = std::size_t(1) << 63;

} // namespace

TEST_CASE("checked_mul returns exact products and names the parameter of a product that overflows") {
    CHECK(sss::checked_mul(0, std::numeric_limits<std::size_t>::max(), "a") == 0);
    CHECK(sss::checked_mul(two_pow_32 - 1, two_pow_32 + 1, "a") == std::numeric_limits<std::size_t>::max());
    CHECK(named([] { (void)sss::checked_mul(two_pow_32, two_pow_32, "grid.nx"); }) == "grid.nx");
    CHECK(sss::checked_elements(1024, 1024, "a") == 1024 * 1024);
    CHECK(named([] { (void)sss::checked_elements(sss::max_elements, 2, "image.count"); }) == "image.count");
}

TEST_CASE("a render of 2^63 pings or 10^9 pings is refused by naming count, before any allocation") {
    const sss::simulator<> sim;
    const sss::scene::flat_seabed<double> seabed(0.0);
    CHECK(named([&] { (void)sim.render(seabed, 0, two_pow_63); }) == "render.count");
    CHECK(named([&] { (void)sim.render(seabed, 0, std::size_t(1000000000)); }) == "render.count");
    CHECK(named([&] { (void)sim.render(seabed, std::numeric_limits<std::size_t>::max(), 2); }) == "render.first");
    // The limit is on the image, not on the count alone: a small render still works.
    const auto w = sim.render(seabed, 0, 2, 1);
    CHECK(w.values.size() == 2 * w.width());
}

TEST_CASE("fractal and ripple grids of 2^32 x 2^32 samples are refused by name") {
    const sss::seabed::fractal_params<float> fp{};
    CHECK(named([&] { (void)sss::seabed::fractal_surface<float>(two_pow_32, two_pow_32, 0.1f, fp, 1); }) ==
          "fractal_surface.nx * ny");
    // Within the size type but beyond max_elements.
    CHECK(named([&] { (void)sss::seabed::fractal_surface<float>(1 << 20, 1 << 20, 0.1f, fp, 1); }) ==
          "fractal_surface.nx * ny");
    // Oversampling multiplies the synthesis grid: checked as well.
    sss::seabed::fractal_params<float> over{};
    over.oversample = 64;
    CHECK(named([&] { (void)sss::seabed::fractal_surface<float>(1 << 13, 1 << 13, 0.1f, over, 1); }) ==
          "fractal_surface.params.oversample");
    const sss::seabed::ripple_params<float> rp{.wavelength_m = 1.0f, .height_m = 0.1f};
    CHECK(named([&] { (void)sss::seabed::ripple_field<float>(two_pow_32, two_pow_32, 0.1f, rp, 1); }) ==
          "make_raster.nx * ny");
    CHECK(named([&] { (void)sss::seabed::make_raster<float, float>(two_pow_63, 4, 1.0f); }) == "make_raster.nx * ny");
}

TEST_CASE("a height field whose nx * ny exceeds max_elements is refused by name") {
    CHECK(named([] { sss::scene::height_field<float>({.nx = std::size_t(1) << 16, .ny = std::size_t(1) << 16, .cell_m = 1.0f}); }) ==
          "height_field.nx * ny");
}

TEST_CASE("a towfish at or below the seabed is an error naming the ping") {
    sss::motion::straight_line_params<double> m;
    m.altitude_m = 10.0;
    const sss::simulator<> sim({}, {}, {}, sss::motion::straight_line<double>(m));
    // Seabed at +10 m: the towfish is exactly on it; at +25 m it is 15 m below.
    for (const double seabed_z : {10.0, 25.0}) {
        const sss::scene::flat_seabed<double> seabed(seabed_z);
        CHECK(named([&] { (void)sim.ping(seabed, 7); }) == "ping[7]");
        CHECK(named([&] { (void)sim.render(seabed, 3, 2, 1); }) == "ping[3]");
    }
    // Just above the seabed: renders.
    const sss::scene::flat_seabed<double> seabed(9.5);
    CHECK_NOTHROW((void)sim.ping(seabed, 0));
}

TEST_CASE("an absurd sample rate or a pulse of millions of samples is refused by name, not overflowed") {
    for (const double fs : {1e12, 1e300}) {
        sss::receiver_params rx;
        rx.sample_rate_hz = fs;
        CHECK(named([&] { sss::simulator<> sim({}, {}, {}, {}, rx); }) == "receiver.max_range_m");
    }
    sss::receiver_params rx;
    rx.sample_rate_hz = 1e7;
    rx.max_range_m = 1.0;
    rx.pulse.length_s = 1.0; // 10^7 samples of pulse: a kernel of 10^8 taps
    CHECK(named([&] { sss::simulator<> sim({}, {}, {}, {}, rx); }) == "pulse.length_s");
    rx.pulse.length_s = 1e-3; // 10^4 samples: fine
    CHECK_NOTHROW(sss::simulator<>({}, {}, {}, {}, rx));
}

TEST_CASE("a grid header promising more values than its file holds is refused before the heights are allocated") {
    const auto file_error_of = [](auto&& read) -> std::string {
        try {
            read();
        } catch (const sss::file_error& e) {
            return e.what();
        }
        return {};
    };
    {
        std::ofstream("huge.asc") << "ncols 1073741824\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n";
        CHECK(file_error_of([] { (void)sss::io::read_esri_ascii<float>("huge.asc"); }).find("too large") !=
              std::string::npos);
        std::ofstream("tall.asc") << "ncols 40000\nnrows 40000\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n";
        CHECK(file_error_of([] { (void)sss::io::read_esri_ascii<float>("tall.asc"); }).find("cannot fit") !=
              std::string::npos);
    }
    {
        std::ofstream("huge.pgm", std::ios::binary) << "P5\n1073741824 1073741824\n65535\n" << std::string(8, '\0');
        CHECK(file_error_of([] { (void)sss::io::read_pgm16<float>("huge.pgm", 1.0f, {0, 0}, {1.0f, 0.0f}); })
                  .find("file ends") != std::string::npos);
    }
    {
        std::ofstream("huge.raw", std::ios::binary) << std::string(16, '\0');
        std::ofstream("huge.raw.txt") << "format sss-height-raw-f32le 1\nnx 1073741824\nny 1073741824\ncell_m 1\n"
                                         "origin_x_m 0\norigin_y_m 0\n";
        CHECK(file_error_of([] { (void)sss::io::read_raw_f32<float>("huge.raw"); }).find("too large") !=
              std::string::npos);
    }
}

TEST_CASE("ground-range labels and images of 2^62 cells a side, or from a mis-sized label image, are refused by name") {
    sss::label_image slant;
    slant.pings = 4;
    slant.samples = 100;
    slant.dt_s = 1e-4;
    slant.values.resize(4 * 200);
    const std::vector<double> h(4, 10.0);
    const std::size_t huge = std::size_t(1) << 62; // 2 x 2^62 x 4 wraps to 0 in the size type
    CHECK_THROWS_WITH_AS((void)sss::ground_range_labels(slant, h, {.cell_m = 0.05, .cells = huge, .sound_speed_mps = 1500.0}),
                         doctest::Contains("ground_range_params.cells"), sss::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)sss::ground_range_labels(slant, h, {.cell_m = 1e-300, .cells = 0, .sound_speed_mps = 1500.0}),
                         doctest::Contains("ground_range_params.cell_m"), sss::invalid_parameter);
    CHECK_THROWS_WITH_AS((void)sss::ground_range_labels(slant, {10.0, -5.0, 10.0, 10.0}, {}), doctest::Contains("altitude_m"),
                         sss::invalid_parameter);
    sss::label_image short_one = slant;
    short_one.values.resize(10);
    CHECK_THROWS_WITH_AS((void)sss::ground_range_labels(short_one, h, {}), doctest::Contains("label_image.values"),
                         sss::invalid_parameter);
    CHECK(sss::ground_range_labels(slant, h, {}).values.size() == 4 * 2 * 150); // 100 samples of 7.5 cm over 5 cm cells
    sss::waterfall<float> w;
    w.pings = 4;
    w.samples = 100;
    w.dt_s = 1e-4;
    w.values.resize(800);
    CHECK_THROWS_WITH_AS((void)sss::to_ground_range(w, h, 1500.0, 0.05, huge), doctest::Contains("to_ground_range.pixels"),
                         sss::invalid_parameter);
}

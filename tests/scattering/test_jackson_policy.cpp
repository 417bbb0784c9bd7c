// The jackson<T> scattering policy and its backscatter tables: lookup accuracy against the direct model,
// the Scattering concept's contract, and parameter validation.

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <sss/scattering/jackson.hpp>

using namespace sss::scattering;
using sss::deg_to_rad;

static_assert(sss::Scattering<jackson<float>>);
static_assert(sss::Scattering<jackson<double>>);
static_assert(noexcept(std::declval<const jackson<float>&>().backscatter(0.1f, 0u)));
static_assert(noexcept(std::declval<const jackson<double>&>().bistatic(0.1, 0.2, 0.3, 0u)));

TEST_CASE("tabulated backscatter stays within 0.05 dB of the direct model from 0.1 to 90 deg") {
    double worst_f = 0.0, worst_d = 0.0;
    std::size_t largest_table = 0;
    for (const auto& row : sediment_table)
        for (double f : {10e3, 30e3, 100e3, 400e3}) {
            const auto c = make_jackson_coefficients(sediment_preset<double>(row.id), f, 1500.0);
            const jackson_backscatter_table<float> tf(c);
            const jackson_backscatter_table<double> td(c);
            CHECK(td.midpoint_error_db() <= 0.01);
            largest_table = std::max(largest_table, td.intervals());
            double row_worst = 0.0;
            for (double deg = 0.1; deg <= 90.0; deg += 0.0131) {
                const double g = deg_to_rad(deg);
                const double direct = jackson_backscatter(c, g);
                const double ef = std::abs(10.0 * std::log10(double(tf(float(g))) / direct));
                const double ed = std::abs(10.0 * std::log10(td(g) / direct));
                row_worst = std::max({row_worst, ef, ed});
                worst_f = std::max(worst_f, ef);
                worst_d = std::max(worst_d, ed);
            }
            CAPTURE(row.name);
            CAPTURE(f);
            CHECK(row_worst <= 0.05);
        }
    MESSAGE("table vs direct, 0.1-90 deg, 15 sediments x 4 frequencies: worst " << worst_f << " dB (float), " << worst_d
                                                                                 << " dB (double); largest table " << largest_table
                                                                                 << " intervals");
}

TEST_CASE("tabulated backscatter is finite, non-negative and continuous down to exactly 0 deg") {
    const auto c = make_jackson_coefficients(sediment_preset<double>(sediment::medium_sand), 100e3, 1500.0);
    const jackson_backscatter_table<float> t(c);
    CHECK(t(0.0f) == 0.0f);
    CHECK(t(-1.0f) == 0.0f);
    CHECK(t(std::numeric_limits<float>::quiet_NaN()) == 0.0f);
    CHECK(t(2.0f) == t(sss::half_pi_v<float>));
    float prev = 0.0f;
    for (int i = 1; i <= 100000; ++i) { // up to 0.1 deg: monotonic rise from 0
        const float v = t(float(deg_to_rad(1e-6 * i)));
        REQUIRE(std::isfinite(v));
        CHECK(v >= prev);
        prev = v;
    }
}

TEST_CASE("the jackson policy validates its parameters, naming each") {
    auto name_of = [](auto&& f) -> std::string {
        try {
            f();
        } catch (const sss::invalid_parameter& e) {
            return e.parameter();
        }
        return "";
    };
    const auto sand = sediment_preset<float>(sediment::medium_sand);
    CHECK(name_of([&] { jackson<double>({.frequency_hz = 1e5, .sound_speed_mps = 1500.0, .materials = {sediment_preset<double>(sediment::clay)}}); }).empty());
    CHECK(name_of([&] { jackson<float>({.frequency_hz = 0.0f, .materials = {sand}}); }) == "jackson.frequency_hz");
    CHECK(name_of([&] { jackson<float>({.sound_speed_mps = -1.0f, .materials = {sand}}); }) == "jackson.sound_speed_mps");
    CHECK(name_of([&] { jackson<float>({.materials = {}}); }) == "jackson.materials");
    auto bad = sand;
    bad.delta = -0.01f;
    CHECK(name_of([&] { jackson<float>({.materials = {sand, bad}}); }) == "jackson.materials[1].delta");
    bad = sand;
    bad.w2_cm4 = std::numeric_limits<float>::infinity();
    CHECK(name_of([&] { jackson<float>({.materials = {bad}}); }) == "jackson.materials[0].w2_cm4");
}

TEST_CASE("the jackson policy gives each material its own sediment, and ids beyond the list the last one") {
    const jackson<double> s({.frequency_hz = 100e3,
                           .sound_speed_mps = 1500.0,
                           .materials = {sediment_preset<double>(sediment::clay), sediment_preset<double>(sediment::rock)}});
    CHECK(s.material_count() == 2);
    CHECK(s.frequency_hz() == 100e3);
    CHECK(s.sound_speed_mps() == 1500.0);
    const double g = deg_to_rad(30.0);
    const double clay = jackson_backscatter(sediment_preset<double>(sediment::clay), 100e3, 1500.0, g);
    const double rock = jackson_backscatter(sediment_preset<double>(sediment::rock), 100e3, 1500.0, g);
    CHECK(s.backscatter(g, 0) == doctest::Approx(clay).epsilon(0.002).scale(0));
    CHECK(s.backscatter(g, 1) == doctest::Approx(rock).epsilon(0.002).scale(0));
    CHECK(s.backscatter(g, 7) == s.backscatter(g, 1));
    CHECK(s.backscatter(g, std::numeric_limits<std::uint32_t>::max()) == s.backscatter(g, 1));
    CHECK(s.material(5).nu == 2.5);
    CHECK(rock > 10.0 * clay); // rock backscatters far more strongly than clay at 30 deg
}

TEST_CASE("the jackson policy's bistatic equals its backscatter at the backscatter geometry and the direct model elsewhere") {
    const jackson<float> sf({.frequency_hz = 200e3f, .sound_speed_mps = 1500.0f, .materials = {sediment_preset<float>(sediment::medium_sand), sediment_preset<float>(sediment::sandy_mud)}});
    const jackson<double> sd({.frequency_hz = 200e3, .sound_speed_mps = 1500.0, .materials = {sediment_preset<double>(sediment::medium_sand), sediment_preset<double>(sediment::sandy_mud)}});
    for (std::uint32_t m = 0; m < 2; ++m)
        for (int i = 0; i <= 90; ++i) {
            const double g = deg_to_rad(double(i));
            CAPTURE(m);
            CAPTURE(i);
            CHECK(sf.bistatic(float(g), float(g), sss::pi_v<float>, m) == sf.backscatter(float(g), m));
            CHECK(sf.bistatic(float(g), float(g), -sss::pi_v<float>, m) == sf.backscatter(float(g), m));
            CHECK(sd.bistatic(g, g, sss::pi_v<double>, m) == sd.backscatter(g, m));
            const double gs = deg_to_rad(0.5 * i + 3.0);
            const double direct = jackson_bistatic(sd.coefficients(m), g, gs, 2.0);
            CHECK(sd.bistatic(g, gs, 2.0, m) == doctest::Approx(direct).epsilon(1e-12).scale(0));
            CHECK(double(sf.bistatic(float(g), float(gs), 2.0f, m)) == doctest::Approx(direct).epsilon(1e-4).scale(0));
            // Just off the backscatter geometry the direct model continues the tabulated value.
            const double near = sd.bistatic(g, g + 1e-9, sss::pi_v<double>, m);
            if (i > 0) CHECK(std::abs(10.0 * std::log10(near / sd.backscatter(g, m))) <= 0.05);
        }
}

TEST_CASE("the jackson policy answers every input with a finite, non-negative value") {
    const jackson<float> s({.frequency_hz = 100e3f, .sound_speed_mps = 1500.0f, .materials = {sediment_preset<float>(sediment::rough_rock)}});
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (float g : {-1.0f, 0.0f, 1e-30f, 0.7f, sss::half_pi_v<float>, 3.0f, nan})
        for (float phi : {0.0f, 1.0f, sss::pi_v<float>, 10.0f, nan}) {
            CAPTURE(g);
            CAPTURE(phi);
            const float b = s.backscatter(g, 0), bi = s.bistatic(g, 0.5f, phi, 0), bi2 = s.bistatic(0.5f, g, phi, 3);
            CHECK(std::isfinite(b));
            CHECK(b >= 0.0f);
            CHECK(std::isfinite(bi));
            CHECK(bi >= 0.0f);
            CHECK(std::isfinite(bi2));
            CHECK(bi2 >= 0.0f);
        }
}

TEST_CASE("float and double jackson policies agree to within 0.01 dB") {
    for (const auto& row : sediment_table) {
        const jackson<float> sf({.frequency_hz = 50e3f, .sound_speed_mps = 1490.0f, .materials = {sediment_preset<float>(row.id)}});
        const jackson<double> sd({.frequency_hz = 50e3, .sound_speed_mps = 1490.0, .materials = {sediment_preset<double>(row.id)}});
        for (double deg = 0.2; deg <= 90.0; deg += 0.37) {
            const double g = deg_to_rad(deg);
            CAPTURE(row.name);
            CAPTURE(deg);
            CHECK(std::abs(10.0 * std::log10(double(sf.backscatter(float(g), 0)) / sd.backscatter(g, 0))) <= 0.01);
        }
    }
}

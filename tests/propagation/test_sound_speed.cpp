// Mackenzie (1981) sound speed against its published check value and basic oceanographic behaviour.

#include <doctest/doctest.h>

#include <cmath>

#include "sss/propagation/sound_speed.hpp"

using sss::propagation::mackenzie_sound_speed_mps;

TEST_CASE_TEMPLATE("Mackenzie sound speed is 1550.744 m/s at 25 degC, 35 ppt, 1000 m (published check)", T, float,
                   double) {
    const T c = mackenzie_sound_speed_mps(T(25), T(35), T(1000));
    CHECK(std::abs(static_cast<double>(c) - 1550.744) <= 0.001);
}

TEST_CASE("Mackenzie sound speed rises with temperature, salinity and depth over its validity range") {
    for (double t = -2; t <= 28; t += 2)
        for (double s = 25; s <= 40; s += 5)
            for (double d = 0; d <= 8000; d += 1000) {
                const double c = mackenzie_sound_speed_mps(t, s, d);
                CHECK(mackenzie_sound_speed_mps(t + 1, s, d) > c);
                CHECK(mackenzie_sound_speed_mps(t, s + 1, d) > c);
                CHECK(mackenzie_sound_speed_mps(t, s, d + 100) > c);
                CHECK(c > 1400);
                CHECK(c < 1700);
            }
}

TEST_CASE("Mackenzie sound speed reduces to its constant term at 0 degC, 35 ppt, the surface") {
    CHECK(mackenzie_sound_speed_mps(0.0, 35.0, 0.0) == doctest::Approx(1448.96).epsilon(1e-15));
    // Pressure term alone: 1.630e-2 D + 1.675e-7 D^2 at 0 degC.
    CHECK(mackenzie_sound_speed_mps(0.0, 35.0, 2000.0) - 1448.96 == doctest::Approx(32.6 + 0.67).epsilon(1e-12));
}

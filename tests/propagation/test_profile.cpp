// Piecewise-linear sound-speed profiles: evaluation, layers, extrapolation and validation.

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/propagation/profile.hpp"
#include "sss/propagation/sound_speed.hpp"

using namespace sss::propagation;

namespace {
template <class F> std::string thrown_parameter(F&& make) {
    try {
        make();
    } catch (const sss::invalid_parameter& e) {
        return e.parameter();
    }
    return "(no throw)";
}
} // namespace

TEST_CASE_TEMPLATE("A profile interpolates linearly between knots and is constant beyond them", T, float, double) {
    const sound_speed_profile<T> p({T(2), T(10), T(50), T(200)}, {T(1510), T(1506), T(1490), T(1495)});
    CHECK(p.knot_count() == 4);
    CHECK(p.layer_count() == 5);
    // At the knots.
    CHECK(p.speed_mps(T(2)) == T(1510));
    CHECK(p.speed_mps(T(10)) == T(1506));
    CHECK(p.speed_mps(T(50)) == T(1490));
    CHECK(p.speed_mps(T(200)) == T(1495));
    // Between: midpoints and a quarter point.
    CHECK(static_cast<double>(p.speed_mps(T(6))) == doctest::Approx(1508.0).epsilon(1e-7));
    CHECK(static_cast<double>(p.speed_mps(T(30))) == doctest::Approx(1498.0).epsilon(1e-7));
    CHECK(static_cast<double>(p.speed_mps(T(87.5))) == doctest::Approx(1491.25).epsilon(1e-7));
    // Constant extrapolation above the first knot (including the surface and "above" it) and below the last.
    CHECK(p.speed_mps(T(0)) == T(1510));
    CHECK(p.speed_mps(T(-5)) == T(1510));
    CHECK(p.speed_mps(T(5000)) == T(1495));
    // Layer gradients (1/s).
    CHECK(p.gradient_per_s(0) == T(0));
    CHECK(static_cast<double>(p.gradient_per_s(1)) == doctest::Approx(-0.5).epsilon(1e-7));
    CHECK(static_cast<double>(p.gradient_per_s(2)) == doctest::Approx(-0.4).epsilon(1e-7));
    CHECK(static_cast<double>(p.gradient_per_s(3)) == doctest::Approx(5.0 / 150).epsilon(1e-6));
    CHECK(p.gradient_per_s(4) == T(0));
    CHECK(p.min_speed_mps() == T(1490));
    CHECK(p.max_speed_mps() == T(1510));
}

TEST_CASE("Layer lookup puts every depth in exactly one layer, and direction decides on a knot") {
    const sound_speed_profile<double> p({0, 10, 50, 200}, {1500, 1502, 1490, 1495});
    CHECK(p.layer_index(-1.0) == 0);
    CHECK(p.layer_index(0.0) == 1);
    CHECK(p.layer_index(9.999) == 1);
    CHECK(p.layer_index(10.0) == 2);
    CHECK(p.layer_index(199.0) == 3);
    CHECK(p.layer_index(200.0) == 4);
    CHECK(p.layer_index(1e6) == 4);
    // On a knot, a ray moving up is in the layer above it.
    CHECK(p.layer_index(10.0, vertical_direction::down) == 2);
    CHECK(p.layer_index(10.0, vertical_direction::up) == 1);
    CHECK(p.layer_index(0.0, vertical_direction::up) == 0);
    CHECK(p.layer_index(30.0, vertical_direction::up) == 2);

    // Each layer's own c(z) matches the profile inside it, and its bounds are the knots.
    for (std::size_t i = 1; i + 1 < p.layer_count(); ++i) {
        const auto layer = p.layer(i);
        CHECK(layer.z_top_m == p.depths_m()[i - 1]);
        CHECK(layer.z_bottom_m == p.depths_m()[i]);
        CHECK(layer.speed_mps(layer.z_top_m) == doctest::Approx(p.speeds_mps()[i - 1]).epsilon(1e-15));
        CHECK(layer.speed_mps(layer.z_bottom_m) == doctest::Approx(p.speeds_mps()[i]).epsilon(1e-15));
        const double mid = 0.5 * (layer.z_top_m + layer.z_bottom_m);
        CHECK(layer.speed_mps(mid) == doctest::Approx(p.speed_mps(mid)).epsilon(1e-15));
    }
    const auto top = p.layer(0), bottom = p.layer(4);
    CHECK(top.z_top_m == -std::numeric_limits<double>::infinity());
    CHECK(top.z_bottom_m == 0.0);
    CHECK(top.gradient_per_s == 0.0);
    CHECK(top.speed_mps(-100.0) == 1500.0);
    CHECK(bottom.z_top_m == 200.0);
    CHECK(bottom.z_bottom_m == std::numeric_limits<double>::infinity());
    CHECK(bottom.speed_mps(1e4) == 1495.0);
}

TEST_CASE("Binary-search layer lookup agrees with a linear scan on a 5000-knot profile") {
    std::vector<double> z, c;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> step(0.01, 3.0), speed(1480, 1540);
    double depth = -5;
    for (int i = 0; i < 5000; ++i) {
        depth += step(rng);
        z.push_back(depth);
        c.push_back(speed(rng));
    }
    const sound_speed_profile<double> p(z, c);
    std::uniform_real_distribution<double> where(-20, depth + 20);
    for (int k = 0; k < 2000; ++k) {
        const double q = k % 10 == 0 ? z[static_cast<std::size_t>(k)] : where(rng); // some exactly on knots
        std::size_t scan = 0;
        while (scan < z.size() && z[scan] <= q) ++scan;
        REQUIRE(p.layer_index(q) == scan);
        const auto layer = p.layer(scan);
        CHECK(layer.z_top_m <= q);
        CHECK(q < layer.z_bottom_m);
    }
}

TEST_CASE_TEMPLATE("A profile from temperature and salinity uses Mackenzie (1981) at each knot", T, float, double) {
    const auto p = sound_speed_profile<T>::from_temperature_salinity({T(0), T(100), T(1000)}, {T(25), T(12), T(4)},
                                                                   {T(35), T(34.8), T(34.9)});
    CHECK(p.speed_mps(T(1000)) == mackenzie_sound_speed_mps(T(4), T(34.9), T(1000)));
    CHECK(p.speed_mps(T(100)) == mackenzie_sound_speed_mps(T(12), T(34.8), T(100)));
    CHECK(static_cast<double>(p.speed_mps(T(0))) == doctest::Approx(mackenzie_sound_speed_mps(25.0, 35.0, 0.0)).epsilon(1e-6));
    CHECK(thrown_parameter([] {
              (void)sound_speed_profile<T>::from_temperature_salinity({T(0), T(10)}, {T(10), T(9)}, {T(35)});
          }) == "salinity_ppt");
    CHECK(thrown_parameter([] {
              (void)sound_speed_profile<T>::from_temperature_salinity({T(0), T(10)}, {T(10), std::numeric_limits<T>::quiet_NaN()},
                                                                      {T(35), T(35)});
          }) == "temperature_c[1]");
}

TEST_CASE("A uniform profile has one knot and no gradient anywhere") {
    const auto p = sound_speed_profile<double>::constant(1500);
    CHECK(p.knot_count() == 1);
    CHECK(p.layer_count() == 2);
    for (double z : {-10.0, 0.0, 10.0, 1e4}) CHECK(p.speed_mps(z) == 1500);
    CHECK(p.layer(0).gradient_per_s == 0);
    CHECK(p.layer(1).gradient_per_s == 0);
}

TEST_CASE("Invalid knots are rejected with the parameter and knot index named") {
    using P = sound_speed_profile<double>;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    CHECK(thrown_parameter([] { P({}, {}); }) == "depth_m");
    CHECK(thrown_parameter([] { P({0, 1}, {1500}); }) == "speed_mps");
    CHECK(thrown_parameter([] { P({0, 10, 10}, {1500, 1500, 1500}); }) == "depth_m[2]");
    CHECK(thrown_parameter([] { P({0, 10, 5}, {1500, 1500, 1500}); }) == "depth_m[2]");
    CHECK(thrown_parameter([&] { P({0, nan}, {1500, 1500}); }) == "depth_m[1]");
    CHECK(thrown_parameter([&] { P({0, inf}, {1500, 1500}); }) == "depth_m[1]");
    CHECK(thrown_parameter([] { P({0, 10}, {1500, -1500}); }) == "speed_mps[1]");
    CHECK(thrown_parameter([] { P({0, 10}, {0, 1500}); }) == "speed_mps[0]");
    CHECK(thrown_parameter([&] { P({0, 10}, {1500, nan}); }) == "speed_mps[1]");
    CHECK(thrown_parameter([] { P({0, 1e-320}, {1500, 1e300}); }) == "depth_m[1]"); // gradient overflows
    // The message says what was wrong.
    try {
        P({0, 10, 5}, {1500, 1500, 1500});
    } catch (const sss::invalid_parameter& e) {
        CHECK(std::string(e.what()).find("increase") != std::string::npos);
    }
}

// Sea-water absorption: Francois-Garrison and Ainslie-McColm against their check values, and the
// depth and path integrals of absorption against independent high-precision quadrature.

#include <doctest/doctest.h>

#include <cmath>
#include <string>

#include "sss/core/error.hpp"
#include "sss/propagation/absorption.hpp"
#include "sss/propagation/ray_arc.hpp"

using namespace sss::propagation;

namespace {

// |got - printed| within half a unit in the printed value's last digit.
template <class T> bool matches_printed(T got, double printed, double last_digit) {
    return std::abs(static_cast<double>(got) - printed) <= 0.5 * last_digit;
}

// Francois-Garrison written out again in long double, for the integration oracles below.
long double fg_reference(long double f_khz, long double t, long double s, long double d, long double ph) {
    const long double c = 1412.0L + 3.21L * t + 1.19L * s + 0.0167L * d;
    const long double a1 = 8.86L / c * std::pow(10.0L, 0.78L * ph - 5.0L);
    const long double f1 = 2.8L * std::sqrt(s / 35.0L) * std::pow(10.0L, 4.0L - 1245.0L / (273.0L + t));
    const long double a2 = 21.44L * s / c * (1.0L + 0.025L * t);
    const long double p2 = 1.0L - 1.37e-4L * d + 6.2e-9L * d * d;
    const long double f2 = 8.17L * std::pow(10.0L, 8.0L - 1990.0L / (273.0L + t)) / (1.0L + 0.0018L * (s - 35.0L));
    const long double p3 = 1.0L - 3.83e-5L * d + 4.9e-10L * d * d;
    const long double a3 = 4.937e-4L - 2.59e-5L * t + 9.11e-7L * t * t - 1.50e-8L * t * t * t; // t <= 20 here
    const long double ff = f_khz * f_khz;
    return a1 * f1 * ff / (f1 * f1 + ff) + a2 * p2 * f2 * ff / (f2 * f2 + ff) + a3 * p3 * ff;
}

// Composite 5-point Gauss-Legendre in long double over n panels: the oracle for smooth integrands.
template <class F> long double integrate_ld(F&& f, long double a, long double b, int n) {
    static const long double x[5] = {-0.906179845938663992797626878299392965L, -0.538469310105683091036314420700208805L,
                                     0.0L, 0.538469310105683091036314420700208805L,
                                     0.906179845938663992797626878299392965L};
    static const long double w[5] = {0.236926885056189087514264040719917363L, 0.478628670499366468041291514835638192L,
                                     0.568888888888888888888888888888888889L, 0.478628670499366468041291514835638192L,
                                     0.236926885056189087514264040719917363L};
    const long double h = (b - a) / n;
    long double sum = 0;
    for (int i = 0; i < n; ++i) {
        const long double m = a + (i + 0.5L) * h;
        for (int k = 0; k < 5; ++k) sum += w[k] * f(m + 0.5L * h * x[k]);
    }
    return sum * h / 2;
}

} // namespace

TEST_CASE_TEMPLATE("Francois-Garrison matches its check table at 0 m and 1000 m (pH 8, S 35, 10 degC)", T, float,
                   double) {
    struct row { double f_hz, depth_m, printed, last_digit; };
    const row table[] = {
        {1e3, 0, 0.0601, 1e-4},     {1e4, 0, 0.9626, 1e-4},     {1e5, 0, 33.630, 1e-3},     {3e5, 0, 73.139, 1e-3},
        {1e3, 1000, 0.0584, 1e-4},  {1e4, 1000, 0.8454, 1e-4},  {1e5, 1000, 29.241, 1e-3},  {3e5, 1000, 65.752, 1e-3},
    };
    for (const auto& r : table) {
        const T a = francois_garrison_db_per_km<T>(T(r.f_hz), T(10), T(35), T(r.depth_m), T(8));
        INFO("f = " << r.f_hz << " Hz, D = " << r.depth_m << " m: " << a << " dB/km, printed " << r.printed);
        CHECK(matches_printed(a, r.printed, r.last_digit));
        // The per-frequency model evaluates the same formula.
        const francois_garrison<T> model(T(r.f_hz), water_properties<T>{T(10), T(35), T(8)});
        CHECK(static_cast<double>(model.db_per_km(T(r.depth_m))) == doctest::Approx(static_cast<double>(a)).epsilon(1e-5));
    }
}

TEST_CASE_TEMPLATE("Francois-Garrison terms and relaxation frequencies match the reference at 100 kHz, 10 degC, 0 m",
                   T, float, double) {
    const auto terms = francois_garrison_contributions<T>(T(1e5), T(10), T(35), T(0), T(8));
    CHECK(matches_printed(terms.boric_acid_db_per_km, 0.1157, 1e-4));
    CHECK(matches_printed(terms.magnesium_sulphate_db_per_km, 30.407, 1e-3));
    CHECK(matches_printed(terms.pure_water_db_per_km, 3.108, 1e-3));
    CHECK(matches_printed(terms.boric_acid_relaxation_hz / T(1000), 1.1165, 1e-4));
    CHECK(matches_printed(terms.magnesium_sulphate_relaxation_hz / T(1000), 75.93, 1e-2));
    CHECK(terms.boric_acid_relaxation_hz == francois_garrison_boric_acid_relaxation_hz(T(10), T(35)));
    CHECK(terms.magnesium_sulphate_relaxation_hz == francois_garrison_magnesium_sulphate_relaxation_hz(T(10), T(35)));
    CHECK(static_cast<double>(terms.total_db_per_km()) ==
          doctest::Approx(static_cast<double>(francois_garrison_db_per_km<T>(T(1e5), T(10), T(35), T(0), T(8))))
              .epsilon(1e-6));
}

TEST_CASE("Francois-Garrison pure-water coefficient uses 4.937e-4, not the misprinted 4.397e-4") {
    // At 10 degC: A3 = 4.937e-4 - 2.59e-4 + 9.11e-5 - 1.5e-5 = 3.108e-4 dB/km/kHz^2.
    CHECK(francois_garrison_a3(10.0) == doctest::Approx(3.108e-4).epsilon(1e-12));
    CHECK(francois_garrison_a3(0.0) == doctest::Approx(4.937e-4).epsilon(1e-12));
    // The two published branches nearly meet at the 20 degC switch (2.201e-4 vs 2.200e-4).
    CHECK(francois_garrison_a3(20.0) == doctest::Approx(francois_garrison_a3(20.000001)).epsilon(1e-3).scale(0));
}

TEST_CASE("Francois-Garrison absorption grows with frequency and falls with depth in the sonar band") {
    double previous = 0;
    for (double f = 100; f <= 1e6; f *= 1.25) {
        const double a = francois_garrison_db_per_km(f, 10.0, 35.0, 0.0, 8.0);
        CHECK(a > previous);
        previous = a;
    }
    for (double f : {1e4, 1e5, 4e5}) {
        CHECK(francois_garrison_db_per_km(f, 10.0, 35.0, 2000.0, 8.0) < francois_garrison_db_per_km(f, 10.0, 35.0, 0.0, 8.0));
    }
}

TEST_CASE_TEMPLATE("Ainslie-McColm matches its check values (pH 8, S 35, 10 degC, 0 m)", T, float, double) {
    CHECK(matches_printed(ainslie_mccolm_db_per_km<T>(T(1e4), T(10), T(35), T(0), T(8)), 0.987, 1e-3));
    CHECK(matches_printed(ainslie_mccolm_db_per_km<T>(T(1e5), T(10), T(35), T(0), T(8)), 34.34, 1e-2));
    CHECK(matches_printed(ainslie_mccolm_db_per_km<T>(T(3e5), T(10), T(35), T(0), T(8)), 76.15, 1e-2));
}

TEST_CASE("Ainslie-McColm takes depth in metres and applies e^(-z/6) with z in km") {
    // 100 kHz is MgSO4-dominated; at z = 6 km that term is exactly e^-1 of its surface value.
    const double f = 1e5, t = 10, s = 35, ph = 8;
    const double f2 = 42 * std::exp(t / 17);
    const double mgso4_surface = 0.52 * (1 + t / 43) * (s / 35) * f2 * 1e4 / (f2 * f2 + 1e4);
    const double water_surface = 0.00049 * 1e4 * std::exp(-t / 27);
    const double d = ainslie_mccolm_db_per_km(f, t, s, 0.0, ph) - ainslie_mccolm_db_per_km(f, t, s, 6000.0, ph);
    CHECK(d == doctest::Approx(mgso4_surface * (1 - std::exp(-1.0)) + water_surface * (1 - std::exp(-6.0 / 17))).epsilon(1e-12));
    const ainslie_mccolm<double> model(f, {t, s, ph});
    for (double z : {0.0, 150.0, 3000.0, 6000.0}) {
        CHECK(model.db_per_km(z) == doctest::Approx(ainslie_mccolm_db_per_km(f, t, s, z, ph)).epsilon(1e-13));
    }
}

TEST_CASE("Ainslie-McColm stays within 10% of Francois-Garrison, as its authors state") {
    double worst = 0;
    for (double t : {0.0, 5.0, 10.0, 15.0, 20.0})
        for (double d : {0.0, 1000.0, 3000.0})
            for (double s : {30.0, 35.0})
                for (double f : {200.0, 1e3, 3e3, 1e4, 3e4, 1e5, 3e5, 1e6}) {
                    const double r = ainslie_mccolm_db_per_km(f, t, s, d, 8.0) / francois_garrison_db_per_km(f, t, s, d, 8.0);
                    worst = std::max(worst, std::abs(r - 1));
                }
    MESSAGE("largest |AM/FG - 1| over the grid: " << worst);
    CHECK(worst < 0.10);
}

TEST_CASE("Francois-Garrison depth model matches the free function at every depth") {
    const water_properties<double> w{4.0, 34.5, 7.9};
    for (double f : {500.0, 12e3, 100e3, 455e3}) {
        const francois_garrison<double> model(f, w);
        for (double z = 0; z <= 8000; z += 250) {
            CHECK(model.db_per_km(z) ==
                  doctest::Approx(francois_garrison_db_per_km(f, w.temperature_c, w.salinity_ppt, z, w.ph)).epsilon(1e-13));
        }
    }
}

TEST_CASE("Mean absorption over a depth interval matches high-precision integration") {
    const water_properties<double> w{10.0, 35.0, 8.0};
    double worst = 0;
    for (double f : {1e3, 3e4, 1e5, 4e5}) {
        const francois_garrison<double> fg(f, w);
        const ainslie_mccolm<double> am(f, w);
        const double intervals[][2] = {{0, 6000}, {0, 100}, {1000, 1010}, {250, 4000}, {4000, 250}, {77, 77}};
        for (const auto& iv : intervals) {
            const long double z0 = iv[0], z1 = iv[1];
            long double ref_fg, ref_am;
            if (z0 == z1) {
                ref_fg = fg_reference(f / 1000, 10, 35, z0, 8);
                ref_am = am.db_per_km(iv[0]);
            } else {
                ref_fg = integrate_ld([&](long double z) { return fg_reference(f / 1000, 10, 35, z, 8); }, z0, z1, 64) / (z1 - z0);
                ref_am = integrate_ld([&](long double z) { return static_cast<long double>(am.db_per_km(static_cast<double>(z))); },
                                      z0, z1, 64) / (z1 - z0);
            }
            const double e_fg = std::abs(depth_mean_db_per_km(fg, iv[0], iv[1]) / static_cast<double>(ref_fg) - 1);
            const double e_am = std::abs(depth_mean_db_per_km(am, iv[0], iv[1]) / static_cast<double>(ref_am) - 1);
            worst = std::max({worst, e_fg, e_am});
        }
    }
    MESSAGE("worst relative error of the 5-point depth mean: " << worst);
    CHECK(worst < 1e-11);
}

TEST_CASE("Straight-path absorption is length times the depth mean, and the same both ways") {
    const francois_garrison<double> fg(1e5, {10.0, 35.0, 8.0});
    const double z0 = 20, z1 = 1520, length = 3000; // a 30 degree straight path
    const double one_way = straight_path_absorption_db(fg, z0, z1, length);
    const double back = straight_path_absorption_db(fg, z1, z0, length);
    CHECK(one_way == doctest::Approx(back).epsilon(1e-14));
    const long double ref =
        integrate_ld([&](long double s) { return fg_reference(100, 10, 35, z0 + (z1 - z0) * s / length, 8); }, 0.0L,
                     static_cast<long double>(length), 64) / 1000;
    CHECK(one_way == doctest::Approx(static_cast<double>(ref)).epsilon(1e-11));
    // ~3 km at ~30 dB/km
    CHECK(one_way > 80);
    CHECK(one_way < 100);
}

TEST_CASE("Absorption along a curved ray arc matches high-precision integration along the arc") {
    const francois_garrison<double> fg(1e5, {10.0, 35.0, 8.0});
    // A turning arc: 8 degrees down from 200 m in a strong gradient, back up to 200 m.
    const gradient_layer<double> layer{0, 3000, 0, 1480, 0.3};
    const auto step = step_through_layer(layer, 200.0, 8 * 3.14159265358979323846 / 180, vertical_direction::down);
    REQUIRE(step.turned);
    const auto& arc = step.arc;
    const double loss = path_absorption_db(fg, arc.length_m, [&](double s) { return arc_point(arc, s).depth_m; });
    // Oracle: the arc's depth in closed form, z(s) = z0 + (cos(phi0 - k s) - cos phi0)/k, in long double.
    const long double phi0 = arc.start_incline_rad;
    const long double k = std::cos(phi0) / arc.start_speed_mps * arc.gradient_per_s;
    const long double ref = integrate_ld(
        [&](long double s) { return fg_reference(100, 10, 35, arc.start_depth_m + (std::cos(phi0 - k * s) - std::cos(phi0)) / k, 8); },
        0.0L, static_cast<long double>(arc.length_m), 256) / 1000;
    MESSAGE("arc absorption " << loss << " dB, relative error " << std::abs(loss / static_cast<double>(ref) - 1));
    CHECK(loss == doctest::Approx(static_cast<double>(ref)).epsilon(1e-12));
}

TEST_CASE("Absorption models reject invalid frequency and water properties, naming the parameter") {
    const auto param = [](auto&& make) {
        try {
            make();
        } catch (const sss::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(no throw)");
    };
    CHECK(param([] { (void)francois_garrison<double>(-1.0, {}); }) == "f_hz");
    CHECK(param([] { (void)francois_garrison<double>(std::nan(""), {}); }) == "f_hz");
    CHECK(param([] { (void)ainslie_mccolm<double>(1e5, {10.0, -1.0, 8.0}); }) == "water.salinity_ppt");
    CHECK(param([] { (void)francois_garrison<float>(1e5f, {80.0f, 35.0f, 8.0f}); }) == "water.temperature_c");
    CHECK(param([] { (void)francois_garrison<double>(1e5, {10.0, 35.0, 14.0}); }) == "water.ph");
}

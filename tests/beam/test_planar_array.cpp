// The planar array beam: its 3D pattern against the closed form of an N x M array of rectangular elements
// with tilt, the two-way product, and an extent that holds every direction above the threshold.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

#include "sss/beam/directivity.hpp"
#include "sss/beam/planar_array.hpp"
#include "sss/core/constants.hpp"

namespace {

using sss::beam::array_layout;
using sss::beam::planar_array;
using sss::beam::planar_array_params;

constexpr double pi = sss::pi_v<double>;

/// One-way amplitude of N uniform elements of size a at pitch d along one axis, from the textbook formulas
/// written out here (long double; callers keep away from the removable singularities).
long double closed_axis(std::size_t n, double a, double d, double lambda, double u) {
    const long double x = pi * a * u / lambda;
    long double e = std::abs(x) < 1e-12L ? 1.0L : std::sin(x) / x;
    if (n > 1) {
        const long double p = pi * d * u / lambda;
        e *= std::sin(static_cast<long double>(n) * p) / (static_cast<long double>(n) * std::sin(p));
    }
    return e;
}

planar_array_params<double> multi_element_params() {
    planar_array_params<double> p;
    p.frequency_hz = 100000.0; // lambda = 15 mm
    p.sound_speed_mps = 1500.0;
    p.depression_deg = 25.0;
    p.transmit.along = {8, 0.04, 0.05, {}};
    p.transmit.vertical = {4, 0.01, 0.012, {}};
    p.receive = array_layout<double>{{6, 0.06, 0.065, {}}, {2, 0.02, 0.025, {}}};
    return p;
}

} // namespace

TEST_CASE("The one-way patterns are those of an N x M array of rectangular elements with direction cosines "
          "u = sin a, v = cos a sin(e - tilt)") {
    const planar_array<double> beam(multi_element_params());
    const double lambda = 0.015, tilt = sss::deg_to_rad(25.0);
    CHECK(beam.wavelength_m() == doctest::Approx(lambda));
    CHECK(beam.transmit_power(0.0, tilt) == doctest::Approx(1.0).epsilon(1e-14));
    CHECK(beam.receive_power(0.0, tilt) == doctest::Approx(1.0).epsilon(1e-14));
    int checked = 0;
    for (double a = -0.7; a <= 0.7; a += 0.0123) {
        for (double e = -0.9; e <= 1.5; e += 0.0171) {
            const double u = std::sin(a), v = std::cos(a) * std::sin(e - tilt);
            // Keep away from the array factors' removable singularities (checked in test_directivity).
            if (std::abs(std::sin(pi * 0.05 * u / lambda)) < 1e-3 || std::abs(std::sin(pi * 0.012 * v / lambda)) < 1e-3 ||
                std::abs(std::sin(pi * 0.065 * u / lambda)) < 1e-3 || std::abs(std::sin(pi * 0.025 * v / lambda)) < 1e-3)
                continue;
            const long double tx = closed_axis(8, 0.04, 0.05, lambda, u) * closed_axis(4, 0.01, 0.012, lambda, v);
            const long double rx = closed_axis(6, 0.06, 0.065, lambda, u) * closed_axis(2, 0.02, 0.025, lambda, v);
            CHECK(beam.transmit_power(a, e) == doctest::Approx(static_cast<double>(tx * tx)).epsilon(1e-10).scale(1e-12));
            CHECK(beam.receive_power(a, e) == doctest::Approx(static_cast<double>(rx * rx)).epsilon(1e-10).scale(1e-12));
            ++checked;
        }
    }
    CHECK(checked > 10000);
}

TEST_CASE("The two-way weight is the transmit power pattern times the receive power pattern") {
    const planar_array<double> beam(multi_element_params());
    const auto ext = beam.extent(sss::side::starboard);
    double largest_ratio_gap = 0.0;
    for (double a = ext.along_min_rad; a <= ext.along_max_rad; a += (ext.along_max_rad - ext.along_min_rad) / 97.0) {
        for (double e = ext.depression_min_rad; e <= ext.depression_max_rad;
             e += (ext.depression_max_rad - ext.depression_min_rad) / 89.0) {
            const double tx = beam.transmit_power(a, e), rx = beam.receive_power(a, e);
            CHECK(beam.weight(sss::side::starboard, a, e) == doctest::Approx(tx * rx).epsilon(1e-14).scale(1e-300));
            CHECK(beam.weight(sss::side::port, a, e) == beam.weight(sss::side::starboard, a, e));
            largest_ratio_gap = std::max(largest_ratio_gap, std::abs(tx - rx));
        }
    }
    CHECK(largest_ratio_gap > 0.05); // transmit and receive do differ: the product is not a square
    // Without a receive array the transmitting array receives: the weight is its pattern squared.
    planar_array_params<double> p = multi_element_params();
    p.receive.reset();
    const planar_array<double> mono(p);
    CHECK(mono.weight(sss::side::port, 0.01, 0.5) ==
          doctest::Approx(std::pow(mono.transmit_power(0.01, 0.5), 2)).epsilon(1e-14));
}

TEST_CASE("A 0.5 m element at 100 kHz has the published 1.5228 deg one-way half-power width along track") {
    planar_array_params<double> p; // defaults: 0.5 m x 0.02 m, one element each way, 20 deg tilt
    const planar_array<double> beam(p);
    const double tilt = sss::deg_to_rad(20.0);
    const auto crossing = [&](auto f, double level) {
        double lo = 0.0, hi = 0.02;
        for (int i = 0; i < 100; ++i) (f(0.5 * (lo + hi)) > level ? lo : hi) = 0.5 * (lo + hi);
        return lo;
    };
    const double one_way = crossing([&](double a) { return beam.transmit_power(a, tilt); }, 0.5);
    CHECK(sss::rad_to_deg(2.0 * one_way) == doctest::Approx(1.5228).epsilon(1e-3));
    // Two-way half power: b^4 = 1/2, the one-way width at power 1/sqrt 2.
    const double two_way = crossing([&](double a) { return beam.weight(sss::side::starboard, a, tilt); }, 0.5);
    CHECK(2.0 * two_way == doctest::Approx(sss::beam::line_aperture_width_rad(0.5, 0.015, std::sqrt(0.5))).epsilon(1e-9));
}

TEST_CASE("The vertical pattern is centred on the tilt: half power at e = tilt +- asin(1.391557 lambda / (pi h))") {
    for (double tilt_deg : {0.0, 15.0, 40.0}) {
        planar_array_params<double> p;
        p.depression_deg = tilt_deg;
        p.transmit.vertical = {1, 0.05, 0.0, {}};
        const planar_array<double> beam(p);
        const double tilt = sss::deg_to_rad(tilt_deg);
        const double half = std::asin(1.3915573 * 0.015 / (pi * 0.05));
        CHECK(beam.transmit_power(0.0, tilt) == doctest::Approx(1.0));
        CHECK(beam.transmit_power(0.0, tilt + half) == doctest::Approx(0.5).epsilon(1e-6));
        CHECK(beam.transmit_power(0.0, tilt - half) == doctest::Approx(0.5).epsilon(1e-6));
        // Off the across-track plane v shrinks by cos(along): the same level needs a larger depression offset.
        const double a = 0.3;
        CHECK(beam.transmit_power(a, tilt + std::asin(std::sin(half) / std::cos(a))) / beam.transmit_power(a, tilt) ==
              doctest::Approx(0.5).epsilon(1e-6));
    }
}

TEST_CASE("Nothing is radiated behind the baffled array face") {
    planar_array_params<double> p;
    p.depression_deg = 60.0;
    p.transmit.vertical = {1, 0.005, 0.0, {}}; // nearly omnidirectional in the vertical
    const planar_array<double> beam(p);
    CHECK(beam.transmit_power(0.0, sss::deg_to_rad(-29.0)) > 0.3); // just in front of the face
    CHECK(beam.transmit_power(0.0, sss::deg_to_rad(-31.0)) == 0.0); // just behind it
    CHECK(beam.direction_cosines(0.0, sss::deg_to_rad(-31.0)).z < 0.0);
    CHECK(beam.extent(sss::side::port).depression_min_rad >= sss::deg_to_rad(-30.0) - 1e-12);
}

namespace {

/// Grid from -pi/2 to pi/2 through 0 with the given step, both ends included.
std::vector<double> grid(double step) {
    std::vector<double> g{-sss::half_pi_v<double>};
    for (int k = -static_cast<int>(sss::half_pi_v<double> / step); k * step < sss::half_pi_v<double>; ++k)
        if (k * step > -sss::half_pi_v<double>) g.push_back(k * step);
    g.push_back(sss::half_pi_v<double>);
    return g;
}

/// Scans directions densely: every one whose two-way level (unclipped by the extent) reaches the threshold
/// must lie in the extent (where the weight is the two-way pattern; 0 outside), and the extent must not reach past the outermost of them by more than a grid step.
void check_extent(const planar_array_params<double>& p, double along_step_deg, double dep_step_deg) {
    const planar_array<double> beam(p);
    const double t = std::pow(10.0, p.threshold_db / 10.0);
    const auto ext = beam.extent(sss::side::starboard);
    const double sa = sss::deg_to_rad(along_step_deg), se = sss::deg_to_rad(dep_step_deg);
    double max_along = 0.0, min_dep = 10.0, max_dep = -10.0;
    std::size_t above = 0, outside = 0, wrong_weight = 0;
    const std::vector<double> along = grid(sa), depression = grid(se);
    for (double a : along) {
        for (double e : depression) {
            const double w = beam.transmit_power(a, e) * beam.receive_power(a, e);
            const bool inside = a >= ext.along_min_rad && a <= ext.along_max_rad && e >= ext.depression_min_rad &&
                                e <= ext.depression_max_rad;
            const double weight = beam.weight(sss::side::starboard, a, e);
            if (inside ? std::abs(weight - w) > 1e-12 * w : weight != 0.0) ++wrong_weight;
            if (w < t) continue;
            ++above;
            if (!inside) ++outside;
            max_along = std::max(max_along, std::abs(a));
            min_dep = std::min(min_dep, e);
            max_dep = std::max(max_dep, e);
        }
    }
    MESSAGE("extent along +-" << sss::rad_to_deg(ext.along_max_rad) << " deg (scan " << sss::rad_to_deg(max_along)
                              << "), depression " << sss::rad_to_deg(ext.depression_min_rad) << ".."
                              << sss::rad_to_deg(ext.depression_max_rad) << " deg (scan " << sss::rad_to_deg(min_dep)
                              << ".." << sss::rad_to_deg(max_dep) << "), " << above << " directions above");
    CHECK(above > 0);
    CHECK(outside == 0);
    CHECK(wrong_weight == 0); // the weight is the two-way pattern inside the extent and 0 outside
    CHECK(ext.along_min_rad == -ext.along_max_rad);
    CHECK(ext.along_max_rad <= max_along + 1.5 * sa);
    CHECK(ext.depression_max_rad <= max_dep + 1.5 * se);
    CHECK(ext.depression_min_rad >= min_dep - 1.5 * se);
}

} // namespace

TEST_CASE("The extent holds every direction above the threshold and little more: single elements, -30 dB") {
    check_extent(planar_array_params<double>{}, 0.1, 1.0);
}

TEST_CASE("The extent holds every direction above the threshold and little more: grating lobes in visible space") {
    planar_array_params<double> p;
    p.depression_deg = 30.0;
    p.transmit.along = {4, 0.01, 0.04, {}};     // pitch 2.7 lambda: grating lobes at u = 0.375, 0.75
    p.transmit.vertical = {3, 0.05, 0.05, {}};  // a narrower vertical fan: a finite depression extent
    check_extent(p, 0.25, 0.25);
    const planar_array<double> beam(p);
    CHECK(std::sin(beam.extent(sss::side::port).along_max_rad) > 0.75);
}

TEST_CASE("The extent holds every direction above the threshold and little more: Hann shading, -40 dB") {
    planar_array_params<double> p;
    p.threshold_db = -40.0;
    p.depression_deg = 10.0;
    std::vector<double> hann(16);
    for (std::size_t i = 0; i < hann.size(); ++i) hann[i] = std::pow(std::sin(pi * (static_cast<double>(i) + 0.5) / 16.0), 2);
    p.transmit.along = {16, 0.007, 0.0075, hann};
    p.transmit.vertical = {1, 0.1, 0.0, {}};
    check_extent(p, 0.4, 0.4); // lobes 7 deg wide along, 8 deg in depression
}

TEST_CASE("The extent holds every direction above the threshold and little more: separate arrays, -25 dB") {
    planar_array_params<double> p;
    p.threshold_db = -25.0;
    p.depression_deg = 10.0;
    p.transmit = {{1, 0.2, 0.0, {}}, {1, 0.03, 0.0, {}}};
    p.receive = array_layout<double>{{10, 0.04, 0.05, {}}, {2, 0.06, 0.06, {}}};
    check_extent(p, 0.1, 0.5);
}

TEST_CASE("The extent holds every direction above the threshold and little more: -60 dB, many sidelobes") {
    planar_array_params<double> p;
    p.threshold_db = -60.0;
    p.transmit.along = {1, 0.3, 0.0, {}};
    p.transmit.vertical = {1, 0.08, 0.0, {}};
    check_extent(p, 0.1, 0.5);
}

TEST_CASE_TEMPLATE("The planar array works in float as in double", T, float, double) {
    planar_array_params<T> p;
    p.transmit.along = {8, T(0.04), T(0.05), {}};
    const planar_array<T> beam(p);
    planar_array_params<double> pd;
    pd.transmit.along = {8, 0.04, 0.05, {}};
    const planar_array<double> ref(pd);
    const auto e = beam.extent(sss::side::starboard);
    const auto r = ref.extent(sss::side::starboard);
    CHECK(static_cast<double>(e.along_max_rad) == doctest::Approx(r.along_max_rad).epsilon(1e-4));
    CHECK(static_cast<double>(e.depression_min_rad) == doctest::Approx(r.depression_min_rad).epsilon(1e-4));
    for (double a = -0.02; a <= 0.02; a += 0.001)
        CHECK(static_cast<double>(beam.weight(sss::side::port, static_cast<T>(a), T(0.4))) ==
              doctest::Approx(ref.weight(sss::side::port, a, 0.4)).epsilon(1e-4).scale(1e-6));
}

TEST_CASE("Invalid planar array parameters are rejected, naming the parameter") {
    const auto name_of = [](const planar_array_params<double>& p) {
        try {
            planar_array<double> b(p);
        } catch (const sss::invalid_parameter& e) {
            return e.parameter();
        }
        return std::string("(none)");
    };
    planar_array_params<double> p;
    p.frequency_hz = 0.0;
    CHECK(name_of(p) == "planar_array.frequency_hz");
    p = {};
    p.threshold_db = 0.0;
    CHECK(name_of(p) == "planar_array.threshold_db");
    p = {};
    p.depression_deg = 91.0;
    CHECK(name_of(p) == "planar_array.depression_deg");
    p = {};
    p.transmit.along = {4, 0.05, 0.04, {}};
    CHECK(name_of(p) == "planar_array.transmit.along.pitch_m");
    p = {};
    p.receive = array_layout<double>{};
    p.receive->vertical = {3, 0.01, 0.02, {1.0, 1.0}};
    CHECK(name_of(p) == "planar_array.receive.vertical.shading");
    p.receive->vertical = {3, 0.01, 0.02, {1.0, -1.0, 1.0}};
    CHECK(name_of(p) == "planar_array.receive.vertical.shading");
    p.receive->vertical = {0, 0.01, 0.02, {}};
    CHECK(name_of(p) == "planar_array.receive.vertical.count");
    p.receive->vertical = {1, std::nan(""), 0.0, {}};
    CHECK(name_of(p) == "planar_array.receive.vertical.element_m");
    p.receive->vertical = {3, 0.01, 0.02, {0.5, 1.0, 0.5}};
    CHECK(name_of(p) == "(none)");
}

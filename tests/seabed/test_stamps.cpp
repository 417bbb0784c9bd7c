// Stamped features: shapes, volumes, placement and rotation, footprints and parameter checks.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/seabed/fractal.hpp"
#include "sss/seabed/stamps.hpp"

namespace {

using namespace sss::seabed;
constexpr double pi = sss::pi_v<double>;

raster<double> flat(std::size_t n, double cell, double z = 0.0) { return make_raster<double, double>(n, n, cell, z); }

double volume_m3(const raster<double>& h, double base = 0.0) {
    double v = 0;
    for (double z : h.values) v += z - base;
    return v * h.cell_m * h.cell_m;
}

/// Height at a raster-local point that is a sample (x, y multiples of the cell).
double at(const raster<double>& h, double x, double y) {
    return h(static_cast<std::size_t>(std::lround(x / h.cell_m)), static_cast<std::size_t>(std::lround(y / h.cell_m)));
}

} // namespace

TEST_CASE("mound: cos^2 profile of the given height, volume pi a b H (1/2 - 2/pi^2), oriented by its heading") {
    auto h = flat(400, 0.01, 1.0);
    mound<double> m;
    m.center_x_m = 2.0;
    m.center_y_m = 2.0;
    m.radius_u_m = 1.2;
    m.radius_v_m = 0.6;
    m.heading_deg = 0; // long axis along y
    m.height_m = 0.4;
    stamp(h, m);
    CHECK(at(h, 2.0, 2.0) == doctest::Approx(1.4));
    // Half-way along each semi-axis: H cos^2(pi/4) = H/2.
    CHECK(at(h, 2.0, 2.6) == doctest::Approx(1.2));
    CHECK(at(h, 2.3, 2.0) == doctest::Approx(1.2));
    CHECK(at(h, 2.7, 2.0) == doctest::Approx(1.0)); // beyond the short semi-axis
    CHECK(at(h, 2.0, 3.1) > 1.0);                   // within the long one
    CHECK(volume_m3(h, 1.0) == doctest::Approx(pi * 1.2 * 0.6 * 0.4 * (0.5 - 2.0 / (pi * pi))).epsilon(0.002).scale(0));
}

TEST_CASE("trench: floor at full depth, raised-cosine sides, cross-section D (W + F) / 2, rounded ends, berms") {
    auto h = flat(500, 0.01);
    trench<double> t;
    t.x0_m = 1.0;
    t.y0_m = 1.0;
    t.x1_m = 4.0;
    t.y1_m = 4.0; // 45 degrees, length 3 sqrt 2
    t.width_m = 0.8;
    t.floor_width_m = 0.2;
    t.depth_m = 0.3;
    stamp(h, t);
    CHECK(at(h, 2.5, 2.5) == doctest::Approx(-0.3));
    // Across the trench (direction (1, -1)/sqrt 2): mid-side (|d| = 0.25) is half depth; beyond 0.4 m untouched.
    const double s = 1 / std::sqrt(2.0);
    CHECK(trench_offset_m(t, 0.25) == doctest::Approx(-0.15));
    CHECK(at(h, 2.5 + 0.5 * s * 2, 2.5 - 0.5 * s * 2) == 0.0);
    // Rounded end: along the axis beyond the end point by more than W/2 nothing; within, the floor.
    CHECK(at(h, 0.7, 0.7) == 0.0);
    CHECK(at(h, 0.95, 0.95) == doctest::Approx(-0.3));
    // Volume: prism of cross-section D (W + F)/2 over the length, plus the solid of revolution at the
    // two rounded ends (one full turn): 2 pi int_0^{W/2} d c(d) D dd.
    double ends = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const double d = (i + 0.5) * 0.4 / n;
        ends += 2 * pi * d * -trench_offset_m(t, d) * 0.4 / n;
    }
    const double prism = 0.3 * (0.8 + 0.2) / 2 * 3 * std::sqrt(2.0);
    CHECK(-volume_m3(h) == doctest::Approx(prism + ends).epsilon(0.003).scale(0));
    // Berms: crest of height b at |d| = W/2 + bw/2, nothing beyond W/2 + bw.
    t.berm_height_m = 0.05;
    t.berm_width_m = 0.2;
    CHECK(trench_offset_m(t, 0.5) == doctest::Approx(0.05));
    CHECK(trench_offset_m(t, 0.61) == 0.0);
    CHECK(trench_offset_m(t, 0.41) > 0.0);
}

TEST_CASE("scour pit: depth at the centre, volume pi a b D / 3, raised rim beyond the pit") {
    auto h = flat(400, 0.01);
    scour<double> sc;
    sc.center_x_m = 2.0;
    sc.center_y_m = 2.0;
    sc.radius_u_m = 1.0;
    sc.radius_v_m = 0.5;
    sc.heading_deg = 60;
    sc.depth_m = 0.25;
    stamp(h, sc);
    CHECK(at(h, 2.0, 2.0) == doctest::Approx(-0.25));
    CHECK(volume_m3(h) == doctest::Approx(-pi * 1.0 * 0.5 * 0.25 / 3).epsilon(0.002).scale(0));
    // Along the 30-degree axis the pit reaches 1 m; across it 0.5 m.
    const double c = std::cos(sss::deg_to_rad(30.0)), s = std::sin(sss::deg_to_rad(30.0));
    CHECK(scour_offset_m(sc, 0.5) == doctest::Approx(-0.25 * 0.75 * 0.75));
    auto probe = flat(400, 0.01);
    stamp(probe, sc);
    const double along = probe(static_cast<std::size_t>(std::lround((2.0 + 0.9 * c) / 0.01)),
                               static_cast<std::size_t>(std::lround((2.0 + 0.9 * s) / 0.01)));
    CHECK(along < 0.0);
    CHECK(along > -0.02);
    sc.rim_height_m = 0.05;
    sc.rim_width_m = 0.2; // w = 0.2 / sqrt(0.5) in normalised radius
    const double w = 0.2 / std::sqrt(0.5);
    CHECK(scour_offset_m(sc, 1.0 + w / 2) == doctest::Approx(0.05));
    CHECK(scour_offset_m(sc, 1.0 + w * 1.01) == 0.0);
}

TEST_CASE("plate: flat top at the mean seabed under it plus its height, area L W, heading honoured") {
    fractal_params<double> p;
    p.spectrum = jackson_spectrum(0.01, 3.25);
    auto h = fractal_surface<double>(256, 256, 0.02, p, 4);
    const auto before = h;
    plate<double> pl;
    pl.center_x_m = 2.5;
    pl.center_y_m = 2.6;
    pl.length_m = 2.0;
    pl.width_m = 0.6;
    pl.heading_deg = 60;
    pl.top_m = 0.15;
    auto ids = make_raster<std::uint32_t, double>(256, 256, 0.02, 0u);
    stamp(h, ids, pl, 7);
    // Samples well inside share one height, the footprint mean of the seabed plus 0.15 m; samples
    // clear of the edges outside are untouched; the label covers the L x W rectangle.
    const double c = std::cos(sss::heading_to_ccw_from_east_rad(pl.heading_deg)), s = std::sin(sss::heading_to_ccw_from_east_rad(pl.heading_deg));
    const double top = at(h, 2.5, 2.6);
    double inside_spread = 0, outside_change = 0, mean_before = 0, n_in = 0;
    std::size_t labelled = 0;
    for (std::size_t j = 0; j < h.ny; ++j)
        for (std::size_t i = 0; i < h.nx; ++i) {
            const double dx = h.x_m(i) - 2.5, dy = h.y_m(j) - 2.6;
            const double u = dx * c + dy * s, v = -dx * s + dy * c;
            if (std::abs(u) < 0.97 && std::abs(v) < 0.27) {
                inside_spread = std::max(inside_spread, std::abs(h(i, j) - top));
                mean_before += before(i, j);
                n_in += 1;
            }
            if (std::abs(u) > 1.03 || std::abs(v) > 0.33)
                outside_change = std::max(outside_change, std::abs(h(i, j) - before(i, j)));
            if (ids(i, j) == 7) ++labelled;
        }
    CHECK(inside_spread < 1e-12);
    CHECK(outside_change == 0.0);
    // The interior mean is the footprint mean up to the thin edge strip.
    CHECK(top == doctest::Approx(mean_before / n_in + 0.15).epsilon(0.01).scale(0));
    CHECK(static_cast<double>(labelled) * 0.02 * 0.02 == doctest::Approx(2.0 * 0.6).epsilon(0.02).scale(0));
}

TEST_CASE("plate coverage anti-aliases its edges: the covered area is L W to sub-cell accuracy") {
    // On a flat seabed at 0, a plate of height 1: the sum of heights times the cell area is the plate's area.
    for (double heading_deg : {0.0, 17.0, 45.0}) {
        CAPTURE(heading_deg);
        auto h = flat(200, 0.05);
        plate<double> pl;
        pl.center_x_m = 5.01;
        pl.center_y_m = 4.97;
        pl.length_m = 3.3;
        pl.width_m = 1.1;
        pl.heading_deg = 90.0 - heading_deg;
        pl.top_m = 1.0;
        stamp(h, pl);
        CHECK(volume_m3(h) == doctest::Approx(3.3 * 1.1).epsilon(0.01).scale(0));
    }
}

TEST_CASE("features off the raster change nothing and label footprints only where they cover a cell") {
    auto h = flat(50, 0.1);
    mound<double> m;
    m.center_x_m = -10;
    m.center_y_m = 2;
    stamp(h, m);
    CHECK(volume_m3(h) == 0.0);
    plate<double> pl;
    pl.center_x_m = 100;
    stamp(h, pl);
    CHECK(volume_m3(h) == 0.0);
    // A mound half off the edge: only the inside half is applied.
    auto ids = make_raster<std::uint32_t, double>(50, 50, 0.1, 0u);
    m.center_x_m = 0.0;
    m.center_y_m = 2.5;
    m.radius_u_m = m.radius_v_m = 1.0;
    stamp(h, ids, m, 3);
    std::size_t labelled = 0;
    for (auto id : ids.values) labelled += id == 3 ? 1 : 0;
    // Half disc of radius 1 m: pi/2 m^2 = 157 cells of 0.01 m^2 (the column at x = 0 is half a cell).
    CHECK(static_cast<double>(labelled) == doctest::Approx(pi / 2 / 0.01 + 10).epsilon(0.08).scale(0));
}

TEST_CASE("stamps reject invalid parameters and mismatched rasters, naming the field") {
    auto h = flat(10, 0.1);
    auto expect = [&](auto&& f, const char* name) {
        try {
            f();
            FAIL("no exception for " << name);
        } catch (const sss::invalid_parameter& e) {
            CHECK(e.parameter() == name);
        }
    };
    expect([&] { stamp(h, plate<double>{0, 0, -1, 1, 0, 0.1}); }, "stamp.plate.length_m");
    expect([&] { stamp(h, plate<double>{0, 0, 1, 1, 0, NAN}); }, "stamp.plate.top_m");
    expect([&] { stamp(h, trench<double>{0, 0, 1, 0, 0.5, 0.5, 0.1, 0, 0}); }, "stamp.trench.floor_width_m");
    expect([&] { stamp(h, trench<double>{0, 0, 1, 0, 0.5, 0.1, 0.1, 0.05, 0}); }, "stamp.trench.berm_width_m");
    expect([&] { stamp(h, trench<double>{0, 0, 1, 0, 0.5, 0.1, -0.1, 0, 0}); }, "stamp.trench.depth_m");
    expect([&] { stamp(h, mound<double>{0, 0, 0, 1, 0, 0.1}); }, "stamp.mound.radius_u_m");
    expect([&] { stamp(h, mound<double>{0, 0, 1, 1, 0, -0.1}); }, "stamp.mound.height_m");
    expect([&] { stamp(h, scour<double>{0, 0, 1, 1, 0, 0.1, 0.05, 0}); }, "stamp.scour.rim_width_m");
    expect([&] { stamp(h, scour<double>{0, 0, 1, -1, 0, 0.1, 0, 0}); }, "stamp.scour.radius_v_m");
    auto ids = make_raster<std::uint32_t, double>(9, 10, 0.1, 0u);
    expect([&] { stamp(h, ids, mound<double>{}, 1); }, "stamp.regions");
    raster<double> broken{10, 10, 0.1, {}};
    expect([&] { stamp(broken, mound<double>{}); }, "stamp.h.values");
    // float rasters work the same way
    auto hf = make_raster<float, float>(40, 40, 0.05f, 0.0f);
    stamp(hf, mound<float>{1.0f, 1.0f, 0.5f, 0.5f, 0.0f, 0.2f});
    CHECK(hf(20, 20) == doctest::Approx(0.2f));
}

// UTM on WGS 84: the northing along a central meridian is k0 times the meridian's arc (integrated here
// independently), a published conversion is reproduced, the zones' symmetries hold, the inverse undoes the forward
// across and beyond a zone, bad zones are named, and an XTF of a UTM world carries the exact latitudes and
// longitudes of its poses.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "sss/io/utm.hpp"
#include "sss/io/xtf.hpp"

namespace {

using namespace sss;

/// The arc of the WGS 84 meridian from the equator to latitude lat_deg (m): the integral of the meridian radius
/// M = a (1 - e^2) / (1 - e^2 sin^2 phi)^(3/2), by Simpson's rule over 20000 panels.
double meridian_arc_m(double lat_deg) {
    const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2.0 - f);
    const double phi = lat_deg * pi_v<double> / 180.0;
    auto m = [&](double p) {
        const double w = 1.0 - e2 * std::sin(p) * std::sin(p);
        return a * (1.0 - e2) / (w * std::sqrt(w));
    };
    const int panels = 20000;
    const double h = phi / panels;
    double sum = m(0.0) + m(phi);
    for (int i = 1; i < panels; ++i) sum += (i % 2 == 1 ? 4.0 : 2.0) * m(i * h);
    return sum * h / 3.0;
}

// `pings` lines of four samples of 1 (what an XTF of poses needs besides them).
waterfall<double> flat_lines(std::size_t pings) {
    waterfall<double> w;
    w.pings = pings;
    w.samples = 4;
    w.dt_s = 1e-4;
    w.values.assign(w.pings * 2 * w.samples, 1.0);
    return w;
}

} // namespace

TEST_CASE("on a zone's central meridian the easting is 500 km and the northing k0 times the meridian's arc") {
    for (const double lat : {0.0, 10.0, 33.3, 45.0, 57.1, 72.0, 83.5}) {
        CAPTURE(lat);
        double e = 0, n = 0;
        io::geodetic_to_utm({.zone = 31}, {lat, 3.0}, e, n);
        CHECK(e == doctest::Approx(500000.0).epsilon(1e-15));
        CHECK(std::abs(n - 0.9996 * meridian_arc_m(lat)) < 1e-4);
        const io::geodetic_position g = io::utm_to_geodetic({.zone = 31}, 500000.0, n);
        CHECK(std::abs(g.latitude_deg - lat) < 1e-11);
        CHECK(std::abs(g.longitude_deg - 3.0) < 1e-12);
    }
    // 45 deg: 0.9996 x 4 984 944.378 m.
    double e = 0, n = 0;
    io::geodetic_to_utm({.zone = 31}, {45.0, 3.0}, e, n);
    CHECK(n == doctest::Approx(4982950.400).epsilon(1e-9));
}

TEST_CASE("a published conversion: 33.3 N, 44.4 E is 444140.54 E, 3684706.36 N in zone 38 north") {
    // The example of GeographicLib's GeoConvert (Karney), whose series this follows, to its printed centimetres.
    double e = 0, n = 0;
    io::geodetic_to_utm({.zone = 38}, {33.3, 44.4}, e, n);
    CHECK(std::abs(e - 444140.54) < 0.006);
    CHECK(std::abs(n - 3684706.36) < 0.006);
    const io::geodetic_position g = io::utm_to_geodetic({.zone = 38}, 444140.54, 3684706.36);
    CHECK(std::abs(g.latitude_deg - 33.3) < 1e-7);
    CHECK(std::abs(g.longitude_deg - 44.4) < 1e-7);
}

TEST_CASE("eastings mirror about the central meridian, and the southern hemisphere mirrors the northern") {
    double e1 = 0, n1 = 0, e2 = 0, n2 = 0;
    io::geodetic_to_utm({.zone = 10}, {48.0, -123.0 + 2.5}, e1, n1);
    io::geodetic_to_utm({.zone = 10}, {48.0, -123.0 - 2.5}, e2, n2);
    CHECK(std::abs((e1 - 500000.0) + (e2 - 500000.0)) < 1e-7);
    CHECK(std::abs(n1 - n2) < 1e-7);
    double es = 0, ns = 0;
    io::geodetic_to_utm({.zone = 10, .south = true}, {-48.0, -123.0 + 2.5}, es, ns);
    CHECK(std::abs(es - e1) < 1e-7);
    CHECK(std::abs((10000000.0 - ns) - n1) < 1e-7);
}

TEST_CASE("the inverse undoes the forward to 0.1 mm, over a zone and 6 degrees beyond it, in both hemispheres") {
    double worst_m = 0.0;
    for (const bool south : {false, true})
        for (double lat = -80.0; lat <= 84.0; lat += 7.3)
            for (double dl = -9.0; dl <= 9.0; dl += 1.7) {
                const io::utm_zone z{.zone = 33, .south = south};
                const double lon = 15.0 + dl;
                double e = 0, n = 0;
                io::geodetic_to_utm(z, {lat, lon}, e, n);
                const io::geodetic_position g = io::utm_to_geodetic(z, e, n);
                double e2 = 0, n2 = 0;
                io::geodetic_to_utm(z, g, e2, n2);
                worst_m = std::max({worst_m, std::abs(e2 - e), std::abs(n2 - n)});
                CHECK(std::abs(g.latitude_deg - lat) < 1e-9);
                CHECK(std::abs(g.longitude_deg - lon) < 1e-9);
            }
    INFO("worst round trip " << worst_m << " m");
    CHECK(worst_m < 1e-4);
}

TEST_CASE("a UTM zone outside 1 to 60, or a position that is not finite or beyond the series' reach, is named") {
    CHECK_THROWS_WITH_AS((void)io::utm_to_geodetic({.zone = 0}, 5e5, 0.0), doctest::Contains("utm_zone.zone"), invalid_parameter);
    CHECK_THROWS_WITH_AS((void)io::utm_to_geodetic({.zone = 61}, 5e5, 0.0), doctest::Contains("utm_zone.zone"), invalid_parameter);
    CHECK_THROWS_WITH_AS((void)io::utm_to_geodetic({.zone = 31}, std::nan(""), 0.0), doctest::Contains("utm.easting_m"),
                         invalid_parameter);
    CHECK_THROWS_WITH_AS((void)io::utm_to_geodetic({.zone = 31}, 1e9, 0.0), doctest::Contains("utm.easting_m"),
                         invalid_parameter);
    CHECK_THROWS_WITH_AS((void)io::utm_to_geodetic({.zone = 31}, 5e5, 3e7), doctest::Contains("utm.northing_m"),
                         invalid_parameter);
    double e = 0, n = 0;
    CHECK_THROWS_WITH_AS(io::geodetic_to_utm({.zone = 31}, {91.0, 0.0}, e, n),
                         doctest::Contains("geodetic_position.latitude_deg"), invalid_parameter);
    CHECK_THROWS_WITH_AS(io::geodetic_to_utm({.zone = 31}, {0.0, 93.0}, e, n),
                         doctest::Contains("geodetic_position.longitude_deg"), invalid_parameter);
}

TEST_CASE("an XTF of a UTM world carries the exact latitude and longitude of each pose") {
    const waterfall<double> w = flat_lines(3);
    std::vector<pose<double>> poses(3);
    for (std::size_t i = 0; i < poses.size(); ++i) {
        poses[i].position = {652000.0 + 3.0 * double(i), 6230000.0 + 40.0 * double(i), 10.0};
        poses[i].time_s = 0.1 * double(i);
    }
    io::xtf_render_params p{.ping_interval_s = 0.1, .utm = io::utm_zone{.zone = 32}};
    p.header.nav_units = io::xtf_nav_units::latitude_longitude;
    const io::xtf_file f = io::make_xtf<double>(w, poses, p);
    REQUIRE(f.pings.size() == 3u);
    for (std::size_t i = 0; i < 3; ++i) {
        const io::geodetic_position g = io::utm_to_geodetic({.zone = 32}, poses[i].position.x, poses[i].position.y);
        CHECK(f.pings[i].x == g.longitude_deg);
        CHECK(f.pings[i].y == g.latitude_deg);
    }
    // About 56.2 N, 11.5 E (zone 32 spans 6 to 12 E); a local plane about (0, 0) would put it at 4.5 E, 56 N.
    CHECK(f.pings[0].y > 56.0);
    CHECK(f.pings[0].y < 56.3);
    CHECK(f.pings[0].x > 11.4);
    CHECK(f.pings[0].x < 11.6);
    // Ping 1 is 40 m grid north and 3 m grid east of ping 0. True north lies at the grid bearing c of the meridian
    // convergence (about -2.04 deg here, east of the central meridian), so the step goes 40 cos c + 3 sin c grid
    // metres northward (the eastward 3 m takes off 0.11 m). The grid scales ground lengths by the point scale factor
    // k = k0 / sqrt(1 - cos^2(lat) sin^2(l)), about 0.99988 here (the sphere's; the ellipsoid's differs by under
    // 1e-6), and a degree of latitude is 111345.3 m of meridian there.
    const io::utm_zone zone{.zone = 32};
    const double rad = pi_v<double> / 180.0;
    const double c = io::utm_north_grid_bearing_deg(zone, 652001.5, 6230020.0) * rad;
    const double lat = f.pings[0].y, l = (f.pings[0].x - 9.0) * rad;
    const double k = 0.9996 / std::sqrt(1.0 - std::pow(std::cos(lat * rad) * std::sin(l), 2));
    const double metres_per_deg = (meridian_arc_m(lat + 0.005) - meridian_arc_m(lat - 0.005)) / 0.01;
    const double north_m = 40.0 * std::cos(c) + 3.0 * std::sin(c);
    CHECK(f.pings[1].y - f.pings[0].y == doctest::Approx(north_m / (k * metres_per_deg)).epsilon(1e-5).scale(0));
}

TEST_CASE("true north's grid bearing is the meridian convergence: tan c = tan l sin(latitude) to 0.01 deg, 0 on the central "
          "meridian, mirrored east and south") {
    const io::utm_zone z{.zone = 32}; // central meridian 9 E
    const double rad = pi_v<double> / 180.0;
    for (const double e : {200000.0, 300000.0, 450000.0, 700000.0, 800000.0})
        for (const double n : {1000000.0, 4000000.0, 6650000.0, 8500000.0}) {
            const io::geodetic_position g = io::utm_to_geodetic(z, e, n);
            const double l = (g.longitude_deg - 9.0) * rad;
            // West of the central meridian (l < 0) the meridian runs east of grid north: a positive bearing.
            const double spherical = -std::atan(std::tan(l) * std::sin(g.latitude_deg * rad)) / rad;
            CAPTURE(e);
            CAPTURE(n);
            CHECK(std::abs(io::utm_north_grid_bearing_deg(z, e, n) - spherical) <= 0.01);
            const double here = io::utm_north_grid_bearing_deg(z, e, n);
            CHECK(std::abs(io::utm_north_grid_bearing_deg(z, 1e6 - e, n) + here) <= 1e-7);
            CHECK(std::abs(io::utm_north_grid_bearing_deg({.zone = 32, .south = true}, e, 1e7 - n) + here) <= 1e-7);
        }
    CHECK(std::abs(io::utm_north_grid_bearing_deg(z, 500000.0, 6650000.0)) < 1e-9);
}

TEST_CASE("an XTF of a UTM world gives headings from true north: a towfish heading grid north 200 km west of the central "
          "meridian at 60 N heads 3.1 degrees west of true north") {
    const waterfall<double> w = flat_lines(2);
    std::vector<pose<double>> poses(2);
    for (std::size_t i = 0; i < poses.size(); ++i) {
        poses[i].position = {300000.0, 6650000.0 + 10.0 * double(i), 10.0};
        poses[i].time_s = 0.1 * double(i);
        poses[i].yaw_rad = 0.0; // grid north
    }
    io::xtf_render_params p{.ping_interval_s = 0.1, .utm = io::utm_zone{.zone = 32}};
    p.header.nav_units = io::xtf_nav_units::latitude_longitude;
    const io::xtf_file f = io::make_xtf<double>(w, poses, p);
    const double c = io::utm_north_grid_bearing_deg({.zone = 32}, 300000.0, 6650000.0);
    MESSAGE("convergence " << c << " deg, heading " << f.pings[0].heading_deg);
    CHECK(c == doctest::Approx(3.1).epsilon(0.02));
    CHECK(f.pings[0].heading_deg == doctest::Approx(360.0 - c).epsilon(1e-9));
    // In projected metres (the UTM metres themselves) the heading is from true north too; in a world that is not
    // UTM, from its +y.
    p.header.nav_units = io::xtf_nav_units::projected_m;
    CHECK(io::make_xtf<double>(w, poses, p).pings[0].heading_deg == doctest::Approx(360.0 - c).epsilon(1e-9));
    p.utm.reset();
    CHECK(io::make_xtf<double>(w, poses, p).pings[0].heading_deg == 0.0);
}

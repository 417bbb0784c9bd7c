#pragma once
/// \file
/// Universal Transverse Mercator (UTM) coordinates on WGS 84: latitude and longitude of an easting and northing in
/// a zone, and back, for worlds whose x and y are UTM metres (a georeferenced bathymetry).
///
/// UTM (DMA, 1989, Technical Manual 8358.2, "The Universal Grids"): zone z (1 to 60) is the transverse Mercator
/// projection about the central meridian lambda0 = 6 z - 183 degrees, scaled by k0 = 0.9996, with a false easting of
/// 500 000 m and a false northing of 0 (north) or 10 000 000 m (south). The projection is Krueger's series in the
/// third flattening n = f / (2 - f), to n^6, as given by Karney (2011, "Transverse Mercator with an accuracy of a
/// few nanometers", J. Geodesy 85(8), 475-485, eqs. 7-11 and 35-36): with A = a / (1 + n) (1 + n^2/4 + n^4/64 +
/// n^6/256) the rectifying radius,
///
///     forward:  tau' = conformal tan(latitude) (eq. 7),  xi' = atan2(tau', cos l),  eta' = asinh(sin l / hypot(tau', cos l)),
///               xi = xi' + sum_j alpha_j sin(2 j xi') cosh(2 j eta'),  eta = eta' + sum_j alpha_j cos(2 j xi') sinh(2 j eta'),
///               easting = 500 000 + k0 A eta,  northing = k0 A xi (+ 10 000 000 south);
///     inverse:  xi' = xi - sum_j beta_j sin(2 j xi) cosh(2 j eta),  eta' = eta - sum_j beta_j cos(2 j xi) sinh(2 j eta),
///               l = atan2(sinh eta', cos xi'),  tau' = sin xi' / hypot(sinh eta', cos xi'),  and tan(latitude) from tau'
///               by Newton's method (eqs. 19-21, two or three steps),
///
/// l the longitude from the central meridian. The series is accurate to a few nanometres within 3900 km of the
/// central meridian, far beyond a zone's 6 degrees. Angles in radians above, degrees at the interface.

#include <algorithm>
#include <cmath>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/io/detail/wgs84.hpp"
#include "sss/io/geodetic.hpp"

namespace sss::io {

/// A UTM zone: its number and hemisphere. Plain data.
struct utm_zone {
    int zone = 31;      ///< 1 to 60: the central meridian is 6 zone - 183 degrees
    bool south = false; ///< the southern hemisphere (false northing 10 000 000 m)
};

namespace detail {

/// Krueger's coefficients for WGS 84 (Karney, 2011, eqs. 35 and 36) and the rectifying radius (m).
struct kruger_series {
    double alpha[7]{}; ///< forward, alpha[1..6]
    double beta[7]{};  ///< inverse, beta[1..6]
    double a_rect_m = 0.0;
    double e = 0.0; ///< first eccentricity
};

[[nodiscard]] inline const kruger_series& wgs84_kruger() noexcept {
    static const kruger_series k = [] {
        kruger_series s;
        const double f = sss::detail::wgs84_f, n = f / (2.0 - f);
        const double n2 = n * n, n3 = n2 * n, n4 = n3 * n, n5 = n4 * n, n6 = n5 * n;
        s.a_rect_m = sss::detail::wgs84_a_m / (1.0 + n) * (1.0 + n2 / 4.0 + n4 / 64.0 + n6 / 256.0);
        s.e = std::sqrt(f * (2.0 - f));
        s.alpha[1] = n / 2 - 2 * n2 / 3 + 5 * n3 / 16 + 41 * n4 / 180 - 127 * n5 / 288 + 7891 * n6 / 37800;
        s.alpha[2] = 13 * n2 / 48 - 3 * n3 / 5 + 557 * n4 / 1440 + 281 * n5 / 630 - 1983433 * n6 / 1935360;
        s.alpha[3] = 61 * n3 / 240 - 103 * n4 / 140 + 15061 * n5 / 26880 + 167603 * n6 / 181440;
        s.alpha[4] = 49561 * n4 / 161280 - 179 * n5 / 168 + 6601661 * n6 / 7257600;
        s.alpha[5] = 34729 * n5 / 80640 - 3418889 * n6 / 1995840;
        s.alpha[6] = 212378941 * n6 / 319334400;
        s.beta[1] = n / 2 - 2 * n2 / 3 + 37 * n3 / 96 - n4 / 360 - 81 * n5 / 512 + 96199 * n6 / 604800;
        s.beta[2] = n2 / 48 + n3 / 15 - 437 * n4 / 1440 + 46 * n5 / 105 - 1118711 * n6 / 3870720;
        s.beta[3] = 17 * n3 / 480 - 37 * n4 / 840 - 209 * n5 / 4480 + 5569 * n6 / 90720;
        s.beta[4] = 4397 * n4 / 161280 - 11 * n5 / 504 - 830251 * n6 / 7257600;
        s.beta[5] = 4583 * n5 / 161280 - 108847 * n6 / 3991680;
        s.beta[6] = 20648693 * n6 / 638668800;
        return s;
    }();
    return k;
}

/// tau' = tan of the conformal latitude, from tau = tan of the latitude (Karney, 2011, eq. 7).
[[nodiscard]] inline double conformal_tan(double tau, double e) noexcept {
    const double sigma = std::sinh(e * std::atanh(e * tau / std::hypot(1.0, tau)));
    return tau * std::hypot(1.0, sigma) - sigma * std::hypot(1.0, tau);
}

/// The central meridian of a zone (rad), after checking the zone's number.
[[nodiscard]] inline double utm_central_meridian_rad(const utm_zone& z) {
    sss::require(z.zone >= 1 && z.zone <= 60, "utm_zone.zone", [&] { return "must lie in [1, 60], got " + std::to_string(z.zone); });
    return (6.0 * z.zone - 183.0) * pi_v<double> / 180.0;
}

} // namespace detail

/// Latitude and longitude (WGS 84) of the UTM position (easting_m, northing_m) in zone z (see the file comment),
/// within 4000 km of the zone's central meridian.
[[nodiscard]] inline geodetic_position utm_to_geodetic(const utm_zone& z, double easting_m, double northing_m) {
    const double lon0 = detail::utm_central_meridian_rad(z);
    sss::require(std::abs(easting_m - 5e5) <= 4e6, "utm.easting_m", [&] {
        return "must lie within 4000 km of the central meridian's 500000 m (where the series holds), got " +
               std::to_string(easting_m);
    });
    sss::require(northing_m >= -1e7 && northing_m <= 2e7, "utm.northing_m",
                 [&] { return "must lie in [-10000 km, 20000 km], got " + std::to_string(northing_m); });
    const detail::kruger_series& k = detail::wgs84_kruger();
    constexpr double k0 = 0.9996;
    const double xi = (northing_m - (z.south ? 1e7 : 0.0)) / (k0 * k.a_rect_m);
    const double eta = (easting_m - 5e5) / (k0 * k.a_rect_m);
    double xi1 = xi, eta1 = eta;
    for (int j = 1; j <= 6; ++j) {
        xi1 -= k.beta[j] * std::sin(2 * j * xi) * std::cosh(2 * j * eta);
        eta1 -= k.beta[j] * std::cos(2 * j * xi) * std::sinh(2 * j * eta);
    }
    const double sinh_eta = std::sinh(eta1), cos_xi = std::cos(xi1);
    const double tau1 = std::sin(xi1) / std::hypot(sinh_eta, cos_xi);
    const double lon = std::atan2(sinh_eta, cos_xi);
    // tan(latitude) from tau' by Newton's method (Karney, 2011, eqs. 19-21).
    const double e2 = k.e * k.e;
    double tau = tau1;
    for (int i = 0; i < 5; ++i) {
        const double t1 = detail::conformal_tan(tau, k.e);
        const double slope = (1.0 - e2) * std::hypot(1.0, t1) * std::hypot(1.0, tau) / (1.0 + (1.0 - e2) * tau * tau);
        const double step = (tau1 - t1) / slope;
        tau += step;
        if (!(std::abs(step) > 1e-14 * std::max(1.0, std::abs(tau)))) break;
    }
    const double deg = 180.0 / pi_v<double>;
    double lon_deg = (lon0 + lon) * deg;
    if (lon_deg > 180.0) lon_deg -= 360.0;
    if (lon_deg < -180.0) lon_deg += 360.0;
    return {std::atan(tau) * deg, lon_deg};
}

/// The inverse: UTM easting and northing (m) in zone z of the geodetic position p, written into `easting_m`,
/// `northing_m` (p's longitude may lie outside the zone, up to 35 degrees from its central meridian: the projection
/// extends beyond it).
inline void geodetic_to_utm(const utm_zone& z, const geodetic_position& p, double& easting_m, double& northing_m) {
    const double lon0 = detail::utm_central_meridian_rad(z);
    sss::require_in_range(p.latitude_deg, -90.0, 90.0, "geodetic_position.latitude_deg");
    sss::require_finite(p.longitude_deg, "geodetic_position.longitude_deg");
    const detail::kruger_series& k = detail::wgs84_kruger();
    constexpr double k0 = 0.9996;
    const double rad = pi_v<double> / 180.0;
    const double l = std::remainder(p.longitude_deg * rad - lon0, 2.0 * pi_v<double>);
    sss::require(std::abs(l) <= 35.0 * rad, "geodetic_position.longitude_deg", [&] {
        return "must lie within 35 degrees of zone " + std::to_string(z.zone) + "'s central meridian (where the series holds), got " +
               std::to_string(p.longitude_deg);
    });
    const double tau1 = detail::conformal_tan(std::tan(p.latitude_deg * rad), k.e);
    const double xi1 = std::atan2(tau1, std::cos(l));
    const double eta1 = std::asinh(std::sin(l) / std::hypot(tau1, std::cos(l)));
    double xi = xi1, eta = eta1;
    for (int j = 1; j <= 6; ++j) {
        xi += k.alpha[j] * std::sin(2 * j * xi1) * std::cosh(2 * j * eta1);
        eta += k.alpha[j] * std::cos(2 * j * xi1) * std::sinh(2 * j * eta1);
    }
    easting_m = 5e5 + k0 * k.a_rect_m * eta;
    northing_m = k0 * k.a_rect_m * xi + (z.south ? 1e7 : 0.0);
}

/// The grid bearing of true north at UTM position (easting_m, northing_m) in zone z (deg, clockwise from grid north):
/// the meridian's direction on the grid, that is the meridian convergence (on the sphere tan(c) = tan(l) sin(latitude),
/// l the longitude from the central meridian: Snyder, 1987, "Map Projections: A Working Manual", USGS Professional
/// Paper 1395, eq. 8-9 and p. 62). Positive west of the central meridian in the northern hemisphere, where meridians
/// lean east of grid north as they run north. A direction at grid bearing b_g has the true bearing b_g less this.
/// Found from the projection itself: the grid direction of a step of 10^-5 degrees north and south along the meridian.
[[nodiscard]] inline double utm_north_grid_bearing_deg(const utm_zone& z, double easting_m, double northing_m) {
    const geodetic_position g = utm_to_geodetic(z, easting_m, northing_m);
    constexpr double step_deg = 1e-5;
    double e0 = 0, n0 = 0, e1 = 0, n1 = 0;
    geodetic_to_utm(z, {std::max(g.latitude_deg - step_deg, -90.0), g.longitude_deg}, e0, n0);
    geodetic_to_utm(z, {std::min(g.latitude_deg + step_deg, 90.0), g.longitude_deg}, e1, n1);
    return std::atan2(e1 - e0, n1 - n0) * (180.0 / pi_v<double>);
}

} // namespace sss::io

#pragma once
/// \file
/// Latitude and longitude of world positions, from a geodetic origin.
///
/// The world's x (east) and y (north) metres are taken as a local tangent plane at the origin, mapped by the
/// ellipsoid's radii of curvature there (an equirectangular projection about the origin):
///
///     latitude  = lat0 + y / M(lat0),      M = a (1 - e^2) / (1 - e^2 sin^2 lat0)^(3/2)  (meridian radius)
///     longitude = lon0 + x / (N(lat0) cos lat0),   N = a / sqrt(1 - e^2 sin^2 lat0)     (prime vertical radius)
///
/// (Snyder, 1987, "Map Projections: A Working Manual", USGS Professional Paper 1395, eqs. 4-18 and 4-20), on the
/// WGS 84 ellipsoid, a = 6378137 m, 1/f = 298.257223563 (NIMA, 2000, Technical Report 8350.2, 3rd ed.). Angles in
/// radians above, degrees at the interface. The plane departs from the ellipsoid by about d^2 / (2 R): 8 cm at
/// d = 1 km, 2 m at 5 km from the origin; away from the equator the longitude scale's change with latitude adds
/// about x y tan(lat0) / R (7 m at 5 km east and 5 km north of an origin at 60 degrees), so it serves a survey area
/// of a few kilometres; the inverse is exact (the map is linear). Longitudes are given in (-180, 180], and a
/// difference of longitudes is taken the short way round, so that an area across the antimeridian maps whole.

#include <cmath>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/io/detail/wgs84.hpp"

namespace sss::io {

/// The geodetic position of the world origin (x = y = 0), WGS 84.
struct geodetic_origin {
    double latitude_deg = 0.0;  ///< in [-89, 89] (deg)
    double longitude_deg = 0.0; ///< in [-180, 180] (deg)
};

struct geodetic_position {
    double latitude_deg = 0.0;  ///< (deg), north positive
    double longitude_deg = 0.0; ///< (deg), east positive
};

/// A longitude (deg) in (-180, 180].
[[nodiscard]] inline double normalised_longitude_deg(double longitude_deg) noexcept {
    const double l = std::remainder(longitude_deg, 360.0);
    return l <= -180.0 ? l + 360.0 : l;
}

/// Latitude and longitude of the world point (east_m, north_m) (see the file comment); the longitude in (-180, 180].
[[nodiscard]] inline geodetic_position to_geodetic(const geodetic_origin& o, double east_m, double north_m) {
    sss::require_in_range(o.latitude_deg, -89.0, 89.0, "geodetic_origin.latitude_deg");
    sss::require_in_range(o.longitude_deg, -180.0, 180.0, "geodetic_origin.longitude_deg");
    sss::require_finite(east_m, "east_m");
    sss::require_finite(north_m, "north_m");
    double m_lat = 0, m_lon = 0;
    sss::detail::geodetic_metres_per_radian(o.latitude_deg * pi_v<double> / 180.0, m_lat, m_lon);
    const double latitude = o.latitude_deg + north_m / m_lat * 180.0 / pi_v<double>;
    sss::require(std::abs(latitude) <= 90.0, "north_m", [&] {
        return "lies beyond the pole from the origin: latitude " + std::to_string(latitude) + " deg (the local plane "
               "serves a few kilometres about it)";
    });
    return {latitude, normalised_longitude_deg(o.longitude_deg + east_m / m_lon * 180.0 / pi_v<double>)};
}

/// The inverse: world (east_m, north_m) of a geodetic position, written into `east_m`, `north_m`; the difference of
/// longitudes is taken the short way round (across the antimeridian where that is shorter).
inline void from_geodetic(const geodetic_origin& o, const geodetic_position& p, double& east_m, double& north_m) {
    sss::require_in_range(o.latitude_deg, -89.0, 89.0, "geodetic_origin.latitude_deg");
    sss::require_in_range(o.longitude_deg, -180.0, 180.0, "geodetic_origin.longitude_deg");
    sss::require_finite(p.latitude_deg, "geodetic_position.latitude_deg");
    sss::require_finite(p.longitude_deg, "geodetic_position.longitude_deg");
    double m_lat = 0, m_lon = 0;
    sss::detail::geodetic_metres_per_radian(o.latitude_deg * pi_v<double> / 180.0, m_lat, m_lon);
    north_m = (p.latitude_deg - o.latitude_deg) * pi_v<double> / 180.0 * m_lat;
    east_m = std::remainder(p.longitude_deg - o.longitude_deg, 360.0) * pi_v<double> / 180.0 * m_lon;
}

} // namespace sss::io

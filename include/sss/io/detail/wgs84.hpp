#pragma once
/// \file
/// Internal to io/geodetic.hpp: the WGS 84 ellipsoid and its metres per radian of latitude and longitude.
/// Not part of the API.

#include <cmath>

namespace sss::detail {
inline constexpr double wgs84_a_m = 6378137.0;
inline constexpr double wgs84_f = 1.0 / 298.257223563;
/// Metres per radian of latitude (M) and of longitude (N cos lat) at latitude lat (rad).
inline void geodetic_metres_per_radian(double lat_rad, double& m_lat, double& m_lon) noexcept {
    const double e2 = wgs84_f * (2.0 - wgs84_f);
    const double s = std::sin(lat_rad), w = 1.0 - e2 * s * s;
    m_lat = wgs84_a_m * (1.0 - e2) / (w * std::sqrt(w));
    m_lon = wgs84_a_m / std::sqrt(w) * std::cos(lat_rad);
}
} // namespace sss::detail

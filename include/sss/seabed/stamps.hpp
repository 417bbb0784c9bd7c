#pragma once
/// \file
/// Features pressed into a height raster: plate, trench, mound and scour pit.
///
/// Each feature is a plain struct placed in raster-local metres (sample (ix, iy) at x = ix cell_m,
/// y = iy cell_m; see raster.hpp) and turned to `heading_deg` (clockwise from north, docs/conventions.md). In
/// its own frame, u runs along the heading and v across it (to the left of the heading). `stamp(h, feature)` modifies the heights;
/// `stamp(h, regions, feature, id)` also writes `id` into the region raster wherever the feature covers at
/// least half of a cell (its footprint, defined per feature below).
///
/// - plate: a flat rectangular slab (length_m along u, width_m along v) whose top lies top_m above the
///   mean of the seabed under it (top_m < 0: sunk into it). Its edges are vertical: a sample whose cell is
///   partly covered (4 x 4 sub-samples) takes the covered fraction of the plate height and the rest of
///   its own, so edges do not alias. Footprint: the rectangle.
/// - trench: a straight channel from (x0_m, y0_m) to (x1_m, y1_m) with rounded ends, top width width_m,
///   floor width floor_width_m (< width_m) and depth depth_m. At distance d from the centre segment the
///   seabed is lowered by depth_m c(d): c = 1 on the floor (|d| <= floor/2), c = (1 + cos(pi t)) / 2 with
///   t = (|d| - floor/2) / ((width - floor)/2) on the sides, 0 beyond width/2. Cross-section area
///   depth_m (width_m + floor_width_m) / 2. Optional spoil berms of height berm_height_m and width
///   berm_width_m run along both sides: + berm_height_m sin^2(pi (|d| - width/2) / berm_width_m) for
///   width/2 < |d| < width/2 + berm_width. Footprint: |d| < width/2.
/// - mound: an elliptical bump of semi-axes radius_u_m, radius_v_m and height height_m:
///   + height_m cos^2(pi r / 2) for r = sqrt((u/radius_u)^2 + (v/radius_v)^2) < 1 (smooth at its edge).
///   Volume pi a b height (1/2 - 2/pi^2). Footprint: r < 1.
/// - scour: an elliptical pit of semi-axes radius_u_m, radius_v_m and depth depth_m with a raised rim:
///   - depth_m (1 - r^2)^2 for r < 1 (flat-bottomed, slope continuous at r = 1; volume pi a b depth / 3),
///   + rim_height_m sin^2(pi (r - 1) / w) for 1 < r < 1 + w, w = rim_width_m / sqrt(radius_u radius_v)
///   (the rim width in metres at the mean radius). Footprint: r < 1.
///
/// Parameters are validated (finite; lengths > 0, floor < width, heights >= 0 where stated) and errors
/// name the field. Features may extend beyond the raster: only the samples inside are changed.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/seabed/detail/stamp_footprint.hpp"
#include "sss/seabed/raster.hpp"

namespace sss::seabed {

/// A flat rectangular plate (see the file comment).
template <Real T> struct plate {
    T center_x_m = T(0), center_y_m = T(0); ///< centre of the rectangle (m, raster-local)
    T length_m = T(1);                      ///< side along the heading (m), > 0
    T width_m = T(1);                       ///< side across the heading (m), > 0
    T heading_deg = T(90);                  ///< direction of the length, clockwise from north (deg); 90: east
    T top_m = T(0.1);                       ///< top above the mean seabed under the plate (m); any sign
};

/// A straight trench with rounded ends and optional spoil berms (see the file comment).
template <Real T> struct trench {
    T x0_m = T(0), y0_m = T(0); ///< one end of the centre line (m)
    T x1_m = T(1), y1_m = T(0); ///< other end (m); may equal the first (a round pit)
    T width_m = T(1);           ///< top width (m), > 0
    T floor_width_m = T(0);     ///< width of the flat floor (m), in [0, width_m)
    T depth_m = T(0.2);         ///< depth below the surrounding seabed (m), >= 0
    T berm_height_m = T(0);     ///< height of the spoil berm on each side (m), >= 0
    T berm_width_m = T(0);      ///< width of each berm (m), > 0 when berm_height_m > 0
};

/// An elliptical mound with a cos^2 profile (see the file comment).
template <Real T> struct mound {
    T center_x_m = T(0), center_y_m = T(0); ///< centre (m)
    T radius_u_m = T(1);                    ///< semi-axis along the heading (m), > 0
    T radius_v_m = T(1);                    ///< semi-axis across the heading (m), > 0
    T heading_deg = T(90);                  ///< direction of the u axis, clockwise from north (deg); 90: east
    T height_m = T(0.3);                    ///< height at the centre (m), >= 0
};

/// An elliptical scour pit with a raised rim (see the file comment).
template <Real T> struct scour {
    T center_x_m = T(0), center_y_m = T(0); ///< centre (m)
    T radius_u_m = T(1);                    ///< semi-axis of the pit along the heading (m), > 0
    T radius_v_m = T(1);                    ///< semi-axis across the heading (m), > 0
    T heading_deg = T(90);                  ///< direction of the u axis, clockwise from north (deg); 90: east
    T depth_m = T(0.3);                     ///< depth at the centre (m), >= 0
    T rim_height_m = T(0);                  ///< rim height (m), >= 0
    T rim_width_m = T(0);                   ///< rim width at the mean radius (m), > 0 when rim_height_m > 0
};

/// The placement of a stamp centred on a point: centre and heading finite.
template <class Stamp> void validate_placement(const Stamp& s, const std::string& who) {
    sss::require_finite(s.center_x_m, who + ".center_x_m");
    sss::require_finite(s.center_y_m, who + ".center_y_m");
    sss::require_finite(s.heading_deg, who + ".heading_deg");
}

template <Real T> void validate(const plate<T>& s, const std::string& who) {
    validate_placement(s, who);
    sss::require_positive(s.length_m, who + ".length_m");
    sss::require_positive(s.width_m, who + ".width_m");
    sss::require_finite(s.top_m, who + ".top_m");
}

template <Real T> void validate(const trench<T>& s, const std::string& who) {
    sss::require_finite(s.x0_m, who + ".x0_m");
    sss::require_finite(s.y0_m, who + ".y0_m");
    sss::require_finite(s.x1_m, who + ".x1_m");
    sss::require_finite(s.y1_m, who + ".y1_m");
    sss::require_positive(s.width_m, who + ".width_m");
    sss::require_non_negative(s.floor_width_m, who + ".floor_width_m");
    sss::require(s.floor_width_m < s.width_m, who + ".floor_width_m", "must be < width_m");
    sss::require_non_negative(s.depth_m, who + ".depth_m");
    sss::require_non_negative(s.berm_height_m, who + ".berm_height_m");
    sss::require_non_negative(s.berm_width_m, who + ".berm_width_m");
    sss::require_positive_when(s.berm_height_m != T(0), s.berm_width_m, who + ".berm_width_m", "berm_height_m > 0");
}

template <Real T> void validate(const mound<T>& s, const std::string& who) {
    validate_placement(s, who);
    sss::require_positive(s.radius_u_m, who + ".radius_u_m");
    sss::require_positive(s.radius_v_m, who + ".radius_v_m");
    sss::require_non_negative(s.height_m, who + ".height_m");
}

template <Real T> void validate(const scour<T>& s, const std::string& who) {
    validate_placement(s, who);
    sss::require_positive(s.radius_u_m, who + ".radius_u_m");
    sss::require_positive(s.radius_v_m, who + ".radius_v_m");
    sss::require_non_negative(s.depth_m, who + ".depth_m");
    sss::require_non_negative(s.rim_height_m, who + ".rim_height_m");
    sss::require_non_negative(s.rim_width_m, who + ".rim_width_m");
    sss::require_positive_when(s.rim_height_m != T(0), s.rim_width_m, who + ".rim_width_m", "rim_height_m > 0");
}

/// Lays a plate on the seabed: covered samples take the plate's top, mean seabed under it + top_m.
template <Real T> void stamp(raster<T>& h, const plate<T>& s) {
    detail::require_raster(h, "stamp.h");
    validate(s, "stamp.plate");
    const double theta = heading_to_ccw_from_east_rad(static_cast<double>(s.heading_deg));
    const double c = std::cos(theta), sn = std::sin(theta);
    const double hl = 0.5 * static_cast<double>(s.length_m), hw = 0.5 * static_cast<double>(s.width_m);
    const double cx = static_cast<double>(s.center_x_m), cy = static_cast<double>(s.center_y_m);
    const double reach_x = hl * std::abs(c) + hw * std::abs(sn) + static_cast<double>(h.cell_m);
    const double reach_y = hl * std::abs(sn) + hw * std::abs(c) + static_cast<double>(h.cell_m);
    const double cell = static_cast<double>(h.cell_m);
    const auto inside = [&](double x, double y) {
        const double u = (x - cx) * c + (y - cy) * sn, v = -(x - cx) * sn + (y - cy) * c;
        return std::abs(u) <= hl && std::abs(v) <= hw;
    };
    double sum = 0.0, weight = 0.0;
    detail::for_samples_near(h.nx, h.ny, cell, cx, cy, reach_x, reach_y,
                           [&](std::size_t ix, std::size_t iy, double x, double y) {
                               const double f = detail::coverage(x, y, cell, inside);
                               sum += f * static_cast<double>(h(ix, iy));
                               weight += f;
                           });
    if (weight == 0.0) return; // entirely off the raster
    const double top = sum / weight + static_cast<double>(s.top_m);
    detail::for_samples_near(h.nx, h.ny, cell, cx, cy, reach_x, reach_y,
                           [&](std::size_t ix, std::size_t iy, double x, double y) {
                               const double f = detail::coverage(x, y, cell, inside);
                               if (f > 0.0)
                                   h(ix, iy) = static_cast<T>(f * top + (1.0 - f) * static_cast<double>(h(ix, iy)));
                           });
}

/// The height change of a trench at distance d (m) from its centre segment.
template <Real T> [[nodiscard]] inline double trench_offset_m(const trench<T>& s, double d) noexcept {
    const double w = static_cast<double>(s.width_m), fl = static_cast<double>(s.floor_width_m);
    const double ad = std::abs(d);
    if (ad <= 0.5 * fl) return -static_cast<double>(s.depth_m);
    if (ad < 0.5 * w) {
        const double t = (ad - 0.5 * fl) / (0.5 * (w - fl));
        return -static_cast<double>(s.depth_m) * 0.5 * (1.0 + std::cos(pi_v<double> * t));
    }
    const double bw = static_cast<double>(s.berm_width_m);
    if (s.berm_height_m > T(0) && ad < 0.5 * w + bw) {
        const double sb = std::sin(pi_v<double> * (ad - 0.5 * w) / bw);
        return static_cast<double>(s.berm_height_m) * sb * sb;
    }
    return 0.0;
}

/// Cuts a trench into the seabed (adds trench_offset_m).
template <Real T> void stamp(raster<T>& h, const trench<T>& s) {
    detail::require_raster(h, "stamp.h");
    validate(s, "stamp.trench");
    const double x0 = static_cast<double>(s.x0_m), y0 = static_cast<double>(s.y0_m);
    const double x1 = static_cast<double>(s.x1_m), y1 = static_cast<double>(s.y1_m);
    const double reach = 0.5 * static_cast<double>(s.width_m) + static_cast<double>(s.berm_width_m);
    const double cx = 0.5 * (x0 + x1), cy = 0.5 * (y0 + y1);
    detail::for_samples_near(h.nx, h.ny, static_cast<double>(h.cell_m), cx, cy, 0.5 * std::abs(x1 - x0) + reach,
                           0.5 * std::abs(y1 - y0) + reach, [&](std::size_t ix, std::size_t iy, double x, double y) {
                               const double d = detail::segment_distance(x, y, x0, y0, x1, y1);
                               h(ix, iy) = static_cast<T>(static_cast<double>(h(ix, iy)) + trench_offset_m(s, d));
                           });
}

/// The height change of a mound at normalised elliptical radius r.
template <Real T> [[nodiscard]] inline double mound_offset_m(const mound<T>& s, double r) noexcept {
    if (r >= 1.0) return 0.0;
    const double c = std::cos(0.5 * pi_v<double> * r);
    return static_cast<double>(s.height_m) * c * c;
}

/// Raises a mound on the seabed (adds mound_offset_m).
template <Real T> void stamp(raster<T>& h, const mound<T>& s) {
    detail::require_raster(h, "stamp.h");
    validate(s, "stamp.mound");
    const detail::ellipse_frame e = detail::frame_of(s);
    const double reach = std::max(e.a, e.b);
    detail::for_samples_near(h.nx, h.ny, static_cast<double>(h.cell_m), e.cx, e.cy, reach, reach,
                           [&](std::size_t ix, std::size_t iy, double x, double y) {
                               h(ix, iy) =
                                   static_cast<T>(static_cast<double>(h(ix, iy)) + mound_offset_m(s, e.r(x, y)));
                           });
}

/// Normalised rim width w of a scour (see the file comment).
template <Real T> [[nodiscard]] inline double scour_rim_width(const scour<T>& s) noexcept {
    return static_cast<double>(s.rim_width_m) /
           std::sqrt(static_cast<double>(s.radius_u_m) * static_cast<double>(s.radius_v_m));
}

/// The height change of a scour pit at normalised elliptical radius r.
template <Real T> [[nodiscard]] inline double scour_offset_m(const scour<T>& s, double r) noexcept {
    if (r < 1.0) {
        const double q = 1.0 - r * r;
        return -static_cast<double>(s.depth_m) * q * q;
    }
    const double w = scour_rim_width(s);
    if (s.rim_height_m > T(0) && r < 1.0 + w) {
        const double sr = std::sin(pi_v<double> * (r - 1.0) / w);
        return static_cast<double>(s.rim_height_m) * sr * sr;
    }
    return 0.0;
}

/// Digs a scour pit with its rim (adds scour_offset_m).
template <Real T> void stamp(raster<T>& h, const scour<T>& s) {
    detail::require_raster(h, "stamp.h");
    validate(s, "stamp.scour");
    const detail::ellipse_frame e = detail::frame_of(s);
    const double reach = std::max(e.a, e.b) * (1.0 + (s.rim_height_m > T(0) ? scour_rim_width(s) : 0.0));
    detail::for_samples_near(h.nx, h.ny, static_cast<double>(h.cell_m), e.cx, e.cy, reach, reach,
                           [&](std::size_t ix, std::size_t iy, double x, double y) {
                               h(ix, iy) =
                                   static_cast<T>(static_cast<double>(h(ix, iy)) + scour_offset_m(s, e.r(x, y)));
                           });
}

/// Lays a plate and writes `id` into `regions` over its footprint.
template <Real T> void stamp(raster<T>& h, region_raster<T>& regions, const plate<T>& s, std::uint32_t id) {
    detail::require_same_grid(h, regions);
    stamp(h, s);
    const double theta = heading_to_ccw_from_east_rad(static_cast<double>(s.heading_deg));
    const double c = std::cos(theta), sn = std::sin(theta);
    const double hl = 0.5 * static_cast<double>(s.length_m), hw = 0.5 * static_cast<double>(s.width_m);
    const double cx = static_cast<double>(s.center_x_m), cy = static_cast<double>(s.center_y_m);
    detail::label(regions, cx, cy, hl + hw, hl + hw, id, [&](double x, double y) {
        const double u = (x - cx) * c + (y - cy) * sn, v = -(x - cx) * sn + (y - cy) * c;
        return std::abs(u) <= hl && std::abs(v) <= hw;
    });
}

/// Cuts a trench and writes `id` into `regions` over its footprint.
template <Real T> void stamp(raster<T>& h, region_raster<T>& regions, const trench<T>& s, std::uint32_t id) {
    detail::require_same_grid(h, regions);
    stamp(h, s);
    const double x0 = static_cast<double>(s.x0_m), y0 = static_cast<double>(s.y0_m);
    const double x1 = static_cast<double>(s.x1_m), y1 = static_cast<double>(s.y1_m);
    const double half = 0.5 * static_cast<double>(s.width_m);
    detail::label(regions, 0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * std::abs(x1 - x0) + half,
                0.5 * std::abs(y1 - y0) + half, id,
                [&](double x, double y) { return detail::segment_distance(x, y, x0, y0, x1, y1) < half; });
}

/// Raises a mound and writes `id` into `regions` over its footprint.
template <Real T> void stamp(raster<T>& h, region_raster<T>& regions, const mound<T>& s, std::uint32_t id) {
    detail::require_same_grid(h, regions);
    stamp(h, s);
    const detail::ellipse_frame e = detail::frame_of(s);
    const double reach = std::max(e.a, e.b);
    detail::label(regions, e.cx, e.cy, reach, reach, id, [&](double x, double y) { return e.r(x, y) < 1.0; });
}

/// Digs a scour pit and writes `id` into `regions` over the pit (the rim is not labelled).
template <Real T> void stamp(raster<T>& h, region_raster<T>& regions, const scour<T>& s, std::uint32_t id) {
    detail::require_same_grid(h, regions);
    stamp(h, s);
    const detail::ellipse_frame e = detail::frame_of(s);
    const double reach = std::max(e.a, e.b);
    detail::label(regions, e.cx, e.cy, reach, reach, id, [&](double x, double y) { return e.r(x, y) < 1.0; });
}

} // namespace sss::seabed

#pragma once
/// \file
/// Where a small target lies among one side's launch angles: for each sphere and cylinder of a scene's objects, the
/// along-track and depression launch angles (body frame, rad) of the rays that can meet it.
///
/// The along-track check (simulator.hpp) compares neighbouring columns' located edges; a target whose along-track
/// extent lies between two columns' launch cones is met by neither, so they agree and it vanishes from the line
/// (a sphere 0.16 m across between cones 0.42 m apart). Its span tells the simulator which columns lie over it and
/// which of their launch intervals to divide along track, whatever the columns agree on.
///
/// Each primitive is a set of points with a radius r: a sphere's centre; a cylinder's two cap centres and the points
/// of its axis closest to the towfish and, horizontally, closest to it (where the along-track angle and the depression
/// of a point on the axis are largest; between those points they change monotonically, short of the far side of a
/// cylinder passing under the towfish). For each point at horizontal distance rho and height z (world), the launch
/// depressions of the rays through the corners (rho +- r, z +- r) of its square in the vertical plane of its heading
/// are found on the ray's world depression, the ray followed by the propagation itself to that range (its
/// height_at_range_m, RangeHeightPropagation; else a trace to a vertical wall there). A ray refracted in layered water
/// stays in the vertical plane of its launch, and its height at a range falls monotonically with its launch
/// depression while it does not turn: the rays that meet the primitive near that point pass between the highest and
/// lowest of them. Those world directions are taken to the body frame (along = asin b.x, depression =
/// atan2(b.z, s b.y), beam_direction inverted); the along-track span is widened by the point's angular radius
/// asin(r / distance) either way, and both spans by a tenth of their width (a column's rays at a slightly different
/// along-track angle lie within that). The depression through a corner is found by Newton's method from the straight
/// ray's (two or three steps: refraction bends a ray little), by bisection where that fails; two corners per point
/// where the square lies wholly below or above the towfish. A point whose corners cannot all be found (under the
/// towfish, on the other side, or where the rays turn before it) adds nothing. Only the primitives within the line's
/// range and the beam's along-track extent are followed. A cylinder wider than three columns along track is cut into
/// pieces (target_spans), each its own span where it is thin.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include <glm/matrix.hpp>

#include "sss/beam/concept.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/pose.hpp"
#include "sss/core/ray.hpp"
#include "sss/core/types.hpp"
#include "sss/propagation/concept.hpp"
#include "sss/scene/object_set.hpp"

namespace sss {

/// A target's launch angles on one side (body frame, rad): the rays that can meet it leave within
/// [along_lo, along_hi] x [depression_lo, depression_hi].
struct target_span {
    double along_lo = 0, along_hi = 0;
    double depression_lo = 0, depression_hi = 0;
    /// Its least angular width across its axis (a sphere's, a cylinder's far end's); for a piece of a long cylinder, its
    /// width along track at one depression (rad). How finely the columns over it divide.
    double thickness_rad = 0;
    /// Its width in depression at one along-track angle (rad): a sphere's angular diameter, a cylinder's (or a
    /// piece's) angular thickness * hypot(d_along, d_depression) / |d_along| (d the change between its ends' centres);
    /// +infinity for a cylinder whose ends' centres share their along-track angle (a vertical pole, a cable across the
    /// track), which one column's rays meet all along it or not at all, or whose ends' launch angles are not found.
    double depression_thickness_rad = std::numeric_limits<double>::infinity();
    /// The widest launch interval over it within a column (rad): half a sphere's depression_thickness_rad, an eighth of
    /// a cylinder's (a cylinder's echo across its width, from glint to grazing, wants eight rays there: at half, a
    /// cable nearly along the track came out 6 dB low at its glint; spheres at an eighth cost a dense boulder field 1.8
    /// times the time instead of 1.5); +infinity with depression_thickness_rad.
    double depression_step_rad = std::numeric_limits<double>::infinity();
    /// Whether the columns over it divide along track; false for a piece of a cylinder wider along track at one
    /// depression than a column, whose launch intervals alone are halved (depression_thickness_rad).
    bool along = true;
};

namespace detail {

/// A vertical wall facing the origin's horizontal position at horizontal distance range_m along unit heading
/// (hx, hy): the Scene through which target_spans asks a propagation that is not a RangeHeightPropagation where a
/// ray is at that range.
template <Real T> struct range_wall {
    using value_type = T;
    vec3<T> origin{};
    T hx{}, hy{}, range_m{};

    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const {
        const T along = r.direction.x * hx + r.direction.y * hy;
        if (!(along > T(0))) return std::nullopt;
        const T here = (r.origin.x - origin.x) * hx + (r.origin.y - origin.y) * hy;
        const T t = (range_m - here) / along;
        if (!(t >= T(0) && t <= t_max_m)) return std::nullopt;
        hit<T> h;
        h.distance_m = t;
        h.point = r.origin + t * r.direction;
        h.normal = h.shading_normal = vec3<T>{-hx, -hy, T(0)};
        return h;
    }
    [[nodiscard]] T seabed_height_m(T, T) const noexcept { return origin.z - T(1e6); }
    [[nodiscard]] T top_m() const noexcept { return origin.z + T(1e6); }
};

} // namespace detail

/// The spans of the spheres and cylinders of `objects` on side `sd` of the ping at pose `p` that lie within the
/// along-track extent `ext` and within range_m (the line's range) of the towfish, appended to `out`; column_rad is the
/// along-track width of one column (rad). A primitive whose span is at most three columns wide gives one span. A wider
/// cylinder (a cable or a pipeline oblique to the columns, or one crossing the beam with its ends either side of it) is
/// cut along its axis, over the part within the line's range, into pieces whose ends and middle lie within half a
/// column of each other along track (seen along straight lines; 4096 at most);
/// each piece gives a span, its thickness_rad its width along track at one depression (the band a piece draws over the
/// launch angles is thickness * hypot(d_along, d_depression) / |d_depression| wide along track, d the change between
/// its ends' centres); a piece wider than a column there is marked `along = false` (its columns meet it; only their
/// launch intervals over it are halved). Wider spheres cross columns whose own comparison sees their edges. Rays are followed for one-way time t_max_s.
template <class P, Real T>
void target_spans(const P& propagation, const scene::object_set<T>& objects, const pose<T>& p, side sd,
                  const beam_extent<T>& ext, double column_rad, T t_max_s, double range_m,
                  std::vector<target_span>& out) {
    const double s = double(side_sign<T>(sd));
    const mat3<T> to_body = glm::transpose(p.body_to_world);
    const double x0 = double(p.position.x), y0 = double(p.position.y), z0 = double(p.position.z);
    const double max_along_rad = 3.0 * column_rad;
    const double a_lo = double(ext.along_min_rad) - max_along_rad, a_hi = double(ext.along_max_rad) + max_along_rad;
    // The world depression (down positive) of the ray in the vertical plane of heading (hx, hy) that passes height z
    // at horizontal distance rho; nullopt where no ray in the search interval does.
    constexpr double steepest = 1.565; // rad: 89.7 deg, the steepest ray asked
    const auto depression_through = [&](double hx, double hy, double rho, double z) -> std::optional<double> {
        const double geometric = std::atan2(z0 - z, rho);
        // Height at range rho of the ray at depression e, or +-infinity where it never gets there (it turned).
        const auto height = [&](double e) {
            const ray<T> r{p.position, vec3<T>{static_cast<T>(std::cos(e) * hx), static_cast<T>(std::cos(e) * hy),
                                               static_cast<T>(-std::sin(e))}};
            std::optional<T> z_m;
            if constexpr (RangeHeightPropagation<P>) {
                z_m = propagation.height_at_range_m(r, static_cast<T>(rho), t_max_s);
            } else {
                const detail::range_wall<T> wall{p.position, static_cast<T>(hx), static_cast<T>(hy), static_cast<T>(rho)};
                if (const auto path = propagation.trace(r, wall, t_max_s)) z_m = path->surface.point.z;
            }
            if (z_m) return double(*z_m);
            return e > geometric ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
        };
        // Newton's method from the straight ray, with the straight ray's slope dz/de = -rho / cos^2 e: refraction
        // bends the ray a little, so that slope is close and a few steps reach a micrometre; bisection otherwise.
        const double tol_m = 1e-6 * (rho + 1.0) + 64.0 * double(std::numeric_limits<T>::epsilon()) * (std::abs(z) + rho);
        double e = geometric;
        for (int i = 0; i < 6; ++i) {
            const double hz = height(e);
            if (!std::isfinite(hz)) break;
            if (std::abs(hz - z) <= tol_m) return e;
            const double c = std::cos(e);
            e = std::clamp(e + (hz - z) * c * c / rho, -steepest, steepest);
        }
        double lo = std::max(geometric - 0.35, -steepest), hi = std::min(geometric + 0.35, steepest);
        if (!(height(lo) >= z && height(hi) <= z)) return std::nullopt;
        for (int i = 0; i < 24; ++i) {
            const double mid = 0.5 * (lo + hi);
            (height(mid) >= z ? lo : hi) = mid;
        }
        return 0.5 * (lo + hi);
    };
    // The launch angles (body frame: along track, depression) of the ray in the vertical plane of heading (hx, hy) that
    // passes height z at horizontal distance rho; nullopt where none does, or where it leaves on the other side.
    const auto launch_angles = [&](double hx, double hy, double rho, double z) -> std::optional<std::pair<double, double>> {
        const auto e = depression_through(hx, hy, rho, z);
        if (!e) return std::nullopt;
        const vec3<T> w{static_cast<T>(std::cos(*e) * hx), static_cast<T>(std::cos(*e) * hy), static_cast<T>(-std::sin(*e))};
        const vec3<T> b = to_body * w;
        if (!(s * double(b.y) > 0.0)) return std::nullopt;
        return std::pair{std::asin(std::clamp(double(b.x), -1.0, 1.0)), std::atan2(double(b.z), s * double(b.y))};
    };
    // The span of the points of one primitive with radius r, widened; nullopt where no point is found.
    const auto span_of = [&](const vec3<T>* points, std::size_t n, double r) -> std::optional<target_span> {
        target_span span{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                         std::numeric_limits<double>::infinity(), true};
        // A point whose corners cannot all be found (below the towfish, on the other side, beyond the rays' reach)
        // adds nothing: the span is the other points'.
        for (std::size_t i = 0; i < n; ++i) {
            const double dx = double(points[i].x) - x0, dy = double(points[i].y) - y0, z = double(points[i].z);
            const double rho = std::hypot(dx, dy);
            if (!(rho > 2.0 * r)) continue; // under the towfish
            const double hx = dx / rho, hy = dy / rho;
            const double half = std::asin(std::min(1.0, r / std::hypot(rho, z - z0))); // its angular radius
            // The corners that bound the rays through the square: below the towfish the flattest passes its far top
            // corner and the steepest its near bottom one; above it, the near top and far bottom; else all four.
            double corners[4][2];
            std::size_t n_corners = 0;
            const auto corner = [&](double dr, double dz) { corners[n_corners][0] = dr, corners[n_corners++][1] = dz; };
            if (z + r < z0) {
                corner(r, r);
                corner(-r, -r);
            } else if (z - r > z0) {
                corner(-r, r);
                corner(r, -r);
            } else {
                corner(r, r);
                corner(-r, -r);
                corner(-r, r);
                corner(r, -r);
            }
            target_span here = span;
            here.thickness_rad = std::min(here.thickness_rad, 2.0 * std::asin(std::min(1.0, r / std::hypot(rho, z - z0))));
            bool found = true;
            for (std::size_t q = 0; q < n_corners && found; ++q) {
                const auto a = launch_angles(hx, hy, rho + corners[q][0], z + corners[q][1]);
                found = bool(a);
                if (!found) break;
                here.along_lo = std::min(here.along_lo, a->first - half);
                here.along_hi = std::max(here.along_hi, a->first + half);
                here.depression_lo = std::min(here.depression_lo, a->second);
                here.depression_hi = std::max(here.depression_hi, a->second);
            }
            if (found) span = here;
        }
        if (!(span.along_lo <= span.along_hi)) return std::nullopt; // no point found
        const double wa = 0.1 * (span.along_hi - span.along_lo), we = 0.1 * (span.depression_hi - span.depression_lo);
        span.along_lo -= wa;
        span.along_hi += wa;
        span.depression_lo -= we;
        span.depression_hi += we;
        return span;
    };
    const auto within_beam = [&](const target_span& span) {
        return !(span.along_hi < double(ext.along_min_rad) || span.along_lo > double(ext.along_max_rad));
    };
    // Quick rejection before any trace: a point whose straight-line along-track angle lies well outside the
    // extent, or which lies beyond the line's range (the twentieth covers sound speeds up to 5 % above the one
    // that converts the line's time to range).
    const auto ahead = [&](const vec3<T>& c, double r) {
        const vec3<T> d = c - p.position;
        const double len = double(glm::length(d));
        if (!(len > r) || len - r > 1.05 * range_m) return false;
        const vec3<T> b = to_body * (d / static_cast<T>(len));
        if (!(s * double(b.y) > -r / len)) return false;
        const double along = std::asin(std::clamp(double(b.x), -1.0, 1.0)), half = std::asin(std::min(1.0, r / len));
        return along + half >= a_lo && along - half <= a_hi;
    };
    // Whether a cylinder's axis from a to b, none of whose points passes `ahead`, may still cross the sector: its ends'
    // along-track angles span part of it, and its point closest to the towfish (closest) lies within the line's range.
    const auto across_sector = [&](const vec3<T>& a, const vec3<T>& b, const vec3<T>& closest, double r) {
        if (!(double(glm::length(closest - p.position)) - r <= 1.05 * range_m)) return false;
        const auto along = [&](const vec3<T>& q) {
            const vec3<T> d = q - p.position;
            const T len = glm::length(d);
            return len > T(0) ? std::asin(std::clamp(double((to_body * (d / len)).x), -1.0, 1.0)) : 0.0;
        };
        const double la = along(a), lb = along(b);
        return std::min(la, lb) <= a_hi && std::max(la, lb) >= a_lo;
    };
    // A cylinder's points: its ends, and where its axis passes closest to the towfish and, horizontally, closest below
    // or above it (the along-track angle is largest where the distance is least, the depression where the horizontal
    // distance is).
    const auto axis_points = [&](const vec3<T>& a, const vec3<T>& b, vec3<T> (&points)[4]) {
        const vec3<T> d = b - a;
        const auto closest = [&](const vec3<T>& u, const vec3<T>& v) {
            const T vv = glm::dot(v, v);
            const T f = vv > T(0) ? std::clamp(glm::dot(u, v) / vv, T(0), T(1)) : T(0);
            return a + f * d;
        };
        const vec3<T> to = p.position - a;
        points[0] = a;
        points[1] = b;
        points[2] = closest(to, d);
        points[3] = closest(vec3<T>{to.x, to.y, T(0)}, vec3<T>{d.x, d.y, T(0)});
    };
    for (const scene::object<T>& o : objects.objects()) {
        for (const scene::sphere<T>& sp : o.spheres()) {
            if (!ahead(sp.center_m(), double(sp.radius_m()))) continue;
            auto span = span_of(&sp.center_m(), 1, double(sp.radius_m()));
            if (!span || span->along_hi - span->along_lo > max_along_rad || !within_beam(*span)) continue;
            span->depression_thickness_rad = span->thickness_rad;
            span->depression_step_rad = 0.5 * span->depression_thickness_rad;
            out.push_back(*span);
        }
        for (const scene::cylinder<T>& c : o.cylinders()) {
            const double r = double(c.radius_m());
            // The part of its axis within reach of the towfish (1.05 range_m + r / 2) and on this side of it (at least 4 r
            // out, in the towfish's frame, so that its near end is not taken for one under the towfish): a cable
            // passing under the towfish, or far beyond the line's range, is followed where the side's rays can meet it.
            const vec3<T> a = c.end0_m(), d = c.end1_m() - c.end0_m();
            double f0 = 0.0, f1 = 1.0;
            {
                const vec3<T> w = a - p.position;
                const double dd = double(glm::dot(d, d)), wd = double(glm::dot(w, d));
                const double reach = 1.05 * range_m + 0.5 * r, disc = wd * wd - dd * (double(glm::dot(w, w)) - reach * reach);
                if (dd > 0.0) {
                    if (!(disc > 0.0)) continue;
                    const double root = std::sqrt(disc);
                    f0 = std::max(f0, (-wd - root) / dd);
                    f1 = std::min(f1, (-wd + root) / dd);
                }
                // s y(f) >= 4 r, y(f) = ya + f yd the body-frame y of a + f d.
                const double ya = s * double((to_body * w).y), yd = s * double((to_body * d).y);
                if (yd > 0.0) f0 = std::max(f0, (4.0 * r - ya) / yd);
                else if (yd < 0.0) f1 = std::min(f1, (4.0 * r - ya) / yd);
                else if (!(ya >= 4.0 * r)) continue;
                if (!(f0 <= f1)) continue;
            }
            const auto at = [&](double f) { return f == 1.0 ? c.end1_m() : a + static_cast<T>(f) * d; };
            const vec3<T> end0 = at(f0), end1 = at(f1);
            vec3<T> points[4];
            axis_points(end0, end1, points);
            if (!(ahead(points[0], r) || ahead(points[1], r) || ahead(points[2], r) || ahead(points[3], r) ||
                  across_sector(points[0], points[1], points[2], r)))
                continue;
            // The launch angles of the centre of an end of (a piece of) its axis, and the band the piece draws over
            // the launch angles: its change in along-track angle and in depression from end to end.
            const auto centre = [&](const vec3<T>& q) -> std::optional<std::pair<double, double>> {
                const double dx = double(q.x) - x0, dy = double(q.y) - y0, rho = std::hypot(dx, dy);
                if (!(rho > 2.0 * r)) return std::nullopt;
                return launch_angles(dx / rho, dy / rho, rho, double(q.z));
            };
            const auto band = [&](const vec3<T>& qa, const vec3<T>& qb) -> std::optional<std::pair<double, double>> {
                const auto ea = centre(qa), eb = centre(qb);
                if (!ea || !eb) return std::nullopt;
                return std::pair{std::abs(eb->first - ea->first), std::abs(eb->second - ea->second)};
            };
            auto whole = span_of(points, 4, r);
            if (whole && whole->along_hi - whole->along_lo <= max_along_rad) {
                if (!within_beam(*whole)) continue;
                if (const auto dn = band(end0, end1); dn && dn->first > 0.0)
                    whole->depression_thickness_rad = whole->thickness_rad * std::hypot(dn->first, dn->second) / dn->first;
                whole->depression_step_rad = 0.125 * whole->depression_thickness_rad;
                out.push_back(*whole);
                continue;
            }
            // Cut along its axis, that part, halving each piece until the straight lines from the towfish to its ends
            // and middle lie within half a column of each other along track (at most max_pieces pieces).
            const auto along_at = [&](double f) {
                const vec3<T> q = at(f) - p.position;
                const T len = glm::length(q);
                return len > T(0) ? std::asin(std::clamp(double((to_body * (q / len)).x), -1.0, 1.0)) : 0.0;
            };
            constexpr std::size_t max_pieces = 4096;
            std::vector<std::pair<double, double>> todo{{f0, f1}};
            std::size_t pieces = 1;
            while (!todo.empty()) {
                const auto [lo, hi] = todo.back();
                todo.pop_back();
                const double mid = 0.5 * (lo + hi);
                const double al = along_at(lo), am = along_at(mid), ah = along_at(hi);
                if (std::max({al, am, ah}) - std::min({al, am, ah}) > 0.5 * column_rad && pieces < max_pieces &&
                    mid > lo && mid < hi) {
                    todo.emplace_back(mid, hi);
                    todo.emplace_back(lo, mid);
                    ++pieces;
                    continue;
                }
                const vec3<T> pa = at(lo), pb = at(hi);
                axis_points(pa, pb, points);
                if (!(ahead(points[0], r) || ahead(points[1], r) || ahead(points[2], r) || ahead(points[3], r))) continue;
                auto piece = span_of(points, 4, r);
                if (!piece || piece->along_hi - piece->along_lo > max_along_rad || !within_beam(*piece)) continue;
                // Its width along track at one depression: columns wider than that may pass either side of it.
                const auto band_of = band(pa, pb);
                if (!band_of) continue;
                const double thick = piece->thickness_rad, slant = std::hypot(band_of->first, band_of->second);
                const double along = std::max(thick, thick * slant / std::max(band_of->second, 1e-300));
                if (band_of->first > 0.0) piece->depression_thickness_rad = thick * slant / band_of->first;
                if (!(along < column_rad)) {
                    // Wider along track than a column (a cable nearly along the track): the columns meet it, but two
                    // rays of one may still step over it.
                    if (!std::isfinite(piece->depression_thickness_rad)) continue;
                    piece->along = false;
                }
                piece->thickness_rad = along;
                piece->depression_step_rad = 0.125 * piece->depression_thickness_rad;
                out.push_back(*piece);
            }
        }
    }
}

} // namespace sss

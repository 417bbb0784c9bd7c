#pragma once
/// \file
/// Where a curved ray arc meets a Scene: the arc is handed to the scene as straight chords, and the chord's
/// hit is moved onto the arc.
///
/// The arc (ray_arc.hpp) lies in the vertical plane of the ray. At arc length s from its start it is offset by
///     x(s)  = l(s) cos(phi0 - h),   dz(s) = l(s) sin(phi0 - h),   h = kappa s / 2,   l(s) = s sin(h)/h
/// (horizontal range and depth increase, m; l is the chord from the start, which runs along the mean
/// inclination), and its inclination is phi(s) = phi0 - kappa s; kappa = cos(phi0) g / c0 (1/m) is its signed
/// curvature. A chord spanning arc length ds of a circle of curvature k = |kappa| has sagitta (the largest
/// distance between arc and chord)
///     e = (1 - cos(k ds / 2)) / k  <=  k ds^2 / 8,
/// so chords with ds <= sqrt(8 tol / k) keep every point of the arc within tol of a chord (chord_arc_length_m).
/// A 0.1 mm tolerance (layered's default) in a thermocline of 2 m/s per m at 1500 m/s (k ~ 1.3e-3 1/m) gives
/// 0.78 m chords; under a 0.017 1/s gradient, 8.4 m. Measured on a 3 deg ray in a 5.9 m/s-per-m thermocline: 33 chords over 45 m, the
/// arc at most 0.94 mm from them (tests/propagation/test_layered.cpp).
///
/// The scene's hit on a chord lies on the facet the chord met, within tol of the arc. The arc meets that facet's
/// plane n . (X - H) = 0 (n the facet normal, H the chord's hit) where f(s) = n . (X(s) - H) vanishes; Newton's
/// method, f'(s) = n . t(s) with t the unit tangent, converges from the chord's estimate in one to three steps
/// (the start is within tol / sin(graze) of the root, and a step e leaves about |kappa| e^2 / (2 |f'|), so it
/// stops once that is below rounding; the arc's offset after that last step follows from the one before by its
/// Taylor series to second order, exact to rounding for such a step). On a planar surface
/// (the flat seabed, a triangle) the refined point lies on the surface to rounding, so hit position and arc
/// length are exact, not merely within tol; what tol still bounds is which facet is found: near an edge, or
/// where the arc grazes a surface the chord passes above or below, the answer may differ by up to tol.
/// A straight arc (kappa = 0) is one chord along the ray itself, and its hit is used as it is.
///
/// Clearing chords in open water. A ray crossing open water near the seabed would be handed to the scene chord
/// by chord, each query paying its own set-up. Where the scene can say how far a thick segment runs in open water
/// (ClearanceScene, scene/concept.hpp), a window of chords ahead is first asked about as one: the chord of the
/// arc over the window, with a vertical band of half-height (k L^2 / 8 + tol) / cos(phi) + rounding (L the window's
/// arc length, phi the steepest inclination on it), which holds the arc (its sagitta is at most k L^2 / 8) and every
/// chord of the walk (within tol of the arc). The chords wholly within the cleared length, counted conservatively
/// from the arc's horizontal progress (at most L max cos(phi)), meet nothing and are skipped. The chords traced are
/// the plain walk's, computed the same way, so hits are the same bit for bit; only the number and kind of scene
/// queries change (docs/design/layered.md gives what that saves, and where it does not pay). Windows steeper than
/// about 75 degrees are not cleared.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>

#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/propagation/ray_arc.hpp"
#include "sss/scene/concept.hpp"

namespace sss::propagation {

/// Where an arc lies in the world. Plain data.
template <Real T> struct arc_frame {
    vec3<T> start{};      ///< world position of the arc's start (m)
    vec3<T> horizontal{}; ///< unit horizontal direction of travel (world, z = 0)
};

/// A point of an arc relative to the arc's start. Plain data.
template <Real T> struct arc_offset {
    T range_m{};     ///< horizontal distance from the start (m)
    T depth_m{};     ///< depth increase from the start (m, positive down)
    T sin_incline{}; ///< sine of the inclination below horizontal there
    T cos_incline{}; ///< its cosine (>= 0)
    T sin_half{};    ///< sine of half the turn since the start, sin(kappa s / 2)
    T cos_half{1};   ///< its cosine (>= 0: an arc in one layer turns by at most pi)
};

/// sin(h)/h and cos(h): by their Taylor series, exact to rounding, when |h| <= 1/8 (to h^4 and h^6 below 1e-3, to
/// h^10 and h^12 above), the usual case on a sonar path; else from the library functions.
template <Real T> inline void sinc_cos(T h, T& sinc_h, T& cos_h) noexcept {
    if (std::abs(h) <= T(1e-3)) { // next terms h^6/5040 and h^8/40320: below 1e-21
        const T q = h * h;
        sinc_h = T(1) + q * (T(-1.0 / 6) + q * T(1.0 / 120));
        cos_h = T(1) + q * (T(-0.5) + q * (T(1.0 / 24) + q * T(-1.0 / 720)));
        return;
    }
    if (std::abs(h) <= T(0.125)) {
        const T q = h * h;
        sinc_h = T(1) + q * (T(-1.0 / 6) + q * (T(1.0 / 120) + q * (T(-1.0 / 5040) + q * (T(1.0 / 362880) +
                                                                                         q * T(-1.0 / 39916800)))));
        cos_h = T(1) + q * (T(-0.5) + q * (T(1.0 / 24) + q * (T(-1.0 / 720) + q * (T(1.0 / 40320) +
                                                                               q * (T(-1.0 / 3628800) + q * T(1.0 / 479001600))))));
        return;
    }
    sinc_h = std::sin(h) / h;
    cos_h = std::cos(h);
}

/// The offset at arc length arc_m (m) of an arc starting at inclination phi0 (given as sin_phi0, cos_phi0) with
/// signed curvature kappa_per_m (1/m): the closed forms of the file comment, with no cancellation as kappa -> 0.
template <Real T>
[[nodiscard]] inline arc_offset<T> offset_along_arc(T sin_phi0, T cos_phi0, T kappa_per_m, T arc_m) noexcept {
    const T h = kappa_per_m * arc_m / T(2);
    T sinc_h, ch;
    sinc_cos(h, sinc_h, ch);
    const T sh = h * sinc_h;
    const T chord = arc_m * sinc_h;
    const T sin_mean = sin_phi0 * ch - cos_phi0 * sh; // sin(phi0 - h)
    const T cos_mean = cos_phi0 * ch + sin_phi0 * sh; // cos(phi0 - h)
    // phi = phi0 - 2h: rotate the mean direction by h once more.
    return {chord * cos_mean, chord * sin_mean, sin_mean * ch - cos_mean * sh, cos_mean * ch + sin_mean * sh, sh, ch};
}

/// The offset at arc length s + step_m from the offset o at s, by the Taylor series of the arc to second order in
/// the step: position error about kappa^2 step^3 / 6 (m), inclination error about (kappa step)^3 / 6 (rad). For steps
/// where those are below rounding (a settled Newton step); offset_along_arc otherwise.
template <Real T> [[nodiscard]] inline arc_offset<T> advance_offset(const arc_offset<T>& o, T kappa_per_m, T step_m) noexcept {
    const T d = kappa_per_m * step_m;  // turn over the step (rad): phi falls by d
    const T c2 = T(1) - T(0.5) * d * d; // cos d to second order
    arc_offset<T> out;
    out.range_m = o.range_m + step_m * (o.cos_incline + T(0.5) * d * o.sin_incline);
    out.depth_m = o.depth_m + step_m * (o.sin_incline - T(0.5) * d * o.cos_incline);
    out.sin_incline = o.sin_incline * c2 - o.cos_incline * d;
    out.cos_incline = o.cos_incline * c2 + o.sin_incline * d;
    // Half the turn since the arc's start grows by d/2.
    const T half = T(0.5) * d, c_half = T(1) - T(0.5) * half * half;
    out.sin_half = o.sin_half * c_half + o.cos_half * half;
    out.cos_half = o.cos_half * c_half - o.sin_half * half;
    return out;
}

/// An arc length (m) a chord may span on a circle of curvature |curvature_per_m| (1/m) with the arc staying within
/// tolerance_m (m) of it: sqrt(8 tol / k), from the sagitta's bound (1 - cos(k ds/2))/k <= k ds^2/8, which is
/// within k tol / 6 (relative) of the longest such length; at most half the circle; +infinity on a straight line.
template <Real T> [[nodiscard]] inline T chord_arc_length_m(T curvature_per_m, T tolerance_m) noexcept {
    const T k = std::abs(curvature_per_m);
    if (k == T(0)) return std::numeric_limits<T>::infinity();
    return std::min(std::sqrt(T(8) * tolerance_m / k), pi_v<T> / k);
}

/// A scene hit on an arc: what the scene reported, moved onto the arc, and where along the arc it lies.
template <Real T> struct arc_hit {
    hit<T> surface{};     ///< point on the arc; distance_m is the arc length from the arc's start (m)
    T arc_m{};            ///< arc length from the arc's start to the hit (m)
    arc_offset<T> at{};   ///< the arc's offset at the hit
};

/// The first hit of the scene along an arc between arc lengths s_begin_m and s_end_m (m), found through chords of
/// sagitta at most tolerance_m (m) and refined onto the arc (file comment), handed to
/// `on_hit(const hit<T>& scene_hit, const vec3<T>& point, T arc_m, const arc_offset<T>& at, T clear_x_m)`: the
/// scene's hit on the chord, the point on the arc it refines to, its arc length from the arc's start, the arc's offset
/// there, and the horizontal distance from the arc's start up to which the chords met nothing (the chord's own hit:
/// the scene reports the nearest, so nothing lies on the chord before it; the walk's earlier chords met nothing).
/// Returns whether there was a hit (on_hit called once) or not (not called). The arc starts at inclination phi0, given
/// as (sin_phi0, cos_phi0), with signed curvature kappa_per_m (1/m); `chords` counts the chords handed to the scene
/// (scene.intersect or scene.intersect_after).
/// With clear_open_water, a ClearanceScene is first asked to clear windows of chords (file comment); the hit is the
/// same. The caller may know that the arc and every chord of it meet nothing within horizontal distance x_clear_m (m)
/// of the arc's start, and so up to arc length s_clear_m (m) (both 0 when it does not): the chords that end at
/// s_clear_m or before are skipped (all of them, with no set-up, when the span ends there), and the rest are the plain
/// walk's, so the hit is the same. Over a ResumableScene a chord traced that starts within x_clear_m (the one that
/// reaches past s_clear_m, and any after it that s_clear_m's bound still left inside) starts its query past its own
/// points within x_clear_m (intersect_after), as does the one chord of a straight arc. s_end_m may be +infinity only
/// for a straight arc (zero curvature). (The callback lets a caller build its result from the scene's hit where it
/// lies, with no intermediate copy: a hit is about a hundred bytes.)
template <Scene S, Real T, class OnHit>
bool visit_arc_hit(const S& scene, const arc_frame<T>& frame, T sin_phi0, T cos_phi0, T kappa_per_m, T s_begin_m,
                   T s_end_m, T tolerance_m, bool clear_open_water, T s_clear_m, T x_clear_m, std::size_t& chords,
                   OnHit&& on_hit) {
    if (!(s_end_m > s_begin_m)) return false;
    // Every chord ends within what the caller knows clear (a piece of the arc before its neighbour's hit): no hit.
    if (kappa_per_m != T(0) && s_clear_m >= s_end_m) return false;
    const T sin0 = sin_phi0, cos0 = cos_phi0, kappa = kappa_per_m;
    const vec3<T> down{T(0), T(0), T(-1)};
    const auto world = [&](const arc_offset<T>& o) { return frame.start + frame.horizontal * o.range_m + down * o.depth_m; };
    const T eps = std::numeric_limits<T>::epsilon();
    // The chord from p along dir (unit) to distance t_max_m, handed to the scene past its points that lie within
    // x_clear_m horizontally of the arc's start (a few roundings of the world coordinates and of the distances short
    // of them), where the scene can start there (ResumableScene).
    const auto query = [&](const vec3<T>& p, const vec3<T>& dir, T t_max_m) -> std::optional<hit<T>> {
        if constexpr (ResumableScene<S>) {
            const T dir_h = glm::dot(dir, frame.horizontal);
            if (x_clear_m > T(0) && dir_h > T(1e-3)) {
                const T x_p = glm::dot(p - frame.start, frame.horizontal);
                const T rounding =
                    T(16) * eps * (std::abs(p.x) + std::abs(p.y) + std::abs(p.z) + x_clear_m + std::abs(x_p) + t_max_m);
                const T clear = (x_clear_m - x_p - rounding) / dir_h;
                if (clear > T(0)) return scene.intersect_after(ray<T>{p, dir}, t_max_m, clear);
            }
        }
        return scene.intersect(ray<T>{p, dir}, t_max_m);
    };

    if (kappa == T(0)) { // one chord: the ray itself
        const arc_offset<T> o = offset_along_arc(sin0, cos0, kappa, s_begin_m);
        const vec3<T> chord_start = world(o);
        ++chords;
        const auto h = query(chord_start, frame.horizontal * cos0 + down * sin0, s_end_m - s_begin_m);
        if (!h) return false;
        const T arc_m = s_begin_m + h->distance_m;
        const arc_offset<T> at = offset_along_arc(sin0, cos0, kappa, arc_m);
        on_hit(*h, h->point, arc_m, at, at.range_m);
        return true;
    }

    const T span = s_end_m - s_begin_m;
    // Chords: ceil(span / chord_arc_length_m), without its square root and divisions when one chord will do
    // (k span^2 <= 8 tol and k span <= pi).
    const T k = std::abs(kappa);
    std::size_t n = 1;
    if (k * span * span > T(8) * tolerance_m || k * span > pi_v<T>) {
        const T rate = std::max(std::sqrt(k / (T(8) * tolerance_m)), k / pi_v<T>); // chords per metre
        const T pieces = std::min(std::ceil(span * rate), T(1 << 20));
        n = pieces > T(1) ? static_cast<std::size_t>(pieces) : 1;
    }
    const T ds = n == 1 ? span : span / static_cast<T>(n);
    // Chord k spans arc lengths [s_at(k), s_at(k + 1)].
    const auto s_at = [&](std::size_t i) { return i == n ? s_end_m : s_begin_m + ds * static_cast<T>(i); };
    const vec3<T> p0 = s_begin_m == T(0) ? frame.start : world(offset_along_arc(sin0, cos0, kappa, s_begin_m));
    // Chord k's end q, direction and length from its start p.
    const auto chord_from = [&](std::size_t k_chord, const vec3<T>& p, vec3<T>& q, vec3<T>& dir, T& len) {
        const T s_lo = s_at(k_chord), s_hi = s_at(k_chord + 1);
        if (s_lo == T(0)) { // from the arc's start the chord runs along the mean inclination: no normalising
            T sinc_h, ch;
            const T half = kappa * s_hi * T(0.5);
            sinc_cos(half, sinc_h, ch);
            const T sh = half * sinc_h;
            dir = frame.horizontal * (cos0 * ch + sin0 * sh) + down * (sin0 * ch - cos0 * sh);
            len = s_hi * sinc_h;
            q = p + dir * len;
        } else {
            q = world(offset_along_arc(sin0, cos0, kappa, s_hi));
            const vec3<T> d = q - p;
            len = std::sqrt(glm::dot(d, d));
            dir = d * (T(1) / len);
        }
    };
    // Where chord k starts: the end of chord k - 1, computed as the walk below computes it.
    const auto start_of = [&](std::size_t k_chord) {
        if (k_chord == 0) return p0;
        if (s_at(k_chord - 1) == T(0)) {
            vec3<T> q, dir;
            T len;
            chord_from(k_chord - 1, p0, q, dir, len);
            return q;
        }
        return world(offset_along_arc(sin0, cos0, kappa, s_at(k_chord)));
    };
    // Chords [k, w) that surely meet nothing, by one query over the arc's chord from s_at(k) to s_at(w) with a band
    // that holds the arc and the chords (ClearanceScene); 0 when the arc is too steep or turns too far for the bound.
    [[maybe_unused]] const auto clear_chords = [&](std::size_t k_chord, std::size_t w) -> std::size_t {
        if constexpr (!ClearanceScene<S>) {
            return 0;
        } else {
            const T s_a = s_at(k_chord), s_b = s_at(w);
            const T length = s_b - s_a;
            if (!(k * length <= T(1))) return 0;
            const arc_offset<T> oa = offset_along_arc(sin0, cos0, kappa, s_a);
            const arc_offset<T> ob = offset_along_arc(sin0, cos0, kappa, s_b);
            // The inclination is monotonic along an arc within one layer: its cosine is smallest at an end, largest at
            // an end or, where the arc passes horizontal, 1.
            const T c_lo = std::min(oa.cos_incline, ob.cos_incline);
            if (!(c_lo >= T(0.25))) return 0;
            const T c_hi = (oa.sin_incline < T(0)) != (ob.sin_incline < T(0)) ? T(1)
                                                                               : std::max(oa.cos_incline, ob.cos_incline);
            const vec3<T> a = world(oa), b = world(ob);
            const vec3<T> d = b - a;
            const T len = std::sqrt(glm::dot(d, d));
            if (!(len > T(0))) return 0;
            const vec3<T> dir = d * (T(1) / len);
            const T scale =
                std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z), std::abs(b.x), std::abs(b.y), std::abs(b.z), len});
            const T slack = T(64) * eps * scale;
            // Vertically, the arc lies within e / cos(chord) of this chord (e = k length^2 / 8 >= its sagitta), and
            // a chord of the walk within tol / cos(that chord) of the arc, every inclination here with cosine >= c_lo.
            const T band = (k * length * length * T(0.125) + tolerance_m) / c_lo + slack;
            // A chord of the walk reaches 16 roundings past its end (below): the query reaches past the window's end by
            // more than that horizontally (the chord's cosine is at least c_lo).
            const T reach = len + T(128) * eps * scale;
            const T clear = scene.clear_length_m(ray<T>{a, dir}, reach, band);
            if (clear >= reach) return w - k_chord; // the arc's span and the chords': between the window's ends
            // Horizontally, the arc covers at most c_hi per metre of arc; a few roundings off for where this chord and
            // the walk's points differ.
            const T x_clear = clear * std::sqrt(dir.x * dir.x + dir.y * dir.y) - T(4) * slack;
            if (!(x_clear > T(0))) return 0;
            const T whole = std::floor(x_clear / (ds * c_hi));
            const std::size_t j = whole >= T(1) ? static_cast<std::size_t>(whole) - 1 : 0; // one fewer, for rounding
            return std::min(j, w - k_chord - 1);
        }
    };
    // The walk, chord by chord. With a ClearanceScene, a window of chords ahead (`window_chords`: as many as keep
    // its sagitta within 2 cm, and at least 4) is first asked about as one. A clear window is skipped whole and the
    // next one asked about; after a window that is not, the chords are traced one by one from its first chord not
    // cleared, and the next window is asked about after four of them have met nothing (a ray that came close to the
    // seabed usually meets it within a few chords). The chords traced, and so the hit, are those of the plain walk, bit for bit.
    constexpr bool clearance = ClearanceScene<S>;
    constexpr std::size_t traced_before_asking = 4;
    [[maybe_unused]] const std::size_t window_chords =
        clearance ? std::max<std::size_t>(4, static_cast<std::size_t>(std::min(std::sqrt(T(0.16) / k) / ds, T(1 << 20))))
                  : 0;
    std::size_t traced = traced_before_asking;
    vec3<T> p = p0;
    std::size_t k_first = 0;
    if (s_clear_m > s_begin_m) { // skip the chords [0, k_first), all ending at or before s_clear_m
        const T whole = std::min(std::floor((s_clear_m - s_begin_m) / ds), static_cast<T>(n));
        k_first = whole >= T(1) ? static_cast<std::size_t>(whole) : 0;
        while (k_first > 0 && s_at(k_first) > s_clear_m) --k_first;
        if (k_first > 0) {
            p = start_of(k_first);
            traced = 0; // the ray is about where its neighbour met the scene: trace a few chords before asking
        }
    }
    for (std::size_t k_chord = k_first; k_chord < n;) {
        if constexpr (clearance) {
            if (clear_open_water && traced >= traced_before_asking && n - k_chord >= 4) {
                const std::size_t w = std::min(n, k_chord + window_chords);
                const std::size_t j = clear_chords(k_chord, w);
                if (j > 0) {
                    k_chord += j;
                    p = start_of(k_chord);
                }
                if (k_chord != w) traced = 0;
                continue;
            }
            ++traced;
        }
        const T s_lo = s_at(k_chord), s_hi = s_at(k_chord + 1);
        vec3<T> q, dir;
        T len;
        chord_from(k_chord, p, q, dir, len);
        ++k_chord;
        if (!(len > T(0))) { p = q; continue; }
        // A hit exactly on a chord joint must not slip between the two chords: reach a few roundings past the end.
        const T scale = std::max(std::max(std::abs(p.x), std::abs(p.y)), std::max(std::abs(p.z), len));
        ++chords;
        const auto h = query(p, dir, len + T(16) * eps * scale);
        if (h) {
            // Newton on f(s) = n . (X(s) - H) from the chord's estimate, kept within the chord's neighbourhood.
            const vec3<T> n_hat = h->normal;
            const T n_h = glm::dot(n_hat, frame.horizontal);
            const T n_d = -n_hat.z; // n . (downward unit)
            const T base = glm::dot(n_hat, frame.start - h->point);
            // The start: as far along the arc as the hit is along the chord (chord and arc lengths differ by the
            // factor sinc(kappa ds / 2), within k tol of 1: far less than the sagitta the first step removes).
            T s = s_lo + std::min(h->distance_m, s_hi - s_lo);
            const T lo = std::max(s_lo - (s_hi - s_lo), T(0)), hi = s_hi + (s_hi - s_lo);
            arc_offset<T> o = offset_along_arc(sin0, cos0, kappa, s);
            // After a step e the error left is about |kappa| e^2 / (2 |f'|) (the arc's curvature against the plane):
            // stop once that is below rounding. The arc's offset at the last, settled step follows from the one
            // before by its Taylor series to second order (advance_offset): a settled step has (kappa e)^2 <=
            // 2 kappa max(s_hi, 1) eps, at most about 2 pi eps (an arc turns by at most pi in one layer), so the
            // remainder, kappa^2 e^3 / 6 in position and (kappa e)^3 / 6 in inclination, is below rounding too.
            const T settled = eps * std::max(s_hi, T(1));
            for (int it = 0; it < 8; ++it) {
                const T f = base + o.range_m * n_h + o.depth_m * n_d;
                const T df = o.cos_incline * n_h + o.sin_incline * n_d;
                if (!(std::abs(df) > T(0))) break;
                const T next = std::clamp(s - f / df, lo, hi);
                const T step = next - s;
                s = next;
                if (!(k * step * step > T(2) * std::abs(df) * settled)) {
                    o = advance_offset(o, kappa, step);
                    break;
                }
                o = offset_along_arc(sin0, cos0, kappa, s);
            }
            // Nothing lay on the chord before the scene's hit: clear out to the hit's horizontal distance on it.
            const T x_hit = glm::dot(p - frame.start, frame.horizontal) + h->distance_m * glm::dot(dir, frame.horizontal);
            on_hit(*h, world(o), s, o, x_hit);
            return true;
        }
        p = q;
    }
    return false;
}

/// As visit_arc_hit, returning the hit (surface.distance_m: the arc length from the arc's start), nullopt if none.
template <Scene S, Real T>
[[nodiscard]] std::optional<arc_hit<T>> intersect_arc(const S& scene, const arc_frame<T>& frame, T sin_phi0, T cos_phi0,
                                                      T kappa_per_m, T s_begin_m, T s_end_m, T tolerance_m,
                                                      std::size_t& chords) {
    std::optional<arc_hit<T>> out;
    visit_arc_hit(scene, frame, sin_phi0, cos_phi0, kappa_per_m, s_begin_m, s_end_m, tolerance_m, true, T(0), T(0), chords,
                  [&](const hit<T>& h, const vec3<T>& point, T arc_m, const arc_offset<T>& at, T) {
                      out.emplace(h, arc_m, at);
                      out->surface.point = point;
                      out->surface.distance_m = arc_m;
                  });
    return out;
}

/// As above for a ray_arc (its start inclination, speed and gradient give sin phi0, cos phi0 and kappa).
template <Scene S, Real T>
[[nodiscard]] std::optional<arc_hit<T>> intersect_arc(const S& scene, const ray_arc<T>& arc, const arc_frame<T>& frame,
                                                      T s_begin_m, T s_end_m, T tolerance_m, std::size_t& chords) {
    const T cos0 = std::max(std::cos(arc.start_incline_rad), T(0));
    return intersect_arc(scene, frame, std::sin(arc.start_incline_rad), cos0,
                         cos0 / arc.start_speed_mps * arc.gradient_per_s, s_begin_m, s_end_m, tolerance_m, chords);
}

} // namespace sss::propagation

#pragma once
/// \file
/// Where to launch rays within one along-track column of a beam.
///
/// Depression angles are spaced so that their returns from a nominal seabed (a plane: level at the towfish's altitude,
/// or sloping as the seabed does, nominal_seabed) are evenly spaced in slant range, hence in two-way time: every time
/// sample receives about the same number of rays however steep or grazing the geometry, and the energy between two
/// adjacent rays is spread over the short time span between their returns. With the body rotated by R, the component
/// of a direction in the column against the plane's downward normal is g(e) = A + B cos e + C sin e, and its nominal
/// slant range is H / g(e), H the towfish's distance from the plane; the range is monotone between the extrema of g,
/// and on each monotone piece e(r) has the closed form e = phi -/+ acos((H/r - A)/rho), rho = hypot(B, C),
/// phi = atan2(C, B). A ray reaches geometry within the longest range Rmax only if g >= clearance / Rmax, the
/// clearance being the towfish's distance from the plane less how far geometry rises above it: no ray is launched
/// below that.
/// Where a step is more than column_density::max_range_step of the range it starts from (ranges within 20 steps of
/// the towfish), it is divided geometrically, where the column's ray budget (max_rays) allows.
/// Where no such spacing exists (towfish not above the scene, a column pointing up) the angles are uniform.
/// Either way no step between adjacent angles is wider than column_density::max_step_rad, where the column's ray
/// budget (max_rays) allows: where the returns crowd together in range (near the towfish's altitude, or under a
/// towfish close to the seabed) a step even in range can span many degrees.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "sss/beam/concept.hpp"
#include "sss/core/constants.hpp"

namespace sss {

/// How densely to sample one column.
struct column_density {
    double rays_per_m = 0.0;      ///< rays per metre of nominal slant range (used when `rays` is 0)
    std::size_t rays = 0;         ///< rays over the reachable part of the column (0: use rays_per_m)
    /// Cap per column: each monotone piece of the column takes at most what the pieces before it left, but at least
    /// two rays (and six towards a range minimum), so a column may pass a cap of a few rays.
    std::size_t max_rays = 1u << 16;
    /// Largest step (rad) between adjacent launch angles (within max_rays: a cap the budget cannot meet is widened).
    /// Near the towfish's altitude the returns' spacing in range leaves few rays over a wide span of angles (under a
    /// receiver sampled at 1 kHz, 10 m up, one step is 4.5 degrees at 55 degrees of depression), and a tube's
    /// trapezoid over such a span misses how the beam, the scattering and the footprint change across it; 0: no cap.
    double max_step_rad = 0.0;
    /// Largest step in nominal slant range between adjacent rays, as a fraction of the range (0: none). Close to the
    /// towfish's altitude one range step can be a large part of the range itself, and the echo per unit time falls
    /// several fold across the tube: a towfish 1 mm up with 0.0375 m steps put 14 % too much in the fourth sample
    /// of the echo (0.58 dB, the worst within 80 dB of the peak), and 0.02 dB at 1/20. Such steps are divided
    /// geometrically (where the budget allows). Only ranges within 20 steps of the towfish are touched: with
    /// 0.0375 m steps, below 0.75 m; with a few rays per column (ray_density::across), at any altitude.
    double max_range_step = 0.05;
};

/// The plane a column's rays launch for: world unit normal `up` (pointing up), the towfish `altitude_m` from it (m,
/// along the normal), and no geometry closer to the towfish than `clearance_m` along the normal (m: the altitude less
/// how far the geometry rises above the plane). The level seabed under the towfish is up = (0, 0, 1).
struct nominal_seabed {
    vec3<double> up{0.0, 0.0, 1.0};
    double altitude_m = 0.0;
    double clearance_m = 0.0;
};

namespace detail {

/// `v` with its step i (from v[i - 1] to v[i]) divided into parts[i - 1] parts, the points between at(i, k, n) for
/// k = 1 ... n - 1, every value of v kept bit for bit. The counts are given once, so the output's size and its filling
/// agree whatever the rounding.
template <class At> void divide_steps(std::vector<double>& v, const std::vector<std::size_t>& parts, At&& at) {
    std::size_t total = 1;
    for (const std::size_t n : parts) total += n;
    std::vector<double> divided(total);
    std::size_t j = 0;
    divided[j++] = v.front();
    for (std::size_t i = 1; i < v.size(); ++i) {
        const std::size_t n = parts[i - 1];
        for (std::size_t k = 1; k < n; ++k) divided[j++] = at(i, k, n);
        divided[j++] = v[i];
    }
    v.swap(divided);
}

/// Divides every step of the monotone, finite angles `es` (rad) wider than max_step_rad evenly in angle, keeping every
/// angle it had; where that would take the run past max(budget, es.size()) angles the cap is widened, by factors of
/// two from the smallest step that could fit, until it does not. 0 (or not finite): no cap.
inline void cap_steps(std::vector<double>& es, double max_step_rad, std::size_t budget) {
    if (!(max_step_rad > 0.0) || !std::isfinite(max_step_rad) || es.size() < 2) return;
    const double span = std::abs(es.back() - es.front()); // monotone: the sum of the steps
    if (!std::isfinite(span)) return;
    const double room = double(std::max(budget, es.size()));
    std::vector<std::size_t> parts(es.size() - 1);
    // A run of span S in steps of at most `step` needs at least S / step + 1 angles: no smaller cap can fit.
    double step = std::max(max_step_rad, span / (room - 1.0));
    double total = 0.0;
    for (int widen = 0; widen < 64; ++widen, step *= 2.0) {
        total = 1.0;
        for (std::size_t i = 1; i < es.size(); ++i) total += std::max(std::ceil(std::abs(es[i] - es[i - 1]) / step), 1.0);
        if (total <= room) break;
    }
    if (!(total <= room) || total == double(es.size())) return; // nothing fits, or no step wider than the cap
    for (std::size_t i = 1; i < es.size(); ++i)
        parts[i - 1] = static_cast<std::size_t>(std::max(std::ceil(std::abs(es[i] - es[i - 1]) / step), 1.0));
    divide_steps(es, parts, [&](std::size_t i, std::size_t k, std::size_t n) {
        return es[i - 1] + (es[i] - es[i - 1]) * (double(k) / double(n));
    });
}

/// Divides every step of the increasing, positive ranges `rs` (m) wider than `ratio` times the range it starts from
/// geometrically (each part at most that ratio of its start), keeping every range it had, where max(budget,
/// rs.size()) ranges allow (else nothing); 0 (or not finite): nothing.
inline void cap_range_steps(std::vector<double>& rs, double ratio, std::size_t budget) {
    if (!(ratio > 0.0) || !std::isfinite(ratio) || rs.size() < 2 || !(rs.front() > 0.0)) return;
    const double growth = std::log1p(ratio);
    std::vector<std::size_t> parts(rs.size() - 1);
    double total = 1.0;
    for (std::size_t i = 1; i < rs.size(); ++i) {
        const double a = rs[i - 1], b = rs[i];
        const double n = b - a > ratio * a ? std::ceil(std::log(b / a) / growth) : 1.0;
        total += n;
        parts[i - 1] = n < 1e9 ? static_cast<std::size_t>(n) : std::size_t(1e9);
    }
    if (!(total <= double(std::max(budget, rs.size()))) || total == double(rs.size())) return;
    divide_steps(rs, parts, [&](std::size_t i, std::size_t k, std::size_t n) {
        return rs[i - 1] * std::pow(rs[i] / rs[i - 1], double(k) / double(n));
    });
}

} // namespace detail

namespace detail {

/// One monotone piece of a column's launch depressions: ends at the nearest range and at the farthest reachable one.
struct launch_piece {
    double e_near, e_far; // ends: nearest range and farthest reachable range
    double r_near, r_far; // nominal slant ranges there (m)
    bool far_is_edge;     // the far end is the piece's edge (not cut by the reach)
    bool increasing_g;    // g grows with e on the piece
    double centre;        // the maximum of g this piece climbs towards
};

/// The column's g(e) = A + B cos e + C sin e (the file comment) and its pieces, highest depression first.
struct launch_geometry {
    double A = 0.0, B = 0.0, C = 0.0, rho = 0.0, phi = 0.0;
    std::vector<launch_piece> pieces;
    double span_m = 0.0; // the pieces' nominal ranges together (m)
    bool spaced = false; // false: no spacing in range exists (the angles are uniform)
};

template <Real T>
[[nodiscard]] launch_geometry launch_pieces(side s, T along_rad, double e_lo, double e_hi, const mat3<T>& R,
                                            const nominal_seabed& nominal, double Rmax) {
    launch_geometry lg;
    const double sa = std::sin(double(along_rad)), ca = std::cos(double(along_rad));
    // Up-components (against the plane's normal) of the body axes: R[c] is column c, body axis c in the world; for the
    // level plane the world z components themselves.
    const bool level = nominal.up.x == 0.0 && nominal.up.y == 0.0 && nominal.up.z == 1.0;
    const auto up_of = [&](int c) {
        if (level) return double(R[c][2]);
        return double(R[c][0]) * nominal.up.x + double(R[c][1]) * nominal.up.y + double(R[c][2]) * nominal.up.z;
    };
    lg.A = -up_of(0) * sa;
    lg.B = -up_of(1) * double(side_sign<T>(s)) * ca;
    lg.C = -up_of(2) * ca;
    lg.rho = std::hypot(lg.B, lg.C);
    const double H = nominal.altitude_m;
    // No spacing without a plane at a finite distance and a finite reach: the seabed beyond the scene (height
    // -infinity, an altitude of +infinity) leaves only what rises above it, wherever that is.
    if (!(H > 0.0) || !std::isfinite(H) || !(nominal.clearance_m > 0.0) || !(lg.rho > 1e-12) || !(Rmax > 0.0) ||
        !std::isfinite(Rmax))
        return lg;
    lg.spaced = true;
    // A ray can reach geometry within Rmax only if g >= clearance / Rmax.
    const double g_cut = nominal.clearance_m / Rmax;
    auto g = [&](double e) { return lg.A + lg.B * std::cos(e) + lg.C * std::sin(e); };
    lg.phi = std::atan2(lg.C, lg.B);
    // Split [e_lo, e_hi] at the extrema of g (phi + m pi) into monotone pieces.
    std::vector<double> cuts{e_lo};
    for (int m = -3; m <= 3; ++m) {
        const double x = lg.phi + m * pi_v<double>;
        if (x > e_lo && x < e_hi) cuts.push_back(x);
    }
    cuts.push_back(e_hi);
    std::sort(cuts.begin(), cuts.end());
    for (std::size_t i = cuts.size() - 1; i-- > 0;) { // from the highest depression down
        const double a = cuts[i], b = cuts[i + 1];
        const double mid = 0.5 * (a + b);
        const double centre = lg.phi + std::round((mid - lg.phi) / two_pi_v<double>) * two_pi_v<double>;
        const bool inc = mid < centre;
        const double e_near = inc ? b : a, e_edge_far = inc ? a : b;
        const double g_near = g(e_near), g_far = g(e_edge_far);
        if (!(g_near > g_cut)) continue; // nothing on this piece can be reached
        const bool far_is_edge = g_far >= g_cut;
        const double r_near = H / g_near, r_far = H / std::max(g_far, g_cut);
        lg.pieces.push_back({e_near, e_edge_far, r_near, r_far, far_is_edge, inc, centre});
        lg.span_m += r_far - r_near;
    }
    return lg;
}

} // namespace detail

/// The nominal slant range (m) that the column at `along_rad` on side `s` spaces its rays over, launching for
/// `nominal`: with column_density::rays_per_m it launches about that many rays per metre of it. Where no spacing in
/// range exists (the angles are then uniform over the column, as many as over max_range_m), max_range_m.
template <Real T>
[[nodiscard]] double launch_span_m(side s, T along_rad, T depression_min_rad, T depression_max_rad, const mat3<T>& R,
                                   const nominal_seabed& nominal, T max_range_m) {
    const double e_lo = depression_min_rad, e_hi = depression_max_rad;
    if (!(e_hi > e_lo)) return 0.0;
    const detail::launch_geometry lg = detail::launch_pieces(s, along_rad, e_lo, e_hi, R, nominal, double(max_range_m));
    return lg.spaced ? lg.span_m : double(max_range_m);
}

/// Depression angles (rad) for the column at `along_rad` on side `s`, in descending order (near range first).
/// Quiet NaN entries separate runs that are not adjacent (no energy is shared across them).
/// \param R              body-to-world rotation
/// \param nominal        the plane the rays launch for (see the file comment)
/// \param max_range_m    longest slant range the receiver records (m)
template <Real T>
void depression_angles(std::vector<T>& out, side s, T along_rad, T depression_min_rad, T depression_max_rad,
                       const mat3<T>& R, const nominal_seabed& nominal, T max_range_m, const column_density& density) {
    out.clear();
    const double e_lo = depression_min_rad, e_hi = depression_max_rad;
    if (!(e_hi > e_lo)) return;
    const double Rmax = max_range_m;
    constexpr std::size_t refine_levels = 6;
    const detail::launch_geometry lg = detail::launch_pieces(s, along_rad, e_lo, e_hi, R, nominal, Rmax);
    const double H = nominal.altitude_m, A = lg.A, rho = lg.rho;

    auto uniform = [&](double lo, double hi, std::size_t n) {
        if (density.max_step_rad > 0.0) // as many as the cap needs, up to the budget (clamped below)
            n = std::max(n, static_cast<std::size_t>(std::min(std::ceil((hi - lo) / density.max_step_rad), 1e9)) + 1);
        n = std::clamp<std::size_t>(n, 2, std::max<std::size_t>(density.max_rays, 2));
        for (std::size_t i = 0; i < n; ++i)
            out.push_back(static_cast<T>(hi - (hi - lo) * double(i) / double(n - 1)));
    };
    if (!lg.spaced) {
        const double n = density.rays != 0 ? double(density.rays) : density.rays_per_m * Rmax;
        // (0 rays per metre of an endless range: none asked for, the two edges)
        const std::size_t count = !(n >= 0.0)                     ? 0
                                  : n < double(density.max_rays) ? static_cast<std::size_t>(n)
                                                                 : density.max_rays;
        uniform(e_lo, e_hi, count < density.max_rays ? count + 2 : count);
        return;
    }
    const double span_total = lg.span_m;
    if (lg.pieces.empty() || !(span_total > 0.0)) return;
    const double n_total = std::min(double(density.max_rays),
                                    density.rays != 0 ? double(density.rays) : density.rays_per_m * span_total);
    for (const detail::launch_piece& p : lg.pieces) {
        // At the range minimum (e.g. nadir) the return density grows like 1/sqrt(t - t_min): refine towards
        // it geometrically so that no tube spreads that peak evenly over a whole step.
        const bool at_minimum = std::abs(p.e_near - p.centre) < 1e-9;
        // The piece's share of the column's rays, within what the pieces before it left of the budget.
        const double left = (density.max_rays > out.size() ? double(density.max_rays - out.size()) : 0.0) -
                            (at_minimum ? double(refine_levels) : 0.0);
        const double share = std::ceil(n_total * (p.r_far - p.r_near) / span_total) + 1;
        const auto n = std::max<std::size_t>(2, static_cast<std::size_t>(std::max(0.0, std::min(share, left))));
        std::vector<double> ranges;
        ranges.reserve(n + refine_levels);
        const double step = (p.r_far - p.r_near) / double(n - 1);
        ranges.push_back(p.r_near);
        if (at_minimum)
            for (std::size_t l = refine_levels; l >= 1; --l) ranges.push_back(p.r_near + step * std::pow(0.25, double(l)));
        for (std::size_t i = 1; i < n; ++i) ranges.push_back(p.r_near + step * double(i));
        detail::cap_range_steps(ranges, density.max_range_step, density.max_rays > out.size() ? density.max_rays - out.size() : 0);
        std::vector<double> es(ranges.size());
        for (std::size_t i = 0; i < ranges.size(); ++i) {
            const double c = std::clamp((H / ranges[i] - A) / rho, -1.0, 1.0);
            es[i] = p.increasing_g ? p.centre - std::acos(c) : p.centre + std::acos(c);
        }
        es.front() = p.e_near; // exactly on the beam or piece edge
        if (p.far_is_edge) es.back() = p.e_far;
        // Within what is left of the column's budget.
        detail::cap_steps(es, density.max_step_rad, density.max_rays > out.size() ? density.max_rays - out.size() : 0);
        if (!p.increasing_g) std::reverse(es.begin(), es.end()); // descending in e
        // Pieces meeting at a shared, sampled edge form one run; otherwise separate the runs.
        if (!out.empty()) {
            if (out.back() == static_cast<T>(es.front())) es.erase(es.begin());
            else out.push_back(std::numeric_limits<T>::quiet_NaN());
        }
        for (double e : es) out.push_back(static_cast<T>(e));
    }
}

/// The same launching for the level seabed `altitude_m` below the towfish, with no geometry within `clearance_m` of the
/// towfish's height (m).
template <Real T>
void depression_angles(std::vector<T>& out, side s, T along_rad, T depression_min_rad, T depression_max_rad,
                       const mat3<T>& R, T altitude_m, T clearance_m, T max_range_m, const column_density& density) {
    depression_angles(out, s, along_rad, depression_min_rad, depression_max_rad, R,
                      nominal_seabed{.altitude_m = double(altitude_m), .clearance_m = double(clearance_m)}, max_range_m,
                      density);
}

} // namespace sss

#pragma once
/// \file
/// When two adjacent rays of a column may share their energy as one ray tube, and when the launch angle between
/// them must be bisected to locate an edge (an occlusion, an object's silhouette, a change of surface).
///
/// A ray meeting a facet at angle theta (between the ray and the facet) at two-way time t predicts how fast the
/// time of its neighbours grows with depression: dt/de = t cot theta (s/rad), the footprint r de / sin theta
/// seen along the ray (straight rays; in refracting water a close estimate, which is all a test needs). Two rays
/// de apart on one continuous surface return within a time of about de times that, plus t de^2 / 2 (the second order,
/// which is all there is where a facet faces the ray: a pair about normal incidence on one plane is no edge); a time
/// gap many times larger
/// than the smaller of the two predictions means the surface between them is hidden (the first ray grazes a crest,
/// the next lands beyond the shadow) or that they met different parts of the scene. Such a pair is split by the
/// ray between them, recursively, until the side with the smaller prediction spans less than 1/16 of a sample:
/// the edge is then located, and each ray keeps its half of the tiny step as a point.
/// On one surface, a pair whose echo per radian (beam pattern aside) differs by more than a quarter is split too,
/// down to tubes of half a sample, so that the trapezoid over depression follows the echo where it changes fast.
///
/// Facet edges. A height field is a surface of plane triangles: the echo per radian holds the footprint 1/sin of the
/// angle between ray and facet, which jumps where a ray crosses from one triangle to the next (a ripple's crest
/// or trough, every cell edge of rough relief), while the scattering (from the smooth shading normal) changes
/// smoothly. A trapezoid across such a jump spreads it over the tube: at a ray per sample over 0.25 m cells of
/// ripples at 100 m that leaves 0.3 dB RMS and 1.6 dB at the 99th percentile against a converged render
/// (bench/bench_survey_accuracy.cpp). So a pair of seabed rays on different facets (their geometric normals
/// differ by more than 1e-3 rad) whose echoes per radian differ by more than 5 % is split down to an eighth of a
/// sample, as an edge is located: the jump is then placed to within that, and tubes within one facet are left as
/// they are. On that 256 m copy of the survey it takes 40,000 more rays per ping (a few % more time) and brings both
/// figures down by a third; on the 1 km survey (bench/bench_survey.cpp), whose relief differs, 18 % more rays and
/// time for a few % less error. A level seabed is unchanged bit for bit, and so is a sloping plane whose heights'
/// rounding leaves its facets' normals within 1e-3 rad of each other (any plane in double; in float, heights within
/// about 250 m of zero at 0.05 m cells). Objects keep the quarter. Halving the step takes about
/// log2(span / tolerance) rays per edge; where that is more than three and the seabed shows the two facets meeting,
/// the simulator traces instead the two rays just either side of where their edge lies (facet_edge_crossing,
/// facet_reaches_crossing, ray_density::bracket_facet_edges): the pair between them spans the edge within the
/// tolerance, and the pairs outside it lie on one facet each. Those pairs are halved, never bracketed again: at a
/// grazing end (below) the estimate's first-order error can exceed the bracket's width, and a bracket from the same
/// planes would miss again. Where its two rays straddle the edge, the bracket records it for the along-track check
/// (with ray_density::along_split_seabed) by facet_edge_marks_line, where halving would have located it as an edge by
/// chance; where they miss, the outer pair's halving locates it, or not, as any halving does.
///
/// Grazing ends. The time a pair spans can understate the angle its ends' echoes cover. A ray meeting its facet at
/// grazing incidence (a steep facet seen nearly edge-on) carries an echo per radian that grows as 1/sin of the angle
/// to the facet, hundreds of times its neighbour's, while that facet ends, at an edge or at the next facet, within a
/// tiny fraction of the step: the time the pair spans is then far shorter than what that end's stretch predicts over
/// the step, and a trapezoid or a half step as a point gives the end's large echo to the whole half step. On the 1 km
/// survey such single pieces put +5 dB into one sample at a ray per sample and +13 dB at two. So the larger of the
/// two stretches decides too:
/// - across a facet's edge where one end's echo per radian is more than twice the other's, the tube is refined until
///   the larger stretch over the step, not only the time gap, is below the eighth of a sample;
/// - at a located edge, the ray between the two ends is traced again while the larger stretch spans more than the
///   sixteenth of a sample that located the edge (ends_unresolved); the edge keeps the place the smaller stretch
///   located it at (where the along-track check compares it), and the traced rays only place the energy.
///
/// Sparse columns. The narrowest columns of the along-track division trace every other launch angle
/// (ray_density::along_split_sparse). A shadow of time length L between two rays on one surface, n launch intervals
/// apart, leaves a gap of about n p + L, p one interval's prediction; between adjacent rays it is found when
/// L > 2 p (gap > 3 p), and across n intervals the same L is found when the gap exceeds (1 + 2 / n) times the
/// prediction n p.
///
/// The far edge of coverage (a valid ray whose neighbour returns after the line ends) is located as any edge is: the
/// part of the step within the line holds echo, and the valid end's half step as a point at its own time would put
/// up to twice or none of it into one of the line's last samples. In refracting water the launch angles' spacing
/// (made for straight rays) leaves the last rays a sample or two short of the line's end, with neighbours two
/// samples apart and a stretch (from the facet alone) several times short: a thermocline's line gained 29 % in its
/// second-to-last sample against a render at 16 rays per sample, and is within 0.5 % of it once located.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

namespace sss::detail {

/// What the refinement needs to know of one ray's echo.
struct tube_end {
    bool valid = false;
    double t_s = 0.0;          ///< two-way time (s)
    double stretch = 0.0;      ///< predicted dt/de of its neighbours (s/rad), see time_stretch
    double gain = 0.0;         ///< what the scene gives the echo per radian (scattering x loss / sin theta), beam aside
    std::uint32_t object = 0;  ///< object id of the surface it met
    std::uint32_t material = 0;
    bool faceted = false;      ///< it met the seabed, of plane facets, and their edges are to be refined
    std::array<double, 3> normal{}; ///< the unit geometric normal of the facet it met
};

/// An edge is located when the side it is predicted on spans less than this fraction of a sample.
inline constexpr double located_fraction = 1.0 / 16.0;

enum class tube_verdict : unsigned char {
    continuous, ///< one tube (or, with an end missing, as a tube would be emitted)
    split,      ///< an edge between them not yet located: trace the ray between them
    located,    ///< an edge between them located to a small fraction of a sample: each end keeps its half
    coarse      ///< one surface, but its echo changes too much between them for a trapezoid: trace the ray between
                ///< them if the depth and budget allow, else one tube
};

/// dt/de = t cot theta (s/rad): two-way time `t_s` (s), sin of the angle between ray and facet `sin_facet`.
[[nodiscard]] inline double time_stretch(double t_s, double sin_facet) noexcept {
    const double s = std::clamp(sin_facet, 1e-12, 1.0);
    return t_s * std::sqrt(std::max(0.0, 1.0 - s * s)) / s;
}

/// Whether two rays met different plane facets of the seabed whose edges are refined: their geometric normals more than
/// 1e-3 rad apart (those of one facet, or of coplanar ones, agree to rounding, which a hit's normal carries: it shares a
/// division with the smooth normal at the hit).
[[nodiscard]] inline bool facet_edge(const tube_end& a, const tube_end& b) noexcept {
    const double nx = a.normal[0] - b.normal[0], ny = a.normal[1] - b.normal[1], nz = a.normal[2] - b.normal[2];
    return a.faceted && b.faceted && nx * nx + ny * ny + nz * nz > 1e-6;
}

/// The two-way time (s) a tube between valid rays `de` (rad) apart spans, as its refinement takes it: their time gap;
/// across a facet's edge where one end's echo per radian is more than twice the other's, at least the larger stretch
/// over the step (grazing ends, see the file comment).
[[nodiscard]] inline double tube_span(const tube_end& a, const tube_end& b, double de) noexcept {
    const double gap = std::abs(b.t_s - a.t_s);
    const double lo = std::min(a.gain, b.gain), hi = std::max(a.gain, b.gain);
    return facet_edge(a, b) && hi > 2.0 * lo ? std::max(gap, std::max(a.stretch, b.stretch) * de) : gap;
}

/// Whether the edge between the facets two valid rays met goes to the along-track check (the simulator's column
/// record) as an edge of the line: one end's stretch more than six times the other's. Time per radian kinks sharply
/// there, and where the facets turn from one column to the next the kink moves between them as an occlusion's edge
/// does; near nadir, where the facets face the sonar, the echo's level jumps with it. Halving the step records most
/// such edges as located ones, their time gap exceeding three times the smaller end's prediction (on ping 476
/// starboard of the 1 km survey, 97 % of the located edges whose gap the larger stretch accounts for have a ratio
/// above six); a bracket (facet_edge_crossing) leaves no such gap, so it records them by this test, and the two agree
/// about where the along-track check divides.
[[nodiscard]] inline bool facet_edge_marks_line(const tube_end& a, const tube_end& b) noexcept {
    const double lo = std::min(a.stretch, b.stretch), hi = std::max(a.stretch, b.stretch);
    return a.valid && b.valid && facet_edge(a, b) && hi > 6.0 * lo;
}

/// Judges two rays `de` (rad) apart, with sample interval `dt_s`.
/// `stride`: the launch intervals of their column between them (a sparse column, ray_density::along_split_sparse):
/// their gap is an edge where it exceeds the prediction by twice one interval's, as between adjacent rays.
[[nodiscard]] inline tube_verdict judge_tube(const tube_end& a, const tube_end& b, double de, double dt_s,
                                             std::size_t stride = 1) noexcept {
    // A time gap this many times the prediction is an edge: 3 between adjacent rays, 1 + 2 / stride across more.
    const double gap_ratio = 1.0 + 2.0 / double(std::max<std::size_t>(stride, 1));
    const double gap_floor = 0.25 * dt_s;    // a gap below a quarter sample never is
    const double located = located_fraction * dt_s;
    // A tube whose ends' gains differ more is refined, down to tubes this short; finer across a facet's edge.
    const bool across_facets = facet_edge(a, b);
    const double gain_ratio = across_facets ? 1.05 : 1.25;
    const double fine = across_facets ? dt_s / 8.0 : dt_s / 2.0;
    if (!a.valid && !b.valid) return tube_verdict::continuous;
    if (a.valid != b.valid) {
        const tube_end& v = a.valid ? a : b;
        return v.stretch * de <= located ? tube_verdict::located : tube_verdict::split;
    }
    const double gap = std::abs(b.t_s - a.t_s);
    // To second order: near normal incidence the stretch vanishes and time grows as the square of the step,
    // t (1 + de^2 / 2) over a plane facing the ray (second-order term below).
    const double predicted = std::min(a.stretch, b.stretch) * de + 0.5 * std::min(a.t_s, b.t_s) * de * de;
    if (a.object != b.object || a.material != b.material)
        return gap <= located || predicted <= located ? tube_verdict::located : tube_verdict::split;
    if (gap <= gap_floor || gap <= gap_ratio * predicted) {
        // Facets of a rough surface: the trapezoid over depression is good while the scene's gain changes by
        // less than gain_ratio between the rays, or once the tube spans less than a sub-bin of the sampler.
        // Across a facet's edge with one end's echo more than twice the other's, the end's own stretch bounds how
        // far its facet may reach (grazing ends, see the file comment).
        const double lo = std::min(a.gain, b.gain), hi = std::max(a.gain, b.gain);
        return hi > gain_ratio * lo && tube_span(a, b, de) > fine ? tube_verdict::coarse : tube_verdict::continuous;
    }
    return predicted <= located ? tube_verdict::located : tube_verdict::split;
}

/// Where the sheet of rays between two hits crosses the line that their facets' planes share (facet_edge_crossing).
struct facet_crossing {
    double fraction = -1.0;        ///< of the step from a, in (0, 1); -1 when there is no such crossing
    std::array<double, 3> point{}; ///< the crossing (world, m)
};

/// Where the edge between the facets met by two rays lies along their step: the rays leave origin `o` (world, m), a's
/// hit `p_a` lies on the facet of unit geometric normal `n_a`, b's hit `p_b` on that of `n_b`. The hits move over the
/// seabed within the sheet of rays through o, p_a and p_b, and pass from one facet to the other where that sheet meets
/// the line both facets' planes share, X (solved from the three planes by Cramer's rule, relative to o). The launch
/// angle at X divides the step as the angle at o does: exactly for straight rays in one vertical plane (but that the
/// ratio of the angles' sines stands for theirs, off by about the square of the step's angle), and to first order in
/// the step for a cone's column (the launch direction turns smoothly with depression) and for refracted rays (the
/// direction of a hit from the source, likewise). No crossing (fraction -1) where the line does not cross the
/// sheet between the two hits, where the planes are nearly parallel to each other or to the sheet, or where the hits
/// are in line with o. Where other facets lie between the two, X is off the surface: the caller can tell.
[[nodiscard]] inline facet_crossing facet_edge_crossing(const std::array<double, 3>& o, const std::array<double, 3>& p_a,
                                                        const std::array<double, 3>& n_a,
                                                        const std::array<double, 3>& p_b,
                                                        const std::array<double, 3>& n_b) noexcept {
    using v3 = std::array<double, 3>;
    const auto sub = [](const v3& x, const v3& y) { return v3{x[0] - y[0], x[1] - y[1], x[2] - y[2]}; };
    const auto dot = [](const v3& x, const v3& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    const auto cross = [](const v3& x, const v3& y) {
        return v3{x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]};
    };
    const v3 ua = sub(p_a, o), ub = sub(p_b, o);
    const v3 ns = cross(ua, ub); // the sheet's normal
    const double ns_len = std::sqrt(dot(ns, ns));
    if (!(ns_len > 0.0) || !std::isfinite(ns_len)) return {};
    // n_a . x = n_a . ua, n_b . x = n_b . ub, ns . x = 0 (x = X - o).
    const v3 bc = cross(n_b, ns), ca = cross(ns, n_a);
    const double det = dot(n_a, bc);
    if (!(std::abs(det) > 1e-6 * ns_len)) return {}; // the line nearly parallel to the sheet, or the planes alike
    const double r1 = dot(n_a, ua) / det, r2 = dot(n_b, ub) / det;
    const v3 x{r1 * bc[0] + r2 * ca[0], r1 * bc[1] + r2 * ca[1], r1 * bc[2] + r2 * ca[2]};
    // X between the hits as seen from o: on the same turn from ua as ub, and before ub.
    const v3 ax = cross(ua, x), xb = cross(x, ub);
    if (!(dot(ax, ns) > 0.0) || !(dot(xb, ns) > 0.0)) return {};
    // The angles' ratio by their sines' (the step is small: the ratio is off by about the square of the angle).
    const double f = std::sqrt(dot(ax, ax) * dot(ub, ub) / (dot(x, x) * dot(ns, ns)));
    if (!(f > 0.0 && f < 1.0)) return {};
    return {f, {o[0] + x[0], o[1] + x[1], o[2] + x[2]}};
}

/// Whether the facet met at `p` (world, m; unit normal `n`, pointing up) reaches the crossing `x` of
/// facet_edge_crossing, as the seabed's heights say (`height(x_m, y_m)`, world z, m): halfway from x back to p, and a
/// twentieth of the way, the seabed lies in the facet's plane to a tenth of what the other facet's plane (turned from
/// it by `angle`, rad) would differ there. Where another facet lies between the two, the seabed leaves the plane
/// before x. A point is not asked where the rounding of the world coordinates (`eps`, the scene scalar's epsilon, times
/// their size, the facet's slope and a few roundings) is as large as what it must tell apart; false where neither can
/// be (a facet steeper than 84 degrees, a step too small, a footprint too far from the grid's origin to tell).
template <class Height>
[[nodiscard]] bool facet_reaches_crossing(const std::array<double, 3>& x, const std::array<double, 3>& p,
                                          const std::array<double, 3>& n, double angle, double eps, Height&& height) {
    if (!(n[2] > 0.1)) return false;
    const double slope = std::sqrt(n[0] * n[0] + n[1] * n[1]) / n[2];
    const double dx = p[0] - x[0], dy = p[1] - x[1], dz = p[2] - x[2];
    const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
    bool asked = false;
    for (const double t : {0.5, 0.05}) {
        const double qx = x[0] + t * dx, qy = x[1] + t * dy;
        const double plane = p[2] - (n[0] * (qx - p[0]) + n[1] * (qy - p[1])) / n[2];
        const double h = height(qx, qy);
        const double apart = 0.1 * t * angle * d; // a tenth of the other plane's difference
        const double rounding = 4.0 * eps * ((std::abs(qx) + std::abs(qy)) * slope + std::abs(h) + 1.0);
        if (!(rounding < apart)) continue;
        asked = true;
        if (!(std::abs(h - plane) <= apart + rounding)) return false;
    }
    return asked;
}

/// Of two valid rays `de` (rad) apart across a located edge (judge_tube: tube_verdict::located), whether the larger
/// of their stretches still spans more than the located fraction of a sample `dt_s` over the step: the ray between
/// them is then traced so that the grazing end's echo lands where its facet is, not as half the step in one point.
[[nodiscard]] inline bool ends_unresolved(const tube_end& a, const tube_end& b, double de, double dt_s) noexcept {
    return a.valid && b.valid && std::max(a.stretch, b.stretch) * de > located_fraction * dt_s;
}

} // namespace sss::detail

#pragma once
/// \file
/// When two adjacent rays of a column may share their energy as one ray tube, and when the launch angle between
/// them must be bisected to locate an edge (an occlusion, an object's silhouette, a change of surface).
///
/// A ray meeting a facet at angle theta (between the ray and the facet) at two-way time t predicts how fast the
/// time of its neighbours grows with depression: dt/de = t cot theta (s/rad), the footprint r de / sin theta
/// seen along the ray (straight rays; in refracting water a close estimate, which is all a test needs). Two rays
/// de apart on one continuous surface return within a time of about de times that; a time gap many times larger
/// than the smaller of the two predictions means the surface between them is hidden (the first ray grazes a crest,
/// the next lands beyond the shadow) or that they met different parts of the scene. Such a pair is split by the
/// ray between them, recursively, until the side with the smaller prediction spans less than 1/16 of a sample:
/// the edge is then located, and each ray keeps its half of the tiny step as a point.
/// On one surface, a pair whose echo per radian (beam pattern aside) differs by more than a factor of two
/// (facets of a rough seabed facing the sonar differently) is split too, down to tubes of half a sample, so that
/// the trapezoid over depression resolves the relief's shading (finer tubes change the line by less than
/// 0.01 dB RMS on the rough test scenes and cost 10% more rays).
/// A pair whose valid ray's surface would carry on beyond the end of the line (the far edge of coverage) is left
/// as it is: nothing the receiver records lies between them.

#include <algorithm>
#include <cmath>
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
};

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

/// Judges two rays `de` (rad) apart, with sample interval `dt_s` and the line ending at two-way time `t_line_s`.
[[nodiscard]] inline tube_verdict judge_tube(const tube_end& a, const tube_end& b, double de, double dt_s,
                                             double t_line_s) noexcept {
    constexpr double gap_ratio = 3.0;        // a time gap this many times the prediction is an edge
    const double gap_floor = 0.25 * dt_s;    // a gap below a quarter sample never is
    const double located = dt_s / 16.0;      // an edge is located when its sides span less than this
    constexpr double gain_ratio = 1.25;      // a tube whose ends' gains differ more is refined
    const double fine = dt_s / 2.0;          // down to tubes this short
    if (!a.valid && !b.valid) return tube_verdict::continuous;
    if (a.valid != b.valid) {
        const tube_end& v = a.valid ? a : b;
        if (v.t_s + v.stretch * de >= t_line_s) return tube_verdict::continuous; // the far edge of coverage
        return v.stretch * de <= located ? tube_verdict::located : tube_verdict::split;
    }
    const double gap = std::abs(b.t_s - a.t_s);
    const double predicted = std::min(a.stretch, b.stretch) * de;
    if (a.object != b.object || a.material != b.material)
        return gap <= located || predicted <= located ? tube_verdict::located : tube_verdict::split;
    if (gap <= gap_floor || gap <= gap_ratio * predicted) {
        // Facets of a rough surface: the trapezoid over depression is good while the scene's gain changes by
        // less than gain_ratio between the rays, or once the tube spans less than a sub-bin of the sampler.
        const double lo = std::min(a.gain, b.gain), hi = std::max(a.gain, b.gain);
        return hi > gain_ratio * lo && gap > fine ? tube_verdict::coarse : tube_verdict::continuous;
    }
    return predicted <= located ? tube_verdict::located : tube_verdict::split;
}

} // namespace sss::detail

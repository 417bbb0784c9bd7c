#pragma once
/// \file
/// Geometric spreading of a ray tube in a horizontally stratified ocean, differentiated analytically through
/// the layers.
///
/// A point source at depth z_A (speed c_A) launches rays at grazing angle theta0; by cylindrical symmetry the
/// tube between theta0 and theta0 + dtheta0, psi and psi + dpsi holds the solid angle cos(theta0) dtheta0 dpsi,
/// and where it meets depth z at horizontal range r its cross-section normal to the ray is
/// r dpsi |dr/dtheta0|_z sin(theta) dtheta0. Energy conservation gives the intensity relative to that at 1 m
/// (Jensen, Kuperman, Porter & Schmidt, "Computational Ocean Acoustics", 2nd ed. 2011, chapter 3, ray
/// amplitudes by the ray-tube method; the project's physics reference, section 4):
///
///     S_AB = I/I(1 m) = cos(theta0) / (r sin(theta) |dr/dtheta0|_z).
///
/// dr/dtheta0 follows the rays' Snell invariant xi = cos(theta0)/c_A: in a layer of constant gradient g the
/// range between depths z_a and z_b is dx = (sin phi_a - sin phi_b)/(xi g) with phi the signed inclination
/// (+ down) and sin^2 phi = 1 - xi^2 c^2, and differentiating at fixed z_a, z_b gives
///
///     d(dx)/dxi = (1/(g xi^2)) (1/sin phi_b - 1/sin phi_a) = q / (sin phi_a sin phi_b),   q = dx / xi,
///
/// a form that cancels nothing, holds for g = 0 (dx = dz cot phi) and across a turning point inside the layer
/// (then sin phi_a and sin phi_b have opposite signs and the derivative is negative). With dxi/dtheta0 =
/// -sin(theta0)/c_A and r = xi Q, Q = sum of q over the pieces, the formula becomes
///
///     S_AB = c_A^2 / (Q w),   w = |sin phi_hit sum_i q_i sin phi0 / (sin phi_a,i sin phi_b,i)|,
///
/// where, in the first piece, sin phi0 / sin phi_a = 1 exactly, and in the last, sin phi_hit / sin phi_b = 1:
/// so w stays finite for a horizontal launch and for a hit at a turning point. For a vertical ray (xi = 0)
/// q is the limit integral of c dz over the piece. Isovelocity: q = c s per piece, so S_AB = 1/s^2 for path
/// length s. A piece that starts horizontally on a layer boundary (a ray grazing a change of gradient: a shadow
/// boundary, where neighbouring rays part) gives an infinitely wide tube: S_AB = 0. A piece of no length (a ray
/// launched horizontally on a knot, or crossing one) adds nothing and is not counted as the first. At a caustic
/// (neighbouring rays crossing, w -> 0) ray theory's intensity grows without bound where the wave's stays finite
/// (an Airy-function correction would need the frequency): the tube is held no narrower than 1/1000 of the
/// spherical tube of the same Q, so that S_AB is at most 30 dB above c_A^2 / Q^2 (spherical spreading over the
/// path in uniform water). (ray_tube_q computes q.)
///
/// The echo needs the return leg's spreading S_BA, from 1 m off the hit back to the transducer. The tube
/// formula for the reversed ray and xi c_A = cos(theta0), xi c_B = cos(theta_hit) give reciprocity
///
///     S_BA = (c_B / c_A)^2 S_AB,
///
/// which is also what pressure reciprocity says: the pressure-squared loss (c_B/c_A) S_AB is the same both ways.

#include <algorithm>
#include <cmath>

#include "sss/core/types.hpp"

namespace sss::propagation {

/// The q = dx / xi of one piece of ray (m^2/s), from depth change dz_m (m), the speeds c_a_mps, c_b_mps (m/s) and
/// the signed sines sin_a, sin_b of the inclination at its ends: q = dz (c_a + c_b) / (sin_a + sin_b) when the piece
/// does not turn (sin^2 phi = 1 - xi^2 c^2 makes dx = xi (c_a + c_b) dz / (sin_a + sin_b); no xi, so it holds
/// for a vertical ray, where it is the integral of c dz), else range_m / xi_s_per_m (a turning ray is never
/// near vertical, so xi is well away from 0 there).
template <Real T>
[[nodiscard]] inline T ray_tube_q(T range_m, T xi_s_per_m, T dz_m, T c_a_mps, T c_b_mps, T sin_a, T sin_b) noexcept {
    if (sin_a * sin_b > T(0)) return dz_m * (c_a_mps + c_b_mps) / (sin_a + sin_b);
    return xi_s_per_m > T(0) ? range_m / xi_s_per_m : T(0);
}

/// Accumulates the sums of the file comment over the pieces of one ray. Plain data.
template <Real T> struct ray_tube {
    T source_speed_mps{}; ///< c_A (m/s)
    T sin_launch{};       ///< sin phi0 of the launch (signed, + down)
    T q_sum{};            ///< Q over the completed pieces (m^2/s)
    T k_sum{};            ///< sum of q_i sin phi0 / (sin phi_a,i sin phi_b,i) over the completed pieces (m^2/s)
    bool started{false};  ///< a piece of some length has been completed

    /// The most a tube may focus: w >= Q / max_focusing (see the file comment; 30 dB).
    static constexpr T max_focusing = T(1000);

    /// Adds a completed piece: its q and the signed sines of its inclination at start and end. A piece of no length
    /// (q = 0) adds nothing: the next piece starts where the ray started, as the first.
    void add_piece(T q, T sin_start, T sin_end) noexcept {
        if (q == T(0)) return;
        const T lead = started ? sin_launch / sin_start : T(1);
        q_sum += q;
        k_sum += q * lead / sin_end;
        started = true;
    }

    /// 1/(Q w) at a hit inside the current piece (arguments as for outgoing_spreading): S_AB = c_A^2/(Q w) and, by
    /// reciprocity, S_BA = c_B^2/(Q w) with c_B the speed at the hit; one division for both. Not finite where Q w
    /// is undefined, where outgoing_spreading gives 0 (callers do the same); w held at least Q / max_focusing.
    [[nodiscard]] T inverse_qw(T q_last, T sin_start, T sin_hit) const noexcept {
        // w = den / num, den = |sin_hit K sin_start + q_last sin_launch| and num = |sin_start| once started: the
        // division by sin_start folded into the one that inverts Q w.
        const T q = q_sum + q_last;
        const T num = started ? std::abs(sin_start) : T(1);
        T den = started ? std::abs(sin_hit * k_sum * sin_start + q_last * sin_launch) : std::abs(sin_hit * k_sum + q_last);
        den = std::max(den, num * q / max_focusing);
        return num / (q * den);
    }

    /// S_AB at a hit inside the current piece, which has q = q_last so far, started at sin phi = sin_start and
    /// reaches the hit at sin phi = sin_hit: intensity relative to that at 1 m from the source. 0 where the tube
    /// is infinitely wide, at most max_focusing c_A^2 / Q^2 at a caustic (see the file comment).
    [[nodiscard]] T outgoing_spreading(T q_last, T sin_start, T sin_hit) const noexcept {
        const T lead = started ? sin_launch / sin_start : T(1);
        const T q = q_sum + q_last;
        const T w = std::max(std::abs(sin_hit * k_sum + q_last * lead), q / max_focusing);
        const T s = source_speed_mps * source_speed_mps / (q * w);
        return std::isfinite(s) ? s : T(0);
    }
};

} // namespace sss::propagation

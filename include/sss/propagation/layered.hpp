#pragma once
/// \file
/// Layered water: rays refracted through a piecewise-linear sound-speed profile, with absorption that depends
/// on depth and spreading from the ray tube.
///
/// Depth reference. The profile (profile.hpp) is in depth, positive down from the sea surface; the world is
/// z up. `layered_params::surface_z_m` is the world z of the sea surface, and a point at world z lies at depth
/// surface_z_m - z. A ray must start in the water (depth >= 0); a ray that climbs back to the surface ends
/// there (surface reflection is not modelled) and meets nothing.
///
/// Tracing. The ray is stepped from layer to layer with the exact constant-gradient arcs of ray_arc.hpp
/// (turning points included); each arc that can reach the scene (deeper than the scene's top_m) is handed to
/// the scene as chords of sagitta at most `chord_tolerance_m`, and the chord's hit is moved onto the arc
/// (arc_intersection.hpp): on planar facets the hit point, path length and time are exact to rounding.
/// Time and horizontal range are sums of the arcs' closed forms; the arrival direction is the bent ray's
/// tangent at the hit, so grazing angles come out right.
///
/// Absorption. alpha(z) (dB/km) from Francois & Garrison (1982) or Ainslie & McColm (1998) (absorption.hpp),
/// with the water's temperature, salinity and pH held constant and the depth varying along the path, is
/// integrated over each arc by three-point Gauss-Legendre in arc length, exact for alpha quintic in arc length.
/// alpha varies with depth on kilometre scales (Francois-Garrison's pressure terms are quadratic in depth,
/// Ainslie-McColm's exponentials have scales of 6 and 17 km), so the rule's error is far below rounding on
/// sonar paths and about 1e-11 relative on a 1000 m vertical arc (tests/propagation/test_layered.cpp).
/// The formula is chosen at run time (`absorption_formula`): the switch costs one predictable branch per
/// evaluation, three per arc, against about ten transcendental functions per arc for the ray itself, and it keeps
/// `layered<T>` a template of T alone, as the policy machinery (rebinding a policy to another scalar type)
/// expects. Francois-Garrison is the default: it is the reference formula, and with its transcendentals
/// evaluated once at construction it is the cheaper of the two per depth here (Ainslie-McColm needs two
/// exponentials per depth).
///
/// Spreading (ray_tube.hpp). `path::spreading` is the return leg's S_BA: intensity back at the transducer
/// relative to that 1 m off the hit. The echo of a footprint needs exactly that one: the outgoing tube S_AB
/// sets the footprint's area (1/S_AB per steradian) and its incident intensity (S_AB), and the two cancel;
/// S_BA = (c_hit/c_source)^2 S_AB by reciprocity. In isovelocity water both are 1/r^2. S_AB itself is in
/// `layered_path::outgoing_spreading`.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/propagation/absorption.hpp"
#include "sss/propagation/arc_intersection.hpp"
#include "sss/propagation/concept.hpp"
#include "sss/propagation/profile.hpp"
#include "sss/propagation/ray_arc.hpp"
#include "sss/propagation/ray_tube.hpp"
#include "sss/scene/concept.hpp"

namespace sss::propagation {

/// Which published absorption formula layered water uses.
enum class absorption_formula : unsigned char { francois_garrison = 0, ainslie_mccolm = 1 };

template <Real T> struct layered_params {
    T surface_z_m = T(0);              ///< world z of the sea surface (m): depth = surface_z_m - z
    T frequency_hz = T(300000);        ///< acoustic frequency for absorption (Hz)
    water_properties<T> water{};       ///< temperature, salinity, pH for absorption
    absorption_formula absorption = absorption_formula::francois_garrison;
    T chord_tolerance_m = T(1e-3);     ///< largest distance between an arc and the chords handed to the scene (m)
    T reference_speed_mps = T(0);      ///< speed for sampling (m/s); 0: the water column's harmonic mean
};

/// Everything a layered trace knows about one path. Plain data.
template <Real T> struct layered_path {
    path<T> result{};           ///< what `trace` returns (spreading: the return leg's, see the file comment)
    T outgoing_spreading{};     ///< S_AB: intensity at the hit relative to that 1 m from the source
    T source_speed_mps{};       ///< c at the source (m/s)
    T hit_speed_mps{};          ///< c at the hit (m/s)
    T range_m{};                ///< horizontal distance from the source to the hit (m)
    T path_length_m{};          ///< arc length from the source to the hit (m)
    std::size_t arcs = 0;       ///< layer arcs followed, the last one included
    std::size_t chords = 0;     ///< calls to the scene's intersect
};

template <Real T> class layered {
public:
    using value_type = T;

    /// Throws sss::invalid_parameter naming the field ("layered.frequency_hz", ...) for a non-finite surface_z_m,
    /// a frequency or chord tolerance not > 0, water outside check_water_properties ("water.temperature_c", ...),
    /// or a negative or non-finite reference speed.
    explicit layered(sound_speed_profile<T> profile, const layered_params<T>& p = {})
        : profile_(std::move(profile)), p_(validated(p)), fg_(p.frequency_hz, p.water), am_(p.frequency_hz, p.water) {
        layers_.reserve(profile_.layer_count());
        for (std::size_t i = 0; i < profile_.layer_count(); ++i) {
            gradient_layer<T> l = profile_.layer(i);
            // The water ends at the surface: clip the layers to depth >= 0 (layers wholly above never get used).
            l.z_top_m = std::max(l.z_top_m, T(0));
            l.z_bottom_m = std::max(l.z_bottom_m, T(0));
            layers_.push_back(l);
        }
        c_ref_ = p.reference_speed_mps > T(0) ? p.reference_speed_mps : harmonic_mean_speed();
    }

    [[nodiscard]] const sound_speed_profile<T>& profile() const noexcept { return profile_; }
    [[nodiscard]] const layered_params<T>& params() const noexcept { return p_; }

    /// The speed that converts the receiver's range to time and steers ray sampling (m/s): the given
    /// reference_speed_mps, or by default the harmonic mean of c over the water column from the surface to the
    /// deepest knot, depth / integral dz/c (the speed of a vertical ray's average); c(0) when that column is
    /// empty (all knots at or above the surface).
    [[nodiscard]] T reference_speed_mps() const noexcept { return c_ref_; }

    /// Absorption (dB/km) at depth_m (m) with the chosen formula.
    [[nodiscard]] T absorption_db_per_km(T depth_m) const noexcept {
        return p_.absorption == absorption_formula::francois_garrison ? fg_.db_per_km(depth_m) : am_.db_per_km(depth_m);
    }

    /// The ray followed through the water until it meets the scene within one-way time t_max_s (s).
    /// Throws sss::invalid_parameter ("ray.origin") for a ray starting above the sea surface.
    template <Scene S>
    [[nodiscard]] std::optional<path<T>> trace(const ray<T>& r, const S& scene, T t_max_s) const {
        auto p = trace_path(r, scene, t_max_s);
        if (!p) return std::nullopt;
        return p->result;
    }

    /// As `trace`, with the details of the path.
    template <Scene S>
    [[nodiscard]] std::optional<layered_path<T>> trace_path(const ray<T>& r, const S& scene, T t_max_s) const {
        constexpr T inf = std::numeric_limits<T>::infinity();
        constexpr T eps = std::numeric_limits<T>::epsilon();
        const T depth0 = p_.surface_z_m - r.origin.z;
        if (!(depth0 >= T(0)))
            throw invalid_parameter("ray.origin", "lies above the sea surface (world z " + std::to_string(r.origin.z) +
                                                      " > layered.surface_z_m " + std::to_string(p_.surface_z_m) + ")");
        if (!(t_max_s > T(0))) return std::nullopt;

        const T hlen = std::hypot(r.direction.x, r.direction.y);
        const vec3<T> hdir = hlen > T(0) ? vec3<T>{r.direction.x / hlen, r.direction.y / hlen, T(0)}
                                         : vec3<T>{T(1), T(0), T(0)};
        T z = depth0;
        T phi = std::atan2(-r.direction.z, hlen);
        std::size_t i = profile_.layer_index(z, phi < T(0) ? vertical_direction::up : vertical_direction::down);

        // Geometry lies at depths >= top_depth; chords start a margin above it.
        const T top_depth = p_.surface_z_m - scene.top_m();
        const T margin = std::max(p_.chord_tolerance_m, T(64) * eps * (std::abs(p_.surface_z_m) + std::abs(scene.top_m())));
        const T chord_depth = top_depth - margin;

        layered_path<T> out;
        out.source_speed_mps = layers_[i].speed_mps(z);
        ray_tube<T> tube{out.source_speed_mps, std::sin(phi)};
        T t = 0, x = 0, s_total = 0, absorption_db = 0;
        int zero_steps = 0;
        constexpr std::size_t max_arcs = std::size_t(1) << 24;

        for (std::size_t n_arcs = 0; n_arcs < max_arcs; ++n_arcs) {
            const gradient_layer<T>& layer = layers_[i];
            layer_step<T> st;
            if (zero_steps >= 2) {
                // Horizontal on a knot whose two layers both bend it back: it runs along the knot.
                const T c = layer.speed_mps(z);
                st.arc = {z, c, T(0), T(0), inf};
                st.exit = {z, inf, inf, inf, T(0)};
                st.boundary = layer_exit::none;
            } else {
                st = step_through_layer(layer, z, std::abs(phi), phi < T(0) ? vertical_direction::up : vertical_direction::down);
            }
            const ray_arc<T>& arc = st.arc;
            ++out.arcs;
            const T sin_a = std::sin(arc.start_incline_rad);
            const T cos_a = std::max(std::cos(arc.start_incline_rad), T(0));
            const T xi = cos_a / arc.start_speed_mps;
            const T kappa = xi * arc.gradient_per_s;
            const arc_frame<T> frame{vec3<T>{r.origin.x + hdir.x * x, r.origin.y + hdir.y * x, p_.surface_z_m - arc.start_depth_m},
                                     hdir};

            // Path length the time left allows in this layer (c is largest at one of its bounds).
            const T c_max = layer.gradient_per_s == T(0)
                                ? layer.c_ref_mps
                                : std::max(layer.speed_mps(layer.z_top_m), layer.speed_mps(layer.z_bottom_m));
            const T s_cap = c_max * (t_max_s - t);
            const T s_end = std::min(arc.length_m, s_cap);

            if (const auto s_begin = chord_start(st, kappa, chord_depth, s_end)) {
                if (auto h = intersect_arc(scene, arc, frame, *s_begin, s_end, p_.chord_tolerance_m, out.chords)) {
                    const arc_sample<T> at = arc_point(arc, h->arc_m);
                    const T t_hit = t + at.time_s;
                    if (!(t_hit <= t_max_s)) return std::nullopt;
                    const arc_offset<T>& o = h->at;
                    const T depth_hit = arc.start_depth_m + o.depth_m;
                    out.hit_speed_mps = layer.speed_mps(depth_hit);
                    const T q = ray_tube_q(o.range_m, xi, h->arc_m, arc.start_speed_mps, out.hit_speed_mps);
                    out.outgoing_spreading = tube.outgoing_spreading(q, sin_a, o.sin_incline);
                    const T ratio = out.hit_speed_mps / out.source_speed_mps;
                    absorption_db += arc_absorption_db(arc.start_depth_m, sin_a, cos_a, kappa, h->arc_m);
                    out.range_m = x + o.range_m;
                    out.path_length_m = s_total + h->arc_m;
                    out.result.surface = h->surface;
                    out.result.surface.distance_m = out.path_length_m;
                    out.result.time_s = t_hit;
                    out.result.spreading = out.outgoing_spreading * ratio * ratio;
                    out.result.absorption = std::exp(-ln10_v<T> / T(10) * absorption_db);
                    out.result.arrival = hdir * o.cos_incline + vec3<T>{T(0), T(0), -o.sin_incline};
                    return out;
                }
            }
            if (st.boundary == layer_exit::none || !(arc.length_m <= s_cap)) return std::nullopt;

            // Through the layer: accumulate and move on.
            const arc_sample<T>& e = st.exit;
            const T c_exit = layer.speed_mps(e.depth_m);
            tube.add_piece(ray_tube_q(e.range_m, xi, e.arc_m, arc.start_speed_mps, c_exit), sin_a, std::sin(e.incline_rad));
            absorption_db += arc_absorption_db(arc.start_depth_m, sin_a, cos_a, kappa, e.arc_m);
            t += e.time_s;
            x += e.range_m;
            s_total += e.arc_m;
            zero_steps = e.arc_m == T(0) ? zero_steps + 1 : 0;
            z = e.depth_m;
            phi = e.incline_rad;
            if (st.boundary == layer_exit::bottom) {
                ++i;
            } else {
                if (layer.z_top_m <= T(0) || i == 0) return std::nullopt; // reached the sea surface
                --i;
            }
            if (!(t <= t_max_s)) return std::nullopt;
        }
        return std::nullopt;
    }

private:
    static const layered_params<T>& validated(const layered_params<T>& p) {
        sss::detail::require_finite(p.surface_z_m, "layered.surface_z_m");
        sss::detail::require_positive(p.frequency_hz, "layered.frequency_hz");
        check_water_properties(p.water);
        sss::detail::require_positive(p.chord_tolerance_m, "layered.chord_tolerance_m");
        sss::detail::require_non_negative(p.reference_speed_mps, "layered.reference_speed_mps");
        sss::detail::require(p.absorption == absorption_formula::francois_garrison ||
                                 p.absorption == absorption_formula::ainslie_mccolm,
                             "layered.absorption", "is not a known formula");
        return p;
    }

    /// Arc length from which the arc may meet geometry (it is at depth >= chord_depth there), or nullopt when it
    /// stays shallower than chord_depth up to s_end.
    [[nodiscard]] static std::optional<T> chord_start(const layer_step<T>& st, T kappa, T chord_depth, T s_end) noexcept {
        const ray_arc<T>& arc = st.arc;
        if (!(s_end > T(0))) return std::nullopt;
        if (arc.start_depth_m >= chord_depth) return T(0);
        // The deepest point of the arc: its turning point when it turns while going down, else its end.
        const T phi_a = arc.start_incline_rad;
        T deepest = st.exit.depth_m;
        if (st.turned && phi_a > T(0)) {
            const T sh = std::sin(phi_a / T(2));
            deepest = arc.start_depth_m + T(2) * sh * sh / kappa;
        }
        if (!(deepest >= chord_depth)) return std::nullopt;
        const auto p = arc_point_at_depth(arc, chord_depth);
        if (!p || !(p->arc_m < s_end)) return std::nullopt;
        return p->arc_m;
    }

    /// One-way absorption (dB) along the first len_m (m) of an arc starting at depth z0_m with inclination
    /// (sin_a, cos_a) and curvature kappa (1/m): three-point Gauss-Legendre in arc length (file comment).
    [[nodiscard]] T arc_absorption_db(T z0_m, T sin_a, T cos_a, T kappa, T len_m) const noexcept {
        if (!(len_m > T(0))) return T(0);
        const T half = len_m / T(2);
        const T off = half * T(0.774596669241483377035853079956479922L); // sqrt(3/5)
        const auto alpha = [&](T s) {
            return absorption_db_per_km(std::max(z0_m + offset_along_arc(sin_a, cos_a, kappa, s).depth_m, T(0)));
        };
        const T mean = (T(5) * (alpha(half - off) + alpha(half + off)) + T(8) * alpha(half)) / T(18);
        return mean * len_m / T(1000);
    }

    /// depth / integral_0^depth dz/c over the water column down to the deepest knot.
    [[nodiscard]] T harmonic_mean_speed() const noexcept {
        const auto depths = profile_.depths_m();
        const T bottom = depths.back();
        if (!(bottom > T(0))) return profile_.speed_mps(T(0));
        T slowness = 0; // integral of dz/c (s)
        for (const gradient_layer<T>& l : layers_) {
            const T a = std::max(l.z_top_m, T(0)), b = std::min(l.z_bottom_m, bottom);
            if (!(b > a)) continue;
            const T ca = l.speed_mps(a);
            const T e = l.gradient_per_s * (b - a) / ca; // c(b)/c(a) - 1
            slowness += (b - a) / ca * (std::abs(e) < T(1e-4) ? T(1) - e / T(2) + e * e / T(3) : std::log1p(e) / e);
        }
        return bottom / slowness;
    }

    sound_speed_profile<T> profile_;
    layered_params<T> p_;
    francois_garrison<T> fg_;
    ainslie_mccolm<T> am_;
    std::vector<gradient_layer<T>> layers_;
    T c_ref_{};
};

static_assert(Propagation<layered<float>> && Propagation<layered<double>>);

} // namespace sss::propagation

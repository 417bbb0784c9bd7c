#pragma once
/// \file
/// Layered water: rays refracted through a piecewise-linear sound-speed profile, with absorption that depends
/// on depth and spreading from the ray tube. Design notes, the reasoning behind the choices below and measured
/// costs: docs/design/layered.md.
///
/// Depth reference. The profile (profile.hpp) is in depth, positive down from the sea surface; the world is
/// z up. `layered_params::surface_z_m` is the world z of the sea surface, and a point at world z lies at depth
/// surface_z_m - z. A ray must start in the water (depth >= 0); a ray that climbs back to the surface ends
/// there (surface reflection is not modelled) and meets nothing.
///
/// Tracing. The ray is stepped from layer to layer with the exact constant-gradient arcs of ray_arc.hpp
/// (turning points included); each arc that can reach the scene (deeper than the scene's top_m) is handed to
/// the scene as chords of sagitta at most `chord_tolerance_m`, and the chord's hit is moved onto the arc
/// (arc_intersection.hpp): on planar facets the hit point, path length and time are exact to rounding. A scene that
/// meets arcs itself (ArcScene: a height field, or a scene of one and objects) is handed each such arc whole instead,
/// and meets it on the arc (scene/height_field_arc.hpp), its objects still by chords up to that hit: one or two walks
/// of the grid per layer (the stretch the arc surely stays in the layer, then the rest) rather than one per chord,
/// and the hit on the arc itself rather than on a chord within tolerance of it (the same to far below the tolerance,
/// save where the arc grazes a crest the chords pass, or the reverse).
/// The arrival direction is the bent ray's tangent at the hit, so grazing angles come out right. Over a GuidedScene
/// a ray traced beside a steeper neighbour from the same origin (the rays of a column in trace_many, the refinement's
/// rays in trace_beside) skips the chords its neighbour's path vouches for, and a ResumableScene starts its walk along the
/// chord that reaches past them after the part of it vouched for too (intersect_after): the same hit, in fewer chords
/// and cells; an ArcScene starts the arc's walk from there (intersect_arc), with the same hit whatever the start.
///
/// Absorption. alpha(z) (dB/km) from Francois & Garrison (1982, JASA 72, 896-907 and 1879-1890) or Ainslie &
/// McColm (1998, JASA 103, 1671-1672) (absorption.hpp), with temperature, salinity and pH held constant and the
/// depth varying along the path, integrated over each arc by three-point Gauss-Legendre in arc length.
///
/// Launch table (launch_table.hpp, `launch_table = true` by default). Above the scene's top_m the water alone
/// decides a ray's path, so rays are looked up in a table over launch angle built for the current source depth
/// and scene top and validated against exact tracing (1e-10 relative in double, 64 epsilons in float). A result
/// depends only on the ray, the scene's top and the water, never on which rays came before or on the thread.
/// Hidden state: the tables live in a `thread_local` cache (the last four per thread, keyed by a per-water id
/// that copies share), filled by the `const` trace methods. It is invisible in results, holds up to four tables
/// per thread for the life of the thread, and lets threads share one `layered` without locks; turn the table off
/// for rays from ever-changing origins, where it would be rebuilt for nearly every ray.
///
/// Spreading (ray_tube.hpp). `path::spreading` is the return leg's S_BA: intensity back at the transducer
/// relative to that 1 m off the hit; S_AB is in `layered_path::outgoing_spreading`.

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/propagation/absorption.hpp"
#include "sss/propagation/arc_intersection.hpp"
#include "sss/propagation/concept.hpp"
#include "sss/propagation/launch_table.hpp"
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
    /// Largest distance between an arc and the chords handed to the scene (m). A ray that passes an edge (a crest
    /// at grazing incidence) closer than this may be taken to meet it or not (docs/design/layered.md). Over an
    /// ArcScene only its objects take chords.
    T chord_tolerance_m = T(1e-4);
    T reference_speed_mps = T(0);      ///< speed for sampling (m/s); 0: the water column's harmonic mean
    bool launch_table = true;          ///< look rays up in a per-ping launch table above the geometry (file comment)
    /// Where the scene can clear a thick segment in one query (ClearanceScene), ask it about windows of chords in
    /// open water before tracing them one by one (propagation/arc_intersection.hpp): the same hits, fewer queries.
    /// It pays where rays cross open water in many short chords (strong gradients near the seabed, a scene whose top
    /// lies well above the seabed); where rays run close to the seabed all the way it can cost a little more
    /// (docs/design/layered.md). Not used over an ArcScene, whose seabed is walked along the arc.
    bool clear_open_water = true;
    /// Over a GuidedScene, skip the chords a steeper neighbour's path vouches for (trace_beside, and the rays of a
    /// column in trace_many): the same hits, fewer chords (docs/design/layered.md). Off: every ray is traced alone.
    bool follow_neighbours = true;
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
    std::size_t chords = 0;     ///< chords handed to the scene (intersect, intersect_after; over an ArcScene, its objects)
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
        id_ = next_id_.fetch_add(1, std::memory_order_relaxed);
    }

    [[nodiscard]] const sound_speed_profile<T>& profile() const noexcept { return profile_; }
    [[nodiscard]] const layered_params<T>& params() const noexcept { return p_; }

    /// The speed that converts the receiver's range to time and steers ray sampling (m/s): the given
    /// reference_speed_mps, or by default the harmonic mean of c over the water column from the surface to the
    /// deepest knot, depth / integral dz/c (the speed of a vertical ray's average); c(0) when that column is
    /// empty (all knots at or above the surface).
    [[nodiscard]] T reference_speed_mps() const noexcept { return c_ref_; }

    /// c_max^2 / c(z) (m/s), c_max the fastest speed of the profile (ReachBoundedPropagation): a ray stays in the
    /// vertical plane of its launch, and by Snell's law (cos(theta) / c constant, theta the inclination) it moves
    /// horizontally at c cos(theta) = c^2 cos(theta_0) / c(z) <= (c_max^2 / c(z)) cos(theta_0); its path, at speed at
    /// most c_max <= c_max^2 / c(z), is no longer.
    [[nodiscard]] T reach_speed_mps(T origin_z) const noexcept {
        const T depth = std::max(p_.surface_z_m - origin_z, T(0));
        T c_max = T(0);
        for (const T c : profile_.speeds_mps()) c_max = std::max(c_max, c);
        const T c0 = profile_.speed_mps(depth);
        return c_max * (c_max / c0);
    }

    /// Absorption (dB/km) at depth_m (m) with the chosen formula.
    [[nodiscard]] T absorption_db_per_km(T depth_m) const noexcept {
        return p_.absorption == absorption_formula::francois_garrison ? fg_.db_per_km(depth_m) : am_.db_per_km(depth_m);
    }

    /// The ray followed through the water until it meets the scene within one-way time t_max_s (s).
    /// Throws sss::invalid_parameter ("ray.origin") for a ray starting above the sea surface or not at a finite
    /// point. A ray without a direction (zero or not finite) meets nothing.
    template <Scene S>
    [[nodiscard]] std::optional<path<T>> trace(const ray<T>& r, const S& scene, T t_max_s) const {
        std::optional<path<T>> out;
        march m;
        vec3<T> hdir;
        const trace_start st = start_for(r.origin.z, scene);
        if (launch(r, t_max_s, st, m, hdir)) (void)follow(m, r, hdir, scene, t_max_s, st.chord_depth, out, nullptr);
        return out;
    }

    /// trace(r, scene, t_max_s), bit for bit (GuidedPropagation), given that the ray launched from r's origin along the
    /// unit direction a_launch met nothing within horizontal distance a_clear_range_m (m) of the origin. Over a
    /// GuidedScene the chords within the horizontal distance the scene clears for r (clear_range_beside_m, from the
    /// bound below) are skipped: the walk starts about where the neighbour met the scene, and the chords it traces are
    /// the plain walk's. Any other scene, or a pair the bound does not cover, is traced as by trace.
    ///
    /// The bound (beside_rays). Both rays go down, a the steeper, and neither can level off below the source
    /// (p c_max < 1, p = cos(phi) / c the ray parameter, Snell's invariant; c_min, c_max the slowest and fastest water
    /// from the source down). A ray reaches depth d at horizontal distance X(d, p) = integral from d0 to d of
    /// p c / sqrt(1 - p^2 c^2) dz, and dX/dp = integral of c (1 - p^2 c^2)^(-3/2) dz >= c_min (d - d0) / s^3, s the
    /// largest sine of inclination any ray with parameter at least p_a has (sqrt(1 - p_a^2 c_min^2)). So at a's depth
    /// d, r arrives at least (p_r - p_a) c_min (d - d0) / s^3 further out; coming down at least t_r per metre there
    /// (t = the least tan(phi) along a ray, sqrt(1 - p^2 c_max^2) / (p c_max)), it lies that much times t_r above a at
    /// a's horizontal distance rho, where a has come down at least t_a rho:
    ///     gain = t_r t_a c_min (p_r - p_a) / s^3,
    /// which in isovelocity water is tan(phi_a) - tan(phi_r) to first order in the difference. The margin holds both
    /// rays' chords (within tolerance / cos(phi) of their arcs vertically, cos(phi) >= p_a c_min) and the launch
    /// table's error in range (its validation tolerance, relative to the path length), times the steepest slope.
    template <Scene S>
    [[nodiscard]] std::optional<path<T>> trace_beside(const ray<T>& r, const S& scene, T t_max_s, const vec3<T>& a_launch,
                                                      T a_clear_range_m) const {
        return trace_guided(r, scene, t_max_s, {&a_launch, a_clear_range_m}, {nullptr, T(0)});
    }

    /// trace(r, scene, t_max_s), bit for bit, beside a (as above) where the bound gives r some distance, and beside b
    /// where it does not. The bound's margin (the chords' tolerance) outweighs the gain of a neighbour very close to r:
    /// the simulator's refinement passes the nearer steeper ray of the pair r is launched between as a, and the steeper
    /// ray of the first interval it refines as b, whose larger gain still carries r's walk to about where b met the
    /// scene.
    template <Scene S>
    [[nodiscard]] std::optional<path<T>> trace_beside(const ray<T>& r, const S& scene, T t_max_s, const vec3<T>& a_launch,
                                                      T a_clear_range_m, const vec3<T>& b_launch, T b_clear_range_m) const {
        return trace_guided(r, scene, t_max_s, {&a_launch, a_clear_range_m}, {&b_launch, b_clear_range_m});
    }

    /// paths[k] = trace(rays[k], scene, t_max_s) for every k, bit for bit (the BatchPropagation method). The rays of a
    /// column share their origin, so the launch table and the depths it depends on are found once per origin depth
    /// rather than once per ray; and the rays are launched a block at a time, so that the table lookups, independent
    /// of one another, overlap. Over a GuidedScene the rays are followed from the steeper end of the span, each beside
    /// the last one before it that met the scene, as trace_beside follows them. `paths` must hold at least rays.size()
    /// slots.
    template <Scene S>
    void trace_many(std::span<const ray<T>> rays, const S& scene, T t_max_s, std::span<std::optional<path<T>>> paths) const {
        sss::require(paths.size() >= rays.size(), "layered.trace_many.paths",
                     [&] { return "must hold a slot per ray (" + std::to_string(rays.size()) + "), got " + std::to_string(paths.size()); });
        constexpr std::size_t block = 16;
        const std::size_t n = rays.size();
        // From the steeper end (a column comes ordered by depression either way).
        const bool guided = GuidedScene<S> && p_.follow_neighbours;
        const bool reverse = guided && n > 1 && rays[n - 1].direction.z < rays[0].direction.z;
        const auto at = [&](std::size_t j) { return reverse ? n - 1 - j : j; };
        std::optional<trace_start> st;
        march m[block];
        vec3<T> hdir[block];
        T chord_depth[block];
        water_below water{};
        bool alive[block];
        std::size_t guide = n; // the last ray followed that met the scene (none yet)
        for (std::size_t first = 0; first < n; first += block) {
            const std::size_t count = std::min(block, n - first);
            for (std::size_t i = 0; i < count; ++i) {
                const ray<T>& r = rays[at(first + i)];
                if (!st || st->origin_z != r.origin.z) {
                    st = start_for(r.origin.z, scene);
                    if constexpr (GuidedScene<S>) water = water_for(*st);
                }
                alive[i] = launch(r, t_max_s, *st, m[i], hdir[i]);
                chord_depth[i] = st->chord_depth;
            }
            for (std::size_t i = 0; i < count; ++i) {
                const std::size_t k = at(first + i);
                std::optional<path<T>>& slot = paths[k];
                slot.reset();
                if (!alive[i]) continue;
                T clear = T(0);
                if constexpr (GuidedScene<S>) {
                    if (guided && guide < n && rays[guide].origin == rays[k].origin)
                        if (const auto b = beside(rays[k], hdir[i], rays[guide].direction, paths[guide]->clear_range_m, water))
                            clear = scene.clear_range_beside_m(*b);
                }
                (void)follow(m[i], rays[k], hdir[i], scene, t_max_s, chord_depth[i], slot, nullptr, clear);
                if (slot) guide = k;
            }
        }
    }

    /// The world height (m) of the ray launched along r where it has gone range_m horizontally from its origin along
    /// its heading (RangeHeightPropagation): the arc through that range, layer by layer, with no scene; none where it
    /// does not get there within one-way time t_max_s (it reached the sea surface or ran out of time first). The ray
    /// stays in the vertical plane of its launch and its range only grows, so the point is unique. Throws as `trace`
    /// for a ray starting above the sea surface.
    [[nodiscard]] std::optional<T> height_at_range_m(const ray<T>& r, T range_m, T t_max_s) const {
        if (!(range_m >= T(0))) return std::nullopt;
        const trace_start st = start_above(r.origin.z, std::numeric_limits<T>::infinity()); // no skipping: any range may be asked
        march m;
        vec3<T> hdir;
        if (!launch(r, t_max_s, st, m, hdir)) return std::nullopt;
        int zero_steps = 0;
        for (std::size_t n_arcs = 0; n_arcs < (std::size_t(1) << 24); ++n_arcs) {
            const gradient_layer<T>& layer = layers_[m.layer];
            if (!m.phi_known) {
                m.phi = std::atan2(m.sin_phi, m.cos_phi);
                m.phi_known = true;
            }
            layer_step<T> step;
            if (zero_steps >= 2) { // horizontal along a knot, as `follow` runs it
                m.phi = m.sin_phi = T(0);
                m.cos_phi = T(1);
                step.arc = {m.z, layer.speed_mps(m.z), T(0), T(0), std::numeric_limits<T>::infinity()};
                step.boundary = layer_exit::none;
            } else {
                step = step_through_layer(layer, m.z, std::abs(m.phi), m.phi < T(0) ? vertical_direction::up : vertical_direction::down);
            }
            const T left_m = range_m - m.x;
            if (step.boundary == layer_exit::none || !(step.exit.range_m < left_m)) {
                auto at = arc_point_at_range(step.arc, std::max(left_m, T(0)));
                // (A range within rounding of where the ray leaves the layer: the exit.)
                if (!at && step.boundary != layer_exit::none) at = step.exit;
                if (!at || !(m.t + at->time_s <= t_max_s)) return std::nullopt;
                return p_.surface_z_m - at->depth_m;
            }
            const bool top = step.boundary == layer_exit::top;
            if (top && (layer.z_top_m <= T(0) || m.layer == 0)) return std::nullopt; // reached the sea surface
            const T g = layer.gradient_per_s, c0 = layer.speed_mps(m.z), xi = m.cos_phi / c0;
            advance(m, detail::arc_start<T>{m.z, c0, m.phi, m.sin_phi, m.cos_phi, g, xi, xi * g}, step, layer);
            zero_steps = step.exit.arc_m == T(0) ? zero_steps + 1 : 0;
            if (top) --m.layer;
            else ++m.layer;
            if (!(m.t <= t_max_s)) return std::nullopt;
        }
        return std::nullopt;
    }

    /// As `trace`, with the details of the path.
    template <Scene S>
    [[nodiscard]] std::optional<layered_path<T>> trace_path(const ray<T>& r, const S& scene, T t_max_s) const {
        std::optional<path<T>> result;
        march m;
        vec3<T> hdir;
        details d{};
        const trace_start st = start_for(r.origin.z, scene);
        if (!launch(r, t_max_s, st, m, hdir) || !follow(m, r, hdir, scene, t_max_s, st.chord_depth, result, &d))
            return std::nullopt;
        return layered_path<T>{*result, d.outgoing_spreading, m.tube.source_speed_mps, d.hit_speed_mps, d.range_m,
                               d.path_length_m, m.arcs, m.chords};
    }

private:
    /// What every ray from one origin depth over one scene shares: the depth from which chords are handed to the
    /// scene, and the launch table to it (null where none applies).
    struct trace_start;
    struct march;

    /// A neighbour that may guide a ray (trace_beside): its launch direction and its path's clear_range_m; none when
    /// `launch` is null.
    struct guide_ray {
        const vec3<T>* launch;
        T clear_range_m;
    };

    /// trace_beside with guides a, then b where a gives no distance.
    template <Scene S>
    [[nodiscard]] std::optional<path<T>> trace_guided(const ray<T>& r, const S& scene, T t_max_s, guide_ray a,
                                                      guide_ray b) const {
        std::optional<path<T>> out;
        march m;
        vec3<T> hdir;
        const trace_start st = start_for(r.origin.z, scene);
        if (!launch(r, t_max_s, st, m, hdir)) return out;
        T clear = T(0);
        if constexpr (GuidedScene<S>) {
            if (p_.follow_neighbours) {
                const water_below w = water_for(st);
                for (const guide_ray& g : {a, b}) {
                    if (!g.launch) continue;
                    if (const auto bound = beside(r, hdir, *g.launch, g.clear_range_m, w))
                        clear = scene.clear_range_beside_m(*bound);
                    if (clear > T(0)) break;
                }
            }
        }
        (void)follow(m, r, hdir, scene, t_max_s, st.chord_depth, out, nullptr, clear);
        return out;
    }

    /// The shared start of rays from world z origin_z (throws for an origin above the sea surface).
    template <Scene S> [[nodiscard]] trace_start start_for(T origin_z, const S& scene) const {
        return start_above(origin_z, scene.top_m());
    }

    /// The shared start of rays from world z origin_z over geometry no higher than world z top (m); -infinity: no
    /// geometry, and no chords; +infinity: geometry anywhere, chords from the source and no launch table.
    [[nodiscard]] trace_start start_above(T origin_z, T top) const {
        constexpr T eps = std::numeric_limits<T>::epsilon();
        trace_start st;
        st.origin_z = origin_z;
        st.depth0 = p_.surface_z_m - origin_z;
        if (!std::isfinite(origin_z))
            throw invalid_parameter("ray.origin", "must be finite (world z " + std::to_string(origin_z) + ")");
        if (!(st.depth0 >= T(0)))
            throw invalid_parameter("ray.origin", "lies above the sea surface (world z " + std::to_string(origin_z) +
                                                      " > layered.surface_z_m " + std::to_string(p_.surface_z_m) + ")");
        if (!(top > -std::numeric_limits<T>::infinity())) {
            st.chord_depth = std::numeric_limits<T>::infinity();
            return st;
        }
        if (!(top < std::numeric_limits<T>::infinity())) {
            st.chord_depth = -std::numeric_limits<T>::infinity();
            return st;
        }
        // Geometry lies at depths >= top_depth; chords start a margin above it.
        const T top_depth = p_.surface_z_m - top;
        const T margin = std::max(p_.chord_tolerance_m, T(64) * eps * (std::abs(p_.surface_z_m) + std::abs(top)));
        st.chord_depth = top_depth - margin;
        if (p_.launch_table && st.chord_depth > st.depth0 && std::isfinite(st.chord_depth))
            st.table = &table_for(st.depth0, st.chord_depth);
        return st;
    }

    /// The first part of a trace: the ray `r` set up where its first arc starts, at the source or, through the launch
    /// table, at the depth where chords begin (into m, its horizontal direction into hdir); false when it runs out of
    /// time before that. Every field of m is set here (march has no default values, so that nothing is zeroed twice).
    [[nodiscard]] bool launch(const ray<T>& r, T t_max_s, const trace_start& st, march& m, vec3<T>& hdir) const noexcept {
        if (!(t_max_s > T(0))) return false;
        const T depth0 = st.depth0;
        const T h2 = r.direction.x * r.direction.x + r.direction.y * r.direction.y;
        const T hlen = std::sqrt(h2);
        const T inv_h = T(1) / hlen;
        hdir = hlen > T(0) ? vec3<T>{r.direction.x * inv_h, r.direction.y * inv_h, T(0)} : vec3<T>{T(1), T(0), T(0)};
        // Launch inclination (+ down) as its sine and cosine; the angle itself only when an arc needs it.
        const T inv_len = T(1) / std::sqrt(h2 + r.direction.z * r.direction.z);
        const T sin0 = -r.direction.z * inv_len, cos0 = hlen * inv_len;

        // A ray going up from a source above all the geometry meets nothing unless it turns back down: skip it where
        // it cannot.
        if (sin0 < T(0) && st.chord_depth > depth0 && climbs_to_surface(depth0, cos0)) return false;
        m.set_out(depth0, sin0, cos0);
        T source_speed_mps;
        if (st.table && sin0 > T(0)) {
            const table_entry& e = *st.table;
            source_speed_mps = e.source_speed_mps;
            if (const auto d = e.table->lookup(sin0, cos0)) {
                // Resume at the table's depth; the inclination there follows from Snell's law.
                m.layer = e.resume_layer;
                m.z = st.chord_depth;
                const T c = std::min(cos0 * e.speed_ratio, T(1));
                m.cos_phi = c;
                m.sin_phi = std::sqrt((T(1) - c) * (T(1) + c));
                m.t = d->time_s;
                m.x = d->range_m;
                m.s = d->path_m;
                m.absorption_ratio = d->absorption;
                m.tube = ray_tube<T>{e.source_speed_mps, sin0, d->q_sum, d->k_sum, true};
                return m.t <= t_max_s;
            }
            m.layer = e.source_layer;
        } else {
            m.layer = profile_.layer_index(depth0, sin0 < T(0) ? vertical_direction::up : vertical_direction::down);
            source_speed_mps = layers_[m.layer].speed_mps(depth0);
        }
        m.tube = ray_tube<T>{source_speed_mps, sin0};
        return true;
    }

    /// True when a ray leaving depth depth0 (m) upwards at an inclination of cosine cos0 surely reaches the sea surface
    /// without turning back down: by Snell's law (cos(phi) / c constant) it turns only where c reaches c(depth0) / cos0,
    /// and the water above the source is slower than that everywhere (its fastest point is a knot or an end of the
    /// column), by a margin far above rounding. Such a ray ends at the surface (surface reflection is not modelled).
    [[nodiscard]] bool climbs_to_surface(T depth0, T cos0) const noexcept {
        double c_hi = double(profile_.speed_mps(T(0)));
        for (const gradient_layer<T>& l : layers_) {
            if (!(l.z_top_m < depth0)) break;
            c_hi = std::max({c_hi, double(l.speed_mps(std::max(l.z_top_m, T(0)))),
                             double(l.speed_mps(std::min(l.z_bottom_m, depth0)))});
        }
        return double(cos0) * c_hi < double(profile_.speed_mps(depth0)) * (1.0 - 1e-5);
    }

    /// The water below a source at depth depth0 (m): c there, and the slowest and fastest water from there down (the
    /// last layer goes on at its bottom knot's speed), widened by a few roundings. What trace_beside's bound needs of
    /// the source.
    struct water_below {
        double c0, c_lo, c_hi;
    };
    [[nodiscard]] water_below water_from(T depth0) const noexcept {
        const double eps = double(std::numeric_limits<T>::epsilon());
        const double c0 = double(profile_.speed_mps(depth0));
        double c_lo = c0, c_hi = c0;
        for (const gradient_layer<T>& l : layers_) {
            if (!(l.z_bottom_m > depth0)) continue;
            const double top = double(l.speed_mps(std::max(l.z_top_m, depth0)));
            const double bottom = std::isfinite(l.z_bottom_m) ? double(l.speed_mps(l.z_bottom_m)) : top;
            c_lo = std::min({c_lo, top, bottom});
            c_hi = std::max({c_hi, top, bottom});
        }
        return {c0, c_lo * (1.0 - 16.0 * eps), c_hi * (1.0 + 16.0 * eps)};
    }

    /// water_from(st.depth0), from st's launch table where it has one (kept with the table).
    [[nodiscard]] water_below water_for(const trace_start& st) const noexcept {
        return st.table ? st.table->water : water_from(st.depth0);
    }

    /// What r keeps over its steeper neighbour a (a_dir, clear within rho_a_m) in water w: trace_beside's bound;
    /// nullopt where it does not apply (either ray not going down, a not steeper, a ray that may level off, a
    /// near-vertical ray). hdir is r's horizontal direction as the walk uses it.
    [[nodiscard]] std::optional<scene::beside_rays<T>> beside(const ray<T>& r, const vec3<T>& hdir, const vec3<T>& a_dir,
                                                             T rho_a_m, const water_below& w) const noexcept {
        if (!(rho_a_m > T(0)) || !std::isfinite(rho_a_m)) return std::nullopt;
        // In double: the difference of the two rays' parameters is small against either.
        const double rx = double(r.direction.x), ry = double(r.direction.y), rz = double(r.direction.z);
        const double ax = double(a_dir.x), ay = double(a_dir.y), az = double(a_dir.z);
        const double rh = std::sqrt(rx * rx + ry * ry), ah = std::sqrt(ax * ax + ay * ay);
        const double inv_rl = 1.0 / std::sqrt(rh * rh + rz * rz), inv_al = 1.0 / std::sqrt(ah * ah + az * az);
        const double sin_r = -rz * inv_rl, sin_a = -az * inv_al, cos_r = rh * inv_rl, cos_a = ah * inv_al;
        if (!(sin_r > 0.0) || !(sin_a > sin_r) || !(cos_r >= 1e-3) || !(cos_a >= 1e-3)) return std::nullopt;
        const double p_r = cos_r / w.c0, p_a = cos_a / w.c0;
        const double r_hi = p_r * w.c_hi, a_hi = p_a * w.c_hi, r_lo = p_r * w.c_lo, a_lo = p_a * w.c_lo;
        if (!(r_hi < 1.0 - 1e-6)) return std::nullopt; // r might level off
        // The least and greatest tan(phi) along each ray (Snell: cos(phi) = p c), and s, a's greatest sin(phi).
        const double least_r = std::sqrt((1.0 - r_hi) * (1.0 + r_hi)) / r_hi;
        const double least_a = std::sqrt((1.0 - a_hi) * (1.0 + a_hi)) / a_hi;
        const double most_r = std::sqrt((1.0 - r_lo) * (1.0 + r_lo)) / r_lo;
        const double s = std::sqrt((1.0 - a_lo) * (1.0 + a_lo)), most_a = s / a_lo;
        // p_r - p_a from the cosines' difference, (sin_a^2 - sin_r^2) / (cos_r + cos_a), free of cancellation.
        const double dp = (sin_a - sin_r) * (sin_a + sin_r) / ((cos_r + cos_a) * w.c0);
        const double gain = least_r * least_a * w.c_lo * dp / (s * s * s) * (1.0 - 1e-6);
        const double rho_a = double(rho_a_m);
        const double eps = double(std::numeric_limits<T>::epsilon());
        // The launch table's tolerance in range (relative to the path length, at most rho / (p c_lo) <= rho / a_lo
        // for either ray), with room for rounding.
        const double rel = 2.0 * std::max(1e-10, 64.0 * eps);
        const double world = std::abs(double(r.origin.x)) + std::abs(double(r.origin.y)) + rho_a;
        const double margin =
            2.02 * double(p_.chord_tolerance_m) / a_lo + 2.0 * most_a * (rel * rho_a / a_lo + 8.0 * eps * world);
        return scene::beside_rays<T>{.origin = r.origin,
                                     .heading_r = {hdir.x, hdir.y},
                                     .heading_a = {T(ax / ah), T(ay / ah)},
                                     .rho_a_m = rho_a_m,
                                     .gain = T(gain),
                                     .slope_r = T(most_r * (1.0 + 1e-6)),
                                     .drop_a_m = T(most_a * rho_a * (1.0 + 1e-6)),
                                     .margin_m = T(margin * (1.0 + 1e-6))};
    }

    static const layered_params<T>& validated(const layered_params<T>& p) {
        sss::require_finite(p.surface_z_m, "layered.surface_z_m");
        sss::require_positive(p.frequency_hz, "layered.frequency_hz");
        check_water_properties(p.water);
        sss::require_positive(p.chord_tolerance_m, "layered.chord_tolerance_m");
        sss::require_non_negative(p.reference_speed_mps, "layered.reference_speed_mps");
        sss::require(p.absorption == absorption_formula::francois_garrison ||
                                 p.absorption == absorption_formula::ainslie_mccolm,
                             "layered.absorption", "is not a known formula");
        return p;
    }

    /// Where a ray stands between arcs. No default values: launch and descend set every field.
    struct march {
        std::size_t layer;
        T z, phi, sin_phi, cos_phi; ///< depth (m) and inclination (rad, + down; phi stale unless phi_known)
        bool phi_known;
        T t, x, s;                  ///< time (s), range (m), path (m) so far
        T absorption_ratio;         ///< absorption (intensity ratio) up to where absorption_db starts counting
        T absorption_db;            ///< absorption (dB) since then
        ray_tube<T> tube;           ///< its source_speed_mps is c at the source
        std::size_t arcs, chords;   ///< layer arcs followed, chords handed to the scene

        /// The set-up every trace starts from (launch and the launch table's descents): at depth z_m, inclination
        /// (sin_phi0, cos_phi0) with the angle not yet known, nothing travelled. The caller sets layer and tube.
        void set_out(T z_m, T sin_phi0, T cos_phi0) noexcept {
            z = z_m;
            phi = T(0);
            sin_phi = sin_phi0;
            cos_phi = cos_phi0;
            phi_known = false;
            t = x = s = absorption_db = T(0);
            absorption_ratio = T(1);
            arcs = chords = 0;
        }
    };

    /// What trace_path reports beyond the path.
    struct details {
        T outgoing_spreading, hit_speed_mps, range_m, path_length_m;
    };

    /// Follows the ray from `m` arc by arc until it meets the scene (true, the path in `out` and, when `more` is not
    /// null, the details in *more), leaves the water or runs out of time (false, `out` untouched).
    /// Chords that lie wholly within horizontal distance clear_range_m (m) of the origin are known to meet nothing
    /// (trace_beside) and are skipped; a chord that reaches past it is handed to the scene with its part within it
    /// known clear (visit_arc_hit).
    template <Scene S>
    [[nodiscard]] bool follow(march& m, const ray<T>& r, const vec3<T>& hdir, const S& scene, T t_max_s, T chord_depth,
                              std::optional<path<T>>& out, details* more, T clear_range_m = T(0)) const {
        constexpr T inf = std::numeric_limits<T>::infinity();
        constexpr std::size_t max_arcs = std::size_t(1) << 24;
        int zero_steps = 0;
        for (std::size_t n_arcs = 0; n_arcs < max_arcs; ++n_arcs) {
            const gradient_layer<T>& layer = layers_[m.layer];
            if (zero_steps >= 2) { // horizontal on a knot whose two layers both bend it back: it runs along the knot
                m.phi = T(0);
                m.sin_phi = T(0);
                m.cos_phi = T(1);
                m.phi_known = true;
            }
            ++m.arcs;
            const T g = zero_steps >= 2 ? T(0) : layer.gradient_per_s;
            const T c0 = layer.speed_mps(m.z);
            const T xi = m.cos_phi / c0;
            detail::arc_start<T> a{m.z, c0, m.phi, m.sin_phi, m.cos_phi, g, xi, xi * g};
            const arc_frame<T> frame{vec3<T>{r.origin.x + hdir.x * m.x, r.origin.y + hdir.y * m.x, p_.surface_z_m - m.z}, hdir};
            // A hit on this arc ends the trace: the path, if the hit comes in time.
            bool in_time = false;
            const auto done = [&](const hit<T>& h, const vec3<T>& point, T arc_m, const arc_offset<T>& at, T clear_x_m) {
                in_time = finish(m, a, h, point, arc_m, at, clear_x_m, layer, hdir, t_max_s, out, more);
            };
            // Path length the time left allows in this layer (c is largest at one of its bounds).
            const T c_max = g == T(0) ? c0 : std::max(layer.speed_mps(layer.z_top_m), layer.speed_mps(layer.z_bottom_m));
            const T s_cap = c_max * (t_max_s - m.t);
            // The arc length within which this arc stays within clear_range_m: it goes at most cos(phi) = xi c <=
            // xi c_max horizontally per metre (Snell), a few roundings less.
            T s_clear = T(0);
            const T x_clear = clear_range_m > m.x ? clear_range_m - m.x : T(0);
            if (clear_range_m > m.x) {
                const T cos_hi = std::min(T(1), xi * c_max);
                if (cos_hi > T(1e-3))
                    s_clear = (clear_range_m - m.x) / cos_hi * (T(1) - T(64) * std::numeric_limits<T>::epsilon());
            }

            // Over a scene that meets arcs itself (ArcScene), a piece of the arc, from arc length s_from to s_to
            // (horizontal distances x_from, x_to from its start), is handed to it whole, and the rest of the scene
            // (its objects) as chords up to where the arc met it; otherwise the scene gets chords (visit_arc_hit).
            bool by_arc = false;
            [[maybe_unused]] const scene::vertical_arc<T> arc_v{frame.start, vec2<T>{hdir.x, hdir.y}, a.sin0, a.cos0,
                                                                a.kappa};
            [[maybe_unused]] const auto meet_arc = [&](T s_from, T x_from, T s_to, T x_to) {
                if constexpr (ArcScene<S>) {
                    const auto met = scene.intersect_arc(arc_v, std::max(x_clear, x_from), x_to);
                    T met_arc_m = s_to;
                    arc_offset<T> met_at{};
                    if (met) met_at = offset_at_range(arc_v, met->x_m, met_arc_m);
                    const auto others = scene.arc_others();
                    if (others.top_m() > -inf && met_arc_m > s_from &&
                        visit_arc_hit(others, frame, a.sin0, a.cos0, a.kappa, s_from, met_arc_m, p_.chord_tolerance_m,
                                      false, s_clear, x_clear, m.chords, done))
                        return true;
                    if (met) {
                        done(met->surface, met->surface.point, met_arc_m, met_at, met->x_m);
                        return true;
                    }
                }
                return false;
            };
            if constexpr (ArcScene<S>) by_arc = a.cos0 >= T(0.01); // within 0.6 degrees of vertical: chords

            // Where the arc surely stays in the layer and may meet geometry, look before stepping through the layer.
            T s_done = T(0);
            // The arc length the arc surely stays in the layer (stay_length), and a few roundings of the depths past
            // it, so that a surface lying exactly on the boundary is not missed (world and depth coordinates differ by
            // rounding of their own size); at most s_cap.
            const auto surely_stays = [&] {
                const T slack = T(64) * std::numeric_limits<T>::epsilon() * (std::abs(m.z) + std::abs(p_.surface_z_m)) /
                                std::max(std::abs(a.sin0), T(1e-3));
                return std::min(stay_length(layer, m.z, a) + slack, s_cap);
            };
            if (m.z >= chord_depth && by_arc) {
                // The arc up to where it surely stays in the layer, with no trigonometry for the layer.
                const T stay = surely_stays();
                if (stay > T(0) && std::isfinite(stay)) {
                    const T x_stay = offset_along_arc(a.sin0, a.cos0, a.kappa, stay).range_m;
                    if (meet_arc(T(0), T(0), stay, x_stay)) return in_time;
                    s_done = stay;
                }
            } else if (m.z >= chord_depth) {
                // First at most one chord's worth, with no trigonometry: depth changes no faster than arc length, so
                // the arc stays in the layer over at least the distance to its nearer boundary. Where the scene is
                // near (the usual case after the launch table) that is where the hit is. Not when that distance is
                // below a sixteenth of a chord (a thin layer): the chord would hardly ever meet anything.
                T first = std::min(std::min(m.z - layer.z_top_m, layer.z_bottom_m - m.z), s_cap);
                const T k_first2 = std::abs(a.kappa) * first * first; // 8 x the sagitta of one chord over `first`
                if (a.kappa != T(0) && first > T(0) && T(256) * k_first2 >= T(8) * p_.chord_tolerance_m) {
                    if (k_first2 > T(8) * p_.chord_tolerance_m) first = chord_arc_length_m(a.kappa, p_.chord_tolerance_m);
                    if (visit_arc_hit(scene, frame, a.sin0, a.cos0, a.kappa, T(0), first, p_.chord_tolerance_m,
                                      p_.clear_open_water, s_clear, x_clear, m.chords, done))
                        return in_time;
                    s_done = first;
                }
                const T stay = surely_stays();
                if (stay > s_done) {
                    if (visit_arc_hit(scene, frame, a.sin0, a.cos0, a.kappa, s_done, stay, p_.chord_tolerance_m,
                                      p_.clear_open_water, s_clear, x_clear, m.chords, done))
                        return in_time;
                    s_done = stay;
                }
            }

            if (!m.phi_known) {
                m.phi = std::atan2(m.sin_phi, m.cos_phi);
                a.phi0 = m.phi;
                m.phi_known = true;
            }
            layer_step<T> st;
            if (zero_steps >= 2) {
                st.arc = {m.z, c0, T(0), T(0), inf};
                st.exit = {m.z, inf, inf, inf, T(0)};
                st.boundary = layer_exit::none;
            } else {
                st = step_through_layer(layer, m.z, std::abs(m.phi), m.phi < T(0) ? vertical_direction::up : vertical_direction::down);
            }
            const ray_arc<T>& arc = st.arc;
            const T s_end = std::min(arc.length_m, s_cap);
            if (s_done < s_end) {
                if (const auto s_begin = chord_start(st, a.kappa, chord_depth, s_end)) {
                    if (by_arc) {
                        const T s_from = std::max(*s_begin, s_done);
                        const T x_from =
                            s_from > T(0) ? offset_along_arc(a.sin0, a.cos0, a.kappa, s_from).range_m : T(0);
                        if (meet_arc(s_from, x_from, s_end, offset_along_arc(a.sin0, a.cos0, a.kappa, s_end).range_m))
                            return in_time;
                    } else if (visit_arc_hit(scene, frame, a.sin0, a.cos0, a.kappa, std::max(*s_begin, s_done), s_end,
                                      p_.chord_tolerance_m, p_.clear_open_water, s_clear, x_clear, m.chords, done))
                        return in_time;
                }
            }
            if (st.boundary == layer_exit::none || !(arc.length_m <= s_cap)) return false;

            // Through the layer: accumulate and move on.
            const bool top = st.boundary == layer_exit::top;
            if (top && (layer.z_top_m <= T(0) || m.layer == 0)) return false; // reached the sea surface
            advance(m, a, st, layer);
            zero_steps = st.exit.arc_m == T(0) ? zero_steps + 1 : 0;
            if (top) --m.layer;
            else ++m.layer;
            if (!(m.t <= t_max_s)) return false;
        }
        return false;
    }

    /// Adds a whole arc through a layer to the march.
    void advance(march& m, const detail::arc_start<T>& a, const layer_step<T>& st, const gradient_layer<T>& layer) const {
        const arc_sample<T>& e = st.exit;
        const T sin_e = std::sin(e.incline_rad);
        m.tube.add_piece(ray_tube_q(e.range_m, a.xi, e.depth_m - a.z0, a.c0, layer.speed_mps(e.depth_m), a.sin0, sin_e),
                         a.sin0, sin_e);
        m.absorption_db += arc_absorption_db(a, e.arc_m);
        m.t += e.time_s;
        m.x += e.range_m;
        m.s += e.arc_m;
        m.z = e.depth_m;
        m.phi = e.incline_rad;
        m.sin_phi = sin_e;
        m.cos_phi = std::max(std::cos(e.incline_rad), T(0));
        m.phi_known = true;
    }

    /// The path to a hit on the current arc, into `out` (and the details into *more when not null); false if the hit
    /// comes after t_max_s. The chords met nothing up to horizontal distance clear_x_m from this arc's start.
    [[nodiscard]] bool finish(const march& m, const detail::arc_start<T>& a, const hit<T>& h, const vec3<T>& point,
                              T arc_m, const arc_offset<T>& o, T clear_x_m, const gradient_layer<T>& layer,
                              const vec3<T>& hdir, T t_max_s, std::optional<path<T>>& out, details* more) const {
        T dt;
        if (a.cos0 > T(0)) {
            dt = detail::arc_time(a, o.range_m, o.cos_incline, o.sin_half * o.sin_half);
        } else { // vertical
            const T dz = o.depth_m;
            dt = std::abs(dz) / a.c0 * detail::log1p_ratio(a.g * dz / a.c0);
        }
        const T t_hit = m.t + dt;
        if (!(t_hit <= t_max_s)) return false;
        const T c_hit = layer.speed_mps(a.z0 + o.depth_m);
        const T q = ray_tube_q(o.range_m, a.xi, o.depth_m, a.c0, c_hit, a.sin0, o.sin_incline);
        // S_AB = c_A^2 / (Q w) and S_BA = c_B^2 / (Q w) (ray_tube.hpp), with one division.
        const T inv_qw = m.tube.inverse_qw(q, a.sin0, o.sin_incline);
        const T c_source = m.tube.source_speed_mps;
        const T s_ab = c_source * c_source * inv_qw;
        const T s_ba = c_hit * c_hit * inv_qw;
        const bool finite = std::isfinite(s_ab) && std::isfinite(s_ba);
        // A last piece within a metre of depth and a tenth of a millimetre of sagitta (the usual one after the launch
        // table) needs only the midpoint rule: its depth is then linear in arc length to 1e-4 m, and alpha's own
        // curvature over 1 m of depth is 1e-8 relative, so the rule is off by below 1e-8 of that piece's share. Its
        // midpoint depth is dz/2 + kappa s^2 cos(phi0)/8, to O(kappa^2 s^3) (below 1e-7 m there).
        const T kss = a.kappa * arc_m * arc_m;
        const bool short_piece = std::abs(o.depth_m) < T(1) && std::abs(kss) < T(8e-4);
        const T absorption_db =
            m.absorption_db +
            (short_piece ? absorption_db_per_km(std::max(a.z0 + T(0.5) * o.depth_m + T(0.125) * kss * a.cos0, T(0))) *
                               arc_m * T(1e-3)
                         : arc_absorption_db(a, arc_m));
        // exp(-x) by its series where x < 1e-3 (remainder x^5/120 < 1e-17): the last piece after the launch table.
        const T x = T(0.1) * ln10_v<T> * absorption_db;
        const T decay = x < T(1e-3) ? T(1) - x * (T(1) - x * (T(0.5) - x * (T(1.0 / 6) - x * T(1.0 / 24)))) : std::exp(-x);
        const T path_length = m.s + arc_m;
        out.emplace(h, t_hit, finite ? s_ba : T(0), m.absorption_ratio * decay,
                    hdir * o.cos_incline + vec3<T>{T(0), T(0), -o.sin_incline});
        out->surface.point = point;
        out->surface.distance_m = path_length;
        // Clear up to where the chord met the scene (what a neighbour's walk builds on is this ray's chords, each within
        // the tolerance of its arc: beside's margin holds both rays' chords), less 1e-4 of the range and a few roundings
        // of the world coordinates (the arc's start and the hit are rounded by those, whatever the range).
        const T world_rounding = T(16) * std::numeric_limits<T>::epsilon() *
                                 (std::abs(point.x) + std::abs(point.y) + std::abs(point.z) + std::abs(p_.surface_z_m));
        out->clear_range_m = std::max(T(0), (m.x + clear_x_m) * T(0.9999) - world_rounding);

        if (more) *more = details{finite ? s_ab : T(0), c_hit, m.x + o.range_m, path_length};
        return true;
    }

    /// The offset of arc `v` at horizontal distance x_m (m) from its start, and the arc length to there into arc_m (m):
    /// sin phi = sin phi0 - kappa x (Snell), the turn since the start from sin phi0 - sin phi = 2 cos(mean) sin(half),
    /// mean the average of the two inclinations; arc length = turn / kappa = x / cos(mean) asin(sin(half)) / sin(half).
    [[nodiscard]] static arc_offset<T> offset_at_range(const scene::vertical_arc<T>& v, T x_m, T& arc_m) noexcept {
        arc_offset<T> o;
        o.range_m = x_m;
        o.depth_m = v.depth_m(x_m);
        o.sin_incline = v.sin_at(x_m);
        o.cos_incline = v.cos_at(x_m);
        // cos phi0 + cos phi = 2 cos(mean) cos(half) and sin phi0 + sin phi = 2 sin(mean) cos(half): their ratio to
        // their hypotenuse is cos(mean), with nothing cancelling near vertical.
        const T cs = v.cos_phi0 + o.cos_incline, ss = v.sin_phi0 + o.sin_incline;
        const T cos_mean = cs / std::sqrt(cs * cs + ss * ss);
        const T sh = cos_mean > T(0) ? v.kappa_per_m * x_m / (T(2) * cos_mean) : T(0);
        o.sin_half = sh;
        o.cos_half = std::sqrt(std::max(T(0), (T(1) - sh) * (T(1) + sh)));
        const T asin_ratio = std::abs(sh) < T(1e-3) ? T(1) + sh * sh * (T(1.0 / 6) + sh * sh * T(3.0 / 40))
                                                   : std::asin(std::min(std::abs(sh), T(1))) / std::abs(sh);
        arc_m = cos_mean > T(0) ? x_m / cos_mean * asin_ratio : T(0);
        return o;
    }

    /// A length of arc (m) the ray surely travels before it can leave the layer. When the boundary ahead can be
    /// reached (Snell gives a real sine there, sin_b), exactly the arc length to it, s = 2 dz/(sin_a + sin_b)
    /// atan(w)/w with w = kappa dz/(sin_a + sin_b) (ray_arc.hpp); when the ray turns first, the depth down to the turn
    /// and back past its start to the other boundary. 0 for a horizontal start.
    [[nodiscard]] static T stay_length(const gradient_layer<T>& layer, T z, const detail::arc_start<T>& a) noexcept {
        if (a.sin0 == T(0)) return T(0);
        const bool down = a.sin0 > T(0);
        const T ahead = down ? layer.z_bottom_m : layer.z_top_m;
        if (!std::isfinite(ahead)) return std::numeric_limits<T>::infinity(); // a zero-gradient half-space: straight on
        const T dz = ahead - z;
        const T c = a.xi * layer.speed_mps(ahead);
        if (c < T(1)) {
            const T sin_b = std::copysign(std::sqrt((T(1) - c) * (T(1) + c)), a.sin0);
            const T sum = a.sin0 + sin_b;
            return T(2) * dz / sum * detail::atan_ratio(a.kappa * dz / sum);
        }
        // It turns before the boundary ahead: down to the turning depth and back up past its start at least.
        const T turn = a.sin0 * a.sin0 / ((T(1) + a.cos0) * std::abs(a.kappa));
        return T(2) * turn + (down ? z - layer.z_top_m : layer.z_bottom_m - z);
    }

    /// The ray launched down at inclination (sin_phi0, cos_phi0) from depth z_a, where it first reaches depth z_h
    /// going down all the way (nullopt if it turns or levels off first): the launch table's exact trace.
    [[nodiscard]] std::optional<descent_state<T>> descend(T z_a, T z_h, T sin_phi0, T cos_phi0) const noexcept {
        march m;
        m.set_out(z_a, sin_phi0, cos_phi0);
        m.layer = profile_.layer_index(z_a, vertical_direction::down);
        m.phi = std::atan2(sin_phi0, cos_phi0);
        m.phi_known = true;
        m.tube = ray_tube<T>{layers_[m.layer].speed_mps(z_a), sin_phi0};
        for (std::size_t n = 0; n <= layers_.size(); ++n) {
            gradient_layer<T> layer = layers_[std::min(m.layer, layers_.size() - 1)];
            layer.z_bottom_m = std::min(layer.z_bottom_m, z_h);
            const T c0 = layer.speed_mps(m.z);
            const T xi = m.cos_phi / c0;
            const detail::arc_start<T> a{m.z, c0, m.phi, m.sin_phi, m.cos_phi, layer.gradient_per_s, xi,
                                             xi * layer.gradient_per_s};
            const layer_step<T> st = step_through_layer(layer, m.z, m.phi, vertical_direction::down);
            if (st.boundary != layer_exit::bottom || !(st.exit.incline_rad > T(0))) return std::nullopt;
            advance(m, a, st, layer);
            if (m.z >= z_h) return descent_state<T>{m.x, m.t, m.s, m.absorption_db, m.tube.q_sum, m.tube.k_sum, T(0)};
            ++m.layer;
        }
        return std::nullopt;
    }

    /// A launch table and what a ray resuming from it needs: all functions of the water, z_a and z_h alone.
    struct table_entry {
        std::uint64_t owner = 0;
        T z_a{}, z_h{};
        std::optional<launch_table<T>> table;
        std::size_t source_layer = 0; ///< the layer of a ray leaving z_a downwards
        std::size_t resume_layer = 0; ///< the layer of a ray going down at z_h
        T source_speed_mps{};         ///< c(z_a)
        T speed_ratio{};              ///< c(z_h) / c(z_a): cos(phi_H) = cos(phi0) c(z_h) / c(z_a) (Snell)
        water_below water{};          ///< water_from(z_a): what trace_beside's bound needs of the source
    };

    struct trace_start {
        T origin_z{}, depth0{}, chord_depth{};
        const table_entry* table = nullptr;
    };

    /// This thread's launch table for source depth z_a and table depth z_h, built when either (or the water) changes.
    /// A thread keeps the last four (tables of waters or depths used in turn, as when a program alternates two
    /// waters, are then not rebuilt at every switch: a build costs about a thousand exact descents).
    [[nodiscard]] const table_entry& table_for(T z_a, T z_h) const {
        constexpr std::size_t kept = 4;
        thread_local std::array<table_entry, kept> cache;
        thread_local std::size_t last = 0, oldest = 0;
        const auto holds = [&](const table_entry& e) { return e.owner == id_ && e.z_a == z_a && e.z_h == z_h && e.table; };
        if (holds(cache[last])) return cache[last];
        for (std::size_t i = 0; i < kept; ++i)
            if (holds(cache[i])) return cache[last = i];
        table_entry& e = cache[oldest];
        last = oldest;
        oldest = (oldest + 1) % kept;
        e.owner = 0; // not valid until built (the build may throw std::bad_alloc)
        const T tolerance = std::max(T(1e-10), T(64) * std::numeric_limits<T>::epsilon());
        e.table.emplace([&](T sn, T cs) { return descend(z_a, z_h, sn, cs); }, tolerance);
        e.owner = id_;
        e.z_a = z_a;
        e.z_h = z_h;
        e.source_layer = profile_.layer_index(z_a, vertical_direction::down);
        e.resume_layer = profile_.layer_index(z_h, vertical_direction::down);
        e.source_speed_mps = layers_[e.source_layer].speed_mps(z_a);
        e.speed_ratio = layers_[e.resume_layer].speed_mps(z_h) / e.source_speed_mps;
        e.water = water_from(z_a);
        return e;
    }

    /// Arc length from which the arc may meet geometry (it is at depth >= chord_depth there), or nullopt when it
    /// stays shallower than chord_depth up to s_end. When the whole of [0, s_end] would take at most two chords, the
    /// chords simply start at 0 (finding the exact depth crossing would cost more than the chord it saves).
    [[nodiscard]] std::optional<T> chord_start(const layer_step<T>& st, T kappa, T chord_depth, T s_end) const noexcept {
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
        // Sagitta of the whole span (small-angle form): at most two chords' worth of tolerance.
        if (std::abs(kappa) * s_end * s_end <= T(32) * p_.chord_tolerance_m) return T(0);
        const auto p = arc_point_at_depth(arc, chord_depth);
        if (!p || !(p->arc_m < s_end)) return std::nullopt;
        return p->arc_m;
    }

    /// One-way absorption (dB) along the first len_m (m) of the arc `a`: three-point Gauss-Legendre in arc length
    /// (file comment).
    [[nodiscard]] T arc_absorption_db(const detail::arc_start<T>& a, T len_m) const noexcept {
        if (!(len_m > T(0))) return T(0);
        const T half = len_m / T(2);
        const T off = half * T(0.774596669241483377035853079956479922L); // sqrt(3/5)
        const auto alpha = [&](T s) {
            return absorption_db_per_km(std::max(a.z0 + offset_along_arc(a.sin0, a.cos0, a.kappa, s).depth_m, T(0)));
        };
        const T mean = (T(5) * (alpha(half - off) + alpha(half + off)) + T(8) * alpha(half)) * T(1.0 / 18);
        return mean * len_m * T(1e-3);
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
            slowness += (b - a) / ca * detail::log1p_ratio(e);
        }
        return bottom / slowness;
    }

    sound_speed_profile<T> profile_;
    layered_params<T> p_;
    francois_garrison<T> fg_;
    ainslie_mccolm<T> am_;
    std::vector<gradient_layer<T>> layers_;
    T c_ref_{};
    std::uint64_t id_ = 0; ///< identifies the water for the launch-table cache (copies share it: same water)
    inline static std::atomic<std::uint64_t> next_id_{1};
};

static_assert(Propagation<layered<float>> && Propagation<layered<double>>);
static_assert(RangeHeightPropagation<layered<float>> && RangeHeightPropagation<layered<double>>);

} // namespace sss::propagation

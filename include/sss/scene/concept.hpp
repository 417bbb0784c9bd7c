#pragma once
/// \file
/// The Scene concept: geometry only (it knows nothing of sound).
///
/// | expression                      | type                       | meaning                                              |
/// |---------------------------------|----------------------------|------------------------------------------------------|
/// | `S::value_type`                 | float or double            | scalar type of the geometry                          |
/// | `s.intersect(r, t_max_m)`       | `std::optional<hit<T>>`    | nearest hit along `r` with 0 < distance <= t_max_m   |
/// | `s.seabed_height_m(x_m, y_m)`   | `T`                        | world z of the seabed below (x, y) (m)               |
/// | `s.top_m()`                     | `T`                        | world z above which no geometry exists (m)           |
///
/// `r` is a `ray<T>` with unit direction. `intersect` must be watertight: a ray never slips between two
/// pieces of one surface. `seabed_height_m` and `top_m` only steer ray sampling (they never decide a hit).
///
/// Optional (`BatchScene`): a scene that can share work among many rays (the rays of one column of a ping share
/// their origin and come ordered by depression) also offers
///
/// | `s.intersect_many(rays, t_max_m, hits)` | `void` | hits[k] = s.intersect(rays[k], t_max_m), up to rounding |
///
/// with `rays` a `std::span<const ray<T>>` and `hits` a `std::span<std::optional<hit<T>>>` of the same size.
/// `sss::intersect_all` calls it where it exists and falls back to one `intersect` per ray, so callers need not
/// ask.
///
/// Optional (`AreaScene`): a scene that can bound its geometry over part of the plane also offers
///
/// | `s.top_m(lo, hi)` | `T` | world z above which no geometry exists over x in [lo.x, hi.x], y in [lo.y, hi.y] (m) |
///
/// with `lo`, `hi` `vec2<T>` (world x, y, m): at most `top_m()`, and -infinity where nothing lies over the
/// rectangle. The simulator asks it for the rectangle a side's rays can reach (sampling/reach.hpp), so that one
/// high point elsewhere in a large scene does not make every ray look for geometry from that height down
/// (scene/area_view.hpp).
///
/// Optional (`PlaneBoundedScene`): a scene that can bound its geometry over part of the plane against a sloping plane
/// also offers
///
/// | `s.rise_above_m(lo, hi, plane)` | `double` | no geometry over the rectangle rises higher above `plane` (m) |
///
/// with `plane` a `scene::sloping_plane` (scene/sloping_plane.hpp) and `lo`, `hi` as above: the height is measured
/// vertically; conservative (any larger value will do), and -infinity where nothing lies over the rectangle. Over a
/// sloping seabed the simulator launches a side's rays for a plane fitted to it (sss::simulator::trace): how far they
/// must reach follows from how high the geometry rises above that plane, not above the level through the towfish's
/// nadir.
///
/// Optional (`ClearanceScene`): a scene that can tell how far a thick segment runs in open water also offers
///
/// | `s.clear_length_m(r, t_max_m, band_m)` | `T` | a length d in [0, t_max_m]: no geometry within vertical distance band_m of r's points at distances [0, d] |
///
/// Conservative: any d that is no longer than the true one will do (0 always does), and geometry closer than
/// band_m to the segment's start gives 0. Layered water hands a scene curved rays as many short chords
/// (propagation/arc_intersection.hpp); one query over a long chord, with the band covering the arc's sagitta,
/// clears the chords a ray passes in open water without tracing each of them.
///
/// Optional (`GuidedScene`): a scene that can use what a neighbouring ray found also offers
///
/// | `s.intersect_beside(r, t_max_m, a, a_clear_m)` | `std::optional<hit<T>>` | s.intersect(r, t_max_m), bit for bit |
/// | `s.clear_range_beside_m(b)` | `T` | a horizontal distance rho: ray r of b meets nothing within rho of b.origin |
///
/// given that ray `a` (a `ray<T>` from r's origin) met nothing for distances below a_clear_m (m), save a hit of
/// rounding alone that the exact geometry does not have (height_field_beside.hpp says when); `b` is a
/// `scene::beside_rays<T>`, what a ray r is known to keep over a neighbour a that met nothing (beside_rays.hpp), and
/// rho is conservative like a clear length (0 always does). The simulator's refinement traces a ray between two it
/// has traced (sampling/detail/tube_refinement.hpp) and passes the steeper of them: a height field starts the new
/// ray's walk about where the neighbour's ended (height_field_beside.hpp); bent rays skip the chords within rho
/// (propagation/layered.hpp).
///
/// Optional (`ResumableScene`): a scene that can start a ray's walk past a distance the caller knows clear also offers
///
/// | `s.intersect_after(r, t_max_m, clear_m)` | `std::optional<hit<T>>` | s.intersect(r, t_max_m), bit for bit |
///
/// given that r stays in open water (above the seabed, outside every object) for distances below clear_m (m), with
/// the same exception as above. Bent rays hand a chord that starts within what a neighbour vouches for
/// (clear_range_beside_m) to it, with the part of the chord within rho as clear_m: the chord's walk then starts about
/// where the neighbour's path ended instead of at the chord's start.
///
/// Optional (`ArcScene`): a scene that meets a curved ray's arc itself (scene/vertical_arc.hpp: a circular arc in a
/// vertical plane, a ray's path through one layer of water whose sound speed changes linearly with depth), in part of
/// its geometry at least, also offers
///
/// | `s.intersect_arc(a, x_clear_m, x_end_m)` | `std::optional<scene::arc_surface_hit<T>>` | the first hit of arc a on that part |
/// | `s.arc_others()` | a Scene | the rest of its geometry (`scene::no_geometry<T>` where there is none) |
///
/// with `a` a `scene::vertical_arc<T>`: where the arc first comes down onto that part within horizontal distance
/// x_end_m (m) of its start, given that it meets nothing before x_clear_m (m; 0 when nothing is known), the same to the
/// last bit whatever such x_clear_m is given; the hit's point lies on the arc. An arc that turns vertical before
/// x_end_m is met up to that point (beyond it, it curls back over distances already passed). A height field meets arcs
/// in all of itself; a scene of a height field and objects, in its seabed, its objects being the rest. Layered water
/// then traces a ray through each layer by one query on that part and chords on the rest (propagation/layered.hpp), so
/// that a view of the scene with fewer objects near (area_view) gives the same paths.

#include <concepts>
#include <cstddef>
#include <optional>
#include <span>

#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/beside_rays.hpp"
#include "sss/scene/sloping_plane.hpp"
#include "sss/scene/vertical_arc.hpp"

namespace sss {

template <class S>
concept Scene = Real<typename S::value_type> &&
    requires(const S& s, const ray<typename S::value_type>& r, typename S::value_type t) {
        { s.intersect(r, t) } -> std::same_as<std::optional<hit<typename S::value_type>>>;
        { s.seabed_height_m(t, t) } -> std::same_as<typename S::value_type>;
        { s.top_m() } -> std::same_as<typename S::value_type>;
    };

/// A Scene that traces many rays at once (see the table above).
template <class S>
concept BatchScene = Scene<S> && requires(const S& s, std::span<const ray<typename S::value_type>> rays,
                                          typename S::value_type t,
                                          std::span<std::optional<hit<typename S::value_type>>> hits) {
    { s.intersect_many(rays, t, hits) };
};

/// A Scene that bounds its geometry over a rectangle of the plane (see the table above).
template <class S>
concept AreaScene = Scene<S> && requires(const S& s, const vec2<typename S::value_type>& p) {
    { s.top_m(p, p) } -> std::same_as<typename S::value_type>;
};

/// A Scene that bounds its geometry against a sloping plane over a rectangle (see the table above).
template <class S>
concept PlaneBoundedScene = Scene<S> && requires(const S& s, const vec2<typename S::value_type>& p,
                                                 const scene::sloping_plane& plane) {
    { s.rise_above_m(p, p, plane) } -> std::same_as<double>;
};

/// A Scene that bounds how far a thick segment runs in open water (see the table above).
template <class S>
concept ClearanceScene = Scene<S> && requires(const S& s, const ray<typename S::value_type>& r, typename S::value_type t) {
    { s.clear_length_m(r, t, t) } -> std::same_as<typename S::value_type>;
};

/// A Scene that takes a neighbouring ray's clear distance as a guide (see the table above).
template <class S>
concept GuidedScene = Scene<S> && requires(const S& s, const ray<typename S::value_type>& r, typename S::value_type t,
                                           const scene::beside_rays<typename S::value_type>& b) {
    { s.intersect_beside(r, t, r, t) } -> std::same_as<std::optional<hit<typename S::value_type>>>;
    { s.clear_range_beside_m(b) } -> std::same_as<typename S::value_type>;
};

/// A Scene that starts a ray's walk past a distance the caller knows clear (see the table above).
template <class S>
concept ResumableScene = Scene<S> && requires(const S& s, const ray<typename S::value_type>& r, typename S::value_type t) {
    { s.intersect_after(r, t, t) } -> std::same_as<std::optional<hit<typename S::value_type>>>;
};

/// A Scene that meets a curved ray's arc itself (see the table above).
template <class S>
concept ArcScene = Scene<S> && requires(const S& s, const scene::vertical_arc<typename S::value_type>& a,
                                        typename S::value_type t) {
    { s.intersect_arc(a, t, t) } -> std::same_as<std::optional<scene::arc_surface_hit<typename S::value_type>>>;
    { s.arc_others() } -> Scene;
};

/// hits[k] = scene.intersect(rays[k], t_max_m) for every k, through the scene's own batch method when it has one.
/// `hits` must hold at least rays.size() slots.
template <Scene S>
void intersect_all(const S& scene, std::span<const ray<typename S::value_type>> rays, typename S::value_type t_max_m,
                   std::span<std::optional<hit<typename S::value_type>>> hits) {
    if constexpr (BatchScene<S>) {
        scene.intersect_many(rays, t_max_m, hits.first(rays.size()));
    } else {
        for (std::size_t k = 0; k < rays.size(); ++k) hits[k] = scene.intersect(rays[k], t_max_m);
    }
}

} // namespace sss

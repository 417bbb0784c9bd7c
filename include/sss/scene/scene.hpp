#pragma once
/// \file
/// A seabed with objects on it and above it: any seabed that models sss::Scene, plus an object_set.
///
/// `intersect` returns the nearest hit over both: the seabed first, then the objects on the ray's piece
/// up to the seabed hit (so objects behind the seabed, and the boxes they sit in, cost nothing); an object
/// hit at exactly the seabed's distance wins. Shadows need nothing more: a ray stopped by an object never
/// reaches the seabed behind it. `seabed_height_m` is the seabed's (objects do not change the nominal
/// altitude that steers ray sampling); `top_m` is the higher of the seabed's top and the objects' tops, and
/// `top_m(lo, hi)` the same over a rectangle: the simulator launches a side's rays for the seabed's top and the
/// objects' over the area those rays can reach, towards everything that can return an echo.

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>

#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/concept.hpp"
#include "sss/scene/object_set.hpp"

namespace sss::scene {

/// The objects of a scene as a Scene of their own (none: nothing), for what a scene that meets arcs in its seabed
/// leaves to chords (ArcScene's arc_others). Holds a pointer: the objects must outlive it.
template <Real T> struct object_view {
    using value_type = T;
    const object_set<T>* objects = nullptr;
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const noexcept {
        if (!objects) return std::nullopt;
        return objects->intersect(r, t_max_m);
    }
    [[nodiscard]] T seabed_height_m(T, T) const noexcept { return -std::numeric_limits<T>::infinity(); }
    [[nodiscard]] T top_m() const noexcept { return objects ? objects->top_m() : -std::numeric_limits<T>::infinity(); }
};

template <Scene Seabed> class scene {
public:
    using value_type = typename Seabed::value_type;
    using T = value_type;

    explicit scene(Seabed seabed, object_set<T> objects = {})
        : seabed_(std::move(seabed)), objects_(std::move(objects)) {}

    [[nodiscard]] const Seabed& seabed() const noexcept { return seabed_; }
    [[nodiscard]] const object_set<T>& objects() const noexcept { return objects_; }

    /// Nearest hit over seabed and objects with 0 < distance <= t_max_m.
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const {
        std::optional<hit<T>> h = seabed_.intersect(r, t_max_m);
        nearer_object(r, t_max_m, h);
        return h;
    }

    /// intersect(r, t_max_m), bit for bit, with the seabed guided by what ray `a` from the same origin found: it met
    /// nothing for distances below a_clear_m (m) (GuidedScene, when the seabed is one).
    [[nodiscard]] std::optional<hit<T>> intersect_beside(const ray<T>& r, T t_max_m, const ray<T>& a, T a_clear_m) const
        requires GuidedScene<Seabed>
    {
        std::optional<hit<T>> h = seabed_.intersect_beside(r, t_max_m, a, a_clear_m);
        nearer_object(r, t_max_m, h);
        return h;
    }

    /// intersect(r, t_max_m), bit for bit, given that r stays in open water (above the seabed, outside every object)
    /// for distances below clear_m (m) (ResumableScene, when the seabed is one): the seabed's walk starts there; the
    /// objects are asked as by intersect.
    [[nodiscard]] std::optional<hit<T>> intersect_after(const ray<T>& r, T t_max_m, T clear_m) const
        requires ResumableScene<Seabed>
    {
        std::optional<hit<T>> h = seabed_.intersect_after(r, t_max_m, clear_m);
        nearer_object(r, t_max_m, h);
        return h;
    }

    /// Horizontal distance (m) from b.origin within which ray r of b surely meets nothing (GuidedScene, when the seabed
    /// is one): the shorter of the seabed's and the objects' (object_set::clear_range_beside_m).
    [[nodiscard]] T clear_range_beside_m(const beside_rays<T>& b) const
        requires GuidedScene<Seabed>
    {
        const T d = seabed_.clear_range_beside_m(b);
        if (objects_.empty() || !(d > T(0))) return d;
        return objects_.clear_range_beside_m(b, d);
    }

    /// hits[k] = intersect(rays[k], t_max_m) for every k: the seabed's hits together (sss::intersect_all, so a
    /// seabed that shares work among rays does), then the objects ray by ray up to each seabed hit.
    void intersect_many(std::span<const ray<T>> rays, T t_max_m, std::span<std::optional<hit<T>>> hits) const {
        sss::require(hits.size() == rays.size(), "scene.intersect_many.hits",
                             [&] { return "must hold one slot per ray (" + std::to_string(rays.size()) + "), got " +
                                 std::to_string(hits.size()); });
        intersect_all(seabed_, rays, t_max_m, hits);
        if (objects_.empty()) return;
        for (std::size_t k = 0; k < rays.size(); ++k)
            if (auto o = objects_.intersect(rays[k], hits[k] ? hits[k]->distance_m : t_max_m)) hits[k] = *o;
    }

    /// The seabed's intersect_arc (ArcScene, when the seabed meets arcs in all of itself): the objects are the rest
    /// (arc_others).
    [[nodiscard]] std::optional<arc_surface_hit<T>> intersect_arc(const vertical_arc<T>& a, T x_clear_m, T x_end_m) const
        requires ArcScene<Seabed> && std::same_as<decltype(std::declval<const Seabed&>().arc_others()), no_geometry<T>>
    {
        return seabed_.intersect_arc(a, x_clear_m, x_end_m);
    }
    /// The objects, as a Scene (ArcScene).
    [[nodiscard]] object_view<T> arc_others() const noexcept
        requires ArcScene<Seabed> && std::same_as<decltype(std::declval<const Seabed&>().arc_others()), no_geometry<T>>
    {
        return object_view<T>{objects_.empty() ? nullptr : &objects_};
    }

    /// How far r runs with no geometry within vertical distance band_m (ClearanceScene, when the seabed is one):
    /// the shorter of the seabed's and the objects' clear lengths.
    [[nodiscard]] T clear_length_m(const ray<T>& r, T t_max_m, T band_m) const
        requires ClearanceScene<Seabed>
    {
        const T d = seabed_.clear_length_m(r, t_max_m, band_m);
        if (objects_.empty() || !(d > T(0))) return d;
        return objects_.clear_length_m(r, d, band_m);
    }

    [[nodiscard]] T seabed_height_m(T x_m, T y_m) const { return seabed_.seabed_height_m(x_m, y_m); }
    [[nodiscard]] T top_m() const { return std::max(seabed_.top_m(), objects_.top_m()); }
    /// The same over the rectangle [lo, hi] (world x, y, m; see AreaScene): the seabed's own there when it can
    /// tell (else its top), and the objects' that reach over the rectangle.
    [[nodiscard]] T top_m(const vec2<T>& lo, const vec2<T>& hi) const {
        T s;
        if constexpr (AreaScene<Seabed>) s = seabed_.top_m(lo, hi);
        else s = seabed_.top_m();
        return std::max(s, objects_.top_m(lo, hi));
    }
    /// How far the seabed and the objects over the rectangle [lo, hi] rise above `plane` (PlaneBoundedScene, where the
    /// seabed is one).
    [[nodiscard]] double rise_above_m(const vec2<T>& lo, const vec2<T>& hi, const sloping_plane& plane) const
        requires PlaneBoundedScene<Seabed>
    {
        return std::max(seabed_.rise_above_m(lo, hi, plane), objects_.rise_above_m(lo, hi, plane));
    }

private:
    /// Replaces the seabed's hit h by the objects' nearest hit before it (within t_max_m when h is none), if any.
    void nearer_object(const ray<T>& r, T t_max_m, std::optional<hit<T>>& h) const {
        if (objects_.empty()) return;
        if (auto o = objects_.intersect(r, h ? h->distance_m : t_max_m)) h = *o;
    }

    Seabed seabed_;
    object_set<T> objects_;
};

template <class Seabed> scene(Seabed) -> scene<Seabed>;
template <class Seabed, class Objects> scene(Seabed, Objects) -> scene<Seabed>;

} // namespace sss::scene

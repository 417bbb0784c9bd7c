#pragma once
/// \file
/// A scene seen from one side of one ping: the same geometry, with the top of what lies over the rectangle the
/// side's rays can reach (sampling/reach.hpp) instead of the whole scene's. A curved-ray propagation hands the
/// scene pieces of its path only below the top (propagation/layered.hpp), so in a large scene one hill or moored
/// mine elsewhere no longer makes every ray of every ping look for geometry from its height down. Over a scene
/// with objects, a side with no object over its rectangle asks the seabed alone.
///
/// Every query is the underlying scene's, unchanged: for rays that stay over the rectangle the view and the scene
/// are the same geometry. The view holds a pointer: the scene must outlive it.

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/concept.hpp"
#include "sss/scene/scene.hpp"

namespace sss::scene {

/// Any AreaScene over the rectangle [lo, hi] (world x, y, m).
template <AreaScene S> class area_view {
public:
    using value_type = typename S::value_type;
    using T = value_type;

    /// Where nothing lies over the rectangle (the top is -infinity), the scene's own top stands: rays then meet
    /// nothing anyway, and a finite top keeps every depth computed from it finite.
    area_view(const S& scene, const vec2<T>& lo, const vec2<T>& hi) : scene_(&scene), top_(bounded_top(scene, lo, hi)) {}

    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const { return scene_->intersect(r, t_max_m); }
    [[nodiscard]] std::optional<hit<T>> intersect_beside(const ray<T>& r, T t_max_m, const ray<T>& a, T a_clear_m) const
        requires GuidedScene<S>
    {
        return scene_->intersect_beside(r, t_max_m, a, a_clear_m);
    }
    [[nodiscard]] std::optional<hit<T>> intersect_after(const ray<T>& r, T t_max_m, T clear_m) const
        requires ResumableScene<S>
    {
        return scene_->intersect_after(r, t_max_m, clear_m);
    }
    [[nodiscard]] T clear_range_beside_m(const beside_rays<T>& b) const
        requires GuidedScene<S>
    {
        return scene_->clear_range_beside_m(b);
    }
    void intersect_many(std::span<const ray<T>> rays, T t_max_m, std::span<std::optional<hit<T>>> hits) const
        requires BatchScene<S>
    {
        scene_->intersect_many(rays, t_max_m, hits);
    }
    [[nodiscard]] T clear_length_m(const ray<T>& r, T t_max_m, T band_m) const
        requires ClearanceScene<S>
    {
        return scene_->clear_length_m(r, t_max_m, band_m);
    }
    [[nodiscard]] auto arc_others() const
        requires ArcScene<S>
    {
        return scene_->arc_others();
    }
    [[nodiscard]] std::optional<arc_surface_hit<T>> intersect_arc(const vertical_arc<T>& a, T x_clear_m, T x_end_m) const
        requires ArcScene<S>
    {
        return scene_->intersect_arc(a, x_clear_m, x_end_m);
    }
    [[nodiscard]] T seabed_height_m(T x_m, T y_m) const { return scene_->seabed_height_m(x_m, y_m); }
    [[nodiscard]] T top_m() const noexcept { return top_; }
    [[nodiscard]] const S& whole() const noexcept { return *scene_; }

private:
    static T bounded_top(const S& s, const vec2<T>& lo, const vec2<T>& hi) {
        const T all = s.top_m(), here = s.top_m(lo, hi);
        return std::isfinite(here) ? std::min(here, all) : all;
    }
    const S* scene_;
    T top_;
};

/// A seabed with objects over the rectangle: the objects are asked only when one of them reaches over it.
template <Scene Seabed> class area_view<scene<Seabed>> {
public:
    using value_type = typename Seabed::value_type;
    using T = value_type;

    area_view(const scene<Seabed>& s, const vec2<T>& lo, const vec2<T>& hi)
        : scene_(&s), objects_near_(std::isfinite(s.objects().top_m(lo, hi))) {
        const T all = s.top_m(), here = s.top_m(lo, hi);
        top_ = std::isfinite(here) ? std::min(here, all) : all;
    }

    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const {
        if (objects_near_) return scene_->intersect(r, t_max_m);
        return scene_->seabed().intersect(r, t_max_m);
    }
    [[nodiscard]] std::optional<hit<T>> intersect_beside(const ray<T>& r, T t_max_m, const ray<T>& a, T a_clear_m) const
        requires GuidedScene<Seabed>
    {
        if (objects_near_) return scene_->intersect_beside(r, t_max_m, a, a_clear_m);
        return scene_->seabed().intersect_beside(r, t_max_m, a, a_clear_m);
    }
    [[nodiscard]] std::optional<hit<T>> intersect_after(const ray<T>& r, T t_max_m, T clear_m) const
        requires ResumableScene<Seabed>
    {
        if (objects_near_) return scene_->intersect_after(r, t_max_m, clear_m);
        return scene_->seabed().intersect_after(r, t_max_m, clear_m);
    }
    [[nodiscard]] T clear_range_beside_m(const beside_rays<T>& b) const
        requires GuidedScene<Seabed>
    {
        if (objects_near_) return scene_->clear_range_beside_m(b);
        return scene_->seabed().clear_range_beside_m(b);
    }
    void intersect_many(std::span<const ray<T>> rays, T t_max_m, std::span<std::optional<hit<T>>> hits) const {
        if (objects_near_) scene_->intersect_many(rays, t_max_m, hits);
        else intersect_all(scene_->seabed(), rays, t_max_m, hits);
    }
    [[nodiscard]] T clear_length_m(const ray<T>& r, T t_max_m, T band_m) const
        requires ClearanceScene<Seabed>
    {
        if (objects_near_) return scene_->clear_length_m(r, t_max_m, band_m);
        return scene_->seabed().clear_length_m(r, t_max_m, band_m);
    }
    /// The seabed's intersect_arc (ArcScene, as the scene's), and the objects as the rest where one reaches over the
    /// rectangle (none otherwise).
    [[nodiscard]] std::optional<arc_surface_hit<T>> intersect_arc(const vertical_arc<T>& a, T x_clear_m, T x_end_m) const
        requires ArcScene<scene<Seabed>>
    {
        return scene_->intersect_arc(a, x_clear_m, x_end_m);
    }
    [[nodiscard]] object_view<T> arc_others() const
        requires ArcScene<scene<Seabed>>
    {
        return objects_near_ ? scene_->arc_others() : object_view<T>{};
    }
    [[nodiscard]] T seabed_height_m(T x_m, T y_m) const { return scene_->seabed_height_m(x_m, y_m); }
    [[nodiscard]] T top_m() const noexcept { return top_; }
    [[nodiscard]] const scene<Seabed>& whole() const noexcept { return *scene_; }
    /// True when an object reaches over the rectangle (else the objects are not asked).
    [[nodiscard]] bool objects_near() const noexcept { return objects_near_; }
    /// This view for rays that stay over the rectangle [lo, hi] (world x, y, m), which lies within this view's: the
    /// objects are asked only when one of them reaches over it (object_set::reaches_over). The top stays this view's,
    /// so that rays are followed as they are through this view (layered water starts its chords from the top).
    [[nodiscard]] area_view within(const vec2<T>& lo, const vec2<T>& hi) const noexcept {
        area_view v = *this;
        v.objects_near_ = objects_near_ && scene_->objects().reaches_over(lo, hi);
        return v;
    }

private:
    const scene<Seabed>* scene_;
    bool objects_near_;
    T top_{};
};

template <class S, class V> area_view(const S&, const V&, const V&) -> area_view<S>;

} // namespace sss::scene

#pragma once
// A scene that counts the rays handed to it: one intersection query per ray with straight propagation (and a ray
// per slot of intersect_many, where the scene it wraps has that). It offers no guided or clearance queries, so a
// simulator traces each ray through it alone: the same hits, bit for bit, as through the scene itself. It bounds its
// geometry over a rectangle and against a plane as the scene it wraps does, so that over a seabed the same rays are
// launched (over a scene::scene with objects, the launch takes the whole scene's top, not the seabed's and the
// objects' over the side's area: it shows no seabed() and objects()).

#include <cstddef>
#include <optional>
#include <span>

#include <sss/core/hit.hpp>
#include <sss/core/ray.hpp>
#include <sss/scene/concept.hpp>

namespace sss_test {

template <class Inner> class counting_scene {
public:
    using value_type = typename Inner::value_type;
    using T = value_type;

    counting_scene(const Inner& inner, std::size_t& count) : inner_(&inner), count_(&count) {}

    [[nodiscard]] std::optional<sss::hit<T>> intersect(const sss::ray<T>& r, T t_max_m) const {
        ++*count_;
        return inner_->intersect(r, t_max_m);
    }
    void intersect_many(std::span<const sss::ray<T>> rays, T t_max_m, std::span<std::optional<sss::hit<T>>> hits) const
        requires requires(const Inner& s) { s.intersect_many(rays, t_max_m, hits); }
    {
        *count_ += rays.size();
        inner_->intersect_many(rays, t_max_m, hits);
    }
    [[nodiscard]] T seabed_height_m(T x, T y) const { return inner_->seabed_height_m(x, y); }
    [[nodiscard]] T top_m() const { return inner_->top_m(); }
    // The bounds over a rectangle, where the scene it wraps has them: a simulator then launches through it as through
    // that scene (it traces through an area view of it, still one query per ray).
    [[nodiscard]] T top_m(const sss::vec2<T>& lo, const sss::vec2<T>& hi) const
        requires sss::AreaScene<Inner>
    {
        return inner_->top_m(lo, hi);
    }
    [[nodiscard]] double rise_above_m(const sss::vec2<T>& lo, const sss::vec2<T>& hi,
                                      const sss::scene::sloping_plane& plane) const
        requires sss::PlaneBoundedScene<Inner>
    {
        return inner_->rise_above_m(lo, hi, plane);
    }

private:
    const Inner* inner_;
    std::size_t* count_;
};

} // namespace sss_test

#pragma once
/// \file
/// Isovelocity water: straight rays, spherical spreading and a constant absorption coefficient.
///
/// One-way intensity at range r (m) relative to 1 m: spreading 1/r^2 (TL = 20 log10 r dB) times absorption
/// 10^(-alpha r / 10^4) with alpha in dB/km (Urick, Principles of Underwater Sound, 3rd ed., ch. 5).

#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/propagation/concept.hpp"
#include "sss/scene/concept.hpp"

namespace sss::propagation {

template <Real T> struct straight_params {
    T sound_speed_mps = T(1500);      ///< speed of sound in the water (m/s)
    T absorption_db_per_km = T(60);   ///< one-way absorption (dB/km); about 60 dB/km near 300 kHz
};

template <Real T> class straight {
public:
    using value_type = T;

    /// Default parameters (non-explicit, so `{}` builds one).
    straight() : straight(straight_params<T>{}) {}

    explicit straight(const straight_params<T>& p) : p_(p) {
        sss::require_in_range(p.sound_speed_mps, T(1000), T(2500), "straight.sound_speed_mps");
        sss::require_non_negative(p.absorption_db_per_km, "straight.absorption_db_per_km");
        loss_per_m_ = std::log(T(10)) * p.absorption_db_per_km / T(10000);
    }

    [[nodiscard]] const straight_params<T>& params() const noexcept { return p_; }
    [[nodiscard]] T reference_speed_mps() const noexcept { return p_.sound_speed_mps; }
    /// Rays run straight at the speed of sound: in time t, c t along their direction (ReachBoundedPropagation).
    [[nodiscard]] T reach_speed_mps(T) const noexcept { return p_.sound_speed_mps; }

    template <Scene S>
    [[nodiscard]] std::optional<path<T>> trace(const ray<T>& r, const S& scene, T t_max_s) const {
        return to_path(r, scene.intersect(r, t_max_s * p_.sound_speed_mps));
    }

    /// The world height (m) of the ray along r where it has gone range_m horizontally from its origin
    /// (RangeHeightPropagation): origin z + range_m d_z / |d_h| for direction d; none for a vertical ray, or where
    /// that point lies beyond c t_max_s along the ray.
    [[nodiscard]] std::optional<T> height_at_range_m(const ray<T>& r, T range_m, T t_max_s) const {
        const T horizontal = std::sqrt(r.direction.x * r.direction.x + r.direction.y * r.direction.y);
        const T length = std::sqrt(horizontal * horizontal + r.direction.z * r.direction.z);
        if (!(range_m >= T(0) && horizontal > T(0))) return std::nullopt;
        if (!(range_m * length <= t_max_s * p_.sound_speed_mps * horizontal)) return std::nullopt;
        return r.origin.z + range_m * r.direction.z / horizontal;
    }

    /// trace(r, scene, t_max_s), bit for bit, given that the ray from r's origin along a_launch met nothing within
    /// horizontal distance a_clear_range_m (m) (GuidedPropagation): a GuidedScene is told that it met nothing for
    /// distances along it below a_clear_range_m divided by its horizontal part; any other scene is asked as by trace.
    template <Scene S>
    [[nodiscard]] std::optional<path<T>> trace_beside(const ray<T>& r, const S& scene, T t_max_s, const vec3<T>& a_launch,
                                                      T a_clear_range_m) const {
        if constexpr (GuidedScene<S>) {
            const T ha = std::sqrt(a_launch.x * a_launch.x + a_launch.y * a_launch.y);
            const T clear_m = ha > T(0) ? a_clear_range_m / ha : T(0);
            return to_path(r, scene.intersect_beside(r, t_max_s * p_.sound_speed_mps, ray<T>{r.origin, a_launch}, clear_m));
        } else {
            return trace(r, scene, t_max_s);
        }
    }

    /// paths[k] = trace(rays[k], scene, t_max_s) for every k, the scene's hits found together (sss::intersect_all),
    /// so a scene that shares work among the rays of a column (BatchScene) gets them all at once.
    template <Scene S>
    void trace_many(std::span<const ray<T>> rays, const S& scene, T t_max_s, std::span<std::optional<path<T>>> paths) const {
        sss::require(paths.size() == rays.size(), "straight.trace_many.paths",
                             [&] { return "must hold one slot per ray (" + std::to_string(rays.size()) + "), got " +
                                 std::to_string(paths.size()); });
        std::vector<std::optional<hit<T>>> hits(rays.size());
        intersect_all(scene, rays, t_max_s * p_.sound_speed_mps, std::span<std::optional<hit<T>>>(hits));
        for (std::size_t k = 0; k < rays.size(); ++k) paths[k] = to_path(rays[k], hits[k]);
    }

private:
    /// The path to hit h of ray r (none without a hit). It met nothing before the hit: clear_range_m is the hit's
    /// horizontal distance, less 1e-4 of it for rounding.
    [[nodiscard]] std::optional<path<T>> to_path(const ray<T>& r, const std::optional<hit<T>>& h) const {
        if (!h) return std::nullopt;
        const T range_m = h->distance_m;
        const T horizontal = std::sqrt(r.direction.x * r.direction.x + r.direction.y * r.direction.y);
        return path<T>{*h, range_m / p_.sound_speed_mps, T(1) / (range_m * range_m), std::exp(-loss_per_m_ * range_m),
                       r.direction, range_m * horizontal * T(0.9999)};
    }

    straight_params<T> p_;
    T loss_per_m_{};
};

static_assert(Propagation<straight<float>> && Propagation<straight<double>>);
static_assert(BatchPropagation<straight<double>, scene::flat_seabed<double>>);
static_assert(RangeHeightPropagation<straight<float>> && RangeHeightPropagation<straight<double>>);

} // namespace sss::propagation

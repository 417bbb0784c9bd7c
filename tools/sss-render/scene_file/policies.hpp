#pragma once
/// \file
/// The beam and the motion of sss-render's simulators, each a run-time choice among the library's policies of
/// its family: `scene_beam` holds an ideal fan or a planar array, `scene_motion` a perturbed track or a sampled
/// trajectory, both of the scene's scalar T (float or double). Each satisfies its family's concept
/// (beam/concept.hpp, motion/concept.hpp) by passing every call to the policy it holds, so the whitelist in
/// build.hpp stays at one instantiation per scalar, scattering and water instead of multiplying by every beam
/// and motion. The dispatch is a std::get_if per call (no std::visit, which may throw
/// std::bad_variant_access): `weight` stays noexcept, and a scene of the ideal fan and the perturbed motion
/// renders bit for bit what a simulator of those two policies renders.

#include <sss/beam/concept.hpp>
#include <sss/beam/ideal_fan.hpp>
#include <sss/beam/planar_array.hpp>
#include <sss/core/constants.hpp>
#include <sss/motion/concept.hpp>
#include <sss/motion/perturbed.hpp>
#include <sss/motion/trajectory.hpp>

#include <cstddef>
#include <limits>
#include <utility>
#include <variant>

namespace sss::scene_file {

/// The beam a scene asks for: an ideal fan or a planar array, of the scene's scalar T (render.precision).
template <Real T> class scene_beam {
public:
    using value_type = T;
    using fan = sss::beam::ideal_fan<T>;
    using array = sss::beam::planar_array<T>;

    explicit scene_beam(fan b) : b_(std::move(b)) {}
    explicit scene_beam(array b) : b_(std::move(b)) {}

    [[nodiscard]] sss::beam_extent<T> extent(side s) const noexcept {
        if (const auto* a = std::get_if<array>(&b_)) return a->extent(s);
        return std::get_if<fan>(&b_)->extent(s);
    }
    [[nodiscard]] T weight(side s, T along_rad, T depression_rad) const noexcept {
        if (const auto* a = std::get_if<array>(&b_)) return a->weight(s, along_rad, depression_rad);
        return std::get_if<fan>(&b_)->weight(s, along_rad, depression_rad);
    }
    /// The planar array's along-track step; 0 for the ideal fan, which the simulator reads as "no columns beyond
    /// ray_density.along" (simulator::along_columns), what a fan without the member gets.
    [[nodiscard]] T along_resolution_rad(side s) const noexcept {
        if (const auto* a = std::get_if<array>(&b_)) return a->along_resolution_rad(s);
        return T(0);
    }
    /// The planar array held, or nullptr.
    [[nodiscard]] const array* planar() const noexcept { return std::get_if<array>(&b_); }
    [[nodiscard]] const std::variant<fan, array>& held() const noexcept { return b_; }

private:
    std::variant<fan, array> b_;
};

/// Full widths of a beam's two-way pattern at half power (-3 dB), for the XTF header's beam angles (deg).
struct half_power_widths {
    double along_deg = 0;    ///< along track, in the plane of the axis
    double vertical_deg = 0; ///< in the tilted across-track plane, along = 0
};

/// The ideal fan's widths as given; the planar array's found from its weight: from the axis (along 0, depression
/// `depression_deg`) outward in steps small against the main lobe, the first step below half power bisected.
template <Real T> [[nodiscard]] half_power_widths widths_of(const scene_beam<T>& b, double depression_deg) {
    const auto* a = b.planar();
    if (!a) {
        const auto& p = std::get_if<typename scene_beam<T>::fan>(&b.held())->params();
        return {double(p.along_width_deg), double(p.vertical_width_deg)};
    }
    const double tilt = depression_deg * sss::pi_v<double> / 180.0;
    // The angle from the axis where the weight first falls below 1/2 along direction (da, de) (rad).
    const auto half = [&](double da, double de, double step) {
        const auto w = [&](double x) { return double(a->weight(side::starboard, T(x * da), T(tilt + x * de))); };
        double lo = 0;
        while (lo < sss::half_pi_v<double> && w(lo + step) >= 0.5) lo += step;
        double hi = lo + step;
        for (int k = 0; k < 60; ++k) (w(0.5 * (lo + hi)) >= 0.5 ? lo : hi) = 0.5 * (lo + hi);
        return 0.5 * (lo + hi);
    };
    const double along_step = double(a->along_resolution_rad(side::starboard)) / 16.0;
    const double to_deg = 180.0 / sss::pi_v<double>;
    return {2.0 * half(1, 0, along_step) * to_deg, (half(0, 1, 1e-3) + half(0, -1, 1e-3)) * to_deg};
}

/// The towfish's motion a scene asks for: a perturbed track (straight line, turn, oscillations) or a trajectory
/// sampled in a file, of the scene's scalar T.
template <Real T> class scene_motion {
public:
    using value_type = T;
    using perturbed = sss::motion::perturbed<T>;
    using trajectory = sss::motion::trajectory<T>;

    explicit scene_motion(perturbed m) : m_(std::move(m)) {}
    explicit scene_motion(trajectory m) : m_(std::move(m)) {}

    /// The pose at ping i; a trajectory throws sss::invalid_parameter("ping") beyond its last ping.
    [[nodiscard]] sss::pose<T> pose_at(std::size_t ping) const {
        if (const auto* t = std::get_if<trajectory>(&m_)) return t->pose_at(ping);
        return std::get_if<perturbed>(&m_)->pose_at(ping);
    }
    /// Ping i's time since ping 0 (s) in double: pose_at's time_s without T's rounding.
    [[nodiscard]] double time_since_ping0_s(std::size_t ping) const {
        if (const auto* t = std::get_if<trajectory>(&m_)) return t->time_since_ping0_s(ping);
        return static_cast<double>(ping) * static_cast<double>(std::get_if<perturbed>(&m_)->params().ping_interval_s);
    }
    /// The track without oscillations (perturbed), or the trajectory's pose: the swath geometry of coverage.hpp.
    [[nodiscard]] sss::pose<T> nominal_pose_at(std::size_t ping) const {
        if (const auto* t = std::get_if<trajectory>(&m_)) return t->pose_at(ping);
        return std::get_if<perturbed>(&m_)->nominal_pose_at(ping);
    }
    /// Pings 0 .. ping_count() - 1 have a pose: the trajectory's count, or no limit for a perturbed track.
    [[nodiscard]] std::size_t ping_count() const noexcept {
        if (const auto* t = std::get_if<trajectory>(&m_)) return t->ping_count();
        return std::numeric_limits<std::size_t>::max();
    }
    /// The trajectory held, or nullptr.
    [[nodiscard]] const trajectory* sampled() const noexcept { return std::get_if<trajectory>(&m_); }

private:
    std::variant<perturbed, trajectory> m_;
};

static_assert(AlongResolvedBeam<scene_beam<float>> && Motion<scene_motion<float>>);
static_assert(AlongResolvedBeam<scene_beam<double>> && Motion<scene_motion<double>>);

} // namespace sss::scene_file

#pragma once
/// \file
/// One specular bounce (the Bell & Linnett rule): a ray that meets the seabed or an object also continues in the
/// specular direction, weighted by the coherent reflection coefficient of the surface; what it meets next
/// scatters back to the transducer along the same path, and the travel time is the sum of the legs.
///
/// `specular_bounce<S>` is the scattering policy S with the bounce switched on: the simulator reads the static
/// member `specular_bounce_enabled` (its value: a policy declaring it false does not bounce) and traces the
/// second leg; a simulator built on plain S compiles without it and pays nothing. S must model `Reflecting`:
///
/// | expression                           | type | meaning                                                          |
/// |--------------------------------------|------|------------------------------------------------------------------|
/// | `s.reflection(graze_rad, m, patch_m)`| T    | coherent intensity reflection coefficient |R|^2 in [0, 1] of    |
/// |                                      |      | material m at grazing angle graze_rad, roughness finer than      |
/// |                                      |      | patch_m (m) reducing it                                          |
///
/// Along the bounced path the sound passes the bounce twice (out and back), so the echo carries |R|^4.

#include <concepts>
#include <cstdint>

#include "sss/core/error.hpp"
#include "sss/scattering/concept.hpp"

namespace sss {

template <class S>
concept Reflecting = Scattering<S> && requires(const S& s, typename S::value_type a, std::uint32_t m) {
    { s.reflection(a, m, a) } noexcept -> std::same_as<typename S::value_type>;
};

} // namespace sss

namespace sss::scattering {

template <Reflecting S> class specular_bounce : public S {
public:
    using value_type = typename S::value_type;
    using base_type = S;
    /// Marks the policy for the simulator: trace one specular bounce per ray.
    static constexpr bool specular_bounce_enabled = true;

    /// \param base     the scattering policy
    /// \param patch_m  scale (m) below which roughness reduces the coherent reflection: the scene's cell size
    explicit specular_bounce(S base, value_type patch_m = value_type(0.1)) : S(std::move(base)), patch_m_(patch_m) {
        sss::require_positive(patch_m, "specular_bounce.patch_m");
    }

    [[nodiscard]] const S& base() const noexcept { return *this; }
    [[nodiscard]] value_type patch_m() const noexcept { return patch_m_; }

    /// Intensity reflection coefficient of one pass through the bounce.
    [[nodiscard]] value_type bounce_reflection(value_type graze_rad, std::uint32_t material) const noexcept {
        return S::reflection(graze_rad, material, patch_m_);
    }

private:
    value_type patch_m_;
};

} // namespace sss::scattering

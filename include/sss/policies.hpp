#pragma once
/// \file
/// The shipped policies of one scalar type, named once: `sss::policies<float>::jackson` is
/// `sss::scattering::jackson<float>`, and `sss::policies<float>::simulator<...>` composes them.
///
///     using P = sss::policies<float>;
///     const P::simulator<P::jackson, P::straight, P::planar_array, P::perturbed> sim(...);
///     const P::simulator<> plain;   // lambertian, straight, ideal_fan, straight_line
///
/// Mixing scalar types is impossible by construction (the simulator also checks it).

#include "sss/beam/ideal_fan.hpp"
#include "sss/beam/planar_array.hpp"
#include "sss/core/types.hpp"
#include "sss/motion/perturbed.hpp"
#include "sss/motion/straight_line.hpp"
#include "sss/motion/trajectory.hpp"
#include "sss/propagation/layered.hpp"
#include "sss/propagation/straight.hpp"
#include "sss/scattering/hard_target.hpp"
#include "sss/scattering/jackson.hpp"
#include "sss/scattering/lambertian.hpp"
#include "sss/simulator.hpp"

namespace sss {

/// Every shipped policy, and the simulator, for one scalar type T (float or double).
template <Real T> struct policies {
    using value_type = T;

    // Scattering
    using lambertian = scattering::lambertian<T>;
    using jackson = scattering::jackson<T>;
    using hard_target = scattering::hard_target<T>;
    // Propagation
    using straight = propagation::straight<T>;
    using layered = propagation::layered<T>;
    // Beam
    using ideal_fan = beam::ideal_fan<T>;
    using planar_array = beam::planar_array<T>;
    // Motion
    using straight_line = motion::straight_line<T>;
    using perturbed = motion::perturbed<T>;
    using trajectory = motion::trajectory<T>;

    /// The simulator over these policies; each defaults to the simplest of its family.
    template <Scattering S = lambertian, Propagation P = straight, Beam B = ideal_fan, Motion M = straight_line>
    using simulator = sss::simulator<S, P, B, M>;
};

} // namespace sss

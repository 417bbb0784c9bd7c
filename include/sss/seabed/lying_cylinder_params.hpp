#pragma once
/// \file
/// The parameters of a cylinder lying on the seabed (seabed/targets.hpp builds it, and includes this header).

#include "sss/core/types.hpp"
#include "sss/scene/surface_ids.hpp"

namespace sss::seabed {

/// A cylinder lying on the seabed, resting on the upper hull of the seabed profile along its axis.
template <Real T> struct lying_cylinder_params {
    vec2<T> center_m{T(0), T(0)}; ///< world (x, y) of the middle of its axis (m)
    T heading_deg = T(90);        ///< direction of its axis, clockwise from north (deg); 90: east
    T length_m = T(2);            ///< length (m), > 0
    T radius_m = T(0.25);         ///< radius (m), > 0
    T profile_step_m = T(0.05);   ///< seabed sample spacing along the axis (m), > 0
    scene::surface_ids ids{.material = 1, .object = 0, .label = 3}; ///< the cylinder's ids
};

} // namespace sss::seabed

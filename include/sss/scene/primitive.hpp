#pragma once
/// \file
/// What every object primitive (sphere.hpp, cylinder.hpp) shares: the ids its hits carry, its bounding
/// box, and the rules of its ray intersection.
///
/// Rules of intersection, the same for every primitive:
/// - A primitive is a closed solid; a ray's hit is its nearest crossing of the solid's surface with
///   0 < t <= t_max_m. The crossings are found as the interval [t_in, t_out] of the ray inside the solid
///   (an intersection of intervals for a capped cylinder), so a ray can never slip between two faces.
/// - A ray that starts inside the solid hits the inside of its surface where it leaves (t_out), and the
///   hit's normals point inwards: `hit.normal` always faces the ray (dot(normal, direction) <= 0), which is
///   what the simulator expects. A ray that starts exactly on the surface and leaves it does not hit (t = 0 is
///   excluded); one that starts on it to rounding (a hit point as computed, half of them just inside) may hit it
///   again a rounding's distance away, as from inside. Sonar rays start in the water, and a ray leaving a surface
///   (the simulator's specular bounce) starts a millimetre-scale offset off it; propagation models' pieces start
///   where the previous piece ended, in the water.
/// - A tangent ray (it touches the surface without entering, to rounding) hits at the touching point,
///   with a normal perpendicular to the ray; the simulator gives such a hit no energy (zero projected area).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>

#include <glm/geometric.hpp>

#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/box.hpp"
#include "sss/scene/detail/box_test.hpp"
#include "sss/scene/detail/primitive_checks.hpp"
#include "sss/scene/detail/solid_crossing.hpp"
#include "sss/scene/surface_ids.hpp"

#pragma once
/// \file
/// sss: sidescan sonar simulation by ray tracing. The umbrella header: everything public.

#include "sss/version.hpp"

#include "sss/core/constants.hpp"
#include "sss/core/decibel.hpp"
#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/pose.hpp"
#include "sss/core/ray.hpp"
#include "sss/core/render_control.hpp"
#include "sss/core/thread_pool.hpp"
#include "sss/core/types.hpp"

#include "sss/scene/concept.hpp"
#include "sss/scene/flat_seabed.hpp"

#include "sss/scattering/concept.hpp"
#include "sss/scattering/jackson.hpp"
#include "sss/scattering/lambertian.hpp"
#include "sss/scattering/specular_bounce.hpp"
#include "sss/scattering/reflection.hpp"
#include "sss/scattering/sediments.hpp"

#include "sss/propagation/concept.hpp"
#include "sss/propagation/absorption.hpp"
#include "sss/propagation/profile.hpp"
#include "sss/propagation/ray_arc.hpp"
#include "sss/propagation/sound_speed.hpp"
#include "sss/propagation/straight.hpp"

#include "sss/beam/concept.hpp"
#include "sss/beam/directivity.hpp"
#include "sss/beam/ideal_fan.hpp"
#include "sss/beam/planar_array.hpp"

#include "sss/motion/concept.hpp"
#include "sss/motion/perturbed.hpp"
#include "sss/motion/straight_line.hpp"
#include "sss/motion/trajectory.hpp"

#include "sss/receiver/image.hpp"
#include "sss/receiver/pulse.hpp"
#include "sss/receiver/receiver.hpp"
#include "sss/receiver/time_sampler.hpp"

#include "sss/sampling/launch_angles.hpp"

#include "sss/io/height_field_io.hpp"
#include "sss/io/sound_speed_profile.hpp"
#include "sss/io/trajectory_csv.hpp"

#include "sss/propagation/arc_intersection.hpp"
#include "sss/propagation/launch_table.hpp"
#include "sss/propagation/layered.hpp"
#include "sss/propagation/ray_tube.hpp"

#include "sss/scattering/jackson_bistatic.hpp"
#include "sss/scattering/jackson_table.hpp"
#include "sss/scattering/jackson_terms.hpp"

#include "sss/scene/cylinder.hpp"
#include "sss/scene/height_field.hpp"
#include "sss/scene/height_field_fan.hpp"
#include "sss/scene/height_field_pyramid.hpp"
#include "sss/scene/height_field_surface.hpp"
#include "sss/scene/height_field_tracer.hpp"
#include "sss/scene/height_field_wedge.hpp"
#include "sss/scene/object.hpp"
#include "sss/scene/object_set.hpp"
#include "sss/scene/primitive.hpp"
#include "sss/scene/scene.hpp"
#include "sss/scene/sphere.hpp"

#include "sss/seabed/composite.hpp"
#include "sss/seabed/fft.hpp"
#include "sss/seabed/fractal.hpp"
#include "sss/seabed/power_law_spectrum.hpp"
#include "sss/seabed/random.hpp"
#include "sss/seabed/raster.hpp"
#include "sss/seabed/ripples.hpp"
#include "sss/seabed/stamps.hpp"
#include "sss/seabed/targets.hpp"
#include "sss/seabed/wave_sum.hpp"

#include "sss/simulator.hpp"

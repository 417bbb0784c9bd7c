#pragma once
/// \file
/// The ids an object primitive's hits carry: material, object and class (label). Part of scene/primitive.hpp,
/// which includes it.

#include <cstdint>

namespace sss::scene {

/// The ids a primitive's hits carry (see core/hit.hpp).
struct surface_ids {
    std::uint32_t material = 0; ///< scattering material id
    std::uint32_t object = 0;   ///< object id; must not be `no_object` (that id means the seabed)
    std::uint32_t label = 0;    ///< object class id: the ground-truth label of the hits
};

} // namespace sss::scene

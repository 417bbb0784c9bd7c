#pragma once
/// \file
/// Internal to the object primitives: the checks of their ids and of their vector parameters. Not part of the API.

#include <string>

#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/types.hpp"
#include "sss/scene/surface_ids.hpp"

namespace sss::scene::detail {

/// Throws unless `ids.object` is a real object id; `who` prefixes the parameter name.
inline void require_object_ids(const surface_ids& ids, const std::string& who) {
    sss::require(ids.object != no_object, who + ".ids.object",
                         "must not be sss::no_object (reserved for the seabed)");
}

/// Throws unless every component of `v` is finite; `name` names it.
template <Real T> void require_finite_vec(const vec3<T>& v, const std::string& name) {
    sss::require_finite(v.x, name + ".x");
    sss::require_finite(v.y, name + ".y");
    sss::require_finite(v.z, name + ".z");
}

} // namespace sss::scene::detail

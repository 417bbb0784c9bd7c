#pragma once
/// \file
/// Internal to scene/object_set.hpp: a node of the flattened bounding-volume hierarchy and the tags of its items.
/// Not part of the API.

#include <cstdint>

#include "sss/core/types.hpp"
#include "sss/scene/box.hpp"

namespace sss::scene::detail {

/// One node of the flattened hierarchy: an inner node's left child follows it, its right child is at
/// `offset`; a leaf's primitives are items [offset, offset + count).
template <Real T> struct bvh_node {
    box<T> bounds;
    std::uint32_t offset = 0;
    std::uint32_t count = 0; ///< 0 for an inner node
    std::uint32_t axis = 0;  ///< split axis of an inner node
};

/// Item tags: which primitive array, and the index in it.
inline constexpr std::uint32_t cylinder_tag = 0x80000000u;

} // namespace sss::scene::detail

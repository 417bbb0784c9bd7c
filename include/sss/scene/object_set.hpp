#pragma once
/// \file
/// Many objects, and the culling that keeps rays far from all of them nearly free: a bounding volume
/// hierarchy (BVH) over every primitive of every object.
///
/// Build: top-down, splitting each node where the surface-area heuristic (MacDonald & Booth, 1990, "Heuristics
/// for ray tracing using space subdivision", The Visual Computer 6(3) 153-166) is lowest among 16 bins of the
/// primitives' centroids along the widest axis (binned as in Wald, 2007, "On fast construction of SAH-based
/// bounding volume hierarchies", IEEE Symposium on Interactive Ray Tracing); a node becomes a leaf when it
/// holds at most 4 primitives and splitting would not pay. Boxes are padded by a few ulps of their
/// coordinates so that rounding in the box test never culls a primitive that the exact test would hit.
/// Traversal: depth first, near child first, each box tested against [0, nearest hit so far]
/// (the slab test of Kay & Kajiya, 1986, SIGGRAPH, with the NaN of 0 x inf, a ray in a box's face plane,
/// read as inside). A ray whose piece passes outside the sphere around the root box costs one point-to-segment
/// distance (no division); one that misses the root box, one box test more.
///
/// The brute-force search (every object, every primitive) is kept to check the hierarchy against.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/beside_rays.hpp"
#include "sss/scene/detail/bvh_node.hpp"
#include "sss/scene/detail/solid_crossing.hpp"
#include "sss/scene/object.hpp"
#include "sss/scene/sloping_plane.hpp"

namespace sss::scene {

template <Real T> class object_set {
public:
    using value_type = T;

    /// An empty set: every ray misses.
    object_set() = default;

    /// Builds the hierarchy over every primitive of `objects`.
    explicit object_set(std::vector<object<T>> objects) : objects_(std::move(objects)) {
        for (const object<T>& o : objects_) {
            for (const sphere<T>& s : o.spheres()) spheres_.push_back(s);
            for (const cylinder<T>& c : o.cylinders()) cylinders_.push_back(c);
            bounds_.expand(o.bounds());
            object_boxes_.push_back(detail::padded(o.bounds()));
        }
        sss::require(cylinders_.size() < detail::cylinder_tag && spheres_.size() < detail::cylinder_tag,
                             "object_set.objects", "too many primitives (at most 2^31 of each kind)");
        build();
    }

    [[nodiscard]] const std::vector<object<T>>& objects() const noexcept { return objects_; }
    [[nodiscard]] std::size_t size() const noexcept { return objects_.size(); }
    [[nodiscard]] bool empty() const noexcept { return objects_.empty(); }
    [[nodiscard]] std::size_t primitive_count() const noexcept { return spheres_.size() + cylinders_.size(); }
    [[nodiscard]] std::size_t node_count() const noexcept { return nodes_.size(); }
    /// Box containing every object (empty box for an empty set).
    [[nodiscard]] const box<T>& bounds() const noexcept { return bounds_; }
    /// Highest world z of any object (m); -infinity for an empty set.
    [[nodiscard]] T top_m() const noexcept { return empty() ? -std::numeric_limits<T>::infinity() : bounds_.hi.z; }
    /// The highest top among the objects whose bounding boxes reach over the rectangle [lo, hi] (world x, y, m);
    /// -infinity when none does.
    [[nodiscard]] T top_m(const vec2<T>& lo, const vec2<T>& hi) const noexcept {
        T m = -std::numeric_limits<T>::infinity();
        for (const object<T>& o : objects_) {
            const box<T>& b = o.bounds();
            if (b.hi.x >= lo.x && b.lo.x <= hi.x && b.hi.y >= lo.y && b.lo.y <= hi.y) m = std::max(m, b.hi.z);
        }
        return m;
    }

    /// No object over the rectangle [lo, hi] (world x, y, m) rises more than this above `plane` (vertically, m): over
    /// each object whose bounding box reaches over the rectangle, the box's top less the plane's lowest point over the
    /// part of the box's footprint within the rectangle; -infinity when none does.
    [[nodiscard]] double rise_above_m(const vec2<T>& lo, const vec2<T>& hi, const sloping_plane& plane) const noexcept {
        double m = -std::numeric_limits<double>::infinity();
        for (const object<T>& o : objects_) {
            const box<T>& b = o.bounds();
            if (!(b.hi.x >= lo.x && b.lo.x <= hi.x && b.hi.y >= lo.y && b.lo.y <= hi.y)) continue;
            const double x0 = double(std::max(b.lo.x, lo.x)), x1 = double(std::min(b.hi.x, hi.x));
            const double y0 = double(std::max(b.lo.y, lo.y)), y1 = double(std::min(b.hi.y, hi.y));
            m = std::max(m, double(b.hi.z) - plane.lowest_m(x0, y0, x1, y1));
        }
        return m;
    }

    /// Whether a leaf box of the hierarchy reaches over the rectangle [lo, hi] (world x, y, m): false only where no
    /// object can lie over it. Through the hierarchy (a node's box holds its children's), so a column of a ping asks
    /// in a few box tests however many objects there are.
    [[nodiscard]] bool reaches_over(const vec2<T>& lo, const vec2<T>& hi) const noexcept {
        if (nodes_.empty()) return false;
        std::array<std::uint32_t, max_depth> stack;
        std::size_t top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const detail::bvh_node<T>& n = nodes_[stack[--top]];
            const box<T>& b = n.bounds;
            if (!(b.hi.x >= lo.x && b.lo.x <= hi.x && b.hi.y >= lo.y && b.lo.y <= hi.y)) continue;
            if (n.count > 0) return true;
            stack[top++] = static_cast<std::uint32_t>(&n - nodes_.data()) + 1;
            stack[top++] = n.offset;
        }
        return false;
    }

    /// Nearest hit over all objects with 0 < distance <= t_max_m, through the hierarchy.
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const noexcept {
        if (nodes_.empty()) return std::nullopt;
        { // Early out without divisions: the piece [0, t_max] passes farther from the root box's centre than
          // its half diagonal (padded).
            const vec3<T> f = r.origin - root_center_;
            const T t = std::clamp(-glm::dot(f, r.direction), T(0), t_max_m);
            const vec3<T> g = f + r.direction * t;
            if (glm::dot(g, g) > root_radius2_) return std::nullopt;
        }
        const detail::box_ray<T> br(r);
        T t_best = t_max_m;
        std::uint32_t best = no_item;
        detail::crossing<T> best_crossing{};
        std::array<std::uint32_t, max_depth> stack;
        std::size_t top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const detail::bvh_node<T>& n = nodes_[stack[--top]];
            T t_entry;
            if (!detail::hits_box(n.bounds, br, t_best, t_entry)) continue;
            if (n.count > 0) {
                for (std::uint32_t i = n.offset, e = n.offset + n.count; i < e; ++i) {
                    const std::uint32_t item = items_[i];
                    const auto c = (item & detail::cylinder_tag) ? cylinders_[item & ~detail::cylinder_tag].first_crossing(r, t_best)
                                                                 : spheres_[item].first_crossing(r, t_best);
                    if (c) {
                        t_best = c->t;
                        best = item;
                        best_crossing = *c;
                    }
                }
                continue;
            }
            const std::uint32_t left = static_cast<std::uint32_t>(&n - nodes_.data()) + 1, right = n.offset;
            // Near child on top of the stack: the one on the side the ray comes from.
            if (r.direction[static_cast<int>(n.axis)] < T(0)) {
                stack[top++] = left;
                stack[top++] = right;
            } else {
                stack[top++] = right;
                stack[top++] = left;
            }
        }
        if (best == no_item) return std::nullopt;
        // The hit at the crossing found: solving again with t_best as the limit would need the same rounding twice,
        // which a compiler that fuses multiply-adds (-march=native with FMA) does not promise, and lose the hit.
        return (best & detail::cylinder_tag) ? cylinders_[best & ~detail::cylinder_tag].hit_at(r, best_crossing)
                                             : spheres_[best].hit_at(r, best_crossing);
    }

    /// How far r runs with no object within vertical distance band_m of it (ClearanceScene): where it enters the
    /// first leaf box of the hierarchy grown by band_m up and down (and a few roundings across), t_max_m if none.
    [[nodiscard]] T clear_length_m(const ray<T>& r, T t_max_m, T band_m) const noexcept {
        if (!(band_m >= T(0))) return T(0); // no band (or NaN): nothing can be promised
        if (nodes_.empty()) return t_max_m;
        const T across = T(16) * std::numeric_limits<T>::epsilon() *
                         std::max({std::abs(r.origin.x), std::abs(r.origin.y), std::abs(r.origin.z), t_max_m, T(1)});
        const vec3<T> grow{across, across, band_m + across};
        const detail::box_ray<T> br(r);
        T t_best = t_max_m;
        std::array<std::uint32_t, max_depth> stack;
        std::size_t top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const detail::bvh_node<T>& n = nodes_[stack[--top]];
            const box<T> b{n.bounds.lo - grow, n.bounds.hi + grow};
            T t_entry;
            if (!detail::hits_box(b, br, t_best, t_entry)) continue;
            if (n.count > 0) {
                t_best = std::min(t_best, t_entry);
                continue;
            }
            stack[top++] = static_cast<std::uint32_t>(&n - nodes_.data()) + 1;
            stack[top++] = n.offset;
        }
        return t_best;
    }

    /// Horizontal distance (m) from b.origin within which ray r of b (beside_rays.hpp) surely meets no object: r runs
    /// in the vertical plane of b.heading_r, no lower than z0 - slope_r rho - margin_m at horizontal distance rho, so
    /// it can be inside a box of the hierarchy only where the horizontal ray crosses the box's footprint and that bound
    /// has come down to the box's top. The least such distance over the leaf boxes (a node's is no more than its
    /// children's), or limit_m (m) when that is less (boxes reached only beyond it are not looked into).
    [[nodiscard]] T clear_range_beside_m(const beside_rays<T>& b, T limit_m) const noexcept {
        constexpr T inf = std::numeric_limits<T>::infinity();
        if (nodes_.empty()) return limit_m;
        if (!(b.slope_r >= T(0)) || !(b.margin_m >= T(0)) || !std::isfinite(b.heading_r.x) ||
            !std::isfinite(b.heading_r.y) || !std::isfinite(b.origin.x) || !std::isfinite(b.origin.y) ||
            !std::isfinite(b.origin.z))
            return T(0); // nothing can be promised
        const T across = T(16) * std::numeric_limits<T>::epsilon() *
                         std::max({std::abs(b.origin.x), std::abs(b.origin.y), std::abs(b.origin.z), T(1)});
        const T ox = b.origin.x, oy = b.origin.y, high = b.origin.z - b.margin_m;
        const T ix = T(1) / b.heading_r.x, iy = T(1) / b.heading_r.y; // +-infinity along an axis
        // Where the bound reaches z_top and the horizontal ray is within [lo, hi]: +infinity when never.
        const auto reach = [&](const box<T>& bx) {
            const T lx = bx.lo.x - across, hx = bx.hi.x + across, ly = bx.lo.y - across, hy = bx.hi.y + across;
            T enter = T(0), leave = inf;
            if (b.heading_r.x != T(0)) {
                const T t1 = (lx - ox) * ix, t2 = (hx - ox) * ix;
                enter = std::max(enter, std::min(t1, t2));
                leave = std::min(leave, std::max(t1, t2));
            } else if (ox < lx || ox > hx) {
                return inf;
            }
            if (b.heading_r.y != T(0)) {
                const T t1 = (ly - oy) * iy, t2 = (hy - oy) * iy;
                enter = std::max(enter, std::min(t1, t2));
                leave = std::min(leave, std::max(t1, t2));
            } else if (oy < ly || oy > hy) {
                return inf;
            }
            const T above = high - bx.hi.z; // the bound comes down to the box's top at above / slope_r
            const T down = above <= T(0) ? T(0) : (b.slope_r > T(0) ? above / b.slope_r * T(0.999) : inf);
            const T first = std::max(enter, down);
            return first <= leave ? first : inf;
        };
        T best = limit_m;
        std::array<std::uint32_t, max_depth> stack;
        std::size_t top = 0;
        stack[top++] = 0;
        while (top > 0) {
            const detail::bvh_node<T>& n = nodes_[stack[--top]];
            const T first = reach(n.bounds);
            if (!(first < best)) continue;
            if (n.count > 0) {
                best = first;
                continue;
            }
            stack[top++] = static_cast<std::uint32_t>(&n - nodes_.data()) + 1;
            stack[top++] = n.offset;
        }
        return best;
    }

    /// intersect by testing every object (each behind its own bounding box): the reference.
    [[nodiscard]] std::optional<hit<T>> intersect_brute_force(const ray<T>& r, T t_max_m) const noexcept {
        std::optional<hit<T>> best;
        const detail::box_ray<T> br(r);
        T t_best = t_max_m, t_entry;
        for (std::size_t i = 0; i < objects_.size(); ++i) {
            if (!detail::hits_box(object_boxes_[i], br, t_best, t_entry)) continue;
            if (auto h = objects_[i].intersect(r, t_best)) {
                t_best = h->distance_m;
                best = h;
            }
        }
        return best;
    }

private:
    static constexpr std::uint32_t no_item = 0xffffffffu;
    static constexpr std::size_t max_depth = 64;  // stack size; the build stops splitting well before
    static constexpr std::size_t max_leaf = 4;    // primitives a leaf may hold when a split would not pay
    static constexpr std::size_t bins = 16;

    struct build_item {
        box<T> bounds;
        vec3<T> centroid;
        std::uint32_t item;
    };

    void build() {
        std::vector<build_item> work;
        work.reserve(primitive_count());
        for (std::size_t i = 0; i < spheres_.size(); ++i) {
            const box<T> b = detail::padded(spheres_[i].bounds());
            work.push_back({b, b.center(), static_cast<std::uint32_t>(i)});
        }
        for (std::size_t i = 0; i < cylinders_.size(); ++i) {
            const box<T> b = detail::padded(cylinders_[i].bounds());
            work.push_back({b, b.center(), static_cast<std::uint32_t>(i) | detail::cylinder_tag});
        }
        if (work.empty()) return;
        nodes_.reserve(2 * work.size());
        split(work, 0, work.size(), 0);
        const box<T>& root = nodes_.front().bounds;
        root_center_ = root.center();
        const T half_diagonal = glm::length(root.extent()) * T(0.5) * (T(1) + T(64) * std::numeric_limits<T>::epsilon());
        root_radius2_ = half_diagonal * half_diagonal;
        items_.reserve(work.size());
        for (const build_item& w : work) items_.push_back(w.item);
    }

    /// Builds the subtree over work[first, last) at `depth`; returns its node index.
    std::uint32_t split(std::vector<build_item>& work, std::size_t first, std::size_t last, std::size_t depth) {
        const auto index = static_cast<std::uint32_t>(nodes_.size());
        nodes_.emplace_back();
        box<T> bounds, centroids;
        for (std::size_t i = first; i < last; ++i) {
            bounds.expand(work[i].bounds);
            centroids.expand(work[i].centroid);
        }
        nodes_[index].bounds = bounds;
        const std::size_t n = last - first;
        auto make_leaf = [&] {
            nodes_[index].offset = static_cast<std::uint32_t>(first);
            nodes_[index].count = static_cast<std::uint32_t>(n);
            return index;
        };
        const vec3<T> ext = centroids.extent();
        int axis = 0;
        if (ext.y > ext[axis]) axis = 1;
        if (ext.z > ext[axis]) axis = 2;
        const bool can_leaf = n <= max_leaf;
        // The depth limit keeps the traversal stack (max_depth entries) from overflowing: a leaf, however full.
        if (n == 1 || depth + 2 >= max_depth) return make_leaf();
        if (!(ext[axis] > T(0))) // coincident centroids: split by count, whatever the cost
            return n <= max_leaf ? make_leaf() : split_at(work, first, first + n / 2, last, depth, axis, index);
        // Binned surface-area heuristic along the widest axis of the centroids.
        struct bin {
            box<T> bounds;
            std::size_t count = 0;
        };
        std::array<bin, bins> b{};
        const T lo = centroids.lo[axis], scale = T(bins) / ext[axis];
        auto bin_of = [&](const build_item& w) {
            const auto k = static_cast<std::size_t>(std::max(T(0), (w.centroid[axis] - lo) * scale));
            return std::min(k, bins - 1);
        };
        for (std::size_t i = first; i < last; ++i) {
            bin& x = b[bin_of(work[i])];
            x.bounds.expand(work[i].bounds);
            ++x.count;
        }
        std::array<T, bins> right_area{};
        std::array<std::size_t, bins> right_count{};
        box<T> acc;
        std::size_t cnt = 0;
        for (std::size_t k = bins - 1; k > 0; --k) {
            acc.expand(b[k].bounds);
            cnt += b[k].count;
            right_area[k] = acc.half_area();
            right_count[k] = cnt;
        }
        acc = box<T>{};
        cnt = 0;
        T best_cost = std::numeric_limits<T>::infinity();
        std::size_t best_k = 0;
        for (std::size_t k = 1; k < bins; ++k) { // split between bins k-1 and k
            acc.expand(b[k - 1].bounds);
            cnt += b[k - 1].count;
            if (cnt == 0 || right_count[k] == 0) continue;
            const T cost = acc.half_area() * T(cnt) + right_area[k] * T(right_count[k]);
            if (cost < best_cost) {
                best_cost = cost;
                best_k = k;
            }
        }
        if (best_k == 0) return n <= max_leaf ? make_leaf() : split_at(work, first, first + n / 2, last, depth, axis, index);
        // A leaf costs n primitive tests; a split one traversal step (~ one test) plus the children's tests
        // weighted by the chance that a ray through this box enters them (area ratio).
        const T area = bounds.half_area();
        const T split_cost = T(1) + (area > T(0) ? best_cost / area : T(n));
        if (can_leaf && T(n) <= split_cost) return make_leaf();
        const auto mid = std::partition(work.begin() + static_cast<std::ptrdiff_t>(first),
                                        work.begin() + static_cast<std::ptrdiff_t>(last),
                                        [&](const build_item& w) { return bin_of(w) < best_k; });
        return split_at(work, first, static_cast<std::size_t>(mid - work.begin()), last, depth, axis, index);
    }

    /// Makes node `index` an inner node over [first, mid) and [mid, last) (by count if either side is empty).
    std::uint32_t split_at(std::vector<build_item>& work, std::size_t first, std::size_t mid, std::size_t last,
                           std::size_t depth, int axis, std::uint32_t index) {
        if (mid == first || mid == last) {
            mid = first + (last - first) / 2;
            std::nth_element(work.begin() + static_cast<std::ptrdiff_t>(first), work.begin() + static_cast<std::ptrdiff_t>(mid),
                             work.begin() + static_cast<std::ptrdiff_t>(last),
                             [axis](const build_item& a, const build_item& b) { return a.centroid[axis] < b.centroid[axis]; });
        }
        nodes_[index].axis = static_cast<std::uint32_t>(axis);
        split(work, first, mid, depth + 1);
        const std::uint32_t right = split(work, mid, last, depth + 1);
        nodes_[index].offset = right;
        return index;
    }

    std::vector<object<T>> objects_;
    std::vector<box<T>> object_boxes_; // padded bounds of each object, contiguous for the brute-force search
    std::vector<sphere<T>> spheres_;
    std::vector<cylinder<T>> cylinders_;
    std::vector<std::uint32_t> items_;
    std::vector<detail::bvh_node<T>> nodes_;
    vec3<T> root_center_{};
    T root_radius2_{};
    box<T> bounds_{};
};

} // namespace sss::scene

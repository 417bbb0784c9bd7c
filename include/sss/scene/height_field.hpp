#pragma once
/// \file
/// The seabed as a height field: heights at the vertices of a regular grid, two triangles per cell
/// (the surface is defined in height_field_surface.hpp), per-cell material and region ids, and exact,
/// watertight ray intersection accelerated by a maximum pyramid (height_field_tracer.hpp).
///
/// Layout: nx x ny vertices, heights[iy * nx + ix] is vertex (ix, iy) at world
/// (origin.x + ix cell_m, origin.y + iy cell_m): x east, y north, row 0 the southern edge. The
/// (nx - 1) x (ny - 1) cells are numbered the same way, cell (ix, iy) at index iy (nx - 1) + ix.
///
/// Memory: the heights, the optional id arrays, and the pyramid (about a third of the heights' bytes).
///
/// Bit for bit. The batch and guided traces below give intersect's hits "bit for bit": each computes the same
/// expressions as the single-ray walk. That holds where every expression rounds alike wherever it is inlined. A
/// compiler that fuses a*b + c into one rounding (GCC and Clang do by default where the target has FMA, as with
/// -march=native) may fuse it in one place and not another; the paths then differ in the last bits, each still a hit
/// of the same surface. sss's own targets keep multiply-adds unfused when built for the native processor.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sss/core/checked_size.hpp"
#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/ray.hpp"
#include "sss/scene/concept.hpp"
#include "sss/scene/height_field_arc.hpp"
#include "sss/scene/height_field_beside.hpp"
#include "sss/scene/height_field_fan.hpp"
#include "sss/scene/height_field_wedge.hpp"
#include "sss/scene/height_field_pyramid.hpp"
#include "sss/scene/height_field_surface.hpp"
#include "sss/scene/height_field_tracer.hpp"
#include "sss/scene/sloping_plane.hpp"

namespace sss::scene {

/// A height field's grid, heights and per-cell ids.
template <Real T> struct height_field_params {
    std::size_t nx = 0;             ///< vertices along x (east), >= 2
    std::size_t ny = 0;             ///< vertices along y (north), >= 2
    T cell_m = T(1);                ///< vertex spacing (m), finite and > 0
    vec2<T> origin_m{T(0), T(0)};   ///< world (x, y) of vertex (0, 0) (m), finite
    std::vector<T> heights_m{};     ///< nx * ny vertex heights, world z (m), row-major from the south row; finite
    std::vector<std::uint32_t> materials{}; ///< per-cell scattering material ids, (nx-1) * (ny-1), or empty for all 0
    std::vector<std::uint32_t> regions{};   ///< per-cell region ids (the ground-truth label of hits), same size rule
};

/// Heights held outside the height field, e.g. in a memory-mapped file (io/mapped_height_field.hpp): `data` points
/// at nx * ny heights laid out as height_field's, and stays valid while `keeper` lives (the height field and its
/// copies hold it).
template <Real T> struct external_heights {
    const T* data = nullptr;
    std::shared_ptr<const void> keeper{};
    /// Optional, a hint: the constructor reads the heights in two passes from the south row (the checks and bounds,
    /// then the pyramid), and calls read_done(first, count) in each pass with bands of rows [first, first + count)
    /// that this pass will not read again. The heights must stay readable (the next pass and the rays read them);
    /// a memory map drops the bands' pages from resident memory here, so that building the field never holds the
    /// heights.
    std::function<void(std::size_t first, std::size_t count)> read_done{};
};

template <Real T> class height_field {
public:
    using value_type = T;

    /// Throws invalid_parameter naming the field ("height_field.nx", "height_field.heights_m[i]", ...).
    explicit height_field(height_field_params<T> p)
        : heights_(std::move(p.heights_m)), materials_(std::move(p.materials)), regions_(std::move(p.regions)) {
        init(p.nx, p.ny, p.cell_m, p.origin_m, heights_.data(), heights_.size());
    }

    /// The same over heights held elsewhere (`heights.data`, nx * ny values, kept alive by `heights.keeper`), e.g.
    /// a memory-mapped file: nothing is copied; the heights are read here in two passes of row bands (checks and
    /// bounds, then the pyramid; see external_heights::read_done) and then as rays need them. `p.heights_m` must be
    /// empty; heights_m() is empty for such a field, heights() views them.
    height_field(height_field_params<T> p, external_heights<T> heights)
        : external_(std::move(heights.keeper)), materials_(std::move(p.materials)), regions_(std::move(p.regions)) {
        sss::require(heights.data != nullptr, "height_field.heights.data", "must not be null");
        sss::require(p.heights_m.empty(), "height_field.heights_m", "must be empty when the heights are external");
        external_data_ = heights.data;
        init(p.nx, p.ny, p.cell_m, p.origin_m, heights.data, checked_elements(p.nx, p.ny, "height_field.nx * ny"),
             heights.read_done);
    }

    height_field(const height_field& o)
        : heights_(o.heights_), external_(o.external_), external_data_(o.external_data_), materials_(o.materials_),
          regions_(o.regions_), pyramid_(o.pyramid_), grid_(o.grid_), bounds_(o.bounds_) {
        grid_.heights = data();
    }
    height_field(height_field&& o) noexcept
        : heights_(std::move(o.heights_)), external_(std::move(o.external_)), external_data_(o.external_data_),
          materials_(std::move(o.materials_)), regions_(std::move(o.regions_)), pyramid_(std::move(o.pyramid_)),
          grid_(o.grid_), bounds_(o.bounds_) {
        grid_.heights = data();
    }
    height_field& operator=(height_field o) noexcept {
        swap(o);
        return *this;
    }
    ~height_field() = default;

    void swap(height_field& o) noexcept {
        heights_.swap(o.heights_);
        external_.swap(o.external_);
        std::swap(external_data_, o.external_data_);
        materials_.swap(o.materials_);
        regions_.swap(o.regions_);
        std::swap(pyramid_, o.pyramid_);
        std::swap(grid_, o.grid_);
        std::swap(bounds_, o.bounds_);
    }

    /// Nearest hit from above with 0 < distance <= t_max_m (accelerated traversal). Normals point up, towards
    /// the water the ray came from; see height_field_tracer.hpp for the rules on rays from below.
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const noexcept {
        return to_hit(r, trace_accelerated(grid_, pyramid_, bounds_, r, t_max_m));
    }
    /// intersect(r, t_max_m), bit for bit, given that ray `neighbour` from the same origin met nothing of the surface
    /// for distances below neighbour_clear_m (m) (GuidedScene): where the neighbour is steeper by enough, r's walk
    /// starts about where the neighbour's ended (height_field_beside.hpp) instead of from the top down. The one
    /// exception, a hit of rounding alone before the neighbour's, is in that file's comment.
    [[nodiscard]] std::optional<hit<T>> intersect_beside(const ray<T>& r, T t_max_m, const ray<T>& neighbour,
                                                         T neighbour_clear_m) const noexcept {
        const T s_clear = clear_beside_m(grid_, pyramid_, bounds_, r, neighbour, neighbour_clear_m);
        return to_hit(r, trace_accelerated(grid_, pyramid_, bounds_, r, t_max_m, s_clear));
    }
    /// intersect(r, t_max_m), bit for bit, given that r stays above the surface for distances below clear_m (m)
    /// (ResumableScene): the walk starts at the entry crossing of the cell that holds that distance, as
    /// intersect_beside's does, with the same one exception (height_field_beside.hpp). A ray that is under the surface
    /// there (from inside the sediment, or into the footprint through its side below the surface) breaks the promise:
    /// it is taken to be above, and its first crossing after is reported. Bent rays hand the scene a chord that starts
    /// within what a neighbour vouches for this way (propagation/layered.hpp).
    [[nodiscard]] std::optional<hit<T>> intersect_after(const ray<T>& r, T t_max_m, T clear_m) const noexcept {
        return to_hit(r, trace_accelerated(grid_, pyramid_, bounds_, r, t_max_m, clear_m));
    }
    /// Nothing: intersect_arc answers for all of this scene (ArcScene).
    [[nodiscard]] static constexpr no_geometry<T> arc_others() noexcept { return {}; }
    /// Where arc `a` first comes down onto the surface within horizontal distance x_end_m (m) of its start, given that
    /// it meets nothing before x_clear_m (m; 0 when nothing is known) (ArcScene): the walk of height_field_arc.hpp,
    /// the hit on the arc itself; the same to the last bit whatever x_clear_m the arc is above.
    [[nodiscard]] std::optional<arc_surface_hit<T>> intersect_arc(const vertical_arc<T>& a, T x_clear_m,
                                                                  T x_end_m) const noexcept {
        const auto g = trace_arc(grid_, pyramid_, bounds_, a, x_clear_m, x_end_m);
        if (!g) return std::nullopt;
        const vec3<T> p = a.at(g->x_m);
        const T u = (p.x - grid_.origin_m.x) * grid_.inv_cell_m - static_cast<T>(g->ix);
        const T v = (p.y - grid_.origin_m.y) * grid_.inv_cell_m - static_cast<T>(g->iy);
        arc_surface_hit<T> out{make_hit(ray<T>{p, vec3<T>{T(0), T(0), T(-1)}}, T(0), g->ix, g->iy,
                                        gradients_at(grid_, g->ix, g->iy, g->triangle, u, v)),
                               g->x_m};
        out.surface.distance_m = g->x_m;
        return out;
    }
    /// Horizontal distance (m) from b.origin within which ray r of b surely stays above the surface, from what b
    /// says of r and a neighbour that met nothing (GuidedScene; bent rays use it: propagation/layered.hpp): the chain
    /// of height_field_beside.hpp; 0 where it does not apply.
    [[nodiscard]] T clear_range_beside_m(const beside_rays<T>& b) const noexcept {
        return sss::scene::clear_range_beside_m(grid_, pyramid_, bounds_, b);
    }
    /// How far r runs with nothing of the surface within band_m below it (ClearanceScene; above a height field
    /// is water): where r lowered by band_m first meets the surface (t_max_m if it does not), provided the lowered
    /// start lies over the footprint and clearly above the surface there (it then cannot come from below, and a
    /// segment that leaves the footprint never comes back); 0 otherwise.
    [[nodiscard]] T clear_length_m(const ray<T>& r, T t_max_m, T band_m) const noexcept {
        if (!(band_m >= T(0))) return T(0); // no band (or NaN): nothing can be promised
        const ray<T> low{vec3<T>{r.origin.x, r.origin.y, r.origin.z - band_m}, r.direction};
        const T u = (low.origin.x - grid_.origin_m.x) * grid_.inv_cell_m;
        const T v = (low.origin.y - grid_.origin_m.y) * grid_.inv_cell_m;
        if (!(u >= T(0) && v >= T(0) && u <= T(grid_.nx - 1) && v <= T(grid_.ny - 1))) return T(0);
        const T h = height_at_grid(grid_, u, v);
        const T margin = T(64) * std::numeric_limits<T>::epsilon() *
                         (std::abs(low.origin.z) + std::abs(h) + std::abs(low.origin.x) + std::abs(low.origin.y));
        if (!(low.origin.z > h + margin)) return T(0);
        const auto g = trace_accelerated(grid_, pyramid_, bounds_, low, t_max_m);
        return g ? g->distance_m : t_max_m;
    }
    /// The same, by the reference traversal (every cell along the ray): slower, kept to check the other.
    [[nodiscard]] std::optional<hit<T>> intersect_reference(const ray<T>& r, T t_max_m) const noexcept {
        return to_hit(r, trace_reference(grid_, bounds_, r, t_max_m));
    }

    /// Hits for many rays: hits[k] = intersect(rays[k], t_max_m), up to rounding. Runs of at least
    /// `min_fan_rays` consecutive rays that share their origin and horizontal heading (a sidescan fan at one
    /// along-track angle, ordered by depression either way) are traced together in one sweep along the
    /// surface under them (height_field_fan.hpp), at a small cost per ray; the sweep evaluates the surface along
    /// the fan's plane, so its hits differ from intersect's by rounding. Runs that share the origin but not
    /// the vertical plane (a column of a rolled, pitched or conical beam: headings within
    /// detail::wedge_max_spread_rad) go through the wedge sweep (height_field_wedge.hpp): an envelope per ring
    /// of the wedge, then a short exact walk per ray, whose hits are intersect's bit for bit. Other rays go one by
    /// one.
    /// Throws invalid_parameter unless hits.size() == rays.size().
    void intersect_many(std::span<const ray<T>> rays, T t_max_m, std::span<std::optional<hit<T>>> hits) const {
        sss::require(hits.size() == rays.size(), "height_field.intersect_many.hits",
                             [&] { return "must hold one slot per ray (" + std::to_string(rays.size()) + "), got " +
                                 std::to_string(hits.size()); });
        // Working memory for one fan at a time (at most detail::max_fan_rays rays): the rays' slopes, and
        // where the sweep found each ray coming down, turned into hits in a second pass over the fan.
        fan_scratch scratch;
        if (rays.size() >= min_fan_rays) scratch.resize(std::min(rays.size(), detail::max_fan_rays));
        std::vector<detail::wedge_slope<T>> wedge_slopes; // the same for a wedge run, when one comes
        std::size_t i = 0;
        while (i < rays.size()) {
            const detail::fan_run run = rays.size() - i >= min_fan_rays
                                            ? detail::find_fan_run(rays, i, std::span(scratch.slopes))
                                            : detail::fan_run{};
            if (run.count >= min_fan_rays) {
                const auto fan = rays.subspan(i, run.count);
                const auto fan_out = hits.subspan(i, run.count);
                if (sweep_fan(grid_, bounds_, fan, std::span<const detail::fan_slope<T>>(scratch.slopes).first(run.count),
                              run.steep_first, t_max_m, std::span(scratch.segment_of), std::span(scratch.segments),
                              fan_batch, [&](std::size_t k_begin, std::size_t k_end) {
                                  fan_hits(fan, scratch, t_max_m, fan_out, k_begin, k_end);
                              })) {
                    i += run.count;
                    continue;
                }
            }
            // Not one vertical plane (or too sparse a fan to sweep): a run that shares the origin and a thin wedge
            // of headings goes through the wedge sweep, anything else ray by ray.
            if (rays.size() - i >= min_fan_rays) {
                if (wedge_slopes.empty()) wedge_slopes.resize(std::min(rays.size(), detail::max_fan_rays));
                const detail::wedge_run<T> w = detail::find_wedge_run(rays, i, std::span(wedge_slopes));
                if (w.count >= min_fan_rays) {
                    const auto part = rays.subspan(i, w.count);
                    const auto out = hits.subspan(i, w.count);
                    // The hits go out in batches (grid_hits): the gradients of a batch are read before any hit is
                    // built, so that the rays' reads of the grid overlap instead of waiting on each other.
                    std::array<std::pair<std::size_t, grid_hit<T>>, wedge_batch> pending;
                    std::size_t held = 0;
                    trace_wedge(grid_, pyramid_, bounds_, part,
                                std::span<const detail::wedge_slope<T>>(wedge_slopes).first(w.count), w, t_max_m,
                                [&](std::size_t k, const grid_hit<T>* g) {
                                    if (!g) {
                                        out[k].reset();
                                        return;
                                    }
                                    // Field by field: *g was just stored that way, and one wide load of it
                                    // would wait for the stores to retire instead of taking them forwarded.
                                    auto& [slot_k, slot] = pending[held++];
                                    slot_k = k;
                                    slot.distance_m = g->distance_m;
                                    slot.ix = g->ix;
                                    slot.iy = g->iy;
                                    slot.triangle = g->triangle;
                                    if (held == wedge_batch) {
                                        grid_hits(part, std::span(pending).first(held), out);
                                        held = 0;
                                    }
                                });
                    grid_hits(part, std::span(pending).first(held), out);
                    i += w.count;
                    continue;
                }
            }
            hits[i] = intersect(rays[i], t_max_m);
            ++i;
        }
    }
    /// Shortest run of rays that intersect_many traces as one fan.
    static constexpr std::size_t min_fan_rays = 16;

    /// Surface height (m) at world (x_m, y_m) by the triangle rule; outside the grid's footprint the point
    /// is clamped to the nearest point of the footprint (the edge heights continue outwards).
    [[nodiscard]] T seabed_height_m(T x_m, T y_m) const noexcept {
        return height_at_grid(grid_, (x_m - grid_.origin_m.x) * grid_.inv_cell_m,
                              (y_m - grid_.origin_m.y) * grid_.inv_cell_m);
    }
    /// Highest vertex (m): no geometry above it.
    [[nodiscard]] T top_m() const noexcept { return bounds_.top_m; }
    /// No geometry above it over the rectangle [lo, hi] (world x, y, m): the highest block of the maximum pyramid
    /// among those covering the rectangle's cells, at the finest level that needs at most 16 blocks along each axis
    /// (so at least the highest vertex there, and at most top_m()); -infinity for a rectangle off the grid.
    [[nodiscard]] T top_m(const vec2<T>& lo, const vec2<T>& hi) const noexcept {
        const std::optional<cell_span> cells = cells_under(lo, hi);
        if (!cells) return -std::numeric_limits<T>::infinity(); // off the grid (or NaN)
        if (pyramid_.levels() == 0) return bounds_.top_m;
        const std::int32_t level = block_level(*cells, 16);
        T m = -std::numeric_limits<T>::infinity();
        for (std::int32_t by = cells->c >> level; by <= (cells->d >> level); ++by)
            for (std::int32_t bx = cells->a >> level; bx <= (cells->b >> level); ++bx)
                m = std::max(m, pyramid_.max_m(level, bx, by));
        return m;
    }
    /// No geometry over the rectangle [lo, hi] (world x, y, m) rises more than this above `plane` (vertically, m;
    /// PlaneBoundedScene): over each block of the maximum pyramid that covers the rectangle's cells (as top_m(lo, hi)
    /// takes them), at the finest level that needs at most 64 blocks along each axis, the block's highest vertex less
    /// the plane's lowest point over the block; -infinity for a rectangle off the grid. It may exceed the rise of every
    /// vertex over the rectangle by the rise of a vertex within a block and a cell of it, and by the plane's change
    /// across a block.
    [[nodiscard]] double rise_above_m(const vec2<T>& lo, const vec2<T>& hi, const sloping_plane& plane) const noexcept {
        const std::optional<cell_span> cells = cells_under(lo, hi);
        if (!cells) return -std::numeric_limits<double>::infinity(); // off the grid (or NaN)
        const double cell = double(grid_.cell_m), x0 = double(grid_.origin_m.x), y0 = double(grid_.origin_m.y);
        // The rise of the block of vertices [i0, i1] x [j0, j1] whose highest vertex is top.
        const auto block_rise = [&](double top, std::int32_t i0, std::int32_t i1, std::int32_t j0, std::int32_t j1) {
            return top - plane.lowest_m(x0 + cell * i0, y0 + cell * j0, x0 + cell * i1, y0 + cell * j1);
        };
        if (pyramid_.levels() == 0) { // one cell
            T top = grid_.at(0, 0);
            for (std::int32_t y = 0; y <= 1; ++y)
                for (std::int32_t x = 0; x <= 1; ++x) top = std::max(top, grid_.at(x, y));
            return block_rise(double(top), 0, 1, 0, 1);
        }
        const std::int32_t level = block_level(*cells, 64);
        double m = -std::numeric_limits<double>::infinity();
        for (std::int32_t by = cells->c >> level; by <= (cells->d >> level); ++by)
            for (std::int32_t bx = cells->a >> level; bx <= (cells->b >> level); ++bx)
                m = std::max(m, block_rise(double(pyramid_.max_m(level, bx, by)), bx << level,
                                           std::min((bx + 1) << level, grid_.nx - 1), by << level,
                                           std::min((by + 1) << level, grid_.ny - 1)));
        return m;
    }
    /// Lowest vertex (m).
    [[nodiscard]] T bottom_m() const noexcept { return bounds_.bottom_m; }

    [[nodiscard]] std::size_t nx() const noexcept { return static_cast<std::size_t>(grid_.nx); }
    [[nodiscard]] std::size_t ny() const noexcept { return static_cast<std::size_t>(grid_.ny); }
    [[nodiscard]] T cell_m() const noexcept { return grid_.cell_m; }
    [[nodiscard]] vec2<T> origin_m() const noexcept { return grid_.origin_m; }
    /// Height of vertex (ix, iy) (m); no bounds check.
    [[nodiscard]] T height_m(std::size_t ix, std::size_t iy) const noexcept { return data()[iy * nx() + ix]; }
    /// All vertex heights (m), row-major from the south row (empty for external heights: see heights()).
    [[nodiscard]] const std::vector<T>& heights_m() const noexcept { return heights_; }
    /// All vertex heights (m), row-major from the south row, wherever they are held.
    [[nodiscard]] std::span<const T> heights() const noexcept { return {data(), nx() * ny()}; }
    /// Material id of cell (ix, iy).
    [[nodiscard]] std::uint32_t material(std::size_t ix, std::size_t iy) const noexcept {
        return materials_.empty() ? 0u : materials_[iy * (nx() - 1) + ix];
    }
    /// Region id of cell (ix, iy).
    [[nodiscard]] std::uint32_t region(std::size_t ix, std::size_t iy) const noexcept {
        return regions_.empty() ? 0u : regions_[iy * (nx() - 1) + ix];
    }
    /// Per-cell ids as given (empty when all 0).
    [[nodiscard]] const std::vector<std::uint32_t>& materials() const noexcept { return materials_; }
    [[nodiscard]] const std::vector<std::uint32_t>& regions() const noexcept { return regions_; }

    /// The grid as a view, for the free functions of height_field_surface.hpp and height_field_tracer.hpp.
    [[nodiscard]] const height_grid_view<T>& grid() const noexcept { return grid_; }
    [[nodiscard]] const max_pyramid<T>& pyramid() const noexcept { return pyramid_; }

    /// Bytes of the heights themselves.
    [[nodiscard]] std::size_t height_bytes() const noexcept { return nx() * ny() * sizeof(T); }
    /// Bytes of the acceleration structure beyond the heights (the pyramid).
    [[nodiscard]] std::size_t acceleration_bytes() const noexcept { return pyramid_.bytes(); }

private:
    /// Cells [a, b] x [c, d] (indices) that hold a rectangle of the plane.
    struct cell_span {
        std::int32_t a, b, c, d;
    };
    /// The cells holding the rectangle [lo, hi] (world x, y, m): [u0, u1 - 1] in cells from vertex (0, 0), and the cell
    /// before u0 when the rectangle starts on a vertex line (its vertices are the same, but rounding of the world
    /// coordinate could put it there); none for a rectangle off the grid (or NaN). A rectangle within rounding of the
    /// grid's edge lines is on the grid: a world coordinate computed as origin + i cell rounds by about eps (|x| +
    /// |origin|), in cells eps (|x| + |origin|) / cell, and in float at survey coordinates that is many times eps.
    [[nodiscard]] std::optional<cell_span> cells_under(const vec2<T>& lo, const vec2<T>& hi) const noexcept {
        const double fu0 = double(lo.x - grid_.origin_m.x) * double(grid_.inv_cell_m);
        const double fu1 = double(hi.x - grid_.origin_m.x) * double(grid_.inv_cell_m);
        const double fv0 = double(lo.y - grid_.origin_m.y) * double(grid_.inv_cell_m);
        const double fv1 = double(hi.y - grid_.origin_m.y) * double(grid_.inv_cell_m);
        const double cx = double(grid_.nx - 2), cy = double(grid_.ny - 2); // last cell index
        constexpr double eps = double(std::numeric_limits<T>::epsilon());
        const auto slack = [&](T world, T origin, double f) { // none for an infinite coordinate: off stays off
            return std::isfinite(f) ? eps * (2.0 + std::abs(f) + (std::abs(double(world)) + std::abs(double(origin))) *
                                                                       double(grid_.inv_cell_m))
                                    : 0.0;
        };
        if (!(fu1 >= -slack(hi.x, grid_.origin_m.x, fu1)) || !(fv1 >= -slack(hi.y, grid_.origin_m.y, fv1)) ||
            !(fu0 <= cx + 1.0 + slack(lo.x, grid_.origin_m.x, fu0)) || !(fv0 <= cy + 1.0 + slack(lo.y, grid_.origin_m.y, fv0)))
            return std::nullopt;
        const double u0 = std::floor(fu0), u1 = std::ceil(fu1), v0 = std::floor(fv0), v1 = std::ceil(fv1);
        return cell_span{static_cast<std::int32_t>(std::clamp(u0 - 1.0, 0.0, cx)),
                         static_cast<std::int32_t>(std::clamp(u1, 0.0, cx)),
                         static_cast<std::int32_t>(std::clamp(v0 - 1.0, 0.0, cy)),
                         static_cast<std::int32_t>(std::clamp(v1, 0.0, cy))};
    }
    /// The finest level of the maximum pyramid (at least 1, at most its levels) at which `cells` lie within at most
    /// `blocks` blocks along each axis.
    [[nodiscard]] std::int32_t block_level(const cell_span& cells, std::int32_t blocks) const noexcept {
        std::int32_t level = 1;
        while (level < pyramid_.levels() &&
               ((cells.b >> level) - (cells.a >> level) >= blocks || (cells.d >> level) - (cells.c >> level) >= blocks))
            ++level;
        return level;
    }
    /// Checks the grid and builds the bounds and the pyramid over heights `values` (size of them).
    /// read_done (may be empty): see external_heights.
    void init(std::size_t nx, std::size_t ny, T cell_m, vec2<T> origin_m, const T* values, std::size_t size,
              const std::function<void(std::size_t, std::size_t)>& read_done = {}) {
        constexpr std::size_t max_n = std::size_t(1) << 30;
        sss::require(nx >= 2 && nx <= max_n, "height_field.nx",
                     [&] { return "must lie in [2, 2^30] (vertices), got " + std::to_string(nx); });
        sss::require(ny >= 2 && ny <= max_n, "height_field.ny",
                     [&] { return "must lie in [2, 2^30] (vertices), got " + std::to_string(ny); });
        sss::require_positive(cell_m, "height_field.cell_m");
        sss::require(std::isfinite(T(1) / cell_m), "height_field.cell_m",
                     [&] { return "must have a finite inverse (the walk divides by it), got " + std::to_string(cell_m); });
        sss::require_finite(origin_m.x, "height_field.origin_m.x");
        sss::require_finite(origin_m.y, "height_field.origin_m.y");
        const std::size_t n = checked_elements(nx, ny, "height_field.nx * ny"), cells = (nx - 1) * (ny - 1);
        sss::require(size == n, "height_field.heights_m",
                     [&] { return "must hold nx * ny = " + std::to_string(n) + " values, got " + std::to_string(size); });
        sss::require(materials_.empty() || materials_.size() == cells, "height_field.materials", [&] {
            return "must be empty or hold (nx-1) * (ny-1) = " + std::to_string(cells) + " ids, got " +
                   std::to_string(materials_.size());
        });
        sss::require(regions_.empty() || regions_.size() == cells, "height_field.regions", [&] {
            return "must be empty or hold (nx-1) * (ny-1) = " + std::to_string(cells) + " ids, got " +
                   std::to_string(regions_.size());
        });
        // Rows already handed to read_done: it is told of bands of at least release_rows rows (a few MiB for
        // wide grids), and of the rest at the end of each pass.
        constexpr std::size_t release_rows = 64;
        std::size_t released = 0;
        const auto rows_read = [&](std::size_t rows) {
            if (!read_done || rows < released + (rows < ny ? release_rows : 1)) return;
            read_done(released * nx, (rows - released) * nx);
            released = rows;
        };
        bounds_.bottom_m = std::numeric_limits<T>::infinity();
        bounds_.top_m = -std::numeric_limits<T>::infinity();
        for (std::size_t iy = 0; iy < ny; ++iy) {
            for (std::size_t ix = 0; ix < nx; ++ix) {
                const std::size_t i = iy * nx + ix;
                const T h = values[i];
                if (!std::isfinite(h))
                    throw invalid_parameter("height_field.heights_m[" + std::to_string(i) + "]",
                                            "must be finite, got " + std::to_string(h) + " at vertex (ix " +
                                                std::to_string(ix) + ", iy " + std::to_string(iy) + ")");
                bounds_.bottom_m = std::min(bounds_.bottom_m, h);
                bounds_.top_m = std::max(bounds_.top_m, h);
            }
            rows_read(iy + 1);
        }
        grid_.heights = values;
        grid_.nx = static_cast<std::int32_t>(nx);
        grid_.ny = static_cast<std::int32_t>(ny);
        grid_.cell_m = cell_m;
        grid_.inv_cell_m = T(1) / cell_m;
        grid_.origin_m = origin_m;
        released = 0; // the pyramid reads the rows again, from the south
        pyramid_ = max_pyramid<T>(grid_, [&](std::int32_t rows) { rows_read(static_cast<std::size_t>(rows)); });
    }

    [[nodiscard]] const T* data() const noexcept { return external_data_ != nullptr ? external_data_ : heights_.data(); }

    [[nodiscard]] std::optional<hit<T>> to_hit(const ray<T>& r, const std::optional<grid_hit<T>>& g) const noexcept {
        if (!g) return std::nullopt;
        return to_hit(r, *g);
    }
    [[nodiscard]] hit<T> to_hit(const ray<T>& r, const grid_hit<T>& g) const noexcept {
        const vec3<T> p = r.at(g.distance_m);
        const T a = (p.x - grid_.origin_m.x) * grid_.inv_cell_m - static_cast<T>(g.ix);
        const T b = (p.y - grid_.origin_m.y) * grid_.inv_cell_m - static_cast<T>(g.iy);
        return make_hit(r, g.distance_m, g.ix, g.iy, gradients_at(grid_, g.ix, g.iy, g.triangle, a, b));
    }
    /// The hit of ray r at distance s in cell (ix, iy) where the surface has gradients gr, every field.
    [[nodiscard]] hit<T> make_hit(const ray<T>& r, T s, std::int32_t ix, std::int32_t iy,
                                  const hit_gradients<T>& gr) const noexcept {
        hit<T> h;
        h.distance_m = s;
        h.point = r.at(s);
        // Both normals from their gradients, sharing one division: n = (-gx, -gy, 1) / sqrt(1 + |g|^2).
        const vec2<T> gt = gr.triangle, gs = gr.smooth;
        const T lt = std::sqrt(T(1) + gt.x * gt.x + gt.y * gt.y), ls = std::sqrt(T(1) + gs.x * gs.x + gs.y * gs.y);
        const T inv = T(1) / (lt * ls), it = inv * ls, is = inv * lt;
        h.normal = vec3<T>{-gt.x * it, -gt.y * it, it};
        h.shading_normal = vec3<T>{-gs.x * is, -gs.y * is, is};
        const std::size_t c = grid_.cell_index(ix, iy);
        h.material = materials_.empty() ? 0u : materials_[c];
        h.object = no_object;
        h.label = regions_.empty() ? 0u : regions_[c];
        return h;
    }

    /// How many rays a fan's sweep settles before intersect_many turns them into hits.
    static constexpr std::size_t fan_batch = 32;

    /// What intersect_many keeps per fan ray: its slope, and the segment of the profile it comes down on.
    struct fan_scratch {
        std::vector<detail::fan_slope<T>> slopes;
        std::vector<std::uint32_t> segment_of;
        std::vector<detail::fan_segment<T>> segments;
        void resize(std::size_t n) {
            slopes.resize(n);
            segment_of.resize(n);
            segments.resize(n);
        }
    };

    /// The hits of a swept fan, in batches: first the distance of every ray of the batch, then the
    /// gradients under them, then the hits, so that the rays of a batch overlap in the pipeline instead of
    /// waiting on each other's square roots and divisions.
    void fan_hits(std::span<const ray<T>> fan, const fan_scratch& sc, T t_max_m, std::span<std::optional<hit<T>>> hits,
                  std::size_t k_begin, std::size_t k_end) const noexcept {
        constexpr std::size_t batch = 16;
        const T inv_c = grid_.inv_cell_m;
        for (std::size_t k0 = k_begin; k0 < k_end; k0 += batch) {
            const std::size_t m = std::min(batch, k_end - k0);
            T dist[batch];
            hit_gradients<T> gr[batch];
            const detail::fan_segment<T>* seg[batch];
            for (std::size_t j = 0; j < m; ++j) {
                const std::size_t k = k0 + j;
                const std::uint32_t c = sc.segment_of[k];
                seg[j] = c == detail::no_fan_segment ? nullptr : &sc.segments[c];
                dist[j] = seg[j] ? detail::fan_distance(*seg[j], sc.slopes[k], t_max_m) : T(0);
            }
            for (std::size_t j = 0; j < m; ++j) {
                if (!(dist[j] > T(0))) continue;
                const vec3<T> p = fan[k0 + j].at(dist[j]);
                const T a = (p.x - grid_.origin_m.x) * inv_c - static_cast<T>(seg[j]->ix);
                const T b = (p.y - grid_.origin_m.y) * inv_c - static_cast<T>(seg[j]->iy);
                gr[j] = gradients_at(grid_, seg[j]->ix, seg[j]->iy, seg[j]->triangle, a, b);
            }
            for (std::size_t j = 0; j < m; ++j) {
                if (k0 + j + 2 * batch < hits.size()) { // the slots come from memory: ask for them ahead
                    const auto* slot = reinterpret_cast<const unsigned char*>(&hits[k0 + j + 2 * batch]);
                    sss::detail::prefetch(slot);
                    sss::detail::prefetch(slot + sizeof(std::optional<hit<T>>) - 1);
                }
                if (dist[j] > T(0))
                    hits[k0 + j].emplace(make_hit(fan[k0 + j], dist[j], seg[j]->ix, seg[j]->iy, gr[j]));
                else
                    hits[k0 + j].reset();
            }
        }
    }

    /// How many of a wedge run's grid hits intersect_many turns into hits at once (grid_hits).
    static constexpr std::size_t wedge_batch = 16;

    /// The hits of rays rays[k] at grid hits g, for each (k, g) of `found` (at most wedge_batch), into hits[k]: as
    /// to_hit, in three passes (the points, the gradients under them, the hits), as fan_hits does.
    void grid_hits(std::span<const ray<T>> rays, std::span<const std::pair<std::size_t, grid_hit<T>>> found,
                   std::span<std::optional<hit<T>>> hits) const noexcept {
        const std::size_t m = found.size();
        T a[wedge_batch], b[wedge_batch];
        hit_gradients<T> gr[wedge_batch];
        for (std::size_t j = 0; j < m; ++j) {
            const auto& [k, g] = found[j];
            const vec3<T> p = rays[k].at(g.distance_m);
            a[j] = (p.x - grid_.origin_m.x) * grid_.inv_cell_m - static_cast<T>(g.ix);
            b[j] = (p.y - grid_.origin_m.y) * grid_.inv_cell_m - static_cast<T>(g.iy);
        }
        for (std::size_t j = 0; j < m; ++j) {
            const grid_hit<T>& g = found[j].second;
            gr[j] = gradients_at(grid_, g.ix, g.iy, g.triangle, a[j], b[j]);
        }
        for (std::size_t j = 0; j < m; ++j) {
            const auto& [k, g] = found[j];
            hits[k].emplace(make_hit(rays[k], g.distance_m, g.ix, g.iy, gr[j]));
        }
    }

    std::vector<T> heights_;
    std::shared_ptr<const void> external_; // keeps external heights alive
    const T* external_data_ = nullptr;     // external heights, or null when heights_ holds them
    std::vector<std::uint32_t> materials_;
    std::vector<std::uint32_t> regions_;
    max_pyramid<T> pyramid_;
    height_grid_view<T> grid_{};
    height_bounds<T> bounds_{};
};

static_assert(Scene<height_field<float>> && Scene<height_field<double>>);

} // namespace sss::scene

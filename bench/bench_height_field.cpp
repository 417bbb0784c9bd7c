// Ray tracing of the seabed height field on the reference scene: a 4096 x 4096 rough height field at
// 0.25 m cells (1 km square; swell, dunes, ripples and white noise, +-2.5 m), a towfish 10 m above the
// mean seabed, and pings of 2 x 2048 x 8 rays (port and starboard fans; 8 along-track angles within
// +-0.5 deg; 2048 depression angles from 60 deg down to the one that reaches 100 m slant range on the
// flat mean bottom, spaced evenly in slant range). Rays/s (items/s) per core, single-threaded, for
//   reference    intersect_reference(): every cell along the ray,
//   accelerated  intersect(): the maximum pyramid, one ray at a time,
//   fans         intersect_many(): a ping's fans swept together,
// and, on the same pings with cone columns (a beam's along-track columns, whose headings vary with depression),
// accelerated against intersect_many (which then takes its wedge sweep, height_field_wedge.hpp; the intersect_many
// rows also report differ_from_intersect, the fraction of rays whose hit differs from intersect()'s in any bit: 0
// for the wedge sweep, whose hits are intersect's exactly),
//   bilinear     a plain DDA over bilinear patches (a quadratic per cell), the alternative surface,
// and the memory of the acceleration beyond the heights. When the build finds Embree 3 (optional), the
// same triangles and rays are also traced by Embree (rtcIntersect8 packets and rtcIntersect1), checked
// against intersect() and timed against the fans. Another tracer plugs in as one more `tracer` type:
// Tracer<T>{hf} builds it from the height field, and trace(rays, t_max, hits) fills one optional hit
// per ray; register it with TRACE_BENCHMARKS (the Embree ones are float only and registered directly).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include <sss/scene/height_field.hpp>

#include "support/rough_relief.hpp"

#ifdef SSS_HAVE_EMBREE
#include <embree3/rtcore.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#endif

namespace {

using sss::ray;
using sss::vec2;
using sss::vec3;
using sss::scene::height_field;

constexpr std::size_t grid_n = 4096;
constexpr double cell_m = 0.25;
constexpr double altitude_m = 10.0;
constexpr double range_m = 100.0;
constexpr int rays_per_fan = 2048;
constexpr int along_track_angles = 8;
constexpr int pings = 64;
constexpr double pi = 3.141592653589793;

template <class T> const height_field<T>& scene() {
    static const height_field<T> hf({.nx = grid_n, .ny = grid_n, .cell_m = T(cell_m), .origin_m = vec2<T>{T(0), T(0)}, .heights_m = sss_bench::rough_heights<T>(grid_n, cell_m)});
    return hf;
}

// One ping from (x, y, altitude) heading +x: starboard then port, each 8 fans of 2048 rays ordered by
// slant range (steep first). Fans are vertical planes at azimuths +-0.5 deg off the beam; with `cones`,
// each along-track angle a is instead a cone about the array axis, as a beam's columns are (body direction
// (sin a, s cos a cos e, cos a sin e): the rays share the origin but their headings vary with depression).
template <class T> std::vector<ray<T>> ping_rays(double x, double y, bool cones = false) {
    std::vector<ray<T>> rays;
    rays.reserve(2 * along_track_angles * rays_per_fan);
    const double r_min = altitude_m / std::sin(60 * pi / 180);
    for (int side : {1, -1})
        for (int a = 0; a < along_track_angles; ++a) {
            const double along = (-0.5 + double(a) / (along_track_angles - 1)) * pi / 180;
            for (int i = 0; i < rays_per_fan; ++i) {
                const double slant = r_min + (double(i) + 0.5) / rays_per_fan * (range_m - r_min);
                const double dep = std::asin(altitude_m / slant);
                const vec3<double> d =
                    cones ? vec3<double>{std::sin(along), side * std::cos(along) * std::cos(dep),
                                         -std::cos(along) * std::sin(dep)}
                          : vec3<double>{std::cos(dep) * std::sin(along), side * std::cos(dep) * std::cos(along),
                                         -std::sin(dep)};
                rays.push_back(ray<T>{vec3<T>{T(x), T(y), T(altitude_m)}, vec3<T>(d)});
            }
        }
    return rays;
}

template <class T> const std::vector<std::vector<ray<T>>>& all_pings(bool cones = false) {
    static const auto make = [](bool c) {
        std::vector<std::vector<ray<T>>> v;
        for (int k = 0; k < pings; ++k) v.push_back(ping_rays<T>(150 + 11.5 * k, 512 + 37.0 * (k % 7), c));
        return v;
    };
    static const auto fans = make(false);
    if (!cones) return fans;
    static const auto cone_pings = make(true);
    return cone_pings;
}

// The tracers: trace(rays, t_max, hits).
template <class T> struct reference_tracer {
    const height_field<T>& hf;
    void trace(std::span<const ray<T>> rays, T t_max, std::span<std::optional<sss::hit<T>>> hits) const {
        for (std::size_t k = 0; k < rays.size(); ++k) hits[k] = hf.intersect_reference(rays[k], t_max);
    }
    static const char* name() { return "reference: every cell, triangles"; }
};
template <class T> struct accelerated_tracer {
    const height_field<T>& hf;
    void trace(std::span<const ray<T>> rays, T t_max, std::span<std::optional<sss::hit<T>>> hits) const {
        for (std::size_t k = 0; k < rays.size(); ++k) hits[k] = hf.intersect(rays[k], t_max);
    }
    static const char* name() { return "accelerated: maximum pyramid, one ray at a time"; }
};
template <class T> struct fan_tracer {
    const height_field<T>& hf;
    void trace(std::span<const ray<T>> rays, T t_max, std::span<std::optional<sss::hit<T>>> hits) const {
        hf.intersect_many(rays, t_max, hits);
    }
    static const char* name() { return "fans: intersect_many, one sweep per fan"; }
};

// The alternative surface: each cell a bilinear patch h = h00 (1-a)(1-b) + h10 a (1-b) + h01 (1-a) b +
// h11 a b, traced by a plain DDA; along a ray f = z - h is quadratic inside a cell, so each cell needs
// the first root of a quadratic where f goes from + to -. Only the distance is reported (no normals).
template <class T> struct bilinear_tracer {
    const height_field<T>& hf;
    void trace(std::span<const ray<T>> rays, T t_max, std::span<std::optional<sss::hit<T>>> hits) const {
        for (std::size_t k = 0; k < rays.size(); ++k) hits[k] = one(rays[k], t_max);
    }
    static const char* name() { return "bilinear patches: every cell, quadratic per cell (distance only)"; }

    std::optional<sss::hit<T>> one(const ray<T>& r, T t_max) const {
        namespace d = sss::scene::detail;
        const auto& g = hf.grid();
        d::grid_ray<T> q;
        if (!d::setup_ray(g, sss::scene::height_bounds<T>{hf.bottom_m(), hf.top_m()}, r, t_max, q)) return std::nullopt;
        std::int32_t ix = d::cell_of(q.u0 + q.du * q.s_lo, g.nx - 2), iy = d::cell_of(q.v0 + q.dv * q.s_lo, g.ny - 2);
        T s = q.s_lo;
        for (;;) {
            const T inf = std::numeric_limits<T>::infinity();
            const T sx = q.su > 0 ? d::cross_u(q, ix + 1) : (q.su < 0 ? d::cross_u(q, ix) : inf);
            const T sy = q.sv > 0 ? d::cross_v(q, iy + 1) : (q.sv < 0 ? d::cross_v(q, iy) : inf);
            const T se = std::min(std::min(sx, sy), q.s_hi);
            // f(t) on t = s' - s in [0, se - s], from a, b at s.
            const T a0 = q.u0 + q.du * s - T(ix), b0 = q.v0 + q.dv * s - T(iy);
            const T h00 = g.at(ix, iy), h10 = g.at(ix + 1, iy), h01 = g.at(ix, iy + 1), h11 = g.at(ix + 1, iy + 1);
            const T e = h10 - h00, n = h01 - h00, k = h00 - h10 - h01 + h11;
            const T c0 = (q.z0 + q.dz * s) - (h00 + a0 * e + b0 * n + a0 * b0 * k);
            const T c1 = q.dz - (q.du * (e + b0 * k) + q.dv * (n + a0 * k));
            const T c2 = -q.du * q.dv * k;
            const T len = se - s;
            if (const auto t = first_entry(c0, c1, c2, len)) {
                sss::hit<T> h;
                h.distance_m = s + *t;
                h.point = r.at(h.distance_m);
                return h;
            }
            if (!(se < q.s_hi)) return std::nullopt;
            if (sx <= sy) ix += q.su;
            if (sy <= sx) iy += q.sv;
            if (ix < 0 || iy < 0 || ix > g.nx - 2 || iy > g.ny - 2) return std::nullopt;
            s = se;
        }
    }
    // First t in [0, len] where c0 + c1 t + c2 t^2 goes from > 0 to <= 0.
    static std::optional<T> first_entry(T c0, T c1, T c2, T len) {
        auto f = [&](T t) { return c0 + t * (c1 + t * c2); };
        if (!(c0 > T(0))) return std::nullopt;
        if (std::abs(c2) * len < T(1e-7) * (std::abs(c1) + std::abs(c0) / std::max(len, T(1e-9)))) {
            if (!(c1 < T(0))) return std::nullopt;
            const T t = -c0 / c1;
            return t <= len ? std::optional<T>(t) : std::nullopt;
        }
        const T disc = c1 * c1 - 4 * c2 * c0;
        if (disc < T(0)) return std::nullopt;
        const T sq = std::sqrt(disc);
        const T qq = -T(0.5) * (c1 + (c1 < T(0) ? -sq : sq));
        T r1 = qq / c2, r2 = c0 / qq;
        if (r1 > r2) std::swap(r1, r2);
        for (T t : {r1, r2})
            if (t >= T(0) && t <= len && !(f(std::min(len, t + len * T(1e-6))) > T(0))) return t;
        return std::nullopt;
    }
};

template <template <class> class Tracer, class T, bool cones = false> void trace_pings(benchmark::State& state) {
    const height_field<T>& hf = scene<T>();
    const auto& p = all_pings<T>(cones);
    const Tracer<T> tracer{hf};
    std::vector<std::optional<sss::hit<T>>> hits(p[0].size());
    std::size_t k = 0, rays = 0, hit_count = 0, traced = 0;
    for (auto _ : state) {
        tracer.trace(p[k], T(1.5 * range_m), hits);
        for (const auto& h : hits) hit_count += h ? 1 : 0;
        rays += hits.size();
        benchmark::ClobberMemory();
        k = (k + 1) % p.size();
        ++traced;
    }
    state.SetItemsProcessed(std::int64_t(rays));
    state.SetLabel(std::string(Tracer<T>::name()) + (cones ? " (cone columns)" : ""));
    state.counters["hit_fraction"] = double(hit_count) / double(std::max<std::size_t>(rays, 1));
    state.counters["accel_bytes_per_height_byte"] = double(hf.acceleration_bytes()) / double(hf.height_bytes());
    if constexpr (std::is_same_v<Tracer<T>, fan_tracer<T>>) {
        // The batch's hits against intersect()'s, after the timing, on the pings the timing used: the fraction of
        // rays whose hit differs in any bit (distance or cell). The wedge sweep (cone columns) gives intersect's
        // hits exactly; the fan sweep evaluates the surface along the fan's plane, so rounding moves its hits.
        std::size_t compared = 0, differ = 0;
        for (std::size_t j = 0; j < std::min(p.size(), std::max<std::size_t>(traced, 1)); ++j) {
            tracer.trace(p[j], T(1.5 * range_m), hits);
            for (std::size_t i = 0; i < hits.size(); ++i) {
                const auto one = hf.intersect(p[j][i], T(1.5 * range_m));
                differ += bool(one) != bool(hits[i]) ||
                          (one && (one->distance_m != hits[i]->distance_m || one->label != hits[i]->label));
                ++compared;
            }
        }
        state.counters["differ_from_intersect"] = double(differ) / double(std::max<std::size_t>(compared, 1));
    }
}

#define TRACE_BENCHMARKS(tracer)                                                                                       \
    BENCHMARK_TEMPLATE(trace_pings, tracer, float)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();            \
    BENCHMARK_TEMPLATE(trace_pings, tracer, double)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()

TRACE_BENCHMARKS(reference_tracer);
TRACE_BENCHMARKS(accelerated_tracer);
TRACE_BENCHMARKS(fan_tracer);
TRACE_BENCHMARKS(bilinear_tracer);
// The same pings with cone columns (as a beam's): intersect_many's wedge sweep against one ray at a time.
BENCHMARK_TEMPLATE(trace_pings, accelerated_tracer, float, true)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK_TEMPLATE(trace_pings, fan_tracer, float, true)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK_TEMPLATE(trace_pings, accelerated_tracer, double, true)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();
BENCHMARK_TEMPLATE(trace_pings, fan_tracer, double, true)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

#ifdef SSS_HAVE_EMBREE
// Embree 3 on the same triangles, float only (Embree is float); built when the build files find Embree
// (they define SSS_HAVE_EMBREE). One triangle mesh over the grid's vertices at world (x, y, height), two
// triangles per cell split along the diagonal from vertex (ix, iy) to (ix+1, iy+1) as in
// height_field_surface.hpp, an index buffer over the shared vertex buffer. Build quality medium
// (Embree's default binned-SAH builder for a static scene; high adds spatial splits, which buy little on
// triangles this regular and compact, at more build time and memory). Scene flag robust: watertight
// like intersect(); without it a few rays slip through shared edges (6 of the 64 pings' 2 M rays here)
// and tracing is some 20 % faster. Memory is every byte Embree allocates, its own vertex and index
// buffers included, summed by the device's memory monitor.
class embree_scene {
public:
    explicit embree_scene(const height_field<float>& hf) : device_(rtcNewDevice(nullptr)) {
        if (!device_) throw std::runtime_error("Embree: rtcNewDevice failed");
        rtcSetDeviceMemoryMonitorFunction(device_, &monitor, this);
        const auto& g = hf.grid();
        const auto nx = static_cast<unsigned>(g.nx), ny = static_cast<unsigned>(g.ny);
        const std::size_t vertices = std::size_t(nx) * ny, triangles = 2 * std::size_t(nx - 1) * (ny - 1);
        const auto start = std::chrono::steady_clock::now();
        RTCGeometry mesh = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                              3 * sizeof(float), vertices));
        auto* t = static_cast<unsigned*>(rtcSetNewGeometryBuffer(mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                 3 * sizeof(unsigned), triangles));
        if (!v || !t) throw std::runtime_error("Embree: geometry buffers not allocated");
        for (unsigned iy = 0; iy < ny; ++iy)
            for (unsigned ix = 0; ix < nx; ++ix, v += 3) {
                v[0] = g.origin_m.x + static_cast<float>(ix) * g.cell_m;
                v[1] = g.origin_m.y + static_cast<float>(iy) * g.cell_m;
                v[2] = g.at(static_cast<std::int32_t>(ix), static_cast<std::int32_t>(iy));
            }
        for (unsigned iy = 0; iy + 1 < ny; ++iy)
            for (unsigned ix = 0; ix + 1 < nx; ++ix, t += 6) {
                const unsigned v00 = iy * nx + ix, v10 = v00 + 1, v01 = v00 + nx, v11 = v01 + 1;
                t[0] = v00, t[1] = v10, t[2] = v11; // lower: a >= b
                t[3] = v00, t[4] = v11, t[5] = v01; // upper: a < b
            }
        buffer_bytes_ = vertices * 3 * sizeof(float) + triangles * 3 * sizeof(unsigned);
        rtcCommitGeometry(mesh);
        scene_ = rtcNewScene(device_);
        rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_MEDIUM);
        rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
        rtcAttachGeometry(scene_, mesh);
        rtcReleaseGeometry(mesh);
        rtcCommitScene(scene_);
        if (rtcGetDeviceError(device_) != RTC_ERROR_NONE) throw std::runtime_error("Embree: scene build failed");
        build_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        resident_bytes_ = bytes_.load();
    }
    embree_scene(const embree_scene&) = delete;
    embree_scene& operator=(const embree_scene&) = delete;
    ~embree_scene() {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
    }

    [[nodiscard]] RTCScene scene() const noexcept { return scene_; }
    /// Bytes Embree holds after the build (buffers, BVH and triangle blocks), its peak during the build,
    /// the vertex and index buffers alone, and the build's wall time (s).
    [[nodiscard]] std::int64_t resident_bytes() const noexcept { return resident_bytes_; }
    [[nodiscard]] std::int64_t peak_bytes() const noexcept { return peak_bytes_.load(); }
    [[nodiscard]] std::size_t buffer_bytes() const noexcept { return buffer_bytes_; }
    [[nodiscard]] double build_s() const noexcept { return build_s_; }

    // The hit Embree reports, in the tracers' form: distance, point, geometric normal (Ng normalised,
    // upward), the same as the shading normal (Embree interpolates nothing here), material 0.
    static std::optional<sss::hit<float>> to_hit(const ray<float>& r, unsigned geom_id, float t, float nx, float ny,
                                                 float nz) noexcept {
        if (geom_id == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
        sss::hit<float> h;
        h.distance_m = t;
        h.point = r.at(t);
        const float s = (nz < 0 ? -1.0f : 1.0f) / std::sqrt(nx * nx + ny * ny + nz * nz);
        h.normal = vec3<float>{nx * s, ny * s, nz * s};
        h.shading_normal = h.normal;
        return h;
    }

private:
    static bool monitor(void* self, ssize_t bytes, bool /*post*/) {
        auto& s = *static_cast<embree_scene*>(self);
        const std::int64_t now = s.bytes_ += static_cast<std::int64_t>(bytes);
        std::int64_t peak = s.peak_bytes_.load();
        while (now > peak && !s.peak_bytes_.compare_exchange_weak(peak, now)) {
        }
        return true;
    }

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::atomic<std::int64_t> bytes_{0}, peak_bytes_{0};
    std::int64_t resident_bytes_ = 0;
    std::size_t buffer_bytes_ = 0;
    double build_s_ = 0;
};

const embree_scene& embree() {
    static const embree_scene s(scene<float>());
    return s;
}

// Packets of 8 consecutive rays of a fan (rtcIntersect8), and one ray at a time (rtcIntersect1).
template <class T> struct embree_packet8_tracer {
    static_assert(std::is_same_v<T, float>, "Embree traces float rays");
    const height_field<T>& hf;
    void trace(std::span<const ray<T>> rays, T t_max, std::span<std::optional<sss::hit<T>>> hits) const {
        const RTCScene sc = embree().scene();
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        alignas(32) RTCRayHit8 q;
        alignas(32) int valid[8];
        for (std::size_t k0 = 0; k0 < rays.size(); k0 += 8) {
            const std::size_t n = std::min<std::size_t>(8, rays.size() - k0);
            for (std::size_t j = 0; j < 8; ++j) {
                const ray<T>& r = rays[k0 + std::min(j, n - 1)];
                valid[j] = j < n ? -1 : 0;
                q.ray.org_x[j] = r.origin.x, q.ray.org_y[j] = r.origin.y, q.ray.org_z[j] = r.origin.z;
                q.ray.dir_x[j] = r.direction.x, q.ray.dir_y[j] = r.direction.y, q.ray.dir_z[j] = r.direction.z;
                q.ray.tnear[j] = 0, q.ray.tfar[j] = t_max, q.ray.time[j] = 0;
                q.ray.mask[j] = ~0u, q.ray.id[j] = 0, q.ray.flags[j] = 0;
                q.hit.geomID[j] = RTC_INVALID_GEOMETRY_ID;
                q.hit.instID[0][j] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect8(valid, sc, &context, &q);
            for (std::size_t j = 0; j < n; ++j)
                hits[k0 + j] = embree_scene::to_hit(rays[k0 + j], q.hit.geomID[j], q.ray.tfar[j], q.hit.Ng_x[j],
                                                    q.hit.Ng_y[j], q.hit.Ng_z[j]);
        }
    }
    static const char* name() { return "Embree: same triangles, rtcIntersect8 (8 consecutive rays of a fan)"; }
};
template <class T> struct embree_single_tracer {
    static_assert(std::is_same_v<T, float>, "Embree traces float rays");
    const height_field<T>& hf;
    void trace(std::span<const ray<T>> rays, T t_max, std::span<std::optional<sss::hit<T>>> hits) const {
        const RTCScene sc = embree().scene();
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (std::size_t k = 0; k < rays.size(); ++k) {
            const ray<T>& r = rays[k];
            RTCRayHit q{};
            q.ray.org_x = r.origin.x, q.ray.org_y = r.origin.y, q.ray.org_z = r.origin.z;
            q.ray.dir_x = r.direction.x, q.ray.dir_y = r.direction.y, q.ray.dir_z = r.direction.z;
            q.ray.tnear = 0, q.ray.tfar = t_max, q.ray.mask = ~0u;
            q.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            q.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(sc, &context, &q);
            hits[k] = embree_scene::to_hit(r, q.hit.geomID, q.ray.tfar, q.hit.Ng_x, q.hit.Ng_y, q.hit.Ng_z);
        }
    }
    static const char* name() { return "Embree: same triangles, rtcIntersect1"; }
};

// trace_pings, with the memory counter holding Embree's bytes (all of them) over the heights' bytes.
template <template <class> class Tracer, class T> void trace_pings_embree(benchmark::State& state) {
    trace_pings<Tracer, T>(state);
    state.counters["accel_bytes_per_height_byte"] =
        double(embree().resident_bytes()) / double(scene<T>().height_bytes());
}
BENCHMARK_TEMPLATE(trace_pings_embree, embree_packet8_tracer, float)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();
BENCHMARK_TEMPLATE(trace_pings_embree, embree_single_tracer, float)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime();

// Embree against hf.intersect on the first ping's rays: hit/miss disagreements, the worst relative
// difference of the distances and, where both hit, how many geometric normals differ by more than
// 1 mrad (a hit on a shared edge belongs to either triangle).
template <template <class> class Tracer> std::string embree_agreement() {
    const auto& hf = scene<float>();
    const auto& rays = all_pings<float>()[0];
    const float t_max = float(1.5 * range_m);
    std::vector<std::optional<sss::hit<float>>> hits(rays.size());
    Tracer<float>{hf}.trace(rays, t_max, hits);
    std::size_t disagree = 0, both = 0, normals = 0;
    double worst_rel = 0;
    for (std::size_t k = 0; k < rays.size(); ++k) {
        const auto ours = hf.intersect(rays[k], t_max);
        if (bool(ours) != bool(hits[k])) {
            ++disagree;
            continue;
        }
        if (!ours) continue;
        ++both;
        worst_rel = std::max(worst_rel, std::abs(double(hits[k]->distance_m) - double(ours->distance_m)) /
                                            double(ours->distance_m));
        const double c = double(glm::dot(hits[k]->normal, ours->normal));
        normals += std::acos(std::clamp(c, -1.0, 1.0)) > 1e-3 ? 1 : 0;
    }
    char worst[32];
    std::snprintf(worst, sizeof worst, "%.2e", worst_rel);
    return "worst |d - d_ours| / d_ours " + std::string(worst) + ", normals > 1 mrad apart on " +
           std::to_string(normals) + " of " + std::to_string(both) + " hits, hit/miss disagreements " +
           std::to_string(disagree) + " of " + std::to_string(rays.size());
}

// Rays/s (wall clock) of one tracer on the first 4 pings, best of 5 interleaved rounds, for the ratios
// printed beside the benchmarks (one run, one clock).
std::string embree_ratios() {
    const auto& hf = scene<float>();
    const auto& p = all_pings<float>();
    const float t_max = float(1.5 * range_m);
    std::vector<std::optional<sss::hit<float>>> hits(p[0].size());
    auto time = [&](const auto& tracer) {
        const auto start = std::chrono::steady_clock::now();
        for (std::size_t k = 0; k < 4; ++k) tracer.trace(p[k], t_max, hits);
        benchmark::DoNotOptimize(hits.data());
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    };
    const fan_tracer<float> fans{hf};
    const accelerated_tracer<float> one{hf};
    const embree_packet8_tracer<float> e8{hf};
    const embree_single_tracer<float> e1{hf};
    double best[4] = {1e30, 1e30, 1e30, 1e30};
    for (int round = 0; round < 5; ++round) {
        best[0] = std::min(best[0], time(fans));
        best[1] = std::min(best[1], time(e8));
        best[2] = std::min(best[2], time(one));
        best[3] = std::min(best[3], time(e1));
    }
    const double rays = 4.0 * double(p[0].size());
    auto mrays = [&](int i) { return std::to_string(rays / best[i] * 1e-6); };
    return "fans / Embree packets = " + std::to_string(best[1] / best[0]) + " (" + mrays(0) + " vs " + mrays(1) +
           " M rays/s); accelerated / Embree single = " + std::to_string(best[3] / best[2]) + " (" + mrays(2) +
           " vs " + mrays(3) + " M rays/s); float, best of 5 over 4 pings, wall clock";
}
#endif // SSS_HAVE_EMBREE

// Building the height field: validation, bounds and the maximum pyramid (the heights are given).
template <class T> void build_height_field(benchmark::State& state) {
    const std::vector<T> h(scene<T>().heights_m());
    for (auto _ : state) {
        height_field<T> hf({.nx = grid_n, .ny = grid_n, .cell_m = T(cell_m), .origin_m = vec2<T>{T(0), T(0)}, .heights_m = h});
        benchmark::DoNotOptimize(hf.top_m());
    }
    state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(h.size()));
    state.SetLabel("vertices/s");
}
BENCHMARK_TEMPLATE(build_height_field, float)->Unit(benchmark::kMillisecond);

// How far the two surfaces are apart on this terrain: at a cell's centre the triangles give
// (h00 + h11) / 2 and the bilinear patch (h00 + h10 + h01 + h11) / 4, the largest gap inside the cell.
std::string surface_gap() {
    const auto& g = scene<double>().grid();
    double worst = 0, sum2 = 0;
    for (std::int32_t iy = 0; iy + 1 < g.ny; ++iy)
        for (std::int32_t ix = 0; ix + 1 < g.nx; ++ix) {
            const double d = 0.25 * (g.at(ix, iy) + g.at(ix + 1, iy + 1) - g.at(ix + 1, iy) - g.at(ix, iy + 1));
            worst = std::max(worst, std::abs(d));
            sum2 += d * d;
        }
    const double rms = std::sqrt(sum2 / (double(g.nx - 1) * double(g.ny - 1)));
    return "rms " + std::to_string(rms * 1e3) + " mm, max " + std::to_string(worst * 1e3) + " mm";
}

} // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    const auto& hf = scene<float>();
    benchmark::AddCustomContext("scene",
                                "4096 x 4096 vertices at 0.25 m, rough (+-2.5 m), towfish 10 m up, 100 m range, "
                                "2 x 8 x 2048 rays per ping, " +
                                    std::to_string(pings) + " pings");
    benchmark::AddCustomContext(
        "memory",
        "acceleration / heights = " + std::to_string(double(hf.acceleration_bytes()) / double(hf.height_bytes())) +
            " (total " + std::to_string(1 + double(hf.acceleration_bytes()) / double(hf.height_bytes())) +
            "x the heights)");
    benchmark::AddCustomContext("triangles vs bilinear", "centre-of-cell height gap " + surface_gap());
#ifdef SSS_HAVE_EMBREE
    const auto& e = embree();
    const double heights = double(hf.height_bytes());
    benchmark::AddCustomContext(
        "Embree memory", "Embree / heights = " + std::to_string(double(e.resident_bytes()) / heights) +
                             " (vertex and index buffers " + std::to_string(double(e.buffer_bytes()) / heights) +
                             ", peak during the build " + std::to_string(double(e.peak_bytes()) / heights) +
                             "); build " + std::to_string(e.build_s()) + " s, quality medium");
    benchmark::AddCustomContext("Embree packets vs intersect", embree_agreement<embree_packet8_tracer>());
    benchmark::AddCustomContext("Embree single vs intersect", embree_agreement<embree_single_tracer>());
    benchmark::AddCustomContext("Embree ratio", embree_ratios());
#endif
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

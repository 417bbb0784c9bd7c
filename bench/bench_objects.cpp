// Cost per ray of objects in a scene. Reference pings: 2 x 8 x 2048 rays (port and starboard; 8 along-track angles
// within +-0.5 deg; 2048 depression angles from 60 deg down to the one that reaches 100 m slant range on the flat
// mean bottom, spaced evenly in slant range) from a towfish 10 m above the seabed, 64 pings spread over a
// 200 m x 200 m patch. Seabeds: the flat plane z = 0, and a rough 1024 x 1024 height field at 0.25 m (256 m square,
// +-1.5 m of summed swell and dunes plus 5 cm noise). Objects: 0, 10 or 1000 targets from the builders (sphere and
// cylinder mines on tethers, cylinders lying at random headings, debris pieces, and with 10 or more a 60 m
// pipeline), scattered uniformly over the patch: 1000 objects put about one target every 40 m^2.
// Measured (items/s = rays/s, single-threaded):
//   seabed            the seabed's own intersect (no scene), the baseline;
//   scene/N           scene<Seabed>::intersect with N objects (the hierarchy);
//   far/1000          1000 objects 1 km away from every ray: what culling leaves of their cost;
//   brute/N           the seabed, then every object by its box (object_set::intersect_brute_force).

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <sss/scene/flat_seabed.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/scene/scene.hpp>
#include <sss/seabed/targets.hpp>

namespace {

using sss::ray;
using sss::vec2;
using sss::vec3;
namespace sc = sss::scene;
namespace sb = sss::seabed;

constexpr double altitude_m = 10.0, range_m = 100.0, pi = 3.141592653589793;
constexpr int rays_per_fan = 2048, along_track_angles = 8, pings = 64;
constexpr std::size_t grid_n = 1024;
constexpr double cell_m = 0.25;

// The rough height field (heights about the mean z = 0), centred on the patch: origin (-128, -128).
template <class T> const sc::height_field<T>& rough_seabed() {
    static const sc::height_field<T> hf = [] {
        struct wave {
            double amplitude_m, wavelength_m, direction_deg, phase;
        };
        const wave waves[] = {{0.9, 150, 20, 0.3}, {0.4, 37, 75, 1.1}, {0.15, 9, 140, 2.0}};
        std::vector<T> h(grid_n * grid_n);
        for (std::size_t iy = 0; iy < grid_n; ++iy)
            for (std::size_t ix = 0; ix < grid_n; ++ix) {
                double z = 0;
                for (const wave& w : waves) {
                    const double k = 2 * pi / w.wavelength_m, d = w.direction_deg * pi / 180;
                    z += w.amplitude_m * std::sin(k * (std::cos(d) * double(ix) + std::sin(d) * double(iy)) * cell_m + w.phase);
                }
                std::uint64_t s = (iy * grid_n + ix + 1) * 0x9E3779B97F4A7C15ull;
                s = (s ^ (s >> 31)) * 0xBF58476D1CE4E5B9ull;
                h[iy * grid_n + ix] = T(z + 0.05 * (double(s >> 11) * 0x1.0p-53 - 0.5));
            }
        return sc::height_field<T>({.nx = grid_n, .ny = grid_n, .cell_m = T(cell_m), .origin_m = vec2<T>{T(-128), T(-128)}, .heights_m = std::move(h)});
    }();
    return hf;
}

template <class T> const sc::flat_seabed<T>& flat_seabed() {
    static const sc::flat_seabed<T> f(T(0));
    return f;
}

// n targets over the 200 m patch centred on (cx, cy), resting on the given seabed.
template <class T, class Seabed> std::vector<sc::object<T>> targets(const Seabed& bed, std::size_t n, double cx, double cy) {
    sb::rng g(42);
    const auto height = sb::seabed_height_of(bed);
    std::vector<sc::object<T>> out;
    for (std::size_t k = 0; k < n; ++k) {
        const T x = T(cx + 200 * g.uniform() - 100), y = T(cy + 200 * g.uniform() - 100);
        const auto id = static_cast<std::uint32_t>(k);
        if (k == 0 && n >= 10) {
            sb::pipeline_params<T> p;
            p.route_m = {{x, y}, {x + T(40), y + T(20)}, {x + T(50), y + T(40)}};
            p.radius_m = T(0.3);
            p.max_span_m = T(15);
            p.ids = {1, id, 2};
            out.push_back(sb::pipeline(p, height));
            continue;
        }
        switch (k % 4) {
        case 0:
        case 1: {
            sb::tethered_mine_params<T> m;
            m.anchor_m = {x, y};
            m.shape = k % 4 == 0 ? sb::mine_case::sphere : sb::mine_case::cylinder;
            m.case_height_m = T(2 + 4 * g.uniform());
            m.case_heading_deg = T(360 * g.uniform());
            m.object_id = id;
            out.push_back(sb::tethered_mine(m, height));
            break;
        }
        case 2: {
            sb::lying_cylinder_params<T> c;
            c.center_m = {x, y};
            c.heading_deg = T(360 * g.uniform());
            c.length_m = T(1 + 3 * g.uniform());
            c.radius_m = T(0.2 + 0.3 * g.uniform());
            c.ids = {1, id, 3};
            out.push_back(sb::lying_cylinder(c, height));
            break;
        }
        default: {
            sb::debris_params<T> d;
            d.center_m = {x, y};
            d.radius_m = T(0.5);
            d.count = 1;
            d.seed = k;
            d.first_object_id = id;
            out.push_back(sb::debris_cluster(d, height).front());
        }
        }
    }
    return out;
}

// One ping from (x, y, altitude) heading +x, fans ordered by slant range.
template <class T> std::vector<ray<T>> ping_rays(double x, double y, double z) {
    std::vector<ray<T>> rays;
    rays.reserve(2 * along_track_angles * rays_per_fan);
    const double r_min = altitude_m / std::sin(60 * pi / 180);
    for (int side : {1, -1})
        for (int a = 0; a < along_track_angles; ++a) {
            const double along = (-0.5 + double(a) / (along_track_angles - 1)) * pi / 180;
            for (int i = 0; i < rays_per_fan; ++i) {
                const double slant = r_min + (double(i) + 0.5) / rays_per_fan * (range_m - r_min);
                const double dep = std::asin(altitude_m / slant);
                const vec3<double> d{std::cos(dep) * std::sin(along), side * std::cos(dep) * std::cos(along), -std::sin(dep)};
                rays.push_back(ray<T>{vec3<T>{T(x), T(y), T(z)}, vec3<T>(d)});
            }
        }
    return rays;
}

template <class T> const std::vector<std::vector<ray<T>>>& all_pings() {
    static const auto p = [] {
        std::vector<std::vector<ray<T>>> v;
        for (int k = 0; k < pings; ++k) v.push_back(ping_rays<T>(-90 + 2.8 * k, -90 + 30.0 * (k % 7), altitude_m));
        return v;
    }();
    return p;
}

enum class seabed_kind { flat, rough };
enum class mode { seabed, scene, far, brute };

template <class T, class Seabed> void run(benchmark::State& state, const Seabed& bed, mode m, std::size_t n) {
    const sc::scene world(bed, sc::object_set<T>(m == mode::far ? targets<T>(bed, n, 1000, 1000) : targets<T>(bed, n, 0, 0)));
    const auto& p = all_pings<T>();
    const T t_max = T(1.5 * range_m);
    std::size_t k = 0, rays = 0, object_hits = 0;
    for (auto _ : state) {
        for (const ray<T>& r : p[k]) {
            std::optional<sss::hit<T>> h;
            if (m == mode::seabed) {
                h = bed.intersect(r, t_max);
            } else if (m == mode::brute) {
                h = bed.intersect(r, t_max);
                if (auto o = world.objects().intersect_brute_force(r, h ? h->distance_m : t_max)) h = o;
            } else {
                h = world.intersect(r, t_max);
            }
            object_hits += h && h->object != sss::no_object ? 1 : 0;
            benchmark::DoNotOptimize(h);
        }
        rays += p[k].size();
        k = (k + 1) % p.size();
    }
    state.SetItemsProcessed(std::int64_t(rays));
    state.counters["sec_per_ray"] = benchmark::Counter(double(rays), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["object_hit_fraction"] = double(object_hits) / double(std::max<std::size_t>(rays, 1));
    state.counters["primitives"] = double(world.objects().primitive_count());
}

template <class T> void bench(benchmark::State& state) {
    const auto kind = static_cast<seabed_kind>(state.range(0));
    const auto m = static_cast<mode>(state.range(1));
    const auto n = static_cast<std::size_t>(state.range(2));
    if (kind == seabed_kind::flat) run<T>(state, flat_seabed<T>(), m, n);
    else run<T>(state, rough_seabed<T>(), m, n);
}

void arguments(benchmark::internal::Benchmark* b) {
    b->ArgNames({"rough", "mode", "objects"});
    for (int rough : {0, 1}) {
        b->Args({rough, int(mode::seabed), 0});
        for (int n : {0, 10, 1000}) b->Args({rough, int(mode::scene), n});
        b->Args({rough, int(mode::far), 1000});
        b->Args({rough, int(mode::brute), 10});
        b->Args({rough, int(mode::brute), 1000});
    }
}

BENCHMARK_TEMPLATE(bench, float)->Apply(arguments)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(bench, double)->Apply(arguments)->Unit(benchmark::kMillisecond);

} // namespace

int main(int argc, char** argv) {
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::AddCustomContext("pings", "2 x 8 x 2048 rays from 10 m altitude to 100 m slant range, 64 pings over a "
                                         "200 m patch");
    benchmark::AddCustomContext("seabeds", "rough=0: flat plane; rough=1: 1024 x 1024 height field at 0.25 m (+-1.5 m)");
    benchmark::AddCustomContext("modes", "0 seabed alone, 1 scene (hierarchy), 2 scene with the objects 1 km away, "
                                         "3 seabed + brute force over objects");
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

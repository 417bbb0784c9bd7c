// Cost of propagation per ray: straight rays against layered water, on the same rays over the same flat seabed.
//
// Scene: flat seabed at world z = 0, towfish 10 m above it (depth 50 m, sea surface at z = 60), 4096 rays whose
// straight-line slant ranges to the seabed run from 10 m to 60 m, launched towards varying azimuths, traced in a
// scrambled order; one-way time limit 0.1 s.
// Waters:
//   straight      isovelocity 1500 m/s, 60 dB/km (sss::propagation::straight)
//   uniform       layered, 1500 m/s at five knots (0, 20, 44, 54, 200 m): straight paths, crossing knots
//   thermocline   layered, 1500 m/s at the surface, 1499 at 44 m, 1479 at 54 m (a 20 m/s drop around the towfish),
//                 then +0.0165 1/s (the policy matrix's water)
//   fine          layered, a smooth thermocline (1490 - 10 tanh((z - 49)/3)) on knots every 0.1 m
//   exact         the thermocline traced exactly all the way (launch_table = false)
// and the thermocline once more through trace_many (all rays in one call, the batch method the simulator uses).
// Layered waters use Francois-Garrison absorption at 300 kHz and 1 mm chords, and the launch table unless stated.
// Then whole pings (simulator: Lambert -27 dB, 300 kHz planar array 32 x 2 tilted 15 deg to -30 dB, 40 m range,
// 20 kHz sampling, default ray density), straight against thermocline water, with and without the launch table.
// The two pingers are also timed over rough relief (a height field), where the straight trace itself costs more, and
// so is a pinger in water whose strong gradients reach the seabed, with and without clearing chords in open water.
// Before the benchmarks a summary prints the per-ray cost of each water and its ratio to straight rays, by its own
// timing loop, for trace alone and for whole pings, and how far the launch table's results are from exact tracing on
// the same rays. The machines this runs on are shared and their speed drifts, so the summary times processor time
// (std::clock), not wall time, takes the best of many rounds, and interleaves the rows (every round times each of
// them once): the ratios compare timings taken under the same conditions.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <ctime>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <optional>
#include <span>
#include <vector>

#include <sss/beam/planar_array.hpp>
#include <sss/motion/straight_line.hpp>
#include <sss/propagation/layered.hpp>
#include <sss/propagation/straight.hpp>
#include <sss/scattering/lambertian.hpp>
#include <sss/scene/flat_seabed.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/simulator.hpp>

namespace {

using sss::propagation::layered;
using sss::propagation::layered_params;
using sss::propagation::sound_speed_profile;
using sss::propagation::straight;

constexpr std::size_t ray_count = 4096;

template <class T> std::vector<sss::ray<T>> bench_rays() {
    std::vector<sss::ray<T>> rays(ray_count);
    for (std::size_t i = 0; i < ray_count; ++i) {
        const double range = 10.0 + 50.0 * double((i * 1237) % ray_count) / double(ray_count);
        const double graze = std::asin(10.0 / range), az = 0.0015 * double(i);
        rays[i] = {{T(0), T(0), T(10)},
                   {T(std::cos(graze) * std::cos(az)), T(std::cos(graze) * std::sin(az)), T(-std::sin(graze))}};
    }
    return rays;
}

template <class T> layered_params<T> water_params(bool table = true) {
    layered_params<T> p;
    p.surface_z_m = T(60);
    p.frequency_hz = T(300000);
    p.launch_table = table;
    return p;
}

template <class T> layered<T> uniform_water() {
    return layered<T>(sound_speed_profile<T>({T(0), T(20), T(44), T(54), T(200)}, std::vector<T>(5, T(1500))), water_params<T>());
}
template <class T> layered<T> thermocline_water(bool table = true) {
    return layered<T>(sound_speed_profile<T>({T(0), T(44), T(54), T(200)}, {T(1500), T(1499), T(1479), T(1481.409)}),
                      water_params<T>(table));
}
template <class T> layered<T> fine_water() {
    std::vector<T> d, c;
    for (int k = 0; k <= 1000; ++k) {
        d.push_back(T(0.1 * k));
        c.push_back(T(1490.0 - 10.0 * std::tanh((0.1 * k - 49.0) / 3.0)));
    }
    return layered<T>(sound_speed_profile<T>(d, c), water_params<T>());
}

/// Strong gradients down to the seabed (shallow summer water): 1500 m/s to 44 m, 1490 m/s at the towfish (50 m),
/// 1466 m/s at 62 m, 2 m below the relief's lowest point: chords of about 0.7 m where the rays meet the seabed.
template <class T> layered<T> bottom_gradient_water(bool clear_open_water) {
    layered_params<T> p = water_params<T>();
    p.clear_open_water = clear_open_water;
    return layered<T>(sound_speed_profile<T>({T(0), T(44), T(50), T(62)}, {T(1500), T(1499), T(1490), T(1466)}), p);
}

enum class water { straight, uniform, thermocline, fine, exact };

/// Rough relief under the pingers' track: 641 x 641 vertices at 0.25 m around the origin, swell and ripples of
/// +-1.6 m about z = 0.
const sss::scene::height_field<double>& relief() {
    static const sss::scene::height_field<double> hf = [] {
        constexpr std::size_t n = 641;
        std::vector<double> h(n * n);
        for (std::size_t iy = 0; iy < n; ++iy)
            for (std::size_t ix = 0; ix < n; ++ix) {
                const double x = 0.25 * double(ix), y = 0.25 * double(iy);
                h[iy * n + ix] = 1.2 * std::sin(0.07 * x + 0.03 * y) + 0.3 * std::sin(0.8 * x - 0.5 * y) +
                                 0.1 * std::sin(4.1 * x + 1.7 * y);
            }
        return sss::scene::height_field<double>({.nx = n, .ny = n, .cell_m = 0.25, .origin_m = {-80.0, -80.0}, .heights_m = std::move(h)});
    }();
    return hf;
}

template <class P, class T> double trace_all(const P& p, const std::vector<sss::ray<T>>& rays) {
    const sss::scene::flat_seabed<T> seabed(T(0));
    double sum = 0;
    for (const auto& r : rays)
        if (const auto h = p.trace(r, seabed, T(0.1))) sum += double(h->time_s);
    return sum;
}

// The same through the batch method (BatchPropagation), all rays at once.
template <class P, class T> double trace_batch(const P& p, const std::vector<sss::ray<T>>& rays) {
    const sss::scene::flat_seabed<T> seabed(T(0));
    std::vector<std::optional<sss::path<T>>> paths(rays.size());
    p.trace_many(std::span<const sss::ray<T>>(rays), seabed, T(0.1), std::span<std::optional<sss::path<T>>>(paths));
    double sum = 0;
    for (const auto& h : paths)
        if (h) sum += double(h->time_s);
    return sum;
}

template <class T, water W> void propagation_trace(benchmark::State& state) {
    const auto rays = bench_rays<T>();
    const straight<T> iso({.sound_speed_mps = T(1500), .absorption_db_per_km = T(60)});
    const layered<T> lay = W == water::uniform ? uniform_water<T>() : W == water::fine ? fine_water<T>()
                                                                    : thermocline_water<T>(W != water::exact);
    for (auto _ : state) {
        if constexpr (W == water::straight) benchmark::DoNotOptimize(trace_all(iso, rays));
        else benchmark::DoNotOptimize(trace_all(lay, rays));
    }
    state.SetItemsProcessed(state.iterations() * std::int64_t(ray_count));
    state.SetLabel(W == water::straight ? "straight" : W == water::uniform ? "layered, uniform" :
                   W == water::thermocline ? "layered, thermocline" : W == water::fine ? "layered, 1000 knots" :
                   "layered, thermocline, exact");
}
BENCHMARK_TEMPLATE(propagation_trace, double, water::straight);
BENCHMARK_TEMPLATE(propagation_trace, double, water::uniform);
BENCHMARK_TEMPLATE(propagation_trace, double, water::thermocline);
BENCHMARK_TEMPLATE(propagation_trace, double, water::fine);
BENCHMARK_TEMPLATE(propagation_trace, double, water::exact);
BENCHMARK_TEMPLATE(propagation_trace, float, water::straight);
BENCHMARK_TEMPLATE(propagation_trace, float, water::thermocline);

template <class T, class P>
using ping_simulator = sss::simulator<sss::scattering::lambertian<T>, P, sss::beam::planar_array<T>, sss::motion::straight_line<T>>;

template <class T, class P> ping_simulator<T, P> make_pinger(const P& p) {
    sss::receiver_params rx;
    rx.sample_rate_hz = 20000.0;
    rx.max_range_m = 40.0;
    rx.pulse = {100e-6, sss::pulse_shape::rectangular};
    sss::beam::planar_array_params<T> b;
    b.frequency_hz = T(300000);
    b.depression_deg = T(15);
    b.transmit.along = {32, T(0.0150), T(0.0156), {}};
    b.transmit.vertical = {2, T(0.0190), T(0.0200), {}};
    b.threshold_db = T(-30);
    return ping_simulator<T, P>(sss::scattering::lambertian<T>{T(-27)}, p, sss::beam::planar_array<T>{b},
                                sss::motion::straight_line<T>{{{T(0), T(0)}, T(30), T(2), T(10), T(0.1)}}, rx);
}

template <class T, class P> std::size_t rays_per_ping(const ping_simulator<T, P>& sim) {
    std::size_t n = 0;
    const sss::scene::flat_seabed<T> seabed(T(0));
    for (sss::side sd : {sss::side::port, sss::side::starboard})
        sim.trace(seabed, sim.motion().pose_at(0), sd, [&](const sss::tube_echo<T>&) { ++n; });
    return n; // tubes; one more ray per along-track column and side than tubes, near enough
}

template <class T, water W> void propagation_ping(benchmark::State& state) {
    const sss::scene::flat_seabed<T> seabed(T(0));
    const auto run = [&](const auto& sim) {
        std::size_t i = 0;
        for (auto _ : state) benchmark::DoNotOptimize(sim.ping(seabed, i++ % 16).starboard.data());
        state.SetItemsProcessed(state.iterations() * std::int64_t(rays_per_ping(sim)));
    };
    if constexpr (W == water::straight) run(make_pinger<T>(straight<T>({.sound_speed_mps = T(1500), .absorption_db_per_km = T(60)})));
    else run(make_pinger<T>(thermocline_water<T>(W != water::exact)));
    state.SetLabel(W == water::straight ? "ping, straight" : W == water::exact ? "ping, layered thermocline, exact"
                                                                              : "ping, layered thermocline");
}
BENCHMARK_TEMPLATE(propagation_ping, double, water::straight)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(propagation_ping, double, water::thermocline)->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(propagation_ping, double, water::exact)->Unit(benchmark::kMillisecond);

// Processor seconds taken by f.
template <class F> double seconds(F&& f) {
    const std::clock_t t0 = std::clock();
    f();
    return double(std::clock() - t0) / double(CLOCKS_PER_SEC);
}

// Best of `rounds` timings of each of fs (seconds), the rounds interleaving them.
template <class... F> std::array<double, sizeof...(F)> best_interleaved(int rounds, F&&... fs) {
    std::array<double, sizeof...(F)> best;
    best.fill(1e30);
    for (int k = 0; k < rounds; ++k) {
        std::size_t i = 0;
        ((best[i] = std::min(best[i], seconds(fs)), ++i), ...);
    }
    return best;
}

void print_summary() {
    constexpr int rounds = 15, ping_rounds = 31;
    const auto rays = bench_rays<double>();
    double sink = 0;
    const straight<double> iso({.sound_speed_mps = 1500.0, .absorption_db_per_km = 60.0});
    const auto uniform = uniform_water<double>(), thermo = thermocline_water<double>(), fine = fine_water<double>(),
               exact = thermocline_water<double>(false);
    const auto t = best_interleaved(
        rounds, [&] { sink += trace_all(iso, rays); }, [&] { sink += trace_all(uniform, rays); },
        [&] { sink += trace_all(thermo, rays); }, [&] { sink += trace_batch(thermo, rays); },
        [&] { sink += trace_all(fine, rays); }, [&] { sink += trace_all(exact, rays); });
    std::printf("Per-ray trace cost, flat seabed 10 m below, slant ranges 10-60 m (%zu rays, best of %d):\n", ray_count, rounds);
    std::printf("  %-42s %8.1f ns\n", "straight", 1e9 * t[0] / double(ray_count));
    const char* names[] = {"layered, uniform (5 knots)", "layered, thermocline", "layered, thermocline, trace_many",
                           "layered, smooth thermocline (1000 knots)", "layered, thermocline, exact (no table)"};
    for (std::size_t k = 1; k < t.size(); ++k)
        std::printf("  %-42s %8.1f ns   x%.1f straight\n", names[k - 1], 1e9 * t[k] / double(ray_count), t[k] / t[0]);
    {   // What the launch table costs in accuracy on these rays.
        const sss::scene::flat_seabed<double> seabed(0.0);
        double worst_time = 0, worst_spreading = 0, worst_absorption = 0, worst_position = 0;
        for (const auto& r : rays) {
            const auto a = thermo.trace_path(r, seabed, 0.1), b = exact.trace_path(r, seabed, 0.1);
            if (!a || !b) continue;
            worst_time = std::max(worst_time, std::abs(a->result.time_s / b->result.time_s - 1));
            worst_spreading = std::max(worst_spreading, std::abs(a->result.spreading / b->result.spreading - 1));
            worst_absorption = std::max(worst_absorption, std::abs(a->result.absorption / b->result.absorption - 1));
            worst_position = std::max(worst_position, double(glm::length(a->result.surface.point - b->result.surface.point)));
        }
        std::printf("  launch table against exact tracing (thermocline): worst relative difference in time %.1e, "
                    "spreading %.1e, absorption %.1e; hit position %.1e m\n",
                    worst_time, worst_spreading, worst_absorption, worst_position);
    }

    const sss::scene::flat_seabed<double> seabed(0.0);
    const auto a = make_pinger<double>(straight<double>({.sound_speed_mps = 1500.0, .absorption_db_per_km = 60.0}));
    const auto b = make_pinger<double>(thermocline_water<double>(true));
    const auto c = make_pinger<double>(thermocline_water<double>(false));
    const auto p = best_interleaved(
        ping_rounds, [&] { sink += double(a.ping(seabed, 3).starboard[100]); },
        [&] { sink += double(b.ping(seabed, 3).starboard[100]); }, [&] { sink += double(c.ping(seabed, 3).starboard[100]); });
    const double n[] = {double(rays_per_ping(a)), double(rays_per_ping(b)), double(rays_per_ping(c))};
    std::printf("Whole pings (planar array, 40 m, Lambert; per ray = ping time / rays; best of %d):\n", ping_rounds);
    std::printf("  %-38s %8.3f ms  %6.0f rays  %6.1f ns/ray\n", "straight", 1e3 * p[0], n[0], 1e9 * p[0] / n[0]);
    for (std::size_t k = 1; k < 3; ++k)
        std::printf("  %-38s %8.3f ms  %6.0f rays  %6.1f ns/ray   x%.2f straight per ray\n",
                    k == 1 ? "layered, thermocline" : "layered, thermocline, exact", 1e3 * p[k], n[k], 1e9 * p[k] / n[k],
                    (p[k] / n[k]) / (p[0] / n[0]));

    // The same pings over rough relief, where the straight trace is no longer nearly free: the seabed is a height
    // field (its columns traced together by straight rays, chord by chord by layered ones).
    const auto& hf = relief();
    const auto q = best_interleaved(
        ping_rounds / 2, [&] { sink += double(a.ping(hf, 3).starboard[100]); },
        [&] { sink += double(b.ping(hf, 3).starboard[100]); });
    std::printf("Whole pings over relief (height field 641 x 641 at 0.25 m, +-1.6 m; same pingers, best of %d):\n",
                ping_rounds / 2);
    std::printf("  %-38s %8.3f ms  %6.0f rays  %6.1f ns/ray\n", "straight", 1e3 * q[0], n[0], 1e9 * q[0] / n[0]);
    std::printf("  %-38s %8.3f ms  %6.0f rays  %6.1f ns/ray   x%.2f straight per ray\n", "layered, thermocline",
                1e3 * q[1], n[1], 1e9 * q[1] / n[1], (q[1] / n[1]) / (q[0] / n[0]));
    // Where strong gradients reach the seabed the chords are short, and layered water first clears windows of them
    // in open water by one query (ClearanceScene, propagation/arc_intersection.hpp): against the walk chord by chord
    // (layered_params::clear_open_water = false). Here the rays run within 3 m of the seabed all the way.
    const auto d = make_pinger<double>(bottom_gradient_water<double>(true));
    const auto e = make_pinger<double>(bottom_gradient_water<double>(false));
    const auto r = best_interleaved(
        ping_rounds / 2, [&] { sink += double(d.ping(hf, 3).starboard[100]); },
        [&] { sink += double(e.ping(hf, 3).starboard[100]); });
    const double nd = double(rays_per_ping(d));
    std::printf("  %-38s %8.3f ms  %6.0f rays  %6.1f ns/ray   x%.2f straight per ray\n", "layered, strong gradient to the seabed",
                1e3 * r[0], nd, 1e9 * r[0] / nd, (r[0] / nd) / (q[0] / n[0]));
    std::printf("  %-38s %8.3f ms  %6.0f rays  %6.1f ns/ray   x%.2f straight per ray; time cleared / chord by chord %.2f\n",
                "  the same, chord by chord", 1e3 * r[1], nd, 1e9 * r[1] / nd, (r[1] / nd) / (q[0] / n[0]), r[0] / r[1]);
    std::printf("(checksum %g)\n\n", sink);
}

} // namespace

int main(int argc, char** argv) {
    print_summary();
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}

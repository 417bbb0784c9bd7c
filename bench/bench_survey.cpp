// Survey-scale speed: pings per second on the survey scene (bench/support/survey_scene.hpp: 1024 m of fractal seabed
// at 0.25 m, 4096^2 heights, with two sets of ripples and 20 targets including moored mines and a pipeline; Jackson
// medium sand at 100 kHz, three-layer water, the 100 kHz planar array, a perturbed towfish, 100 m per side in 2048
// samples), in float, for three simulators on 1 and 2 threads (on Linux one thread pinned to each of two processors in
// turn as well, since a shared machine's processors can differ in speed, and two threads against the sum of both):
//   full      Jackson, layered water, planar array, perturbed towfish
//   straight  the same with straight rays (isovelocity water)
//   minimal   Lambert, straight rays, ideal fan, straight-line towfish
// The full simulator again with the seabed's shadow edges out of the along-track check (ray_density::
// along_split_seabed = false; by default they take part here, the columns being coarse at 100 m) gives what that
// check costs; with the check in thirds only (ray_density::along_split = 3 with every column alike, not ninths shared
// by weight), what its second level costs;
// with the division even (ray_density::along_split_by_weight = false: every column to ninths, rather than the columns
// near the array's axis to 27ths and those near its extent's edges to thirds), what sharing it by weight changes;
// with the seabed's facets' edges not refined across track (ray_density::refine_facets = false), what that costs;
// with those edges located by halving the step at every level (ray_density::bracket_facet_edges = false) rather than
// by the rays either side of where each edge lies, what bracketing saves;
// with the division's last level at every launch angle (ray_density::along_split_sparse = false), what tracing
// every other one saves; with the columns near the first return left whole (ray_density::along_split_nadir = false),
// what dividing them there costs; with no column divided where its echo departs from its neighbours' (ray_density::
// along_split_echo = 0), what that check costs; and the echo pieces per ping of each (about one per ray traced), what the refinements
// spend in rays;
// what clearing chords in open water saves in layered water (in the survey's and in one with strong gradients
// down to the seabed), and what following a steeper neighbour saves (layered_params::follow_neighbours). It also prints the scene's build time and the process's peak resident memory after the build,
// the cost of ground-truth labels beside the image (render_labelled, and render then label_render, with the sides
// that trace the bare seabed again: those where a ray meets an object), and the error
// of the full simulator, all four ways, on both sides of several pings spread along the
// track (one line can be lucky: the error varies by a factor of five from line to line), against a converged
// reference (the same simulator at 64 and 256 times the rays, {64, 0, 8} then {128, 0, 16}:
// tests/support/converged_reference.hpp), with how much the reference's last doubling changed it (the reference's own
// error is of that order: about 0.1 dB RMS from {64, 0, 8} to {128, 0, 16}, 0.05 dB to {256, 0, 32}, on the 256 m copy
// of bench/bench_survey_accuracy.cpp).
// Per ray, bent rays against straight ones on the survey's cone columns: alone, beside a steeper neighbour, a column at
// once (the cost layered water adds to a ray, the part of a ping's layered / straight ratio that propagation makes).
//   sss_bench_survey [--pings N] [--size M] [--error-pings K] [--quick] [--per-ray]
// --pings: pings per measurement (default 40, best of 2); --size: the seabed's side in metres (default 1024);
// --error-pings: pings whose lines are compared with the reference (default 4, every 150 m / 0.2 m of track);
// --quick (or a short --benchmark_min_time, as the perf smoke test passes): 128 m, 2 pings, no reference; --per-ray:
// the scene's build and the per-ray costs alone.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <optional>
#include <span>
#include <type_traits>
#include <fstream>
#include <string>
#include <vector>

#if defined(__linux__)
#include <sched.h>
#endif

#include <sss/sss.hpp>

#include "../tests/support/converged_reference.hpp"
#include "support/survey_scene.hpp"

namespace {

using T = float;

/// The peak resident set of this process (VmHWM, MiB), or -1 where /proc does not say.
double peak_rss_mib() {
    std::ifstream in("/proc/self/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("VmHWM:", 0) == 0) return std::atof(line.c_str() + 6) / 1024.0;
    return -1.0;
}

/// The processors this process may run on (Linux; elsewhere none is known and nothing is pinned).
std::vector<int> allowed_cpus() {
    std::vector<int> cpus;
#if defined(__linux__)
    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof(set), &set) == 0)
        for (int c = 0; c < CPU_SETSIZE; ++c)
            if (CPU_ISSET(c, &set)) cpus.push_back(c);
#endif
    return cpus;
}

/// Keeps the calling thread on processor `cpu` (< 0: on every processor of `all`); false where that cannot be done.
/// Threads started meanwhile inherit it: the shared pool's workers are started by the scene's build, before anything
/// is pinned, and a render on 1 thread starts none.
bool pin_calling_thread(int cpu, const std::vector<int>& all) {
#if defined(__linux__)
    cpu_set_t set;
    CPU_ZERO(&set);
    if (cpu >= 0) CPU_SET(cpu, &set);
    else
        for (const int c : all) CPU_SET(c, &set);
    return sched_setaffinity(0, sizeof(set), &set) == 0;
#else
    (void)cpu;
    (void)all;
    return false;
#endif
}

/// Best pings per second of `reps` renders of pings [0, pings) on `threads` threads.
template <class Sim, class Scene> double pings_per_s(const Sim& sim, const Scene& scene, std::size_t pings, unsigned threads,
                                                     int reps) {
    double best = 1e300;
    for (int r = 0; r < reps; ++r) {
        const auto t0 = std::chrono::steady_clock::now();
        const auto w = sim.render(scene, 0, pings, threads);
        best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
        if (w.pings != pings) std::abort();
    }
    return double(pings) / best;
}

/// Processor time (s) of one call of fn: the machines this runs on are shared, and their speed drifts.
template <class Fn> double cpu_s(Fn&& fn) {
    const std::clock_t t0 = std::clock();
    fn();
    return double(std::clock() - t0) / CLOCKS_PER_SEC;
}

/// Rays of seven cone columns per side, as a sidescan column launches them: from `origin`, across track towards
/// `side_x` (+1 starboard, -1 port: the track runs along y), each column at along-track angles 0.008 rad apart, 3000
/// depressions from 3.4 to 61 degrees each, in order of depression.
template <class T> std::vector<std::vector<sss::ray<T>>> cone_columns(const sss::vec3<T>& origin, T side_x) {
    std::vector<std::vector<sss::ray<T>>> columns;
    for (int c = -3; c <= 3; ++c) {
        std::vector<sss::ray<T>> rays;
        for (int i = 0; i < 3000; ++i) {
            const T e = T(0.06) + T(i) / T(3000);
            sss::vec3<T> d{side_x * std::cos(e), std::tan(T(0.008) * T(c)), -std::sin(e)};
            rays.push_back({origin, d / std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z)});
        }
        columns.push_back(std::move(rays));
    }
    return columns;
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false;
    bool per_ray_only = false;
    std::size_t pings = 40;
    std::size_t error_pings = 4;
    double size_m = 1024.0;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) quick = true;
        if (std::strcmp(argv[i], "--per-ray") == 0) per_ray_only = true;
        if (std::strncmp(argv[i], "--benchmark_min_time=", 21) == 0 && std::atof(argv[i] + 21) < 0.1) quick = true;
        if (std::strcmp(argv[i], "--pings") == 0 && i + 1 < argc) pings = std::size_t(std::atol(argv[++i]));
        if (std::strcmp(argv[i], "--size") == 0 && i + 1 < argc) size_m = std::atof(argv[++i]);
        if (std::strcmp(argv[i], "--error-pings") == 0 && i + 1 < argc) error_pings = std::size_t(std::atol(argv[++i]));
    }
    if (quick) size_m = 128.0, pings = 2;
    pings = std::max<std::size_t>(pings, 1);

    sss_bench::survey_params<T> sp;
    sp.size_m = size_m;
    sp.cell_m = 0.25;
    sp.track_m = std::min(sp.track_m, 0.8 * size_m);
    sp.target_band_m = std::min(sp.target_band_m, 0.4 * size_m);
    const double rss0 = peak_rss_mib();
    const auto t_build0 = std::chrono::steady_clock::now();
    const auto sv = sss_bench::make_survey<T>(sp);
    const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_build0).count();
    const double rss1 = peak_rss_mib();
    const std::size_t n = std::size_t(std::lround(size_m / sp.cell_m));
    const double heights_mib = double(n) * double(n) * sizeof(T) / (1024.0 * 1024.0);

    using namespace sss;
    const auto full = [&](const ray_density& d) {
        return simulator<scattering::jackson<T>, propagation::layered<T>, beam::planar_array<T>, motion::perturbed<T>>(
            sv.scattering, sv.water, sv.array, sv.motion, sv.receiver, d);
    };
    const simulator<scattering::jackson<T>, propagation::straight<T>, beam::planar_array<T>, motion::perturbed<T>> straight_sim(
        sv.scattering,
        propagation::straight<T>({.sound_speed_mps = sv.water.reference_speed_mps(), .absorption_db_per_km = T(30)}),
        sv.array, sv.motion, sv.receiver);
    const motion::straight_line<T> line({.start_m = {T(0), T(-0.5 * sp.track_m)},
                                         .speed_mps = T(2),
                                         .altitude_m = T(sp.altitude_m),
                                         .ping_interval_s = T(0.1)});
    const simulator<scattering::lambertian<T>, propagation::straight<T>, beam::ideal_fan<T>, motion::straight_line<T>> minimal(
        scattering::lambertian<T>({.mu_db = {T(-27), T(-10)}}),
        propagation::straight<T>({.sound_speed_mps = sv.water.reference_speed_mps(), .absorption_db_per_km = T(30)}),
        beam::ideal_fan<T>{}, line, sv.receiver);
    const auto full_sim = full({});
    const auto full_objects_only = full({.along_split_seabed = false});
    const auto full_thirds = full({.along_split = 3, .along_split_by_weight = false});
    const auto full_even = full({.along_split_by_weight = false});
    const auto full_plain_facets = full({.refine_facets = false});
    const auto full_dense = full({.along_split_sparse = false});
    const auto full_halving = full({.bracket_facet_edges = false});
    const auto full_nadir_whole = full({.along_split_nadir = false});
    const auto full_echo_off = full({.along_split_echo = 0.0});

    const auto per_ray = [&]() -> bool {
        // Bent rays against straight ones, per ray, on the survey's seabed and targets: the seven cone columns of
        // cone_columns, both sides of pings 100, 250 and 400 (126,000 rays), each column over the scene its rays see
        // (the side's area view narrowed to the column, as the simulator's), traced three ways: each ray alone
        // (trace), each beside the last steeper ray of its column that met the scene (trace_beside, as the
        // refinement's rays are traced), and the column at once (trace_many, as the columns are). Interleaved
        // rounds of processor time on one processor, best of each. Layered water's three ways give the same paths bit
        // for bit (checked here); what a ping's layered / straight ratio needs of a bent ray follows from these and the
        // rest of a ping's time per ray (docs/design/layered.md).
        struct ways {
            double alone = 1e300, beside = 1e300, many = 1e300;
        } bent, flat;
        bool same = true;
        std::size_t rays_total = 0;
        const auto time_water = [&](const auto& water, ways& best) {
            double alone = 0, beside = 0, many = 0;
            rays_total = 0;
            for (const std::size_t ping : {std::size_t(100), std::size_t(250), std::size_t(400)}) {
                const auto pose = full_sim.motion().pose_at(ping);
                for (const side sd : {side::port, side::starboard}) {
                    const auto area = full_sim.side_area(pose, sd);
                    if (!area) continue;
                    const scene::area_view<std::decay_t<decltype(sv.scene)>> side_view(sv.scene, area->lo, area->hi);
                    for (const auto& rays : cone_columns(pose.position, sd == side::starboard ? T(1) : T(-1))) {
                        vec2<T> lo{pose.position.x, pose.position.y}, hi = lo;
                        for (const auto& r : rays) { // where each ray is 110 m out horizontally: past the slant range
                            const T f = T(110) / std::sqrt(r.direction.x * r.direction.x + r.direction.y * r.direction.y);
                            const vec2<T> q{r.origin.x + r.direction.x * f, r.origin.y + r.direction.y * f};
                            lo = glm::min(lo, q);
                            hi = glm::max(hi, q);
                        }
                        const auto view = side_view.within(lo, hi);
                        const T t_max = T(0.5 * double(full_sim.samples_per_line()) * full_sim.dt_s()); // the line's one way
                        std::vector<std::optional<path<T>>> a(rays.size()), b(rays.size()), c(rays.size());
                        alone += cpu_s([&] {
                            for (std::size_t k = 0; k < rays.size(); ++k) a[k] = water.trace(rays[k], view, t_max);
                        });
                        beside += cpu_s([&] {
                            std::size_t guide = rays.size();
                            for (std::size_t k = 0; k < rays.size(); ++k) {
                                const std::size_t j = rays.size() - 1 - k; // steep first
                                b[j] = guide < rays.size()
                                           ? water.trace_beside(rays[j], view, t_max, rays[guide].direction, b[guide]->clear_range_m)
                                           : water.trace(rays[j], view, t_max);
                                if (b[j]) guide = j;
                            }
                        });
                        many += cpu_s([&] { water.trace_many(std::span<const ray<T>>(rays), view, t_max, std::span(c)); });
                        if constexpr (std::is_same_v<std::decay_t<decltype(water)>, propagation::layered<T>>)
                            for (std::size_t k = 0; k < rays.size(); ++k)
                                same = same && a[k].has_value() == b[k].has_value() && a[k].has_value() == c[k].has_value() &&
                                       (!a[k] || (a[k]->time_s == b[k]->time_s && a[k]->time_s == c[k]->time_s &&
                                                  a[k]->surface.point == b[k]->surface.point &&
                                                  a[k]->surface.point == c[k]->surface.point &&
                                                  a[k]->spreading == b[k]->spreading && a[k]->spreading == c[k]->spreading));
                        rays_total += rays.size();
                    }
                }
            }
            best.alone = std::min(best.alone, alone);
            best.beside = std::min(best.beside, beside);
            best.many = std::min(best.many, many);
        };
        const propagation::straight<T> isovelocity(
            {.sound_speed_mps = sv.water.reference_speed_mps(), .absorption_db_per_km = T(30)});
        // On one processor throughout, where it can be chosen: a shared machine's processors can differ in speed.
        const std::vector<int> all = allowed_cpus();
        const bool pinned = !all.empty() && pin_calling_thread(all[0], all);
        for (int round = 0; round < (quick ? 1 : 3); ++round) {
            time_water(sv.water, bent);
            time_water(isovelocity, flat);
        }
        if (pinned) pin_calling_thread(-1, all);
        const double per = 1e9 / double(std::max<std::size_t>(rays_total, 1));
        std::printf("per ray on the survey's cone columns (%zu rays, 1 thread, ns; layered's three ways %s): alone: "
                    "layered %.0f, straight %.0f (%.2f); beside a steeper neighbour: layered %.0f, straight %.0f (%.2f); "
                    "a column at once: layered %.0f, straight %.0f (%.2f)\n",
                    rays_total, same ? "the same bit for bit" : "DIFFER", bent.alone * per, flat.alone * per,
                    bent.alone / flat.alone, bent.beside * per, flat.beside * per, bent.beside / flat.beside,
                    bent.many * per, flat.many * per, bent.many / flat.many);
        return same;
    };

    std::printf("Survey scene, float: %.0f m of seabed at %.2f m (%zu^2 heights, %.0f MiB), built in %.2f s, peak "
                "resident memory %.0f MiB after the build (%.0f MiB before, %.1f times the heights); %zu samples per "
                "side, %zu pings per measurement, best of %d; %u hardware threads\n",
                size_m, sp.cell_m, n, heights_mib, build_s, rss1, rss0, (rss1 - rss0) / heights_mib,
                full_sim.samples_per_line(), pings, quick ? 1 : 2, std::thread::hardware_concurrency());
    if (per_ray_only) return per_ray() ? 0 : 1;
    // One thread on each of the first two processors in turn, pinned, then two threads: a shared machine's
    // processors can differ in speed (on a shared 2-core virtual machine one of the two, which one varying from minute
    // to minute, was seen to render a ping up to 1.35 times slower, apparently its caches shared with other work), and
    // two threads can then give at most 1 + slower / faster times the faster one's speed. "2 / both alone" is the two
    // threads' speed over the sum of the two processors' speeds alone: how well the render divides its work where the
    // process may run on those two processors only. Every other one-thread figure is likewise the best over both
    // processors, pinned, so that the ratios below compare like with like.
    const std::vector<int> cpus = allowed_cpus();
    const bool per_cpu = cpus.size() >= 2 && pin_calling_thread(cpus[0], cpus) && pin_calling_thread(-1, cpus);
    if (per_cpu)
        std::printf("| simulator | 1 thread (the faster processor) | 1 thread on processor %d / %d | 2 threads | 2 / 1 | "
                    "2 / both alone |\n|---|---|---|---|---|---|\n",
                    cpus[0], cpus[1]);
    else
        std::printf("| simulator | 1 thread | 2 threads | 2 / 1 |\n|---|---|---|---|\n");
    const int reps = quick ? 1 : 2;
    // The least of what run() returns (seconds), over reps runs on each of the two processors in turn, pinned
    // (unpinned where processors cannot be chosen); each processor's own least into on_s when given.
    const auto best_pinned_s = [&](auto&& run, double* on_s = nullptr) {
        double on[2] = {1e300, 1e300};
        for (int r = 0; r < reps; ++r) // interleaved
            for (std::size_t k = 0; k < (per_cpu ? 2u : 1u); ++k) {
                if (per_cpu) pin_calling_thread(cpus[k], cpus);
                on[k] = std::min(on[k], run());
            }
        if (per_cpu) pin_calling_thread(-1, cpus);
        if (on_s) on_s[0] = on[0], on_s[1] = on[1];
        return std::min(on[0], on[1]);
    };
    const auto one_thread = [&](const auto& sim, double* on_s = nullptr) {
        return double(pings) / best_pinned_s([&] { return double(pings) / pings_per_s(sim, sv.scene, pings, 1, 1); }, on_s);
    };
    double layered_1 = 0, straight_1 = 0;
    const auto row = [&](const char* name, const auto& sim) {
        double on_s[2] = {0, 0};
        const double one = one_thread(sim, on_s);
        const double two = pings_per_s(sim, sv.scene, pings, 2, reps);
        if (per_cpu) {
            const double on0 = double(pings) / on_s[0], on1 = double(pings) / on_s[1];
            std::printf("| %s | %.1f pings/s | %.1f / %.1f pings/s | %.1f pings/s | %.2f | %.2f |\n", name, one, on0, on1,
                        two, two / one, two / (on0 + on1));
        } else
            std::printf("| %s | %.1f pings/s | %.1f pings/s | %.2f |\n", name, one, two, two / one);
        return one;
    };
    layered_1 = row("full (Jackson, layered, planar array, perturbed)", full_sim);
    straight_1 = row("full with straight rays", straight_sim);
    row("minimal (Lambert, straight, ideal fan, straight line)", minimal);
    std::printf("layered / straight time per ping (1 thread): %.2f\n", straight_1 / layered_1);
    const double objects_only_1 = row("full, the seabed's edges out of the along-track check", full_objects_only);
    std::printf("full: the seabed's edges in the along-track check (the default here) cost %.2f times the time per ping\n",
                objects_only_1 / layered_1);
    const double thirds_1 = row("full, the along-track check in thirds only (along_split = 3)", full_thirds);
    std::printf("full: dividing to ninths (the default) costs %.2f times the time per ping of thirds only\n",
                thirds_1 / layered_1);
    const double even_1 = row("full, the along-track division even (along_split_by_weight = false)", full_even);
    std::printf("full: the division shared by weight (the default) takes %.2f times the time per ping of even division\n",
                even_1 / layered_1);
    const double plain_facets_1 = row("full, facets' edges not refined (refine_facets = false)", full_plain_facets);
    std::printf("full: refining at the facets' edges (the default) takes %.2f times the time per ping of not\n",
                plain_facets_1 / layered_1);
    const double dense_1 = row("full, the division's last level at every launch angle (along_split_sparse = false)",
                               full_dense);
    std::printf("full: the division's last level at every other launch angle (the default) takes %.2f times the time "
                "per ping of every angle\n",
                dense_1 / layered_1);
    const double halving_1 = row("full, facets' edges halved (bracket_facet_edges = false)", full_halving);
    std::printf("full: bracketing the facets' edges (the default) takes %.2f times the time per ping of halving\n",
                halving_1 / layered_1);
    const double nadir_whole_1 = row("full, the columns near the first return left whole (along_split_nadir = false)",
                                     full_nadir_whole);
    std::printf("full: dividing the columns near the first return (the default) takes %.2f times the time per ping of "
                "leaving them whole\n",
                nadir_whole_1 / layered_1);
    const double echo_off_1 = row("full, no column divided where its echo departs (along_split_echo = 0)", full_echo_off);
    std::printf("full: dividing where a column's echo departs from its neighbours' (the default) takes %.2f times the "
                "time per ping of not\n",
                echo_off_1 / layered_1);
    {
        // What the refinements spend: echo pieces per ping (about one per ray traced: a tube per pair of rays, a
        // point per end at a located edge), over the first few pings, both sides.
        const std::size_t counted = std::min<std::size_t>(pings, 4);
        const auto pieces = [&](const auto& sim) {
            std::size_t n = 0;
            for (std::size_t i = 0; i < counted; ++i)
                for (const side sd : {side::port, side::starboard})
                    sim.trace(sv.scene, sim.motion().pose_at(i), sd, [&](const auto&) { ++n; });
            return double(n) / double(counted);
        };
        std::printf("echo pieces per ping (pings 0 to %zu): full %.0f; the seabed's edges out %.0f; thirds only %.0f; "
                    "even division %.0f; facets' edges not refined %.0f; facets' edges halved %.0f; the last level at "
                    "every angle %.0f; near the first return whole %.0f; no division where the echo departs %.0f; "
                    "straight rays %.0f; minimal %.0f\n",
                    counted - 1, pieces(full_sim), pieces(full_objects_only), pieces(full_thirds), pieces(full_even),
                    pieces(full_plain_facets), pieces(full_halving), pieces(full_dense), pieces(full_nadir_whole), pieces(full_echo_off), pieces(straight_sim),
                    pieces(minimal));
    }
    {
        // Clearing chords in open water (layered_params::clear_open_water) against the walk chord by chord, in the
        // survey's water and in water whose strong gradients reach the seabed (1500 m/s to 20 m, 1490 m/s at the
        // towfish, 1470 m/s at 40.5 m: chords of about 0.7 m instead of 2 m); full simulator, the seabed's edges out
        // of the along-track check, 1 thread.
        const std::vector<T> depths(sv.water.profile().depths_m().begin(), sv.water.profile().depths_m().end());
        const auto with_water = [&](const std::vector<T>& speeds, bool clear) {
            propagation::layered_params<T> wp = sv.water.params();
            wp.clear_open_water = clear;
            return simulator<scattering::jackson<T>, propagation::layered<T>, beam::planar_array<T>, motion::perturbed<T>>(
                sv.scattering,
                propagation::layered<T>(propagation::sound_speed_profile<T>(depths, speeds), wp),
                sv.array, sv.motion, sv.receiver, ray_density{.along_split_seabed = false});
        };
        const std::vector<T> survey_speeds(sv.water.profile().speeds_mps().begin(), sv.water.profile().speeds_mps().end());
        const std::vector<T> strong{T(1500), T(1500), T(1490), T(1470)};
        for (const auto* speeds : {&survey_speeds, &strong}) {
            const double cleared = one_thread(with_water(*speeds, true));
            const double plain = one_thread(with_water(*speeds, false));
            std::printf("full, %s, the seabed's edges out (1 thread): chords cleared in open water %.1f pings/s, chord by "
                        "chord %.1f pings/s (time %.2f)\n",
                        speeds == &strong ? "strong gradients to the seabed" : "the survey's water", cleared, plain,
                        plain / cleared);
        }
    }
    {
        // Bent rays beside a steeper neighbour (layered_params::follow_neighbours: the chords its path vouches for are
        // skipped) against every ray traced alone; full simulator as by default, 1 thread.
        propagation::layered_params<T> wp = sv.water.params();
        wp.follow_neighbours = false;
        const simulator<scattering::jackson<T>, propagation::layered<T>, beam::planar_array<T>, motion::perturbed<T>> alone(
            sv.scattering, propagation::layered<T>(sv.water.profile(), wp), sv.array, sv.motion, sv.receiver);
        const double each_alone = one_thread(alone);
        std::printf("full (1 thread): bent rays beside their neighbours %.1f pings/s, each traced alone %.1f pings/s "
                    "(time %.2f)\n",
                    layered_1, each_alone, layered_1 / each_alone);
    }
    if (!per_ray()) return 1;
    {
        // Ground truth beside the image (full simulator, 1 thread): render_labelled, which takes the labels' first
        // pass from the image's own trace and traces the bare seabed only on sides an object reaches, against
        // render followed by label_render (three traces per side).
        const auto per_ping_s = [&](auto&& run) {
            return best_pinned_s([&] {
                       const auto t0 = std::chrono::steady_clock::now();
                       run();
                       return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
                   }) /
                   double(pings);
        };
        const double together = per_ping_s([&] {
            if (render_labelled(full_sim, sv.scene, 0, pings, {.threads = 1}).labels.pings != pings) std::abort();
        });
        const double apart = per_ping_s([&] {
            if (full_sim.render(sv.scene, 0, pings, 1).pings != pings) std::abort();
            if (label_render(full_sim, sv.scene, 0, pings, {.threads = 1}).pings != pings) std::abort();
        });
        // Sides an object reaches over, and among them those where a ray met one: only these trace the bare seabed.
        std::size_t reaching = 0, met = 0;
        for (std::size_t i = 0; i < pings; ++i)
            for (const side sd : {side::port, side::starboard}) {
                const auto p = full_sim.motion().pose_at(i);
                const auto area = full_sim.side_area(p, sd);
                if (area && !std::isfinite(sv.scene.objects().top_m(area->lo, area->hi))) continue;
                ++reaching;
                bool hit = false;
                full_sim.trace(sv.scene, p, sd, [&](const tube_echo<T>& e) { hit = hit || e.surface.object != no_object; });
                met += hit;
            }
        std::printf("full with labels (1 thread): render_labelled %.1f pings/s, render then label_render %.1f pings/s "
                    "(%.2f times the time); the labels add %.0f %% to the image's time; %zu of %zu sides reach an object, "
                    "on %zu a ray meets one (these trace the bare seabed again)\n",
                    1.0 / together, 1.0 / apart, apart / together, 100.0 * (together * layered_1 - 1.0), reaching, 2 * pings,
                    met);
    }

    if (!quick && error_pings > 0) {
        // Pings 150 apart (30 m of track at 0.2 m per ping), within the track the targets lie along.
        const std::size_t step = std::max<std::size_t>(1, std::min<std::size_t>(150, std::size_t(sp.track_m / 0.2) / error_pings));
        std::printf("error against the reference {128, 0, 16} (the seabed's edges in the along-track check), dB over the "
                    "samples within 40 dB of the line's peak:\n");
        std::printf("| ping | side | reference's last doubling, RMS | default: RMS / median / p99 | shadows missed | "
                    "thirds only: RMS / median / p99 | shadows missed | seabed's edges out: RMS / median / p99 | "
                    "shadows missed | even division: RMS / median / p99 | shadows missed | facets not refined: RMS / "
                    "median / p99 | shadows missed | last level at every angle: RMS / median / p99 | shadows missed | "
                    "facets' edges halved: RMS / median / p99 | shadows missed | near the first return whole: RMS / "
                    "median / p99 | shadows missed | no division where the echo departs: RMS / median / p99 | shadows "
                    "missed |\n"
                    "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
        struct total {
            double sum_sq = 0, worst_p99 = 0;
            std::size_t misses = 0, shadows = 0, within = 0;
        } totals[9];
        std::size_t lines = 0;
        for (std::size_t k = 0; k < error_pings; ++k) {
            const auto pose = sv.motion.pose_at(k * step);
            for (const side sd : {side::port, side::starboard}) {
                const auto ref = sss_test::converged_line(
                    full, sv.scene, pose, sd,
                    {.start = ray_density{.along = 64, .across = 0, .per_sample = 8.0, .along_split_seabed = true},
                     .max_doublings = 1});
                std::printf("| %zu | %s | %.3f |", k * step, sd == side::port ? "port" : "starboard", ref.last_change_db);
                int v = 0;
                for (const auto* sim :
                     {&full_sim, &full_thirds, &full_objects_only, &full_even, &full_plain_facets, &full_dense,
                      &full_halving, &full_nadir_whole, &full_echo_off}) {
                    const auto e = sss_test::compare_lines(sss_bench::side_line(*sim, sv.scene, pose, sd), ref.values);
                    std::printf(" %.3f / %.3f / %.3f | %zu of %zu |", e.rms_db, e.median_db, e.p99_db, e.shadow_misses,
                                e.shadow_samples);
                    total& t = totals[v++];
                    t.sum_sq += e.rms_db * e.rms_db;
                    t.worst_p99 = std::max(t.worst_p99, e.p99_db);
                    t.misses += e.shadow_misses;
                    t.shadows += e.shadow_samples;
                    t.within += e.rms_db <= 0.3 && e.p99_db <= 1.0 && e.shadow_misses == 0;
                }
                std::printf("\n");
                ++lines;
            }
        }
        for (int v = 0; v < 9; ++v)
            std::printf("%s: RMS over the lines' RMS %.3f dB, worst p99 %.3f dB, %zu of %zu shadow samples missed; %zu of %zu "
                        "lines within 0.3 dB RMS and 1 dB p99 with no shadow missed\n",
                        v == 0   ? "default"
                        : v == 1 ? "thirds only (along_split = 3)"
                        : v == 2 ? "the seabed's edges out of the along-track check"
                        : v == 3 ? "even division (along_split_by_weight = false)"
                        : v == 4 ? "facets' edges not refined (refine_facets = false)"
                        : v == 5 ? "the division's last level at every angle (along_split_sparse = false)"
                        : v == 6 ? "facets' edges halved (bracket_facet_edges = false)"
                        : v == 7 ? "the columns near the first return whole (along_split_nadir = false)"
                                 : "no division where a column's echo departs (along_split_echo = 0)",
                        std::sqrt(totals[v].sum_sq / double(lines)), totals[v].worst_p99, totals[v].misses,
                        totals[v].shadows, totals[v].within, lines);
    }
    return 0;
}

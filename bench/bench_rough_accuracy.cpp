// Speed against error on rough scenes: what the adaptive refinement of ray tubes (across track at edges and rough
// facets, along track at objects' silhouettes) buys and costs, against the converged reference.
//
// Scenes (tests/support/rough_scenes.hpp): towfish 10 m above z = 0 heading north, 30 m per side, 20 kHz, 100 us
// pulse, Lambert, ideal fan 1 x 50 deg at 20 deg depression, straight rays, double precision, starboard line:
//   ridge     Gaussian ridge 1.5 m high, 0.3 m wide, 20 m to starboard (height field of 0.05 m cells)
//   relief    power-law relief (24 plane waves, 0.5 to 20 m) with two sets of ripples (0.8 m and 0.5 m)
//   trench    a trench 1.2 m deep crossing the beam obliquely
//   lee       a plateau ending in a slope whose plane passes 0.057 deg below the towfish: every ray meeting the
//             slope grazes it (its echo per radian, 1/sin of the angle to the facet, in the hundreds)
//   targets   a lying cylinder, a moored spherical mine and a pipeline spanning a hollow, on gentle rippled relief
//   slope     ripples 0.2 m from crest to trough, 1.3 m long, on a plane rising 0.15 to starboard (0.075 along
//             track): the side launches for the plane, not for the level seabed under the towfish
//   flat      the flat seabed z = 0 (no reference: the refinement must change nothing and cost nothing there)
// For each scene and density {along, 0, per_sample}, with the refinement off (refine_depth 0: the tubes of the
// previous simulator), on (the defaults; the columns are close enough here that the seabed's own shadow edges stay
// out of the along-track check), and on with them forced in (ray_density::along_split_seabed): rays per side (scene queries), time per side (the best of several
// runs, interleaved off/on so both see the same machine), and the error of the line against the converged
// reference (the same simulator doubled from {16, 0, 4} until a doubling changes the line by < 0.05 dB RMS):
// RMS, median and 99th percentile of |dB| over the samples within 40 dB of the reference's peak, and how many of
// the reference's shadow samples (>= 40 dB below their lit surroundings) the line fails to keep as dark.
// Wide beams: the relief under ideal fans 30 and 90 deg wide along track (a short array, one element), at the
// default density, with the along-track columns narrowed where the first return moves across them (the default,
// ray_density::along_onset = 1) and evenly spaced (0), against the same simulator's converged reference.
// Options: --quick (or a short --benchmark_min_time, as the perf smoke test passes) keeps to the default density
// and leaves out the trench and the wide beams;
// --density=ALONG,PER_SAMPLE (repeatable) measures those densities instead of the usual five.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <string>
#include <vector>

#include <sss/sss.hpp>

#include "../tests/support/converged_reference.hpp"
#include "../tests/support/counting_scene.hpp"
#include "../tests/support/rough_scenes.hpp"

namespace {

auto make_sim(const sss::ray_density& d) {
    return sss::simulator<>({}, {}, {}, {}, sss_test::rough_receiver(), d);
}

std::vector<double> starboard(const sss::simulator<>& sim, const auto& scene, const sss::pose<double>& p) {
    sss::time_sampler s(sim.samples_per_line(), sim.dt_s(), sim.receiver().pulse);
    sim.trace(scene, p, sss::side::starboard, [&](const sss::tube_echo<double>& e) { s.add_span(e.t0_s, e.t1_s, e.power); });
    std::vector<double> out;
    s.render(out);
    return out;
}

struct row {
    std::size_t rays = 0;
    double ms = 1e300;
    sss_test::line_error e{};
};

template <class Scene>
void run_scene(const char* name, const Scene& scene, bool with_reference, const std::vector<sss::ray_density>& densities) {
    const auto pose = sss_test::rough_pose<double>(false);
    std::vector<double> ref;
    std::string ref_note = "no reference";
    if (with_reference) {
        const auto r = sss_test::converged_line(make_sim, scene, pose, sss::side::starboard,
                                                {.start = {.along = 16, .across = 0, .per_sample = 4.0}, .max_doublings = 3});
        ref = r.values;
        char buf[160];
        std::snprintf(buf, sizeof buf, "reference {%zu, 0, %g}, last doubling %.3f dB%s", r.density.along,
                      r.density.per_sample, r.last_change_db, r.converged ? "" : " (NOT converged)");
        ref_note = buf;
    }
    std::printf("\n%s: %s\n", name, ref_note.c_str());
    std::printf("| density {along, 0, per_sample} | refinement | rays/side | ms/side | RMS dB | median dB | 99th pct dB | shadow missed |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    for (const sss::ray_density& d0 : densities) {
        const int variants = with_reference ? 3 : 2;
        row rows[3];
        sss::ray_density dens[3] = {d0, d0, d0};
        dens[0].refine_depth = 0;
        dens[2].along_split_seabed = true;
        const char* names[3] = {"off", "on", "on, seabed edges along (forced)"};
        std::vector<double> lines[3];
        for (int i = 0; i < variants; ++i) {
            const auto sim = make_sim(dens[i]);
            std::size_t n = 0;
            const sss_test::counting_scene<Scene> counted(scene, n);
            (void)starboard(sim, counted, pose);
            rows[i].rays = n;
        }
        for (int rep = 0; rep < 7; ++rep)
            for (int i = 0; i < variants; ++i) {
                const auto sim = make_sim(dens[i]);
                const auto t0 = std::chrono::steady_clock::now();
                lines[i] = starboard(sim, scene, pose);
                const auto t1 = std::chrono::steady_clock::now();
                rows[i].ms = std::min(rows[i].ms, 1e3 * std::chrono::duration<double>(t1 - t0).count());
            }
        for (int i = 0; i < variants; ++i) {
            if (with_reference) {
                const auto e = sss_test::compare_lines(lines[i], ref);
                std::printf("| {%zu, 0, %g} | %s | %zu | %.2f | %.3f | %.3f | %.3f | %zu of %zu |\n", d0.along, d0.per_sample,
                            names[i], rows[i].rays, rows[i].ms, e.rms_db, e.median_db, e.p99_db, e.shadow_misses,
                            e.shadow_samples);
            } else {
                const auto e = sss_test::compare_lines(lines[1], lines[0]);
                std::printf("| {%zu, 0, %g} | %s | %zu | %.3f | %s |  |  |  |\n", d0.along, d0.per_sample, i ? "on" : "off",
                            rows[i].rays, rows[i].ms,
                            i ? (std::string("on/off time ") + std::to_string(rows[1].ms / rows[0].ms) +
                                 ", line change RMS " + std::to_string(e.rms_db) + " dB")
                                    .c_str()
                              : "");
            }
        }
    }
}

/// The relief under an ideal fan `along_deg` wide along track: columns narrowed by the first return (the default)
/// against evenly spaced ones, at the default density, against the converged reference.
template <class Scene> void run_wide(const char* name, const Scene& scene, double along_deg) {
    const auto pose = sss_test::rough_pose<double>(false);
    auto make = [&](const sss::ray_density& d) {
        return sss::simulator<>({}, {}, sss::beam::ideal_fan<double>({.along_width_deg = along_deg}), {},
                                sss_test::rough_receiver(), d);
    };
    const auto r = sss_test::converged_line(make, scene, pose, sss::side::starboard,
                                            {.start = {.along = 32, .across = 0, .per_sample = 4.0}, .max_doublings = 4});
    std::printf("\n%s under a fan %g deg wide along track: reference {%zu, 0, %g}, last doubling %.3f dB%s\n", name,
                along_deg, r.density.along, r.density.per_sample, r.last_change_db, r.converged ? "" : " (NOT converged)");
    std::printf("| columns | rays/side | ms/side | RMS dB | median dB | 99th pct dB | shadow missed |\n");
    std::printf("|---|---|---|---|---|---|---|\n");
    row rows[2];
    std::vector<double> lines[2];
    const double onsets[2] = {1.0, 0.0};
    for (int i = 0; i < 2; ++i) {
        std::size_t n = 0;
        const sss_test::counting_scene<Scene> counted(scene, n);
        (void)starboard(make({.along_onset = onsets[i]}), counted, pose);
        rows[i].rays = n;
    }
    for (int rep = 0; rep < 5; ++rep)
        for (int i = 0; i < 2; ++i) {
            const auto sim = make({.along_onset = onsets[i]});
            const auto t0 = std::chrono::steady_clock::now();
            lines[i] = starboard(sim, scene, pose);
            const auto t1 = std::chrono::steady_clock::now();
            rows[i].ms = std::min(rows[i].ms, 1e3 * std::chrono::duration<double>(t1 - t0).count());
        }
    for (int i = 0; i < 2; ++i) {
        const auto e = sss_test::compare_lines(lines[i], r.values);
        std::printf("| %s | %zu | %.2f | %.3f | %.3f | %.3f | %zu of %zu |\n",
                    i == 0 ? "narrowed where the first return moves (default)" : "evenly spaced (along_onset = 0)",
                    rows[i].rays, rows[i].ms, e.rms_db, e.median_db, e.p99_db, e.shadow_misses, e.shadow_samples);
    }
}

} // namespace

int main(int argc, char** argv) {
    bool quick = false;
    std::vector<sss::ray_density> asked;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) quick = true;
        if (std::strncmp(argv[i], "--benchmark_min_time=", 21) == 0 && std::atof(argv[i] + 21) < 0.1) quick = true;
        std::size_t along = 0;
        double per_sample = 0.0;
        if (std::sscanf(argv[i], "--density=%zu,%lf", &along, &per_sample) == 2 && along > 0 && per_sample > 0.0)
            asked.push_back({.along = along, .across = 0, .per_sample = per_sample});
    }
    std::vector<sss::ray_density> densities{sss::ray_density{}};
    if (!asked.empty()) densities = asked;
    else if (!quick) {
        densities.push_back({.along = 8, .across = 0, .per_sample = 2.0});
        densities.push_back({.along = 16, .across = 0, .per_sample = 1.0});
        densities.push_back({.along = 8, .across = 0, .per_sample = 4.0});
        densities.push_back({.along = 32, .across = 0, .per_sample = 4.0});
    }
    std::printf("Speed against error on rough scenes (starboard line, 30 m, 20 kHz; times: best of 7, one thread)\n");
    run_scene("flat", sss::scene::flat_seabed<double>(0.0), false, {sss::ray_density{}});
    run_scene("ridge", sss_test::ridge_field<double>(), true, densities);
    run_scene("relief", sss_test::ripple_field<double>(), true, densities);
    if (!quick) run_scene("trench", sss_test::trench_field<double>(), true, densities);
    run_scene("lee", sss_test::lee_slope_field<double>(0.057), true, densities);
    run_scene("targets", sss_test::target_scene<double>(), true, densities);
    run_scene("slope", sss_test::footprint_field<double>([](double x, double y) {
                  return 0.15 * (x + 0.5 * y) + 0.1 * std::sin(2 * std::numbers::pi * (0.9 * x + 0.3 * y) / 1.3);
              }),
              true, densities);
    if (!quick) {
        run_wide("relief", sss_test::ripple_field<double>(), 30.0);
        run_wide("relief", sss_test::ripple_field<double>(), 90.0);
    }
    return 0;
}

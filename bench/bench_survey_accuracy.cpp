// Speed against error on the survey scene (bench/support/survey_scene.hpp): a fractal seabed with two sets of
// ripples and 20 targets, Jackson medium sand at 100 kHz, three-layer water, a 100 kHz planar array, a perturbed
// towfish, 100 m per side in 2048 samples. For ping 0's starboard line, at the default density {8, 0, 1} with the
// refinement off (the previous tubes), on with only objects' edges in the along-track check, and on as by default
// (the columns are coarse here, so the seabed's shadow edges take part too: ray_density::along_split_seabed), that
// with disagreeing stretches divided into thirds only once (ray_density::along_split = 3, every column alike), that
// with every column divided alike rather than by the beam's weight on it (ray_density::along_split_by_weight), that
// with the seabed's facets' edges not refined across track (ray_density::refine_facets), that with the division's
// last level at every launch angle of its column (ray_density::along_split_sparse), that with the facets' edges
// located by halving the step rather than bracketed (ray_density::bracket_facet_edges), and (not with --quick) down
// to 1/27 of a column, half a ray per sample, and 32 uniform columns without the along-track check: rays per side,
// time per side (best of 3, in turn), and the RMS, median and 99th percentile |dB| error over the samples within
// 40 dB of the reference's peak, and the missed shadow samples, against the same simulator at {128, 0, 16} (256
// times the rays, the seabed's edges in the along-track check; the change from {64, 0, 8} is printed as its
// convergence check: about 0.1 dB RMS, and 0.05 dB for the next doubling).
// The seabed defaults to 256 m at 0.25 m (1024^2 heights) so that a run takes a few minutes; --full builds the
// survey's 1024 m (4096^2 heights). --quick (or a short --benchmark_min_time, as the perf smoke test passes) uses
// 224 m and a reference at {16, 0, 2} from {8, 0, 1}.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include <sss/sss.hpp>

#include "../tests/support/converged_reference.hpp"
#include "support/survey_scene.hpp"

namespace {

using T = double;

} // namespace

int main(int argc, char** argv) {
    bool quick = false, full = false;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--quick") == 0) quick = true;
        if (std::strcmp(argv[i], "--full") == 0) full = true;
        if (std::strncmp(argv[i], "--benchmark_min_time=", 21) == 0 && std::atof(argv[i] + 21) < 0.1) quick = true;
    }
    sss_bench::survey_params<T> sp;
    sp.size_m = full ? 1024.0 : quick ? 224.0 : 256.0;
    sp.cell_m = 0.25;
    const auto t_build0 = std::chrono::steady_clock::now();
    const auto sv = sss_bench::make_survey<T>(sp);
    const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_build0).count();
    auto make = [&](const sss::ray_density& d) {
        return sss::simulator<sss::scattering::jackson<T>, sss::propagation::layered<T>, sss::beam::planar_array<T>,
                              sss::motion::perturbed<T>>(sv.scattering, sv.water, sv.array, sv.motion, sv.receiver, d);
    };
    const auto pose = sv.motion.pose_at(0);
    const auto t_ref0 = std::chrono::steady_clock::now();
    const auto ref = sss_test::converged_line(make, sv.scene, pose, sss::side::starboard,
                                              {.start = quick ? sss::ray_density{.along = 8, .across = 0, .per_sample = 1.0,
                                                                                 .along_split_seabed = true}
                                                              : sss::ray_density{.along = 64, .across = 0, .per_sample = 8.0,
                                                                                 .along_split_seabed = true},
                                               .max_doublings = 1});
    const double ref_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_ref0).count();
    std::printf("Survey scene: %.0f m of seabed at %.2f m (%zu^2 heights, built in %.1f s), %zu samples per side; "
                "reference {%zu, 0, %g} (%.1f s), last doubling changed it by %.3f dB RMS\n",
                sp.size_m, sp.cell_m, std::size_t(std::lround(sp.size_m / sp.cell_m)), build_s, make({}).samples_per_line(),
                ref.density.along, ref.density.per_sample, ref_s, ref.last_change_db);
    std::printf("| density | refinement | rays/side | ms/side | RMS dB | median dB | 99th pct dB | shadow missed |\n");
    std::printf("|---|---|---|---|---|---|---|---|\n");
    struct variant {
        const char* density;
        const char* refinement;
        sss::ray_density d;
    };
    std::vector<variant> vs = {
        {"{8, 0, 1}", "off", {.refine_depth = 0}},
        {"{8, 0, 1}", "on, objects' edges along", {.along_split_seabed = false}},
        {"{8, 0, 1}", "on (default: seabed's edges too, along_split 9)", {}},
        {"{8, 0, 1}", "on, along_split 3 (thirds, not divided again)", {.along_split = 3, .along_split_by_weight = false}},
        {"{8, 0, 1}", "on, the division even (along_split_by_weight = false)", {.along_split_by_weight = false}},
        {"{8, 0, 1}", "on, facets' edges not refined (refine_facets = false)", {.refine_facets = false}},
        {"{8, 0, 1}", "on, the division's last level at every launch angle (along_split_sparse = false)",
         {.along_split_sparse = false}},
        {"{8, 0, 1}", "on, facets' edges halved (bracket_facet_edges = false)", {.bracket_facet_edges = false}},
    };
    if (!quick) { // the frontier beyond: finer division, and uniform columns without the along-track check
        vs.push_back({"{8, 0, 1}", "on, along_split 27", {.along_split = 27}});
        vs.push_back({"{8, 0, 0.5}", "on (half a ray per sample)", {.per_sample = 0.5}});
        vs.push_back({"{32, 0, 1}", "on, along_split 1 (no along-track check)", {.along = 32, .along_split = 1}});
    }
    const std::size_t variants = vs.size();
    std::vector<double> ms(variants, 1e300);
    std::vector<std::vector<double>> lines(variants);
    std::vector<std::size_t> echoes(variants, 0);
    for (int rep = 0; rep < 3; ++rep)
        for (std::size_t i = 0; i < variants; ++i) {
            const auto sim = make(vs[i].d);
            const auto t0 = std::chrono::steady_clock::now();
            lines[i] = sss_bench::side_line(sim, sv.scene, pose, sss::side::starboard);
            ms[i] = std::min(ms[i], 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
            if (rep == 0) {
                std::size_t n = 0;
                sim.trace(sv.scene, pose, sss::side::starboard, [&n](const sss::tube_echo<T>&) { ++n; });
                echoes[i] = n;
            }
        }
    for (std::size_t i = 0; i < variants; ++i) {
        const auto e = sss_test::compare_lines(lines[i], ref.values);
        std::printf("| %s | %s | %zu echoes | %.1f | %.3f | %.3f | %.3f | %zu of %zu |\n", vs[i].density, vs[i].refinement,
                    echoes[i], ms[i], e.rms_db, e.median_db, e.p99_db, e.shadow_misses, e.shadow_samples);
    }
    std::printf("time against off:");
    for (std::size_t i = 1; i < variants; ++i) std::printf("%s %s %s %.3f", i > 1 ? "," : "", vs[i].density, vs[i].refinement, ms[i] / ms[0]);
    std::printf("\n");
    return 0;
}

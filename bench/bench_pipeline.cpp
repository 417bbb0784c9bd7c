// The ping pipeline end to end: rays/s and pings/s of the simulator, and how its accuracy buys speed.
//
// Benchmarks (Google Benchmark; items/s = rays/s, counter pings/s), single thread unless stated:
//   flat       default simulator (Lambert -27 dB, straight rays 1500 m/s with 60 dB/km, ideal fan 1 x 50 deg at
//              20 deg depression, straight line), flat seabed z = 0, towfish 10 m up, 50 m range per side,
//              20 kHz sampling, 100 us rectangular pulse, default ray density {8, 0, 1.0}; float and double.
//   reference  the same but 100 m per side and ray_density{8, 2048}: 2 x 2048 x 8 rays per ping.
//   relief     the reference ping over a rough height field (2048 x 2048 vertices at 0.25 m: swell, dunes, ripples
//              and white noise, +-2.5 m), towfish 10 m above its mean; `columns` traces each column of rays
//              together (the height field's intersect_many: wedge sweep), `one by one` hides intersect_many
//              behind a wrapper so every ray is traced alone (the accelerated single-ray tracer).
//   render     render() of 16 flat pings on 1 and 2 threads (wall clock).
// Rays are counted by tracing one ping through a scene wrapper that counts intersection queries (straight
// rays query the scene once per ray).
//
// Then a speed-against-error table (skip with --no-table; only the table: --table-only): for each scene,
// the time per ping and the dB error (RMS and worst, over the samples within 40 dB of the line's peak) of
// the starboard line against the independent flat-seabed quadrature oracle (tests/support), for
// per_sample = 0.125 ... 4 (along 8) and along = 1 ... 16 (per_sample 1). Scenes: the default fan; the
// default fan with a 20 us pulse; a fan reaching nadir (depression 45, vertical width 90) with 100 us and
// with 20 us pulses; a 300 kHz planar array (32 x 2 elements of 1.5 x 1.9 cm at 1.56 x 2.0 cm pitch, tilted
// 15 deg, extent to -30 dB) with 100 us and 20 us pulses, and with its extent to -40 dB. Each oracle line is
// computed once and reused across densities; a float row at the default density closes each scene.
// The table is written as CSV to --csv=PATH, else $SSS_BENCH_CSV, else pipeline_speed_error.csv.
// A short run (--benchmark_min_time below 0.1 s, as the perf smoke test uses) or --table=quick keeps the
// table to the default scene and three densities; --table=full forces the whole table.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <stdexcept>
#include <utility>
#include <vector>

#include <sss/beam/ideal_fan.hpp>
#include <sss/beam/planar_array.hpp>
#include <sss/motion/straight_line.hpp>
#include <sss/propagation/straight.hpp>
#include <sss/scattering/lambertian.hpp>
#include <sss/scene/flat_seabed.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/simulator.hpp>

#include "../tests/support/compare.hpp"
#include "../tests/support/counting_scene.hpp"
#include "../tests/support/flat_seabed_oracle.hpp"
#include "support/rough_relief.hpp"

namespace {

template <class T, class Beam = sss::beam::ideal_fan<T>>
using flat_simulator = sss::simulator<sss::scattering::lambertian<T>, sss::propagation::straight<T>, Beam,
                                      sss::motion::straight_line<T>>;

/// The default policies with the given beam, receiver and density.
template <class T, class Beam = sss::beam::ideal_fan<T>>
flat_simulator<T, Beam> make_simulator(Beam beam = Beam{}, const sss::receiver_params& rx = {},
                                       const sss::ray_density& density = {}) {
    return flat_simulator<T, Beam>(sss::scattering::lambertian<T>{}, sss::propagation::straight<T>{}, std::move(beam),
                                   sss::motion::straight_line<T>{}, rx, density);
}

/// Rays launched by one ping (both sides).
template <class Sim, class Scene> std::size_t rays_per_ping(const Sim& sim, const Scene& scene, std::size_t index = 0) {
    std::size_t count = 0;
    const sss_test::counting_scene<Scene> counted(scene, count);
    benchmark::DoNotOptimize(sim.ping(counted, index));
    return count;
}

template <class Sim, class Scene>
void run_pings(benchmark::State& state, const Sim& sim, const Scene& scene, const char* what) {
    const std::size_t rays = rays_per_ping(sim, scene);
    std::size_t index = 0;
    for (auto _ : state) {
        auto lines = sim.ping(scene, index++);
        benchmark::DoNotOptimize(lines.port.data());
        benchmark::DoNotOptimize(lines.starboard.data());
        benchmark::ClobberMemory();
    }
    const auto pings = static_cast<std::int64_t>(state.iterations());
    state.SetItemsProcessed(pings * static_cast<std::int64_t>(rays));
    state.counters["pings/s"] = benchmark::Counter(double(pings), benchmark::Counter::kIsRate);
    state.counters["rays/ping"] = double(rays);
    state.counters["samples"] = double(sim.samples_per_line());
    state.SetLabel(what);
}

template <class T> void pipeline_ping_flat(benchmark::State& state) {
    const auto sim = make_simulator<T>();
    const sss::scene::flat_seabed<T> seabed(T(0));
    run_pings(state, sim, seabed, "flat, 10 m altitude, 50 m/side, 20 kHz, density {8, 0, 1}");
}
BENCHMARK_TEMPLATE(pipeline_ping_flat, float);
BENCHMARK_TEMPLATE(pipeline_ping_flat, double);

template <class T> void pipeline_ping_reference(benchmark::State& state) {
    sss::receiver_params rx;
    rx.max_range_m = 100.0;
    const auto sim = make_simulator<T>(sss::beam::ideal_fan<T>{}, rx, sss::ray_density{8, 2048, 1.0});
    const sss::scene::flat_seabed<T> seabed(T(0));
    run_pings(state, sim, seabed, "flat, 10 m altitude, 100 m/side, 20 kHz, density {8, 2048}");
}
BENCHMARK_TEMPLATE(pipeline_ping_reference, float);
BENCHMARK_TEMPLATE(pipeline_ping_reference, double);

/// The relief scene: the benchmarks' rough seabed (support/rough_relief.hpp), 2048 x 2048 vertices at 0.25 m
/// centred on the origin.
template <class T> const sss::scene::height_field<T>& relief() {
    static const sss::scene::height_field<T> hf({.nx = 2048, .ny = 2048, .cell_m = T(0.25), .origin_m = sss::vec2<T>{T(-256), T(-256)}, .heights_m = sss_bench::rough_heights<T>(2048, 0.25)});
    return hf;
}

/// A scene that hides its inner scene's batch method: every ray is traced alone.
template <class Inner> struct one_by_one {
    using value_type = typename Inner::value_type;
    const Inner* inner;
    [[nodiscard]] std::optional<sss::hit<value_type>> intersect(const sss::ray<value_type>& r, value_type t) const {
        return inner->intersect(r, t);
    }
    [[nodiscard]] value_type seabed_height_m(value_type x, value_type y) const { return inner->seabed_height_m(x, y); }
    [[nodiscard]] value_type top_m() const { return inner->top_m(); }
};

template <class T> void pipeline_ping_relief(benchmark::State& state) {
    sss::receiver_params rx;
    rx.max_range_m = 100.0;
    sss::motion::straight_line_params<T> track;
    track.start_m = sss::vec2<T>{T(0), T(-60)};
    const auto sim = flat_simulator<T>(sss::scattering::lambertian<T>{}, sss::propagation::straight<T>{},
                                       sss::beam::ideal_fan<T>{}, sss::motion::straight_line<T>(track), rx,
                                       sss::ray_density{8, 2048, 1.0});
    if (state.range(0) == 1)
        run_pings(state, sim, relief<T>(), "relief 2048^2 at 0.25 m, 10 m altitude, 100 m/side, columns traced together");
    else
        run_pings(state, sim, one_by_one<sss::scene::height_field<T>>{&relief<T>()},
                  "relief 2048^2 at 0.25 m, 10 m altitude, 100 m/side, rays traced one by one");
}
BENCHMARK_TEMPLATE(pipeline_ping_relief, float)->Arg(1)->Arg(0);
BENCHMARK_TEMPLATE(pipeline_ping_relief, double)->Arg(1)->Arg(0);

template <class T> void pipeline_render_flat(benchmark::State& state) {
    constexpr std::size_t pings = 16;
    const auto threads = static_cast<unsigned>(state.range(0));
    const auto sim = make_simulator<T>();
    const sss::scene::flat_seabed<T> seabed(T(0));
    const std::size_t rays = rays_per_ping(sim, seabed);
    for (auto _ : state) {
        auto w = sim.render(seabed, 0, pings, threads);
        benchmark::DoNotOptimize(w.values.data());
        benchmark::ClobberMemory();
    }
    const auto n = static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(pings);
    state.SetItemsProcessed(n * static_cast<std::int64_t>(rays));
    state.counters["pings/s"] = benchmark::Counter(double(n), benchmark::Counter::kIsRate);
    state.counters["threads"] = double(threads);
    state.SetLabel("render() of 16 flat pings, density {8, 0, 1}");
}
BENCHMARK_TEMPLATE(pipeline_render_flat, float)->Arg(1)->Arg(2)->UseRealTime();
BENCHMARK_TEMPLATE(pipeline_render_flat, double)->Arg(1)->Arg(2)->UseRealTime();

// ---------------------------------------------------------------------------------------------------------
// Speed against error.

struct table_options {
    enum class mode { none, quick, full } table = mode::full;
    bool table_only = false;
    bool to_stderr = false; // the benchmark output is machine-readable: keep stdout clean
    std::string csv_path = "pipeline_speed_error.csv";
};

struct row {
    std::string scene;
    std::string scalar;
    std::string sweep;
    sss::ray_density density;
    std::size_t rays = 0;
    double us_per_ping = 0.0;
    sss_test::db_error error;
    bool is_default = false;
};

/// Processor seconds per ping: the best of five batches of pings, each lasting at least `batch_s` of processor
/// time. Processor time, not wall time, and the best batch, not the mean: on a shared machine the noise only
/// ever adds time, and the table runs on one thread.
template <class Sim, class Scene> double seconds_per_ping(const Sim& sim, const Scene& scene, double batch_s) {
    const auto cpu_s = [] { return double(std::clock()) / double(CLOCKS_PER_SEC); };
    benchmark::DoNotOptimize(sim.ping(scene, 0)); // warm the caches and the allocator
    double best = std::numeric_limits<double>::infinity();
    for (int batch = 0; batch < 5; ++batch) {
        std::size_t n = 0;
        double elapsed = 0.0;
        const double t0 = cpu_s();
        do {
            auto lines = sim.ping(scene, n++);
            benchmark::DoNotOptimize(lines.starboard.data());
            elapsed = cpu_s() - t0;
        } while (elapsed < batch_s || n < 2);
        best = std::min(best, elapsed / double(n));
    }
    return best;
}

// The beams of the table, buildable in either scalar type.
struct default_fan {
    template <class T> static sss::beam::ideal_fan<T> make() { return sss::beam::ideal_fan<T>{}; }
};
struct nadir_fan {
    template <class T> static sss::beam::ideal_fan<T> make() {
        return sss::beam::ideal_fan<T>{sss::beam::ideal_fan_params<T>{T(1), T(90), T(45)}};
    }
};
template <int ThresholdDb> struct array_300khz {
    template <class T> static sss::beam::planar_array<T> make() {
        sss::beam::planar_array_params<T> p;
        p.frequency_hz = T(300000);
        p.depression_deg = T(15);
        p.transmit.along = {32, T(0.0150), T(0.0156), {}};
        p.transmit.vertical = {2, T(0.0190), T(0.0200), {}};
        p.threshold_db = T(ThresholdDb);
        return sss::beam::planar_array<T>{p};
    }
};

struct sweep_point {
    const char* sweep;
    sss::ray_density density;
};

std::vector<sweep_point> sweep_points(bool quick) {
    if (quick) return {{"per_sample", {8, 0, 0.5}}, {"per_sample", {8, 0, 1.0}}, {"per_sample", {8, 0, 2.0}}};
    std::vector<sweep_point> v;
    for (double ps : {0.125, 0.25, 0.5, 1.0, 2.0, 4.0}) v.push_back({"per_sample", {8, 0, ps}});
    for (std::size_t along : {1u, 2u, 4u, 8u, 16u}) v.push_back({"along", {along, 0, 1.0}});
    return v;
}

bool is_default_density(const sss::ray_density& d) {
    const sss::ray_density def{};
    return d.along == def.along && d.across == def.across && d.per_sample == def.per_sample;
}

template <class T, class Maker>
row measure(const std::string& scene_name, const char* sweep, const sss::ray_density& density,
            const sss::receiver_params& rx, const std::vector<double>& expected, double batch_s) {
    const auto sim = make_simulator<T>(Maker::template make<T>(), rx, density);
    const sss::scene::flat_seabed<T> seabed(T(0));
    row r;
    r.scene = scene_name;
    r.scalar = sizeof(T) == sizeof(float) ? "float" : "double";
    r.sweep = sweep;
    r.density = density;
    r.rays = rays_per_ping(sim, seabed);
    r.us_per_ping = 1e6 * seconds_per_ping(sim, seabed, batch_s);
    r.error = sss_test::compare_db(sim.ping(seabed, 0).starboard, expected, 40.0);
    r.is_default = is_default_density(density);
    return r;
}

void print_row(std::FILE* out, const row& r) {
    std::fprintf(out, "  %-6s %-10s %5zu %10.3f %9zu %9.1f %7.2f %8.3f %8.3f %6zu/%zu%s\n", r.scalar.c_str(),
                 r.sweep.c_str(), r.density.along, r.density.per_sample, r.rays, r.us_per_ping,
                 double(r.rays) / r.us_per_ping, r.error.rms_db, r.error.worst_db, r.error.worst_index,
                 r.error.compared,
                 r.is_default ? "  <- default" : "");
}

template <class Maker>
void table_scene(std::vector<row>& rows, std::FILE* out, const std::string& name, const char* beam_text, double pulse_s,
                 bool quick) {
    sss::receiver_params rx;
    rx.pulse = {pulse_s, sss::pulse_shape::rectangular};
    const auto probe = make_simulator<double>(Maker::template make<double>(), rx);
    const auto water = probe.propagation().params();
    const auto motion_pose = probe.motion().pose_at(0);

    sss_test::oracle_setup o;
    o.altitude_m = motion_pose.position.z;
    o.yaw_rad = motion_pose.yaw_rad;
    o.c_mps = water.sound_speed_mps;
    o.absorption_db_per_km = water.absorption_db_per_km;
    o.dt_s = probe.dt_s();
    o.samples = probe.samples_per_line();
    o.pulse = sss_test::envelope::rectangular;
    o.pulse_length_s = pulse_s;
    o.source_level = 1.0;
    const auto t0 = std::chrono::steady_clock::now();
    const std::vector<double> expected =
        sss_test::oracle_line(o, probe.beam(), probe.scattering(), sss::side::starboard);
    const double oracle_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    std::fprintf(out, "\n%s: %s, %.0f us pulse; %zu samples; oracle %.2f s\n", name.c_str(), beam_text, pulse_s * 1e6,
                 o.samples, oracle_s);
    std::fprintf(out, "  %-6s %-10s %5s %10s %9s %9s %7s %8s %8s %s\n", "scalar", "sweep", "along", "per_sample",
                 "rays/ping", "us/ping", "Mrays/s", "rms dB", "worst dB", "at/of");
    const double batch_s = quick ? 0.002 : 0.02;
    for (const sweep_point& p : sweep_points(quick)) {
        rows.push_back(measure<double, Maker>(name, p.sweep, p.density, rx, expected, batch_s));
        print_row(out, rows.back());
    }
    rows.push_back(measure<float, Maker>(name, "default", sss::ray_density{}, rx, expected, batch_s));
    print_row(out, rows.back());
    std::fflush(out);
}

void write_csv(const std::vector<row>& rows, const std::string& path) {
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp);
        if (!f) throw std::runtime_error("cannot write " + tmp);
        f << "scene,scalar,sweep,along,per_sample,rays_per_ping,us_per_ping,rms_db,worst_db,worst_sample,compared,"
             "is_default\n";
        for (const row& r : rows) {
            char line[512];
            std::snprintf(line, sizeof line, "\"%s\",%s,%s,%zu,%.6g,%zu,%.6g,%.6g,%.6g,%zu,%zu,%d\n", r.scene.c_str(),
                          r.scalar.c_str(), r.sweep.c_str(), r.density.along, r.density.per_sample, r.rays,
                          r.us_per_ping, r.error.rms_db, r.error.worst_db, r.error.worst_index, r.error.compared,
                          r.is_default ? 1 : 0);
            f << line;
        }
        if (!f.flush()) throw std::runtime_error("cannot write " + tmp);
    }
    std::filesystem::rename(tmp, path);
}

void run_table(const table_options& opt) {
    const bool quick = opt.table == table_options::mode::quick;
    std::FILE* out = opt.to_stderr ? stderr : stdout;
    std::fprintf(out, "\nSpeed against error%s: flat seabed z = 0, towfish 10 m up, 50 m/side, 20 kHz sampling,\n"
                      "Lambert -27 dB, 1500 m/s, 60 dB/km; starboard line vs the quadrature oracle, samples within\n"
                      "40 dB of its peak (at/of: the sample of the worst error / samples compared); us/ping: processor\n"
                      "time, best of 5 batches, one thread.\n",
                 quick ? " (quick: default scene, 3 densities)" : "");
    std::vector<row> rows;
    table_scene<default_fan>(rows, out, "default fan", "ideal fan 1 x 50 deg at 20 deg", 100e-6, quick);
    if (!quick) {
        table_scene<default_fan>(rows, out, "default fan, short pulse", "ideal fan 1 x 50 deg at 20 deg", 20e-6, quick);
        table_scene<nadir_fan>(rows, out, "nadir fan", "ideal fan 1 x 90 deg at 45 deg", 100e-6, quick);
        table_scene<nadir_fan>(rows, out, "nadir fan, short pulse", "ideal fan 1 x 90 deg at 45 deg", 20e-6, quick);
        const char* array_text =
            "planar array 300 kHz, 32 x 2 of 1.5 x 1.9 cm at 1.56 x 2.0 cm, tilt 15 deg, -30 dB extent";
        table_scene<array_300khz<-30>>(rows, out, "planar array", array_text, 100e-6, quick);
        table_scene<array_300khz<-30>>(rows, out, "planar array, short pulse", array_text, 20e-6, quick);
        // The same array with its extent taken down to -40 dB: more along-track sidelobes for the columns to resolve.
        table_scene<array_300khz<-40>>(rows, out, "planar array, -40 dB extent",
                                       "the same planar array, -40 dB extent", 100e-6, quick);
    }
    write_csv(rows, opt.csv_path);
    std::fprintf(out, "\nwrote %s\n", opt.csv_path.c_str());
}

/// Takes this benchmark's own flags out of argv and notes the benchmark flags that shape the table.
table_options parse_options(int& argc, char** argv) {
    table_options opt;
    if (const char* env = std::getenv("SSS_BENCH_CSV"); env && *env) opt.csv_path = env;
    bool forced = false;
    int kept = 1;
    for (int i = 1; i < argc; ++i) {
        const std::string_view a = argv[i];
        if (a == "--no-table") { opt.table = table_options::mode::none; forced = true; continue; }
        if (a == "--table-only") { opt.table_only = true; continue; }
        if (a == "--help") {
            std::printf("bench_pipeline: --no-table | --table=quick | --table=full | --table-only | --csv=PATH "
                        "(default $SSS_BENCH_CSV, else pipeline_speed_error.csv), then Google Benchmark's flags:\n");
        }
        if (a == "--benchmark_list_tests" || a == "--benchmark_list_tests=true") opt.table = table_options::mode::none;
        if (a == "--table=quick") { opt.table = table_options::mode::quick; forced = true; continue; }
        if (a == "--table=full") { opt.table = table_options::mode::full; forced = true; continue; }
        if (a.starts_with("--csv=")) { opt.csv_path = std::string(a.substr(6)); continue; }
        if (a.starts_with("--benchmark_min_time=") && !forced) {
            // 1.7 takes seconds ("0.01"); later versions also "0.01s" or an iteration count "10x".
            const std::string v(a.substr(21));
            const double s = std::strtod(v.c_str(), nullptr);
            if (v.ends_with('x') || s < 0.1) opt.table = table_options::mode::quick;
        }
        if (a.starts_with("--benchmark_format=") && a != "--benchmark_format=console") opt.to_stderr = true;
        argv[kept++] = argv[i];
    }
    argc = kept;
    argv[argc] = nullptr;
    return opt;
}

} // namespace

int main(int argc, char** argv) {
    const table_options opt = parse_options(argc, argv);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    if (!opt.table_only) benchmark::RunSpecifiedBenchmarks();
    int rc = 0;
    if (opt.table != table_options::mode::none) {
        try {
            run_table(opt);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "speed-against-error table failed: %s\n", e.what());
            rc = 1;
        }
    }
    benchmark::Shutdown();
    return rc;
}

// What a record's statistics cost on top of the mean power: seabed speckle, noise and volume reverberation.
//
// Benchmarks (Google Benchmark; counter pings/s), single thread, all float:
//   ping/mean         the default simulator (Lambert -27 dB, straight rays 1500 m/s, ideal fan 1 x 50 deg at 20 deg
//                     depression, straight line), flat seabed z = 0, towfish 10 m up, 50 m range per side, 20 kHz
//                     sampling (1334 samples per line), 100 us rectangular pulse, density {8, 0, 1}: no line stage.
//   ping/speckle      the same through sss::echo_statistics with Rayleigh speckle (transducer 0.5 m).
//   ping/speckle+noise  and sea-state 2 noise at 100 kHz.
//   ping/K+noise+volume K speckle (nu = 2, 1 m texture patches), noise and volume reverberation.
//   ping/hann speckle+noise  speckle and noise with a 100 us Hann pulse (cells summed one by one).
//   stage/...         the stage alone on one ping's two lines (the mean lines rendered once beforehand).
//   ping/chirp        ping/mean with a 10 ms LFM chirp of 20 kHz (a compressed envelope of 400 samples).
//   line/chirp direct, line/chirp Fourier  one line's render (time_sampler::render) of 26,667 samples (200 m at
//                     100 kHz) with a 20 ms LFM chirp of 40 kHz (4000 samples), deposits in every sub-bin: the direct
//                     sum over the pulse's taps against the transforms (render_method; render() takes the cheaper).
// The cost of speckle plus noise is ping/speckle+noise over ping/mean, less one.

#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

#include <sss/receiver/echo_statistics.hpp>
#include <sss/scene/flat_seabed.hpp>
#include <sss/simulator.hpp>

namespace {

using T = float;
using lambert = sss::scattering::lambertian<T>;
using straight = sss::propagation::straight<T>;
using fan = sss::beam::ideal_fan<T>;
using line_motion = sss::motion::straight_line<T>;

const sss::echo_statistics_params speckle_only{.speckle = sss::speckle_params{.transducer_length_m = 0.5}};
const sss::echo_statistics_params speckle_noise{.speckle = sss::speckle_params{.transducer_length_m = 0.5},
                                                .noise = sss::noise_params{}};
const sss::echo_statistics_params everything{.speckle = sss::speckle_params{.transducer_length_m = 0.5, .k_shape = 2.0},
                                             .noise = sss::noise_params{},
                                             .volume = sss::volume_params{}};

template <class Sim> void run_pings(benchmark::State& state, const Sim& sim, const char* what) {
    const sss::scene::flat_seabed<T> seabed(T(0));
    std::size_t index = 0;
    for (auto _ : state) {
        auto lines = sim.ping(seabed, index++);
        benchmark::DoNotOptimize(lines.port.data());
        benchmark::DoNotOptimize(lines.starboard.data());
        benchmark::ClobberMemory();
    }
    state.counters["pings/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["samples"] = double(sim.samples_per_line());
    state.SetLabel(what);
}

sss::receiver_params receiver(sss::pulse_shape shape = sss::pulse_shape::rectangular) {
    return sss::receiver_params{.pulse = sss::pulse{.length_s = 100e-6, .shape = shape}};
}

auto stat_simulator(const sss::echo_statistics_params& p, sss::pulse_shape shape = sss::pulse_shape::rectangular) {
    return sss::simulator<lambert, straight, fan, line_motion, sss::echo_statistics>(
        lambert{}, straight{}, fan{}, line_motion{}, receiver(shape), sss::ray_density{}, sss::echo_statistics(p));
}

void ping_mean(benchmark::State& state) {
    const sss::simulator<lambert, straight, fan, line_motion> sim(lambert{}, straight{}, fan{}, line_motion{}, receiver());
    run_pings(state, sim, "flat, 50 m/side, 100 us CW: mean power only");
}
BENCHMARK(ping_mean)->Name("ping/mean");

void ping_speckle(benchmark::State& state) { run_pings(state, stat_simulator(speckle_only), "Rayleigh speckle"); }
BENCHMARK(ping_speckle)->Name("ping/speckle");

void ping_speckle_noise(benchmark::State& state) { run_pings(state, stat_simulator(speckle_noise), "Rayleigh speckle + noise"); }
BENCHMARK(ping_speckle_noise)->Name("ping/speckle+noise");

void ping_everything(benchmark::State& state) { run_pings(state, stat_simulator(everything), "K speckle + noise + volume"); }
BENCHMARK(ping_everything)->Name("ping/K+noise+volume");

void ping_hann(benchmark::State& state) {
    run_pings(state, stat_simulator(speckle_noise, sss::pulse_shape::hann), "Hann pulse: speckle + noise");
}
BENCHMARK(ping_hann)->Name("ping/hann speckle+noise");

void ping_chirp(benchmark::State& state) {
    const sss::simulator<lambert, straight, fan, line_motion> sim(
        lambert{}, straight{}, fan{}, line_motion{},
        sss::receiver_params{.pulse = sss::pulse{.length_s = 10e-3, .shape = sss::pulse_shape::lfm, .bandwidth_hz = 20e3}});
    run_pings(state, sim, "flat, 50 m/side, 10 ms LFM chirp: mean power only");
}
BENCHMARK(ping_chirp)->Name("ping/chirp");

void line_chirp(benchmark::State& state, sss::render_method method) {
    const double dt = 1e-5;
    sss::time_sampler sampler(26667, dt, sss::pulse{.length_s = 20e-3, .shape = sss::pulse_shape::lfm, .bandwidth_hz = 40e3});
    for (std::size_t i = 0; i < 26667 * sss::time_sampler::sub_bins; ++i) {
        const double t = dt * (double(i) + 0.3) / double(sss::time_sampler::sub_bins);
        sampler.add_span(t, t + 0.05 * dt, 1.0 / (1.0 + double(i)));
    }
    std::vector<double> line;
    for (auto _ : state) {
        sampler.render(line, method);
        benchmark::DoNotOptimize(line.data());
        benchmark::ClobberMemory();
    }
    state.counters["lines/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
    state.counters["fourier_by_default"] = sampler.renders_by_fourier() ? 1.0 : 0.0;
}
BENCHMARK_CAPTURE(line_chirp, direct, sss::render_method::direct)->Name("line/chirp direct")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(line_chirp, fourier, sss::render_method::fourier)->Name("line/chirp Fourier")->Unit(benchmark::kMillisecond);

void stage_alone(benchmark::State& state, const sss::echo_statistics_params& p) {
    const auto sim = stat_simulator(p);
    const sss::simulator<lambert, straight, fan, line_motion> plain(lambert{}, straight{}, fan{}, line_motion{}, receiver());
    const sss::scene::flat_seabed<T> seabed(T(0));
    const auto mean = plain.ping(seabed, 0);
    std::size_t index = 0;
    for (auto _ : state) {
        const auto pose = sim.motion().pose_at(index++);
        for (sss::side sd : {sss::side::port, sss::side::starboard}) {
            std::vector<T> line = sd == sss::side::port ? mean.port : mean.starboard;
            sim.stage().process(line, sss::line_context<T>{.pose = pose, .line_side = sd, .dt_s = sim.dt_s(), .c_mps = 1500.0,
                                                           .altitude_m = 10.0, .pulse = sim.receiver().pulse});
            benchmark::DoNotOptimize(line.data());
        }
    }
    state.counters["pings/s"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK_CAPTURE(stage_alone, speckle + noise, speckle_noise)->Name("stage/speckle+noise");
BENCHMARK_CAPTURE(stage_alone, K + noise + volume, everything)->Name("stage/K+noise+volume");

} // namespace

BENCHMARK_MAIN();

// Cost of one seabed scattering evaluation: the APL-UW model evaluated directly and through its backscatter
// table, monostatic and bistatic, against Lambert's law. Medium sand (TR 9407 Table 2), 100 kHz, c = 1500 m/s;
// grazing angles swept over (0, 90] deg so that no single branch or cache line is favoured.

#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

#include <sss/scattering/jackson.hpp>
#include <sss/scattering/lambertian.hpp>

namespace {

using namespace sss::scattering;

constexpr std::size_t sweep_size = 4096;

template <class T> std::vector<T> grazing_sweep() {
    std::vector<T> g(sweep_size);
    // A stride coprime with the size visits the angles out of order.
    for (std::size_t i = 0; i < sweep_size; ++i) g[i] = T(sss::half_pi_v<double> * double((i * 1237) % sweep_size + 1) / double(sweep_size));
    return g;
}

const jackson_coefficients<double>& sand_coefficients() {
    static const auto c = make_jackson_coefficients(sediment_preset<double>(sediment::medium_sand), 100e3, 1500.0);
    return c;
}

void label(benchmark::State& state, const char* what) {
    state.SetLabel(what);
    state.SetItemsProcessed(state.iterations());
}

void jackson_backscatter_direct(benchmark::State& state) {
    const auto& c = sand_coefficients();
    const auto g = grazing_sweep<double>();
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(jackson_backscatter(c, g[i]));
        i = (i + 1) % sweep_size;
    }
    label(state, "direct TR 9407 model, coefficients precomputed, double");
}
BENCHMARK(jackson_backscatter_direct);

template <class T> void jackson_backscatter_tabulated(benchmark::State& state) {
    const jackson_backscatter_table<T> table(sand_coefficients());
    const auto g = grazing_sweep<T>();
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(table(g[i]));
        i = (i + 1) % sweep_size;
    }
    label(state, "table lookup (sqrt, lerp, exp)");
    state.counters["intervals"] = double(table.intervals());
}
BENCHMARK_TEMPLATE(jackson_backscatter_tabulated, float);
BENCHMARK_TEMPLATE(jackson_backscatter_tabulated, double);

void jackson_bistatic_direct(benchmark::State& state) {
    const auto& c = sand_coefficients();
    const auto g = grazing_sweep<double>();
    std::size_t i = 0;
    for (auto _ : state) {
        const double gs = g[(i + 611) % sweep_size];
        benchmark::DoNotOptimize(jackson_bistatic(c, g[i], gs, 0.25 + 0.001 * double(i % 2048)));
        i = (i + 1) % sweep_size;
    }
    label(state, "direct Williams & Jackson 1998 bistatic model, double");
}
BENCHMARK(jackson_bistatic_direct);

template <class T> void jackson_policy_backscatter(benchmark::State& state) {
    const jackson<T> s({.frequency_hz = T(100e3),
                        .sound_speed_mps = T(1500),
                        .materials = {sediment_preset<T>(sediment::medium_sand), sediment_preset<T>(sediment::clay)}});
    const auto g = grazing_sweep<T>();
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(s.backscatter(g[i], std::uint32_t(i & 1u)));
        i = (i + 1) % sweep_size;
    }
    label(state, "jackson<T>::backscatter, two materials alternating");
}
BENCHMARK_TEMPLATE(jackson_policy_backscatter, float);
BENCHMARK_TEMPLATE(jackson_policy_backscatter, double);

template <class T> void jackson_policy_bistatic(benchmark::State& state) {
    const jackson<T> s({.frequency_hz = T(100e3), .sound_speed_mps = T(1500), .materials = {sediment_preset<T>(sediment::medium_sand)}});
    const auto g = grazing_sweep<T>();
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(s.bistatic(g[i], g[(i + 611) % sweep_size], T(2), 0));
        i = (i + 1) % sweep_size;
    }
    label(state, "jackson<T>::bistatic (direct, evaluated in double)");
}
BENCHMARK_TEMPLATE(jackson_policy_bistatic, float);

void jackson_table_build(benchmark::State& state) {
    const auto& c = sand_coefficients();
    for (auto _ : state) benchmark::DoNotOptimize(jackson_backscatter_table<float>(c).intervals());
    label(state, "one material's table (coefficients precomputed), 0.01 dB midpoint tolerance");
}
BENCHMARK(jackson_table_build)->Unit(benchmark::kMillisecond);

void jackson_coefficients_setup(benchmark::State& state) {
    const auto p = sediment_preset<double>(sediment::medium_sand);
    for (auto _ : state) benchmark::DoNotOptimize(make_jackson_coefficients(p, 100e3, 1500.0));
    label(state, "per-material constants (Gamma functions, slope variance, ...)");
}
BENCHMARK(jackson_coefficients_setup);

template <class T> void lambertian_backscatter(benchmark::State& state) {
    const lambertian<T> s;
    const auto g = grazing_sweep<T>();
    std::size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(s.backscatter(g[i], 0));
        i = (i + 1) % sweep_size;
    }
    label(state, "Lambert's law, for scale");
}
BENCHMARK_TEMPLATE(lambertian_backscatter, float);

} // namespace

BENCHMARK_MAIN();

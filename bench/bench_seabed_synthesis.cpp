// Cost of seabed synthesis: a fractal surface by spectral synthesis (random coefficients + one inverse 2D FFT of
// their Hermitian half, in the surface's own storage) from 512^2 up to 4096^2 samples, the bare complex 2D FFT, a
// three-texture composite seabed with ripples, and two perturbed ripple sets on 4096^2 at 0.25 m (each set's crest
// displacement and height variation, two unit fractal fields drawn in step, each transformed in its own storage).
// Surface: APL-UW medium sand (TR 9407 Table 2: w2 = 0.004446 cm^4, gamma = 3.25), 5 cm cells, output float.

#include <benchmark/benchmark.h>

#include <complex>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <sss/seabed/composite.hpp>
#include <sss/seabed/fft.hpp>
#include <sss/seabed/fractal.hpp>
#include <sss/seabed/ripples.hpp>

namespace {

using namespace sss::seabed;

void fractal_surface_synthesis(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    fractal_params<float> p;
    p.spectrum = jackson_spectrum(0.004446f, 3.25f);
    std::uint64_t seed = 1;
    for (auto _ : state) {
        auto h = fractal_surface<float>(n, n, 0.05f, p, seed++);
        benchmark::DoNotOptimize(h.values.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n * n));
    state.SetLabel("isotropic medium sand, periodic, samples/s = surface samples");
}
BENCHMARK(fractal_surface_synthesis)->Arg(512)->Arg(1024)->Arg(2048)->Arg(4096)->Unit(benchmark::kMillisecond);

void fractal_surface_directional_oversampled(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    fractal_params<float> p;
    p.spectrum = jackson_spectrum(0.004446f, 3.25f);
    p.anisotropy = 3.0f;
    p.direction_rad = 0.5f;
    p.oversample = 2;
    std::uint64_t seed = 1;
    for (auto _ : state) {
        auto h = fractal_surface<float>(n, n, 0.05f, p, seed++);
        benchmark::DoNotOptimize(h.values.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n * n));
    state.SetLabel("anisotropy 3, synthesised on a 2x larger grid and cropped");
}
BENCHMARK(fractal_surface_directional_oversampled)->Arg(1024)->Unit(benchmark::kMillisecond);

void fft_2d_inverse(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    std::vector<std::complex<double>> data(n * n, std::complex<double>(1.0, 0.5));
    for (auto _ : state) {
        fft_2d(data, n, n, fft_direction::backward);
        benchmark::DoNotOptimize(data.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n * n));
    state.SetLabel(is_power_of_two(n) ? "complex double, radix 2" : "complex double, Bluestein");
}
BENCHMARK(fft_2d_inverse)->Arg(1024)->Arg(1000)->Arg(4096)->Unit(benchmark::kMillisecond);

void composite_seabed_synthesis(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    level_partition<float> part;
    part.fractions = {0.4f, 0.3f, 0.3f};
    part.patch_scale_m = 10.0f;
    std::vector<region_texture<float>> textures(3);
    textures[0].id = 1;
    textures[0].roughness.spectrum = jackson_spectrum(0.000518f, 3.25f); // clay
    textures[1].id = 2;
    textures[1].roughness.spectrum = jackson_spectrum(0.016f, 3.25f); // cobble / gravel
    textures[2].id = 3;
    textures[2].roughness.spectrum = jackson_spectrum(0.004446f, 3.25f); // medium sand with ripples
    ripple_params<float> rp;
    rp.wavelength_m = 0.6f;
    rp.height_m = 0.05f;
    rp.symmetry_index = 2.5f;
    rp.perturbation_m = 0.05f;
    textures[2].ripples.push_back(rp);
    std::uint64_t seed = 1;
    for (auto _ : state) {
        const auto idx = partition<float>(n, n, 0.05f, part, seed);
        auto c = compose(idx, textures, 0.2f, seed++);
        benchmark::DoNotOptimize(c.height.values.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n * n));
    state.SetLabel("clay / gravel / rippled sand, level partition, 0.2 m blend");
}
BENCHMARK(composite_seabed_synthesis)->Arg(1024)->Unit(benchmark::kMillisecond);

void ripple_field_synthesis(benchmark::State& state) {
    const auto n = static_cast<std::size_t>(state.range(0));
    const std::vector<ripple_params<float>> sets{
        {.wavelength_m = 0.9f, .height_m = 0.08f, .crest_heading_deg = 72.81f, .symmetry_index = 2.0f,
         .perturbation_m = 0.05f, .height_variation = 0.2f},
        {.wavelength_m = 6.0f, .height_m = 0.3f, .crest_heading_deg = 26.97f, .symmetry_index = 1.5f,
         .perturbation_m = 0.3f, .height_variation = 0.1f}};
    std::uint64_t seed = 1;
    for (auto _ : state) {
        auto h = ripple_field<float>(n, n, 0.25f, sets, seed++);
        benchmark::DoNotOptimize(h.values.data());
    }
    state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n * n));
    state.SetLabel("two perturbed ripple sets (0.9 m and 6 m), 0.25 m cells");
}
BENCHMARK(ripple_field_synthesis)->Arg(4096)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime();

} // namespace

BENCHMARK_MAIN();

// A render through the echo-statistics stage: the mean over seeds is the speckle-free render, the bytes depend on the
// seed only (not on threads or on how the pings are split), noise has the power the sonar equation gives, and the
// water column reverberates as the volume scattering formula says.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <sss/receiver/echo_statistics.hpp>
#include <sss/scene/cylinder.hpp>
#include <sss/scene/flat_seabed.hpp>
#include <sss/scene/object_set.hpp>
#include <sss/scene/scene.hpp>
#include <sss/simulator.hpp>

namespace {

using flat = sss::scene::flat_seabed<double>;
using lambert = sss::scattering::lambertian<double>;
using straight = sss::propagation::straight<double>;
using fan = sss::beam::ideal_fan<double>;
using line_motion = sss::motion::straight_line<double>;
using plain_sim = sss::simulator<lambert, straight, fan, line_motion>;
using stat_sim = sss::simulator<lambert, straight, fan, line_motion, sss::echo_statistics>;

line_motion motion_at(double altitude_m, double speed_mps = 2.0) {
    return line_motion(sss::motion::straight_line_params<double>{.speed_mps = speed_mps, .altitude_m = altitude_m});
}

stat_sim stat_simulator(const sss::echo_statistics_params& p, double altitude_m = 10.0, sss::receiver_params rx = {}) {
    return stat_sim(lambert{}, straight{}, fan{}, motion_at(altitude_m), rx, sss::ray_density{}, sss::echo_statistics(p));
}

/// The rendered volume reverberation of both sides against Urick's level in ten range bins (dB each):
/// SL - 40 log r - 2 alpha r + S_v + 10 log10(r^2 psi(r) c tau / 2), r of each sample (at least 1 m).
template <class Psi>
std::vector<double> volume_errors_db(const sss::waterfall<double>& w, double sl_db, double sv_db, double alpha_db_per_m,
                                     double tau_s, Psi&& psi_sr) {
    constexpr std::size_t bins = 10;
    const std::size_t per_bin = w.samples / bins;
    std::vector<double> errors;
    for (std::size_t b = 0; b < bins; ++b) {
        double got = 0.0, expected = 0.0;
        for (std::size_t k = b * per_bin; k < (b + 1) * per_bin; ++k) {
            const double r = std::max(1.0, 0.5 * 1500.0 * (double(k) + 0.5) * w.dt_s);
            const double rl_db = sl_db - 40.0 * std::log10(r) - 2.0 * alpha_db_per_m * r + sv_db +
                                 10.0 * std::log10(r * r * psi_sr(r) * 1500.0 * tau_s / 2.0);
            expected += std::pow(10.0, rl_db / 10.0) * 2.0 * double(w.pings); // both sides
            for (std::size_t i = 0; i < w.pings; ++i) got += w.at(i, w.samples + k) + w.at(i, w.samples - 1 - k);
        }
        errors.push_back(10.0 * std::log10(got / expected));
        MESSAGE("range bin " << b << ": " << errors.back() << " dB");
    }
    return errors;
}

} // namespace

TEST_CASE("the mean over 64 seeds is the speckle-free render: within 0.1 dB over the line, 4 standard errors per sample") {
    const flat seabed;
    const plain_sim plain(lambert{}, straight{}, fan{}, motion_at(10.0));
    const auto reference = plain.ping(seabed, 3).starboard;
    std::vector<double> sum(reference.size(), 0.0);
    constexpr int seeds = 64;
    for (int s = 0; s < seeds; ++s) {
        const auto line = stat_simulator(sss::echo_statistics_params{.seed = std::uint64_t(1000 + s)}).ping(seabed, 3).starboard;
        for (std::size_t k = 0; k < line.size(); ++k) sum[k] += line[k];
    }
    const double peak = *std::max_element(reference.begin(), reference.end());
    double ratio = 0.0;
    std::size_t counted = 0, outside = 0;
    double worst = 0.0;
    for (std::size_t k = 0; k < reference.size(); ++k) {
        if (!(reference[k] > 1e-6 * peak)) continue; // the seabed's samples
        const double mean = sum[k] / seeds;
        ratio += mean / reference[k];
        ++counted;
        // Exponential intensity: standard deviation = mean, so the standard error of 64 draws is mean / 8.
        const double z = (mean - reference[k]) / (reference[k] / std::sqrt(double(seeds)));
        worst = std::max(worst, std::abs(z));
        if (std::abs(z) > 4.0) ++outside;
    }
    REQUIRE(counted > 500);
    const double line_db = 10.0 * std::log10(ratio / double(counted));
    MESSAGE("mean over 64 seeds / speckle-free, over " << counted << " seabed samples: " << line_db << " dB");
    MESSAGE(outside << " samples beyond 4 standard errors, the worst at " << worst);
    CHECK(std::abs(line_db) < 0.1);
    // The mean of 64 exponential draws exceeds +4 standard errors with probability about 2e-4 (its skewness is
    // 1/4): among about 500 independent samples, 0.1 are expected beyond; more than 2 would be a 1-in-1000 event.
    CHECK(outside <= 2);
    CHECK(worst < 5.5);
}

TEST_CASE("same seed, same bytes on 1, 2 and 8 threads and for the pings rendered in two halves; another seed differs") {
    const flat seabed;
    const sss::echo_statistics_params params{.seed = 7,
                                             .speckle = sss::speckle_params{.k_shape = 2.0},
                                             .noise = sss::noise_params{.source_level_db = 190.0},
                                             .volume = sss::volume_params{}};
    const auto sim = stat_simulator(params);
    const auto one = sim.render(seabed, 0, 12, 1);
    CHECK(sim.render(seabed, 0, 12, 2).values == one.values);
    CHECK(sim.render(seabed, 0, 12, 8).values == one.values);
    const auto first = sim.render(seabed, 0, 5, 2), second = sim.render(seabed, 5, 7, 3);
    std::vector<double> joined(first.values);
    joined.insert(joined.end(), second.values.begin(), second.values.end());
    CHECK(joined == one.values);
    auto other = params;
    other.seed = 8;
    CHECK(stat_simulator(other).render(seabed, 0, 12, 2).values != one.values);
}

TEST_CASE("ambient noise levels: Knudsen's sea-state table falls 17 dB per decade, Mellen's thermal noise rises 20") {
    CHECK(sss::knudsen_noise_level_db(1000.0, 2.0) == doctest::Approx(61.5));
    CHECK(sss::knudsen_noise_level_db(10000.0, 2.0) == doctest::Approx(44.5));
    CHECK(sss::knudsen_noise_level_db(1000.0, 0.5) == doctest::Approx(50.0));
    CHECK(sss::knudsen_noise_level_db(1000.0, 2.5) == doctest::Approx(63.0)); // halfway between 61.5 and 64.5
    CHECK(sss::thermal_noise_level_db(100e3) == doctest::Approx(25.0));
    CHECK(sss::thermal_noise_level_db(1e6) == doctest::Approx(45.0));
    // A 1 m x 10 cm piston at 100 kHz (lambda 1.5 cm): 10 log10(4 pi 0.1 / 0.015^2) = 37.5 dB.
    CHECK(sss::piston_directivity_index_db(1.0, 0.1, 0.015) == doctest::Approx(37.47).epsilon(1e-3));
    // N = NL + 10 log10 B - DI - SL with NL the power sum of both.
    const sss::noise_params np{.frequency_hz = 100e3, .sea_state = 2.0, .directivity_index_db = 20.0, .source_level_db = 200.0};
    const double nl = 10.0 * std::log10(std::pow(10.0, 2.75) + std::pow(10.0, 2.5));
    CHECK(10.0 * std::log10(sss::noise_power(np, 5e-5)) == doctest::Approx(nl + 10.0 * std::log10(20000.0) - 220.0).epsilon(1e-9));
}

TEST_CASE("noise alone has mean power N, and a long record's far range converges to it") {
    const sss::noise_params np{.source_level_db = 180.0};
    const sss::echo_statistics_params params{.seed = 3, .noise = np};
    SUBCASE("no seabed in range") {
        const auto sim = stat_simulator(params, 200.0); // 50 m of range, the seabed 200 m below
        const double n = sim.stage().noise_power_per_sample(sim.dt_s(), 0.0);
        const auto w = sim.render(flat{}, 0, 20, 1);
        double mean = 0;
        for (double v : w.values) mean += v;
        mean /= double(w.values.size());
        MESSAGE("mean noise power " << mean << ", N " << n);
        CHECK(mean / n == doctest::Approx(1.0).epsilon(0.02));
    }
    SUBCASE("the seabed's echo sinks into the noise at far range") {
        const auto sim = stat_simulator(params, 10.0, sss::receiver_params{.max_range_m = 300.0});
        const double n = sim.stage().noise_power_per_sample(sim.dt_s(), 0.0);
        const auto w = sim.render(flat{}, 0, 8, 1);
        double far = 0, near = 0;
        std::size_t far_count = 0, near_count = 0;
        for (std::size_t i = 0; i < w.pings; ++i)
            for (std::size_t k = 0; k < w.samples; ++k) {
                const double v = w.at(i, w.samples + k);
                if (k > w.samples * 8 / 10) { far += v; ++far_count; }
                else if (k > w.samples / 10 && k < w.samples / 5) { near += v; ++near_count; }
            }
        far /= double(far_count);
        near /= double(near_count);
        MESSAGE("near range " << near / n << " N, far range " << far / n << " N");
        CHECK(near > 3.0 * n);
        CHECK(far / n == doctest::Approx(1.0).epsilon(0.03));
    }
}

TEST_CASE("under a compressed chirp the noise is the matched filter's, N0 / T rather than N0 / dt") {
    // A 2 ms chirp of 10 kHz (B T = 20) sampled at 20 kHz: T / dt = 40, the 16 dB by which its echoes' peaks stand
    // further out of the noise than a burst's of the same power.
    const sss::noise_params np{.source_level_db = 180.0};
    const sss::echo_statistics_params params{.seed = 4, .noise = np};
    sss::receiver_params rx;
    rx.pulse = sss::pulse{.length_s = 2e-3, .shape = sss::pulse_shape::lfm, .bandwidth_hz = 1e4};
    const auto sim = stat_simulator(params, 200.0, rx); // no seabed in range: noise alone
    const double burst_n = sim.stage().noise_power_per_sample(sim.dt_s(), 0.0);
    const double chirp_n = sim.stage().noise_power_per_sample(sim.dt_s(), 0.0, rx.pulse);
    CHECK(chirp_n / burst_n == doctest::Approx(sim.dt_s() / 2e-3).epsilon(1e-12));
    const auto w = sim.render(flat{}, 0, 20, 1);
    double mean = 0;
    for (double v : w.values) mean += v;
    mean /= double(w.values.size());
    MESSAGE("mean noise power under the chirp " << 10.0 * std::log10(mean / burst_n) << " dB against the burst's");
    CHECK(mean / chirp_n == doctest::Approx(1.0).epsilon(0.02));
}

TEST_CASE("volume reverberation follows SL - 40 log r - 2 alpha r + S_v + 10 log10(r^2 Psi c tau / 2) within 0.5 dB") {
    const sss::volume_params vp{.sv_db = -75.0, .psi_sr = 0.02, .absorption_db_per_m = 0.04};
    const sss::receiver_params rx{.source_level_db = 200.0};
    const auto sim = stat_simulator(sss::echo_statistics_params{.seed = 5, .speckle = std::nullopt, .volume = vp}, 200.0, rx);
    const auto w = sim.render(flat{}, 0, 40, 1);
    double sum_abs_db = 0.0;
    for (double e : volume_errors_db(w, 200.0, -75.0, 0.04, rx.pulse.length_s, [](double) { return 0.02; }))
        sum_abs_db += std::abs(e);
    CHECK(sum_abs_db / 10.0 < 0.5);
}

TEST_CASE("beyond the seabed's range the water reverberates only in the part of the beam above the seabed") {
    // A fan from 0 to 40 deg of depression, 10 m over a flat seabed of -300 dB: from 10 / sin(40 deg) = 15.6 m out
    // the seabed cuts the fan's lower part, and at range r only asin(10 / r) / 40 deg of it holds water (0.14 at
    // 100 m). Volume reverberation follows Urick's level with Psi times that share; before the seabed, all of Psi.
    const sss::volume_params vp{.sv_db = -60.0, .psi_sr = 0.0, .absorption_db_per_m = 0.02};
    const sss::receiver_params rx{.max_range_m = 100.0, .source_level_db = 200.0};
    const fan wedge({.along_width_deg = 2.0, .vertical_width_deg = 40.0, .depression_deg = 20.0});
    const stat_sim sim(lambert(-300.0), straight{}, wedge, motion_at(10.0), rx, sss::ray_density{},
                       sss::echo_statistics({.seed = 5, .speckle = std::nullopt, .volume = vp}));
    const double psi = 2.0 * std::sin(sss::pi_v<double> / 180.0) * 40.0 * sss::pi_v<double> / 180.0; // the fan's box
    const auto w = sim.render(flat{}, 0, 60, 1);
    const auto share = [](double r) { return r <= 10.0 ? 1.0 : std::min(1.0, std::asin(10.0 / r) / (40.0 * sss::pi_v<double> / 180.0)); };
    double worst_db = 0.0;
    for (double e : volume_errors_db(w, 200.0, -60.0, 0.02, rx.pulse.length_s, [&](double r) { return psi * share(r); }))
        worst_db = std::max(worst_db, std::abs(e));
    CHECK(worst_db < 0.5);
    // Psi = 0 takes the beam's own; without a beam (the stage alone), it is refused, naming the parameter.
    const sss::echo_statistics alone({.speckle = std::nullopt, .volume = vp});
    std::vector<double> line(100, 0.0);
    try {
        alone.process(line, sss::line_context<double>{.dt_s = 1e-4});
        FAIL("no exception");
    } catch (const sss::invalid_parameter& e) {
        CHECK(std::string(e.what()).find("volume.psi_sr") != std::string::npos);
    }
}

TEST_CASE("rendered over a flat seabed: <I^2>/<I>^2 = 2 (Rayleigh) and 2 (1 + 1/nu) (K, nu = 3) about the mean render") {
    const flat seabed;
    // Pings 1 m apart (twice the transducer's length): independent speckle from line to line.
    const line_motion fast(sss::motion::straight_line_params<double>{.speed_mps = 10.0, .altitude_m = 10.0});
    const plain_sim plain(lambert{}, straight{}, fan{}, fast);
    const auto mean = plain.ping(seabed, 0).starboard; // the same in every ping over a flat seabed
    const double peak = *std::max_element(mean.begin(), mean.end());
    for (double nu : {0.0, 3.0}) {
        const sss::echo_statistics_params params{.seed = 21, .speckle = sss::speckle_params{.k_shape = nu, .texture_patch_m = 0.05}};
        const stat_sim sim(lambert{}, straight{}, fan{}, fast, sss::receiver_params{}, sss::ray_density{}, sss::echo_statistics(params));
        const auto w = sim.render(seabed, 0, 150, 2);
        double m1 = 0, m2 = 0;
        std::size_t count = 0;
        for (std::size_t i = 0; i < w.pings; ++i)
            for (std::size_t k = 0; k < w.samples; ++k) {
                if (!(mean[k] > 1e-4 * peak)) continue;
                for (double v : {w.at(i, w.samples + k), w.at(i, w.samples - 1 - k)}) {
                    const double x = v / mean[k];
                    m1 += x;
                    m2 += x * x;
                    ++count;
                }
            }
        m1 /= double(count);
        m2 /= double(count);
        const double expected = nu > 0.0 ? 2.0 * (1.0 + 1.0 / nu) : 2.0;
        MESSAGE("nu " << nu << ": <I/mean> " << m1 << ", <I^2>/<I>^2 " << m2 / (m1 * m1) << " (expected " << expected << ") over " << count << " samples");
        CHECK(m1 == doctest::Approx(1.0).epsilon(0.02));
        CHECK(m2 / (m1 * m1) == doctest::Approx(expected).epsilon(nu > 0.0 ? 0.05 : 0.03));
    }
}

namespace {

// A stage that keeps the materials the simulator hands it and leaves the line alone.
struct material_probe {
    [[nodiscard]] bool needs_materials() const { return true; }
    std::vector<std::uint32_t>* seen = nullptr;
    template <class T> void process(std::vector<T>&, const sss::line_context<T>& ctx) const {
        if (ctx.line_side == sss::side::starboard) seen->assign(ctx.materials.begin(), ctx.materials.end());
    }
};

} // namespace

TEST_CASE("a stage that asks is told each sample's dominant material, and the mean line is unchanged") {
    using sss::scene::cylinder;
    using sss::scene::object;
    using sss::scene::object_set;
    std::vector<object<double>> objs{object<double>({}, {cylinder<double>({25.0, -5.0, 0.5}, {25.0, 5.0, 0.5}, 0.5, {.material = 3, .object = 1})})};
    const sss::scene::scene sc(flat(0.0, 1), object_set<double>(std::move(objs)));
    std::vector<std::uint32_t> seen;
    const sss::simulator<lambert, straight, fan, line_motion, material_probe> probed(
        lambert{}, straight{}, fan{}, motion_at(10.0), sss::receiver_params{}, sss::ray_density{}, material_probe{&seen});
    const plain_sim plain(lambert{}, straight{}, fan{}, motion_at(10.0));
    const auto line = probed.ping(sc, 0).starboard;
    CHECK(line == plain.ping(sc, 0).starboard);
    REQUIRE(seen.size() == line.size());
    // The cylinder's highlight (the peak beyond 20 m of range, sample 533) is material 3; the seabed before it 1.
    const auto peak = static_cast<std::size_t>(std::max_element(line.begin() + 533, line.end()) - line.begin());
    CHECK(seen[peak] == 3U);
    CHECK(seen[peak - 100] == 1U);
}

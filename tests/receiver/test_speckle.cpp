// Seabed speckle behaves as physics says: exponential intensity (Rayleigh amplitude) or K-distributed intensity of
// the chosen shape, the mean power unchanged, correlated across track as the pulse and along track as the
// transducer's co-array dictate, attached to the seabed (same place, same speckle) and to the seed only.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <sss/core/constants.hpp>
#include <sss/core/pose.hpp>
#include <sss/receiver/speckle.hpp>

namespace {

constexpr double c = 1500.0;
constexpr double dt = 5e-5;       // 20 kHz
constexpr std::size_t n = 2000;   // 75 m of slant range
constexpr double altitude = 10.0;

sss::line_context<double> context(double along_m, double tau_s, sss::pulse_shape shape = sss::pulse_shape::rectangular,
                                  sss::side sd = sss::side::starboard, double heading_deg = 0.0) {
    const double yaw = sss::deg_to_rad(heading_deg);
    const sss::vec3<double> pos{along_m * std::sin(yaw), along_m * std::cos(yaw), altitude};
    return sss::line_context<double>{.pose = sss::make_pose(0.0, pos, 0.0, 0.0, yaw), .line_side = sd, .dt_s = dt, .c_mps = c,
                                     .altitude_m = altitude, .pulse = sss::pulse{.length_s = tau_s, .shape = shape}};
}

// Normalised intensities I / mean of one line over a homogeneous seabed (mean 1 everywhere), first sample kept.
std::vector<double> intensities(const sss::seabed_speckle& sp, const sss::line_context<double>& ctx, std::size_t first = 400) {
    const std::vector<double> mean(n, 1.0);
    std::vector<std::complex<double>> z;
    sp.amplitudes(mean, ctx, z);
    std::vector<double> out;
    for (std::size_t k = first; k < n; ++k) out.push_back(std::norm(z[k]));
    return out;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
    double ma = 0, mb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) { ma += a[i]; mb += b[i]; }
    ma /= double(a.size());
    mb /= double(b.size());
    double sab = 0, saa = 0, sbb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    return sab / std::sqrt(saa * sbb);
}

// Independent lines: pings 1 m apart along track (beyond the transducer length 0.5 m).
std::vector<double> pooled(const sss::seabed_speckle& sp, std::size_t pings, double tau_s, std::size_t stride = 1) {
    std::vector<double> all;
    for (std::size_t i = 0; i < pings; ++i) {
        const auto line = intensities(sp, context(double(i) * 1.0, tau_s));
        for (std::size_t k = 0; k < line.size(); k += stride) all.push_back(line[k]);
    }
    return all;
}

} // namespace

TEST_CASE("fully developed speckle: <I^2>/<I>^2 = 2, <A^2>/<A>^2 = 4/pi and the mean power is kept") {
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5}, 11);
    const auto I = pooled(sp, 300, 1e-4);
    double m1 = 0, m2 = 0, a1 = 0;
    for (double v : I) { m1 += v; m2 += v * v; a1 += std::sqrt(v); }
    m1 /= double(I.size());
    m2 /= double(I.size());
    a1 /= double(I.size());
    CHECK(m1 == doctest::Approx(1.0).epsilon(0.01));
    CHECK(m2 / (m1 * m1) == doctest::Approx(2.0).epsilon(0.03));
    CHECK(m1 / (a1 * a1) == doctest::Approx(4.0 / sss::pi_v<double>).epsilon(0.01));
}

TEST_CASE("fully developed speckle: the intensity histogram passes a chi-square test against the exponential") {
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5}, 23);
    // Every 4th sample: 2 pulse lengths apart, so the draws are independent.
    const auto I = pooled(sp, 200, 1e-4, 4);
    constexpr std::size_t bins = 20; // equal probability under Exp(1): edges -ln(1 - i/bins)
    std::vector<double> count(bins, 0.0);
    for (double v : I) {
        const auto b = static_cast<std::size_t>(std::floor(double(bins) * (1.0 - std::exp(-v))));
        count[std::min(b, bins - 1)] += 1.0;
    }
    const double expected = double(I.size()) / double(bins);
    double chi2 = 0;
    for (double o : count) chi2 += (o - expected) * (o - expected) / expected;
    MESSAGE("chi-square " << chi2 << " over " << I.size() << " samples, 19 degrees of freedom");
    CHECK(chi2 < 43.8); // the 0.1% point of chi-square with 19 degrees of freedom
}

TEST_CASE("K-distributed speckle: <I^2>/<I>^2 = 2 (1 + 1/nu) for nu = 1, 3 and 10, mean kept") {
    for (double nu : {1.0, 3.0, 10.0}) {
        // Texture patches of 5 cm: many independent texture values per line.
        const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5, .k_shape = nu, .texture_patch_m = 0.05}, 5);
        const auto I = pooled(sp, 300, 1e-4);
        double m1 = 0, m2 = 0;
        for (double v : I) { m1 += v; m2 += v * v; }
        m1 /= double(I.size());
        m2 /= double(I.size());
        MESSAGE("nu " << nu << ": mean " << m1 << ", <I^2>/<I>^2 " << m2 / (m1 * m1) << " (expected " << 2.0 * (1.0 + 1.0 / nu) << ")");
        CHECK(m1 == doctest::Approx(1.0).epsilon(0.03));
        CHECK(m2 / (m1 * m1) == doctest::Approx(2.0 * (1.0 + 1.0 / nu)).epsilon(0.05));
    }
}

TEST_CASE("a scatterer density makes the K shape follow the resolution cell: spikier where cells are small") {
    // nu = density x range x beam width x ground extent of the pulse: the cell grows with range.
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5, .scatterer_density_per_m2 = 20.0,
                                                     .along_beamwidth_rad = 0.01, .texture_patch_m = 0.05}, 9);
    double near2 = 0, near1 = 0, far2 = 0, far1 = 0;
    for (std::size_t i = 0; i < 300; ++i) {
        const auto I = intensities(sp, context(double(i), 1e-4), 0);
        for (std::size_t k = 300; k < 500; ++k) { near1 += I[k]; near2 += I[k] * I[k]; }
        for (std::size_t k = 1800; k < 2000; ++k) { far1 += I[k]; far2 += I[k] * I[k]; }
    }
    const double near_ratio = near2 * 60000.0 / (near1 * near1), far_ratio = far2 * 60000.0 / (far1 * far1);
    MESSAGE("<I^2>/<I>^2 near " << near_ratio << ", far " << far_ratio);
    CHECK(near_ratio > far_ratio + 0.3);
    CHECK(far_ratio > 2.0);
}

TEST_CASE("a pulse's counting extent (int p)^2 / int p^2: a burst's length, 18/35 of a Hann burst's, about 1.5/B for a chirp") {
    CHECK(sss::counting_extent_s(sss::pulse{.length_s = 1e-4}, 0.0, 1e-4) == doctest::Approx(1e-4).epsilon(1e-12));
    // int sin^4 = 3/8 L, int sin^8 = 35/128 L: (3/8)^2 / (35/128) = 18/35.
    const sss::pulse hann{.length_s = 1e-4, .shape = sss::pulse_shape::hann};
    CHECK(sss::counting_extent_s(hann, 0.0, 1e-4) / 1e-4 == doctest::Approx(18.0 / 35.0).epsilon(1e-9));
    // A compressed chirp of large B T is sinc^2(B t): int sinc^2 = 1/B, int sinc^4 = 2/(3B), so 1.5/B.
    const sss::pulse chirp{.length_s = 2e-2, .shape = sss::pulse_shape::lfm, .bandwidth_hz = 1e4};
    const double extent = sss::counting_extent_s(chirp, chirp.length_s - 8e-4, chirp.length_s + 8e-4);
    MESSAGE("chirp: " << extent * 1e4 << " / B over its main lobe and 8 sidelobes each side");
    CHECK(extent * 1e4 == doctest::Approx(1.5).epsilon(0.03));
}

TEST_CASE("with a scatterer density, a Hann burst's and a chirp's K shape are a rectangular burst's of their counting extent") {
    // About 71 m out: nu = 20 x (71 m x 0.01) x (c t_N / 2) = 1.1 for t_N = 0.1 ms: <I^2>/<I>^2 = 3.9. A 1 ms chirp of
    // 10 kHz and a Hann burst of 0.1 ms / (18/35) count as a 0.1 ms rectangular burst does, though the chirp's window
    // holds 8 sidelobes each side and the Hann burst's is twice as long.
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5, .scatterer_density_per_m2 = 20.0,
                                                     .along_beamwidth_rad = 0.01, .texture_patch_m = 0.05}, 4);
    const auto ratio = [&](const sss::pulse& p) {
        double s1 = 0, s2 = 0;
        for (std::size_t i = 0; i < 300; ++i) {
            auto ctx = context(double(i), p.length_s);
            ctx.pulse = p;
            const auto I = intensities(sp, ctx, 0);
            for (std::size_t k = 1800; k < 2000; ++k) { s1 += I[k]; s2 += I[k] * I[k]; }
        }
        return s2 * 60000.0 / (s1 * s1);
    };
    const sss::pulse chirp{.length_s = 1e-3, .shape = sss::pulse_shape::lfm, .bandwidth_hz = 1e4};
    const double t_n = sss::counting_extent_s(chirp, chirp.length_s - 8e-4, chirp.length_s + 8e-4);
    const double burst = ratio(sss::pulse{.length_s = t_n});
    const double compressed = ratio(chirp);
    const double hann = ratio(sss::pulse{.length_s = 1e-4 * 35.0 / 18.0, .shape = sss::pulse_shape::hann});
    const double rect = ratio(sss::pulse{.length_s = 1e-4});
    MESSAGE("<I^2>/<I>^2: burst of the chirp's extent " << burst << ", chirp " << compressed << "; burst " << rect
            << ", Hann burst of the same extent " << hann);
    CHECK(rect > 3.0);
    CHECK(std::abs(compressed - burst) < 0.1 * burst);
    CHECK(std::abs(hann - rect) < 0.1 * rect);
}

TEST_CASE("adjacent samples correlate as the pulse's |rho_a(dt)|^2: rectangular 4 samples long gives (3/4)^2") {
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5}, 3);
    for (auto shape : {sss::pulse_shape::rectangular, sss::pulse_shape::hann}) {
        const double tau = 4.0 * dt;
        // rho_a(dt) of the amplitude envelope sqrt(p): by quadrature.
        double num = 0, den = 0;
        const sss::pulse p{.length_s = tau, .shape = shape};
        for (int i = 0; i < 100000; ++i) {
            const double t = (i + 0.5) * tau / 100000;
            num += std::sqrt(p.power(t) * p.power(t + dt));
            den += p.power(t);
        }
        const double expected = (num / den) * (num / den);
        std::vector<double> a, b;
        for (std::size_t i = 0; i < 200; ++i) {
            const auto I = intensities(sp, context(double(i), tau, shape), 1000);
            for (std::size_t k = 0; k + 1 < I.size(); ++k) { a.push_back(I[k]); b.push_back(I[k + 1]); }
        }
        const double r = correlation(a, b);
        MESSAGE(std::string(shape == sss::pulse_shape::rectangular ? "rectangular" : "Hann") << ": adjacent-sample intensity correlation "
                << r << ", |rho_a(dt)|^2 = " << expected);
        CHECK(std::abs(r - expected) < 0.05);
    }
}

TEST_CASE("ping-to-ping correlation follows the co-array overlap and vanishes once the advance reaches the length") {
    const double L = 0.5;
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = L}, 17);
    for (double d : {0.03, 0.1, 0.2, 0.3, 0.4, 0.5, 0.75}) {
        std::vector<double> a, b;
        for (std::size_t i = 0; i < 60; ++i) {
            const double y0 = 3.0 * double(i) + 0.37 * double(i % 7) / 7.0; // independent pairs, varied offsets
            const auto I0 = intensities(sp, context(y0, 1e-4)), I1 = intensities(sp, context(y0 + d, 1e-4));
            a.insert(a.end(), I0.begin(), I0.end());
            b.insert(b.end(), I1.begin(), I1.end());
        }
        const double r_field = std::sqrt(std::max(0.0, correlation(a, b)));
        const double expected = sss::coarray_overlap(d, L);
        MESSAGE("d = " << d << " m: field correlation " << r_field << ", co-array overlap " << expected);
        CHECK(std::abs(r_field - expected) < 0.1);
        if (d >= L) CHECK(r_field < 0.1);
    }
}

TEST_CASE("in the water column, before the first return, speckle correlates along track as the co-array's overlap says") {
    // Echo power only in samples 50 to 249, all before the seabed's first return (sample 266 from 10 m up): no
    // seabed cell lies in their windows. Before, they were keyed by L/3 bins: the same within one, independent
    // across a boundary (correlation 1 or 0 instead of the overlap).
    const double L = 0.5;
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = L}, 23);
    std::vector<double> mean(n, 0.0);
    for (std::size_t k = 50; k < 250; ++k) mean[k] = 1.0;
    std::vector<std::complex<double>> z;
    const auto water_column = [&](double along_m) {
        sp.amplitudes(mean, context(along_m, 1e-4), z);
        std::vector<double> out;
        for (std::size_t k = 50; k < 250; ++k) out.push_back(std::norm(z[k]));
        return out;
    };
    for (double d : {0.03, 0.1, 0.2, 0.3, 0.5, 0.75}) {
        std::vector<double> a, b;
        for (std::size_t i = 0; i < 80; ++i) {
            const double y0 = 3.0 * double(i) + 0.37 * double(i % 7) / 7.0;
            const auto I0 = water_column(y0), I1 = water_column(y0 + d);
            a.insert(a.end(), I0.begin(), I0.end());
            b.insert(b.end(), I1.begin(), I1.end());
        }
        // Intensities of a circular Gaussian field correlate as the field's correlation squared.
        const double r = correlation(a, b);
        const double expected = sss::coarray_overlap(d, L);
        MESSAGE("d = " << d << " m: intensity correlation " << r << ", co-array overlap squared " << expected * expected);
        CHECK(std::abs(r - expected * expected) < 0.04);
    }
    // Its mean power is the mean's.
    const auto I = water_column(1.0);
    double m = 0;
    for (double v : I) m += v;
    CHECK(m / double(I.size()) == doctest::Approx(1.0).epsilon(0.3));
}

TEST_CASE("in the water column speckle correlates across track as the pulse says and belongs to a place across track") {
    // Samples 50 to 249 again, with a rectangular pulse 4 samples long: adjacent samples correlate as (3/4)^2, as the
    // seabed's do; a line 7.3 m to starboard of it, at the same place along track, sees other scatterers (before,
    // every line saw the same there).
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5}, 29);
    std::vector<double> mean(n, 0.0);
    for (std::size_t k = 50; k < 250; ++k) mean[k] = 1.0;
    std::vector<std::complex<double>> z;
    const auto water_column = [&](double along_m, double across_m) {
        auto ctx = context(along_m, 4.0 * dt);
        ctx.pose.position.x += across_m;
        sp.amplitudes(mean, ctx, z);
        std::vector<double> out;
        for (std::size_t k = 50; k < 250; ++k) out.push_back(std::norm(z[k]));
        return out;
    };
    std::vector<double> a, b, here, beside;
    for (std::size_t i = 0; i < 100; ++i) {
        const auto I = water_column(1.3 * double(i), 0.0), J = water_column(1.3 * double(i), 7.3);
        a.insert(a.end(), I.begin(), I.end() - 1);
        b.insert(b.end(), I.begin() + 1, I.end());
        here.insert(here.end(), I.begin(), I.end());
        beside.insert(beside.end(), J.begin(), J.end());
    }
    const double adjacent = correlation(a, b), across = correlation(here, beside);
    MESSAGE("adjacent samples " << adjacent << " (0.5625), lines 7.3 m apart " << across);
    CHECK(std::abs(adjacent - 0.5625) < 0.05);
    CHECK(std::abs(across) < 0.05);
}

TEST_CASE("speckle belongs to the seabed: same place and seed, same speckle; another seed or aspect, other speckle") {
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5}, 42);
    const sss::seabed_speckle other(sss::speckle_params{.transducer_length_m = 0.5}, 43);
    auto ctx = context(12.3, 1e-4);
    const auto first = intensities(sp, ctx);
    ctx.pose.time_s = 3600.0; // a second pass, an hour later, over the same ground
    CHECK(intensities(sp, ctx) == first);
    CHECK(correlation(intensities(other, ctx), first) < 0.05);
    // The same ground seen on the reverse heading, from the port side: another aspect, other speckle.
    auto back = context(-12.3, 1e-4, sss::pulse_shape::rectangular, sss::side::port, 180.0);
    CHECK(correlation(intensities(sp, back), first) < 0.05);
    // A ping from the same place heading 0.1 degree off the lattice's heading still sees nearly the same speckle
    // within 30 m (where its co-array has turned by less than a tenth of its length).
    auto slanted_ctx = context(12.3, 1e-4);
    slanted_ctx.pose = sss::make_pose(0.0, slanted_ctx.pose.position, 0.0, 0.0, sss::deg_to_rad(0.1));
    const auto slanted = intensities(sp, slanted_ctx);
    const std::vector<double> near_a(first.begin(), first.begin() + 400), near_b(slanted.begin(), slanted.begin() + 400);
    CHECK(correlation(near_a, near_b) > 0.8);
}

TEST_CASE("survey time decorrelates speckle slowly: nearly the same after a tenth of the time, renewed after it") {
    auto params = [](double t) {
        return sss::speckle_params{.transducer_length_m = 0.5, .survey_time_s = t, .decorrelation_time_s = 86400.0};
    };
    const auto ctx = context(5.0, 1e-4);
    const auto now = intensities(sss::seabed_speckle(params(1000.0), 8), ctx);
    const auto soon = intensities(sss::seabed_speckle(params(1000.0 + 8640.0), 8), ctx);
    const auto later = intensities(sss::seabed_speckle(params(1000.0 + 2.0 * 86400.0), 8), ctx);
    // Field correlation cos(pi/2 x 0.1) = 0.988: intensity correlation 0.976.
    CHECK(correlation(now, soon) > 0.9);
    CHECK(std::abs(correlation(now, later)) < 0.05);
}

TEST_CASE("survey time decorrelates speckle alike wherever in an epoch a lag starts: rho(s) = (1 - s/2) cos(pi s/2) + sin(pi s/2)/pi") {
    CHECK(sss::drift_correlation(0.0) == doctest::Approx(1.0));
    CHECK(sss::drift_correlation(1.0) == doctest::Approx(1.0 / sss::pi_v<double>));
    CHECK(sss::drift_correlation(2.0) == 0.0);
    constexpr double day = 86400.0;
    const auto at = [&](double epochs) { // four lines 1 m apart
        const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5, .survey_time_s = epochs * day,
                                                         .decorrelation_time_s = day}, 8);
        std::vector<double> all;
        for (double along_m : {5.0, 6.0, 7.0, 8.0}) {
            const auto I = intensities(sp, context(along_m, 1e-4), 0);
            all.insert(all.end(), I.begin(), I.end());
        }
        return all;
    };
    // One phase for the whole seabed gave 0.50 for a half-epoch lag from the start of an epoch and 0.73 from its
    // third quarter; each cell's own phase gives rho(1/2)^2 = 0.571 from anywhere.
    for (double lag : {0.25, 0.5, 1.0, 1.5}) {
        const double expected = sss::drift_correlation(lag) * sss::drift_correlation(lag);
        for (double start : {3.0, 3.25, 3.5, 3.75}) {
            const double r = correlation(at(start), at(start + lag));
            MESSAGE("lag " << lag << " epochs from " << start << ": intensity correlation " << r << ", rho^2 " << expected);
            CHECK(std::abs(r - expected) < 0.03);
        }
    }
}

TEST_CASE("a K shape per material: each material's samples follow their own <I^2>/<I>^2") {
    // Material 0 (the near half of the line) fully developed, material 1 (the far half) K with nu = 1.
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5, .k_shape_by_material = {0.0, 1.0},
                                                     .texture_patch_m = 0.05}, 31);
    std::vector<std::uint32_t> materials(n, 0);
    std::fill(materials.begin() + n / 2 + 100, materials.end(), 1U);
    double m1[2] = {0, 0}, m2[2] = {0, 0}, count[2] = {0, 0};
    for (std::size_t i = 0; i < 300; ++i) {
        auto ctx = context(double(i), 1e-4);
        ctx.materials = materials;
        const auto I = intensities(sp, ctx, 0);
        for (std::size_t k = 400; k < n; ++k) {
            if (k > n / 2 && k < n / 2 + 200) continue; // leave the boundary's mixed windows out
            const std::size_t m = materials[k];
            m1[m] += I[k];
            m2[m] += I[k] * I[k];
            count[m] += 1.0;
        }
    }
    const double ratio0 = m2[0] * count[0] / (m1[0] * m1[0]), ratio1 = m2[1] * count[1] / (m1[1] * m1[1]);
    MESSAGE("material 0: " << ratio0 << " (2), material 1: " << ratio1 << " (4)");
    CHECK(ratio0 == doctest::Approx(2.0).epsilon(0.03));
    CHECK(ratio1 == doctest::Approx(4.0).epsilon(0.05));
}

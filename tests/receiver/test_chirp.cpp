// A linear FM chirp compressed by its matched filter: range resolution c / (2B) whatever its length, energy kept
// through the time sampler, and speckle correlated as the compressed pulse's autocorrelation says.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <numeric>
#include <vector>

#include <sss/core/pose.hpp>
#include <sss/receiver/speckle.hpp>
#include <sss/receiver/time_sampler.hpp>

namespace {

constexpr double bandwidth = 20e3; // 20 kHz: c / (2B) = 3.75 cm
constexpr double length = 1e-3;    // 1 ms: a CW pulse this long resolves 75 cm
constexpr double dt = 1.0 / (8.0 * bandwidth);

// Local maxima and the deepest dip between the first two (dB below the lower of them); 0 if fewer than two.
double dip_db(const std::vector<double>& y) {
    std::vector<std::size_t> peaks;
    const double top = *std::max_element(y.begin(), y.end());
    for (std::size_t k = 1; k + 1 < y.size(); ++k)
        if (y[k] > 0.5 * top && y[k] >= y[k - 1] && y[k] > y[k + 1]) peaks.push_back(k);
    if (peaks.size() < 2) return 0.0;
    const double low = *std::min_element(y.begin() + std::ptrdiff_t(peaks[0]), y.begin() + std::ptrdiff_t(peaks[1]));
    return 10.0 * std::log10(std::min(y[peaks[0]], y[peaks[1]]) / low);
}

std::vector<double> two_points(const sss::pulse& p, double separation_s) {
    sss::time_sampler s(1200, dt, p);
    s.add_point(0.002, 1.0);
    s.add_point(0.002 + separation_s, 1.0);
    std::vector<double> y;
    s.render(y);
    return y;
}

} // namespace

TEST_CASE("a chirp resolves two point targets c/(2B) apart that a CW pulse of the same length does not") {
    const sss::pulse chirp{.length_s = length, .shape = sss::pulse_shape::lfm, .bandwidth_hz = bandwidth};
    const sss::pulse cw{.length_s = length};
    // c / (2B) apart in range is 1/B apart in two-way time.
    const double chirp_dip = dip_db(two_points(chirp, 1.0 / bandwidth));
    const double cw_dip = dip_db(two_points(cw, 1.0 / bandwidth));
    MESSAGE("dip between the two echoes: chirp " << chirp_dip << " dB, CW " << cw_dip << " dB");
    CHECK(chirp_dip > 0.5); // the sum of two sinc^2 a main-lobe half-width apart dips about 0.9 dB
    CHECK(cw_dip < 1e-9); // one plateau: flat to rounding (the Fourier path, which this 160-sample pulse takes,
                          // ripples it by about 1e-15 dB)
    // Half as far apart, the chirp does not resolve them either.
    CHECK(dip_db(two_points(chirp, 0.5 / bandwidth)) == 0.0);
}

TEST_CASE("a compressed chirp's echo peaks at its arrival, also within T of the transmission or past the line's end") {
    const sss::pulse chirp{.length_s = length, .shape = sss::pulse_shape::lfm, .bandwidth_hz = bandwidth};
    CHECK(chirp.filter_delay_s() == length);
    CHECK(chirp.peak_delay_s() == 0.0);
    const auto peak_of = [&](double arrival_s, std::vector<double>& y) {
        sss::time_sampler s(1200, dt, chirp);
        s.add_point(arrival_s, 1.0);
        s.render(y);
        return static_cast<std::size_t>(std::max_element(y.begin(), y.end()) - y.begin());
    };
    std::vector<double> y;
    // Arrival at 2 ms: sample 320 starts there; the main lobe is centred on that sample's start.
    std::size_t k = peak_of(0.002 + 0.5 * dt, y);
    CHECK(k == 320);
    const double in_line_peak = y[k];
    // At 0.5 ms, before the filter's delay has passed: the echo is in the line, and peaks at its arrival (sample 80).
    k = peak_of(0.0005 + 0.5 * dt, y);
    CHECK(k == 80);
    // All its energy but the sidelobes more than 0.5 ms before the peak (0.2 %).
    CHECK(std::accumulate(y.begin(), y.end(), 0.0) * dt / chirp.energy_s() == doctest::Approx(1.0).epsilon(5e-3));
    // A quarter of a main lobe (two samples) past the line's end at 1200 dt: the lobe's leading side is in the last
    // samples, sinc^2(1/4) = 0.81 of the peak at two samples from it.
    k = peak_of(1200 * dt + 0.25 / bandwidth, y);
    CHECK(k == 1199);
    CHECK(y[1199] > 0.6 * in_line_peak);
}

TEST_CASE("the compressed chirp's energy is about 1/B and the time sampler conserves it") {
    const sss::pulse chirp{.length_s = length, .shape = sss::pulse_shape::lfm, .bandwidth_hz = bandwidth};
    // int sinc^2(B s) ds = 1/B; the autocorrelation's taper (1 - |s|/T) takes about 1/(B T) of it... within 5%.
    CHECK(chirp.energy_s() * bandwidth == doctest::Approx(1.0).epsilon(0.05));
    CHECK(chirp.power(length) == doctest::Approx(1.0));
    // First null where B s (1 - s/T) = 1: about 1/B from the peak.
    const double null_s = 0.5 * length * (1.0 - std::sqrt(1.0 - 4.0 / (bandwidth * length)));
    CHECK(chirp.power(length + null_s) < 1e-12);
    CHECK(null_s * bandwidth == doctest::Approx(1.0).epsilon(0.06));
    sss::time_sampler s(1200, dt, chirp);
    s.add_span(0.0021, 0.0023, 2.0);
    s.add_point(0.0031, 1.0);
    std::vector<double> y;
    s.render(y);
    const double total = std::accumulate(y.begin(), y.end(), 0.0) * dt;
    CHECK(total / (3.0 * chirp.energy_s()) == doctest::Approx(1.0).epsilon(1e-3));
}

TEST_CASE("speckle under a chirp: adjacent samples correlate as the compressed pulse's |rho_a(dt)|^2") {
    const sss::pulse chirp{.length_s = length, .shape = sss::pulse_shape::lfm, .bandwidth_hz = bandwidth};
    const double sample = 0.5 / bandwidth; // two samples per resolution cell
    double num = 0, den = 0;
    for (int i = 0; i < 200000; ++i) {
        const double t = (i + 0.5) * 2.0 * length / 200000;
        num += chirp.amplitude(t) * chirp.amplitude(t + sample);
        den += chirp.amplitude(t) * chirp.amplitude(t);
    }
    const double expected = (num / den) * (num / den);
    const sss::seabed_speckle sp(sss::speckle_params{.transducer_length_m = 0.5}, 2);
    std::vector<double> a, b;
    const std::vector<double> mean(4000, 1.0);
    std::vector<std::complex<double>> z;
    for (int i = 0; i < 40; ++i) {
        const sss::line_context<double> ctx{.pose = sss::make_pose(0.0, sss::vec3<double>{0.0, double(i), 10.0}, 0.0, 0.0, 0.0),
                                            .line_side = sss::side::starboard, .dt_s = sample, .c_mps = 1500.0,
                                            .altitude_m = 10.0, .pulse = chirp};
        sp.amplitudes(mean, ctx, z);
        for (std::size_t k = 2000; k + 1 < z.size(); ++k) { a.push_back(std::norm(z[k])); b.push_back(std::norm(z[k + 1])); }
    }
    const double ma = std::accumulate(a.begin(), a.end(), 0.0) / double(a.size());
    const double mb = std::accumulate(b.begin(), b.end(), 0.0) / double(b.size());
    double sab = 0, saa = 0, sbb = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
        sab += (a[i] - ma) * (b[i] - mb);
        saa += (a[i] - ma) * (a[i] - ma);
        sbb += (b[i] - mb) * (b[i] - mb);
    }
    const double r = sab / std::sqrt(saa * sbb);
    MESSAGE("adjacent-sample intensity correlation " << r << ", |rho_a|^2 of the compressed chirp " << expected);
    CHECK(std::abs(r - expected) < 0.05);
    CHECK(ma == doctest::Approx(1.0).epsilon(0.03));
}

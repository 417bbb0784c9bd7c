// The time sampler resamples echo energy without distortion: energy is conserved, a pulse lasting whole samples is
// reproduced exactly for any arrival, and the result equals the direct convolution of the echo density with the pulse.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include <sss/receiver/time_sampler.hpp>

namespace {

// Mean power in [t0, t1) of an echo of power P arriving at delay s, with envelope power p: by fine midpoint integration.
double direct_mean(const sss::pulse& p, double P, double s, double t0, double t1, int steps = 20000) {
    double acc = 0;
    const double h = (t1 - t0) / steps;
    for (int i = 0; i < steps; ++i) acc += p.power(t0 + (i + 0.5) * h - s);
    return P * acc * h / (t1 - t0);
}

} // namespace

TEST_CASE("pulse envelopes: rectangular energy equals its length, Hann (sin^4) energy is 3/8 of it") {
    const sss::pulse rect{1e-4, sss::pulse_shape::rectangular};
    const sss::pulse hann{1e-4, sss::pulse_shape::hann};
    CHECK(rect.energy_s() == doctest::Approx(1e-4).epsilon(1e-12));
    CHECK(hann.energy_s() == doctest::Approx(0.375e-4).epsilon(1e-12));
    // The cumulative is the integral of the power envelope.
    double acc = 0;
    const int n = 100000;
    for (int i = 0; i < n; ++i) acc += hann.power((i + 0.5) * 0.6e-4 / n) * 0.6e-4 / n;
    CHECK(hann.cumulative(0.6e-4) == doctest::Approx(acc).epsilon(1e-8));
}

TEST_CASE("kernel taps sum to the pulse energy in samples and the first-moment taps to zero") {
    for (double tau : {0.3e-4, 1e-4, 2.5e-4, 7e-4})
        for (auto shape : {sss::pulse_shape::rectangular, sss::pulse_shape::hann}) {
            const sss::pulse p{tau, shape};
            const sss::time_sampler s(100, 1e-4, p);
            const double k0 = std::accumulate(s.kernel0().begin(), s.kernel0().end(), 0.0);
            const double k1 = std::accumulate(s.kernel1().begin(), s.kernel1().end(), 0.0);
            CHECK(k0 == doctest::Approx(double(sss::time_sampler::sub_bins) * p.energy_s() / 1e-4).epsilon(1e-12));
            CHECK(std::abs(k1) < 1e-12);
        }
}

TEST_CASE("energy is conserved: sum of mean powers x dt equals deposited power x pulse energy") {
    const double dt = 1e-4;
    for (auto shape : {sss::pulse_shape::rectangular, sss::pulse_shape::hann}) {
        const sss::pulse p{2.7e-4, shape};
        sss::time_sampler s(400, dt, p);
        double deposited = 0;
        for (int i = 0; i < 200; ++i) {
            const double t0 = 0.001 + 0.000137 * i, t1 = t0 + 0.00003 * (i % 7);
            const double P = 1.0 + 0.01 * i;
            s.add_span(t0, t1, P);
            deposited += P;
        }
        s.add_point(0.02, 3.0);
        deposited += 3.0;
        std::vector<double> y;
        s.render(y);
        const double total = std::accumulate(y.begin(), y.end(), 0.0) * dt;
        CHECK(total == doctest::Approx(deposited * p.energy_s()).epsilon(1e-12).scale(0));
    }
}

TEST_CASE("a point echo with a pulse of whole samples is reproduced exactly wherever it arrives") {
    const double dt = 1e-4;
    const sss::pulse p{3e-4, sss::pulse_shape::rectangular};
    for (double s_arrival : {0.01, 0.01 + 0.3e-4, 0.01 + 0.77e-4, 0.01234567}) {
        sss::time_sampler s(200, dt, p);
        s.add_point(s_arrival, 2.0);
        std::vector<double> y;
        s.render(y);
        for (std::size_t k = 95; k < 130; ++k)
            CHECK(y[k] == doctest::Approx(direct_mean(p, 2.0, s_arrival, double(k) * dt, double(k + 1) * dt)).epsilon(1e-4).scale(1e-6));
    }
}

TEST_CASE("a step in the echo density, convolved with a Hann pulse, is resolved within 0.5% of the peak") {
    const double dt = 1e-4;
    const sss::pulse p{1.7e-4, sss::pulse_shape::hann}; // not a whole number of samples: the sub-bin model is approximate
    sss::time_sampler s(100, dt, p);
    // A span covering the middle 60% of one sample: two steps inside one sample.
    const double a = 0.00312, b = 0.00318, P = 5.0;
    s.add_span(a, b, P);
    std::vector<double> y;
    s.render(y);
    double peak = 0, worst = 0;
    for (std::size_t k = 29; k < 37; ++k) {
        double exact = 0;
        const int n = 400;
        for (int i = 0; i < n; ++i) exact += direct_mean(p, P / n, a + (i + 0.5) * (b - a) / n, double(k) * dt, double(k + 1) * dt, 4000);
        peak = std::max(peak, exact);
        worst = std::max(worst, std::abs(y[k] - exact));
    }
    INFO("worst error " << worst << " of peak " << peak);
    CHECK(worst <= 0.005 * peak);
}

TEST_CASE("echoes beyond the line's end and before time zero are dropped, never wrapped") {
    sss::time_sampler s(10, 1e-4, sss::pulse{1e-4, sss::pulse_shape::rectangular});
    s.add_point(5e-3, 1.0);
    s.add_point(-1e-3, 1.0);
    s.add_span(0.9e-3, 2e-3, 1.0); // 1/11 of it lands in the last sample
    std::vector<double> y;
    s.render(y);
    CHECK(y[9] == doctest::Approx(0.1e-3 / 1.1e-3 * 0.5).epsilon(1e-9)); // first half-sample of the last bin
    for (std::size_t k = 0; k < 9; ++k) CHECK(y[k] == 0.0);
}

TEST_CASE("the Fourier path renders the direct sum's line to 1e-12 of its peak, with the same exact zeros, and is "
          "taken for long pulses") {
    const double dt = 1e-5;
    struct case_t {
        sss::pulse p;
        bool long_pulse; // spans hundreds of samples: render() should take the Fourier path
    };
    const case_t cases[] = {
        {{.length_s = 3.3e-5, .shape = sss::pulse_shape::rectangular}, false},        // not whole sub-bins: slopes clamped
        {{.length_s = 4e-5, .shape = sss::pulse_shape::hann}, false},                // whole samples: exact
        {{.length_s = 5.03e-3, .shape = sss::pulse_shape::rectangular}, true},       // 503 samples
        {{.length_s = 4e-3, .shape = sss::pulse_shape::hann}, true},                 // 400 samples
        {{.length_s = 2e-3, .shape = sss::pulse_shape::lfm, .bandwidth_hz = 2e4}, true}, // compressed: spans 2T, delayed T
    };
    for (const auto& c : cases) {
        CAPTURE(c.p.length_s);
        sss::time_sampler s(3000, dt, c.p);
        CHECK(s.renders_by_fourier() == c.long_pulse);
        // Its memory: a transform buffer per render where it takes the Fourier path, none where it sums directly.
        CHECK((sss::time_sampler::memory_bytes(3000, dt, c.p).per_render > 0.0) == c.long_pulse);
        // Spans and points over two stretches of the line, with an empty stretch between and after them, levels
        // over 60 dB.
        for (int i = 0; i < 400; ++i) {
            const double t0 = 2e-3 + 1.3e-5 * i + 1e-7 * (i % 3), t1 = t0 + 1e-6 * (i % 11);
            s.add_span(t0, t1, std::pow(10.0, -0.015 * i));
            if (i % 5 == 0) s.add_point(t0 + 3.7e-6, 0.5);
        }
        for (int i = 0; i < 50; ++i) s.add_span(0.02 + 2e-5 * i, 0.02 + 2e-5 * i + 7e-6, 1e-3);
        std::vector<double> direct, fourier;
        s.render(direct, sss::render_method::direct);
        s.render(fourier, sss::render_method::fourier);
        REQUIRE(direct.size() == fourier.size());
        const double peak = *std::max_element(direct.begin(), direct.end());
        REQUIRE(peak > 0.0);
        double worst = 0.0;
        std::size_t zeros = 0, zeros_differ = 0;
        for (std::size_t k = 0; k < direct.size(); ++k) {
            worst = std::max(worst, std::abs(direct[k] - fourier[k]) / peak);
            zeros += direct[k] == 0.0;
            zeros_differ += (direct[k] == 0.0) != (fourier[k] == 0.0);
        }
        CHECK(worst < 1e-12);
        CHECK(zeros > 100);         // before the first echo, between the stretches and after them
        CHECK(zeros_differ == 0);
        // A line over 180 dB (levels falling 0.45 dB a deposit over the second stretch): every sample keeps its own
        // relative accuracy, however far below the line's largest it lies.
        sss::time_sampler deep(3000, dt, c.p);
        for (int i = 0; i < 400; ++i) deep.add_span(2e-3 + 2e-5 * i, 2e-3 + 2e-5 * i + 9e-6, std::pow(10.0, -0.045 * i));
        std::vector<double> deep_direct, deep_fourier;
        deep.render(deep_direct, sss::render_method::direct);
        deep.render(deep_fourier, sss::render_method::fourier);
        double worst_relative = 0.0;
        std::size_t deep_zeros_differ = 0;
        for (std::size_t k = 0; k < deep_direct.size(); ++k)
            if (deep_direct[k] > 0.0)
                worst_relative = std::max(worst_relative, std::abs(deep_fourier[k] - deep_direct[k]) / deep_direct[k]);
            else
                deep_zeros_differ += deep_fourier[k] != 0.0;
        CHECK(worst_relative < 1e-6);
        CHECK(deep_zeros_differ == 0);
        // Energy: both conserve it to rounding.
        const double e_direct = std::accumulate(direct.begin(), direct.end(), 0.0);
        const double e_fourier = std::accumulate(fourier.begin(), fourier.end(), 0.0);
        CHECK(std::abs(e_fourier - e_direct) < 1e-12 * e_direct);
    }
}

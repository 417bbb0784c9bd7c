// Sand ripples: measured wavelength, crest direction, stoss/lee asymmetry, sinuosity and perturbation.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/seabed/detail/cosine.hpp"
#include "sss/seabed/fft.hpp"
#include "sss/seabed/ripples.hpp"

namespace {

using cd = std::complex<double>;
using namespace sss::seabed;
constexpr double pi = sss::pi_v<double>;

/// Hann-windowed spectrum |sum h w e^{-i K.x}|^2 at an arbitrary wave vector (rad/m).
struct zoom_spectrum {
    const raster<double>& h;
    std::vector<double> wx, wy;
    explicit zoom_spectrum(const raster<double>& r) : h(r), wx(r.nx), wy(r.ny) {
        for (std::size_t i = 0; i < r.nx; ++i)
            wx[i] = 0.5 - 0.5 * std::cos(2 * pi * static_cast<double>(i) / static_cast<double>(r.nx));
        for (std::size_t j = 0; j < r.ny; ++j)
            wy[j] = 0.5 - 0.5 * std::cos(2 * pi * static_cast<double>(j) / static_cast<double>(r.ny));
    }
    double operator()(double kx, double ky) const {
        std::vector<cd> ex(h.nx);
        for (std::size_t i = 0; i < h.nx; ++i) ex[i] = std::polar(wx[i], -kx * h.x_m(i));
        cd total(0, 0);
        for (std::size_t j = 0; j < h.ny; ++j) {
            cd row(0, 0);
            for (std::size_t i = 0; i < h.nx; ++i) row += h(i, j) * ex[i];
            total += row * std::polar(wy[j], -ky * h.y_m(j));
        }
        return std::norm(total);
    }
};

/// Wave vector of the strongest spectral peak with |K| in [k_lo, k_hi] (rad/m): the FFT periodogram's
/// best bin, then a pattern search on the windowed spectrum down to 1e-4 of a bin.
std::pair<double, double> spectral_peak(const raster<double>& h, double k_lo, double k_hi) {
    const std::size_t nx = h.nx, ny = h.ny;
    std::vector<cd> c(h.values.begin(), h.values.end());
    fft_2d(c, nx, ny, fft_direction::forward);
    const double dkx = 2 * pi / (static_cast<double>(nx) * h.cell_m),
                 dky = 2 * pi / (static_cast<double>(ny) * h.cell_m);
    double best = -1, bkx = 0, bky = 0;
    for (std::size_t j = 0; j < ny; ++j)
        for (std::size_t i = 0; i < nx / 2; ++i) { // half plane: the spectrum of a real field is symmetric
            const double kx = static_cast<double>(i) * dkx;
            const double ky = (j <= ny / 2 ? static_cast<double>(j) : -static_cast<double>(ny - j)) * dky;
            const double k = std::hypot(kx, ky);
            if (k < k_lo || k > k_hi) continue;
            if (std::norm(c[j * nx + i]) > best) {
                best = std::norm(c[j * nx + i]);
                bkx = kx;
                bky = ky;
            }
        }
    const zoom_spectrum z(h);
    double step = 0.5 * dkx, pbest = z(bkx, bky);
    while (step > 1e-4 * dkx) {
        bool moved = false;
        for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
                if (di == 0 && dj == 0) continue;
                const double p = z(bkx + di * step, bky + dj * step);
                if (p > pbest) {
                    pbest = p;
                    bkx += di * step;
                    bky += dj * step;
                    moved = true;
                }
            }
        if (!moved) step *= 0.5;
    }
    return {bkx, bky};
}

/// Crest direction (rad, in [0, pi)) of ripples whose wave vector is (kx, ky).
double crest_direction(double kx, double ky) {
    double a = std::atan2(ky, kx) + pi / 2;
    a = std::fmod(a, pi);
    return a < 0 ? a + pi : a;
}

/// Smallest angle between two undirected lines (rad).
double line_angle_diff(double a, double b) {
    const double d = std::fmod(std::abs(a - b), pi);
    return std::min(d, pi - d);
}

/// Directional derivative of h along (mx, my) by central differences (interior samples).
std::vector<double> slopes_along(const raster<double>& h, double mx, double my) {
    std::vector<double> s;
    for (std::size_t j = 1; j + 1 < h.ny; ++j)
        for (std::size_t i = 1; i + 1 < h.nx; ++i) {
            const double gx = (h(i + 1, j) - h(i - 1, j)) / (2 * h.cell_m);
            const double gy = (h(i, j + 1) - h(i, j - 1)) / (2 * h.cell_m);
            s.push_back(gx * mx + gy * my);
        }
    return s;
}

/// For crests along y (migration along +x) with a sinusoidal (RSI = 1) profile, the crest displacement
/// d (m) and amplitude of each window of `w` cells (a whole number of wavelengths) of each row, by
/// demodulation: z = -(H/2) cos(2 pi (x + d) / lambda).
struct window_demod {
    std::vector<double> shift_m, amplitude_m;
};
window_demod demodulate(const raster<double>& h, double lambda, std::size_t w) {
    window_demod out;
    for (std::size_t j = 0; j < h.ny; ++j)
        for (std::size_t i0 = 0; i0 + w <= h.nx; i0 += w) {
            cd a(0, 0);
            for (std::size_t i = i0; i < i0 + w; ++i) a += h(i, j) * std::polar(1.0, -2 * pi * h.x_m(i) / lambda);
            a *= -2.0 / static_cast<double>(w); // = (H/2) exp(2 pi i d / lambda)
            out.shift_m.push_back(std::arg(a) * lambda / (2 * pi));
            out.amplitude_m.push_back(2 * std::abs(a));
        }
    return out;
}

double rms_about_mean(const std::vector<double>& v) {
    double m = 0, s = 0;
    for (double x : v) m += x;
    m /= static_cast<double>(v.size());
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / static_cast<double>(v.size()));
}

} // namespace

TEST_CASE("ripples have the requested wavelength and crest direction (spectral peak)") {
    struct config {
        double lambda_m, crest_deg, rsi;
    };
    for (config c : {config{0.7, 30.0, 1.0}, config{1.3, 115.0, 2.5}, config{0.45, 170.0, 1.5}}) {
        CAPTURE(c.lambda_m);
        CAPTURE(c.crest_deg);
        ripple_params<double> p;
        p.wavelength_m = c.lambda_m;
        p.height_m = 0.05;
        p.crest_heading_deg = 90.0 - c.crest_deg;
        p.symmetry_index = c.rsi;
        const auto h = ripple_field<double>(256, 256, 0.05, p, 1);
        const auto [kx, ky] = spectral_peak(h, 1.0, 1e9);
        CHECK(2 * pi / std::hypot(kx, ky) == doctest::Approx(c.lambda_m).epsilon(0.005).scale(0));
        CHECK(sss::rad_to_deg(line_angle_diff(crest_direction(kx, ky), sss::heading_to_ccw_from_east_rad(p.crest_heading_deg))) < 0.5);
    }
}

TEST_CASE("the ripples' inline cosine is within a double rounding of the cosine over [0, pi], exact at its ends") {
    // Dense over the three intervals of the reduction and across their joins at pi/4 and 3 pi/4; the reference is
    // the long double cosine.
    double worst = 0.0;
    for (int i = 0; i <= 200000; ++i) {
        const double x = sss::pi_v<double> * static_cast<double>(i) / 200000.0;
        const long double ref = std::cos(static_cast<long double>(x));
        const long double got = sss::seabed::detail::cos_0_pi(x);
        worst = std::max(worst, static_cast<double>(std::fabs(got - ref)));
    }
    CHECK(worst < 3e-16);
    CHECK(sss::seabed::detail::cos_0_pi(0.0) == 1.0);
    CHECK(sss::seabed::detail::cos_0_pi(sss::pi_v<double>) == -1.0);
}

TEST_CASE("ripple height: crest-to-trough H and RMS H / (2 sqrt 2)") {
    for (double rsi : {1.0, 3.0}) {
        ripple_params<double> p;
        p.wavelength_m = 0.8;
        p.height_m = 0.06;
        p.symmetry_index = rsi;
        p.crest_heading_deg = 0;
        const auto h = ripple_field<double>(160, 8, 0.01, p, 1);
        const auto [lo, hi] = std::minmax_element(h.values.begin(), h.values.end());
        CHECK(*hi - *lo == doctest::Approx(0.06).epsilon(0.01).scale(0));
        CHECK(rms_about_mean(h.values) == doctest::Approx(0.06 / (2 * std::sqrt(2.0))).epsilon(0.01).scale(0));
    }
}

TEST_CASE("ripple asymmetry: lee slopes are RSI times the stoss slopes and the lee faces the migration direction") {
    for (double crest_deg : {90.0, 35.0}) {
        for (double rsi : {3.0, 1.0 / 3.0, 1.0}) {
            CAPTURE(crest_deg);
            CAPTURE(rsi);
            ripple_params<double> p;
            p.wavelength_m = 0.6;
            p.height_m = 0.04;
            p.crest_heading_deg = 90.0 - crest_deg;
            p.symmetry_index = rsi;
            // 300 cells = 5 whole wavelengths along x: every phase equally represented at 90 degrees.
            const auto h = ripple_field<double>(300, 300, 0.01, p, 1);
            const double mx = std::sin(sss::heading_to_ccw_from_east_rad(p.crest_heading_deg)), my = -std::cos(sss::heading_to_ccw_from_east_rad(p.crest_heading_deg));
            double n_rise = 0, n_fall = 0, max_rise = 0, max_fall = 0;
            for (double s : slopes_along(h, mx, my)) {
                if (s > 0)
                    n_rise += 1, max_rise = std::max(max_rise, s);
                else
                    n_fall += 1, max_fall = std::max(max_fall, -s);
            }
            // The stoss fraction f = RSI / (1 + RSI) of the area rises along n (samples within a cell of a
            // crest or trough can fall on the wrong side: 0.02 absolute). The steepest slopes of the two
            // cosine halves are pi H / (2 f lambda) and pi H / (2 (1 - f) lambda): ratio RSI.
            const double f = rsi / (1 + rsi);
            CHECK(std::abs(n_rise / (n_rise + n_fall) - f) < 0.02);
            CHECK(max_fall / max_rise == doctest::Approx(rsi).epsilon(0.02).scale(0));
            CHECK(max_rise == doctest::Approx(pi * 0.04 / (2 * f * 0.6)).epsilon(0.02).scale(0));
        }
    }
}

TEST_CASE("crest sinuosity displaces the crests sinusoidally along the crest line") {
    ripple_params<double> p;
    p.wavelength_m = 0.8; // 16 cells: each row holds 16 whole wavelengths
    p.height_m = 0.05;
    p.crest_heading_deg = 0; // crests along y, migration along +x
    p.sinuosity_m = 0.1;
    p.sinuosity_wavelength_m = 6.4;
    const auto h = ripple_field<double>(256, 256, 0.05, p, 1);
    const auto d = demodulate(h, 0.8, 256);
    // Fit d(y) = A sin(2 pi y / 6.4) + B cos(...) by projection over the 2 whole meander wavelengths.
    double a = 0, b = 0;
    for (std::size_t j = 0; j < h.ny; ++j) {
        const double arg = 2 * pi * h.y_m(j) / 6.4;
        a += d.shift_m[j] * std::sin(arg);
        b += d.shift_m[j] * std::cos(arg);
    }
    a *= 2.0 / static_cast<double>(h.ny);
    b *= 2.0 / static_cast<double>(h.ny);
    CHECK(a == doctest::Approx(0.1).epsilon(0.01).scale(0));
    CHECK(std::abs(b) < 1e-3);
}

TEST_CASE("fractal perturbation displaces crests and varies heights by the requested RMS") {
    ripple_params<double> p;
    p.wavelength_m = 0.4; // 8 cells
    p.height_m = 0.03;
    p.crest_heading_deg = 0;
    p.perturbation_m = 0.03;
    p.height_variation = 0.15;
    p.perturbation_scale_m = 3.2;
    // Demodulating over one wavelength smooths away the field's shortest scales (about 4% of its variance
    // lies below one wavelength for gamma = 3.5 and an outer scale of 8 wavelengths), so the measurement
    // reads about 5% low; over 30 seeds the worst reading was 11% low.
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        CAPTURE(seed);
        const auto h = ripple_field<double>(512, 512, 0.05, p, seed);
        const auto d = demodulate(h, 0.4, 8);
        CHECK(rms_about_mean(d.shift_m) == doctest::Approx(0.03).epsilon(0.15).scale(0));
        std::vector<double> rel;
        for (double a : d.amplitude_m) rel.push_back(a / 0.03);
        CHECK(rms_about_mean(rel) == doctest::Approx(0.15).epsilon(0.15).scale(0));
    }
    // Without perturbation the crests are straight and the heights uniform.
    p.perturbation_m = 0;
    p.height_variation = 0;
    const auto d = demodulate(ripple_field<double>(128, 32, 0.05, p, 1), 0.4, 8);
    CHECK(rms_about_mean(d.shift_m) < 1e-9);
    CHECK(rms_about_mean(d.amplitude_m) < 1e-9);
}

TEST_CASE("two superposed ripple sets show both wavelengths and directions") {
    std::vector<ripple_params<double>> sets(2);
    sets[0].wavelength_m = 0.3;
    sets[0].height_m = 0.015;
    sets[0].crest_heading_deg = 70;
    sets[1].wavelength_m = 1.5;
    sets[1].height_m = 0.1;
    sets[1].crest_heading_deg = -10;
    sets[1].symmetry_index = 2.0;
    const auto h = ripple_field<double>(256, 256, 0.04, std::span<const ripple_params<double>>(sets), 9);
    for (const auto& s : sets) {
        CAPTURE(s.wavelength_m);
        const double k = 2 * pi / s.wavelength_m;
        const auto [kx, ky] = spectral_peak(h, 0.7 * k, 1.4 * k);
        CHECK(2 * pi / std::hypot(kx, ky) == doctest::Approx(s.wavelength_m).epsilon(0.005).scale(0));
        CHECK(sss::rad_to_deg(line_angle_diff(crest_direction(kx, ky), sss::heading_to_ccw_from_east_rad(s.crest_heading_deg))) < 0.5);
    }
}

TEST_CASE("ripples are reproducible from their seed and reject bad parameters by name") {
    ripple_params<double> p;
    p.perturbation_m = 0.02;
    const auto a = ripple_field<double>(64, 64, 0.05, p, 5);
    const auto b = ripple_field<double>(64, 64, 0.05, p, 5);
    const auto c = ripple_field<double>(64, 64, 0.05, p, 6);
    CHECK(a.values == b.values);
    CHECK(a.values != c.values);
    const auto f = ripple_field<float>(64, 64, 0.05f, ripple_params<float>{}, 5);
    CHECK(f.size() == 64 * 64);

    auto expect = [](const ripple_params<double>& q, const char* name) {
        try {
            (void)ripple_field<double>(16, 16, 0.05, q, 1);
            FAIL("no exception for " << name);
        } catch (const sss::invalid_parameter& e) {
            CHECK(e.parameter() == name);
        }
    };
    ripple_params<double> q;
    q.wavelength_m = 0.08; // < 2 cells
    expect(q, "add_ripples.params.wavelength_m");
    q = {};
    q.symmetry_index = 0;
    expect(q, "add_ripples.params.symmetry_index");
    q = {};
    q.sinuosity_m = 0.1;
    expect(q, "add_ripples.params.sinuosity_wavelength_m");
    q = {};
    q.height_variation = 1.5;
    expect(q, "add_ripples.params.height_variation");
    q = {};
    q.height_m = -1;
    expect(q, "add_ripples.params.height_m");
}

TEST_CASE("a phase of pi/2 moves the crests a quarter wavelength against n; a 1 x 1 grid stays finite") {
    // Crests running east: n points south (-y), so the crests move north (+y) by lambda / 4 = 10 cells of 1.25 cm.
    ripple_params<double> p;
    p.wavelength_m = 0.5;
    p.crest_heading_deg = 90.0;
    const auto base = ripple_field<double>(4, 200, 0.0125, p, 3);
    p.phase_rad = sss::pi_v<double> / 2.0;
    const auto moved = ripple_field<double>(4, 200, 0.0125, p, 3);
    double worst = 0.0;
    for (std::size_t iy = 10; iy < 200; ++iy)
        for (std::size_t ix = 0; ix < 4; ++ix)
            worst = std::max(worst, std::abs(moved.values[iy * 4 + ix] - base.values[(iy - 10) * 4 + ix]));
    CHECK(worst < 1e-12);
    // One cell holds no mode of the crests' fractal displacement but the mean: a flat field, not 0 x infinity.
    ripple_params<double> q;
    q.perturbation_m = 0.01;
    q.height_variation = 0.3;
    const auto one = ripple_field<double>(1, 1, 0.1, q, 1);
    CHECK(std::isfinite(one.values[0]));
}

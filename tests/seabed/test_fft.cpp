// The FFT against the defining sum, Parseval's theorem and closed-form transforms.
#include <doctest/doctest.h>

#include <cmath>
#include <algorithm>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/seabed/detail/half_spectrum.hpp"
#include "sss/seabed/fft.hpp"
#include "sss/seabed/random.hpp"

namespace {

using cd = std::complex<double>;
using sss::seabed::fft_direction;

std::vector<cd> random_signal(std::size_t n, std::uint64_t seed) {
    sss::seabed::rng g(seed);
    std::vector<cd> x(n);
    for (auto& v : x) v = cd(g.uniform(-1.0, 1.0), g.uniform(-1.0, 1.0));
    return x;
}

/// The defining sum X_k = sum_n x_n exp(sign 2 pi i n k / N), accumulated in long double with the
/// angle reduced exactly (n k mod N) so that it is a trustworthy reference.
std::vector<cd> direct_dft(const std::vector<cd>& x, int sign) {
    const std::size_t n = x.size();
    std::vector<cd> out(n);
    const long double two_pi = 6.283185307179586476925286766559005768L;
    for (std::size_t k = 0; k < n; ++k) {
        long double re = 0, im = 0;
        for (std::size_t j = 0; j < n; ++j) {
            const long double a = sign * two_pi * static_cast<long double>((j * k) % n) / static_cast<long double>(n);
            const long double c = std::cos(a), s = std::sin(a);
            re += x[j].real() * c - x[j].imag() * s;
            im += x[j].real() * s + x[j].imag() * c;
        }
        out[k] = cd(static_cast<double>(re), static_cast<double>(im));
    }
    return out;
}

double max_abs_diff(const std::vector<cd>& a, const std::vector<cd>& b) {
    double m = 0;
    for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
    return m;
}

double energy(const std::vector<cd>& a) {
    double e = 0;
    for (const auto& v : a) e += std::norm(v);
    return e;
}

} // namespace

TEST_CASE("FFT equals the direct DFT for power-of-two and arbitrary lengths in both directions") {
    for (std::size_t n :
         {1u, 2u, 3u, 4u, 5u, 6u, 7u, 8u, 12u, 16u, 17u, 31u, 64u, 97u, 100u, 128u, 243u, 1000u, 1024u}) {
        CAPTURE(n);
        const auto x = random_signal(n, 100 + n);
        for (int sign : {-1, +1}) {
            CAPTURE(sign);
            auto y = x;
            sss::seabed::fft(y, sign < 0 ? fft_direction::forward : fft_direction::backward);
            const auto ref = direct_dft(x, sign);
            // Inputs of modulus <= sqrt(2): the output scale is sqrt(N); round-off grows like log N.
            const double tol = 1e-14 * std::sqrt(static_cast<double>(n)) * (4.0 + std::log2(static_cast<double>(n)));
            CHECK(max_abs_diff(y, ref) < tol);
        }
    }
}

TEST_CASE("backward(forward(x)) = N x, to rounding, for radix-2 and Bluestein lengths") {
    for (std::size_t n : {256u, 300u, 4096u, 4099u}) {
        CAPTURE(n);
        const auto x = random_signal(n, n);
        auto y = x;
        const sss::seabed::fft_plan plan(n);
        plan.execute(y, fft_direction::forward);
        plan.execute(y, fft_direction::backward);
        for (auto& v : y) v /= static_cast<double>(n);
        CHECK(max_abs_diff(x, y) < 1e-14 * std::log2(static_cast<double>(n)) * 4.0);
    }
}

TEST_CASE("Parseval: sum |X_k|^2 = N sum |x_n|^2 in one and two dimensions") {
    for (std::size_t n : {512u, 600u}) {
        const auto x = random_signal(n, 7);
        auto y = x;
        sss::seabed::fft(y, fft_direction::forward);
        CHECK(energy(y) == doctest::Approx(static_cast<double>(n) * energy(x)).epsilon(1e-13).scale(0));
    }
    for (auto [nx, ny] : {std::pair<std::size_t, std::size_t>{64, 32}, {45, 28}}) {
        const auto x = random_signal(nx * ny, 9);
        auto y = x;
        sss::seabed::fft_2d(y, nx, ny, fft_direction::forward);
        CHECK(energy(y) == doctest::Approx(static_cast<double>(nx * ny) * energy(x)).epsilon(1e-13).scale(0));
    }
}

TEST_CASE("2D FFT equals the direct 2D DFT (square, rectangular, odd sizes; more than one column block)") {
    for (const auto& size : {std::pair<std::size_t, std::size_t>{8, 8}, {6, 10}, {5, 7}, {40, 3}}) {
        const std::size_t nx = size.first, ny = size.second;
        CAPTURE(nx);
        CAPTURE(ny);
        const auto x = random_signal(nx * ny, nx * 31 + ny);
        auto y = x;
        sss::seabed::fft_2d(y, nx, ny, fft_direction::forward);
        double worst = 0;
        for (std::size_t ky = 0; ky < ny; ++ky)
            for (std::size_t kx = 0; kx < nx; ++kx) {
                cd ref(0, 0);
                for (std::size_t iy = 0; iy < ny; ++iy)
                    for (std::size_t ix = 0; ix < nx; ++ix) {
                        const double a =
                            -sss::two_pi_v<double> * (static_cast<double>((ix * kx) % nx) / static_cast<double>(nx) +
                                                      static_cast<double>((iy * ky) % ny) / static_cast<double>(ny));
                        ref += x[iy * nx + ix] * cd(std::cos(a), std::sin(a));
                    }
                worst = std::max(worst, std::abs(ref - y[ky * nx + kx]));
            }
        CHECK(worst < 1e-12);
    }
}

TEST_CASE("a Hermitian half spectrum transforms in place to the real part of the full 2D inverse, in float and double") {
    // The half kx = 0 .. nx/2 of a random Hermitian spectrum, in the field's own storage (detail/half_spectrum.hpp),
    // against the real part of the complex inverse 2D FFT of the whole spectrum: equal to the rounding of the
    // storage type (double, float) relative to the field's RMS; the imaginary part of the reference vanishes.
    const auto run = [](auto zero, std::size_t nx, std::size_t ny) {
        using T = decltype(zero);
        sss::seabed::rng g(nx * 131 + ny);
        std::vector<cd> full(nx * ny);
        for (std::size_t j = 0; j < ny; ++j)
            for (std::size_t i = 0; i < nx; ++i) {
                const std::size_t own = j * nx + i, partner = ((ny - j) % ny) * nx + (nx - i) % nx;
                if (partner < own) continue;
                const cd v(g.normal(), partner == own ? 0.0 : g.normal());
                full[own] = v;
                full[partner] = std::conj(v);
            }
        std::vector<T> values(nx * ny);
        std::vector<std::complex<T>> last(ny);
        const sss::seabed::detail::half_spectrum<T> s{values.data(), last.data(), nx, ny};
        for (std::size_t j = 0; j < ny; ++j)
            for (std::size_t i = 0; i <= nx / 2; ++i) s.set(i, j, full[j * nx + i]);
        const double scale = 0.5;
        sss::seabed::detail::inverse_half_spectrum(s, scale);
        sss::seabed::fft_2d(full, nx, ny, fft_direction::backward);
        double worst = 0, imag = 0, rms = 0;
        for (std::size_t k = 0; k < nx * ny; ++k) {
            worst = std::max(worst, std::abs(static_cast<double>(values[k]) - scale * full[k].real()));
            imag = std::max(imag, std::abs(full[k].imag()));
            rms += std::norm(scale * full[k].real());
        }
        rms = std::sqrt(rms / static_cast<double>(nx * ny));
        CAPTURE(nx);
        CAPTURE(ny);
        CHECK(imag < 1e-12 * rms / scale);
        CHECK(worst <= 64.0 * static_cast<double>(std::numeric_limits<T>::epsilon()) * rms);
    };
    for (const auto& size : {std::pair<std::size_t, std::size_t>{1, 1}, {1, 6}, {5, 1}, {2, 2}, {8, 8}, {6, 10},
                             {5, 7}, {7, 5}, {40, 3}, {64, 33}, {300, 256}}) {
        run(0.0, size.first, size.second);
        run(0.0f, size.first, size.second);
    }
}

TEST_CASE("a complex exponential transforms to a single bin of height N") {
    for (std::size_t n : {64u, 90u}) {
        const std::size_t k0 = 5;
        std::vector<cd> x(n);
        for (std::size_t j = 0; j < n; ++j) {
            const double a = sss::two_pi_v<double> * static_cast<double>(k0 * j) / static_cast<double>(n);
            x[j] = cd(std::cos(a), std::sin(a));
        }
        sss::seabed::fft(x, fft_direction::forward);
        for (std::size_t k = 0; k < n; ++k) {
            CAPTURE(k);
            CHECK(std::abs(x[k] - cd(k == k0 ? static_cast<double>(n) : 0.0, 0.0)) < 1e-11);
        }
    }
}

TEST_CASE("FFT rejects a zero length and mismatched sizes, naming the parameter") {
    CHECK_THROWS_AS(sss::seabed::fft_plan(0), sss::invalid_parameter);
    try {
        (void)sss::seabed::fft_plan(0);
    } catch (const sss::invalid_parameter& e) {
        CHECK(e.parameter() == "fft_plan.n");
    }
    std::vector<cd> x(10);
    try {
        sss::seabed::fft_2d(x, 3, 3, fft_direction::forward);
        FAIL("no exception");
    } catch (const sss::invalid_parameter& e) {
        CHECK(e.parameter() == "fft_2d.data");
    }
    const sss::seabed::fft_plan p(8);
    CHECK_THROWS_AS(p.execute(x, fft_direction::forward), sss::invalid_parameter);
}

#pragma once
/// \file
/// Discrete Fourier transforms of any length, in one and two dimensions (complex double).
///
/// Conventions (no normalisation in either direction, so backward(forward(x)) = N x):
///   forward:  X_k = sum_{n=0}^{N-1} x_n exp(-2 pi i n k / N)
///   backward: x_n = sum_{k=0}^{N-1} X_k exp(+2 pi i n k / N)
/// Power-of-two lengths use an iterative radix-2 decimation-in-time transform (Cooley & Tukey, 1965,
/// Math. Comp. 19, 297-301); other lengths use Bluestein's chirp-z algorithm (Bluestein, 1970, IEEE Trans.
/// Audio Electroacoust. 18(4), 451-455), which rewrites the length-N DFT as a circular convolution of
/// power-of-two length M >= 2N - 1. Twiddle factors are evaluated directly (not by recurrence), so the
/// round-off error grows like log N.

#include <algorithm>
#include <complex>
#include <cstddef>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/error.hpp"
#include "sss/core/thread_pool.hpp"
#include "sss/seabed/detail/complex_multiply.hpp"

namespace sss::seabed {

/// Sign of the exponent: forward exp(-i...), backward exp(+i...).
enum class fft_direction : signed char { forward = -1, backward = +1 };

/// True for 1, 2, 4, 8, ...
[[nodiscard]] constexpr bool is_power_of_two(std::size_t n) noexcept { return n != 0 && (n & (n - 1)) == 0; }

/// Smallest power of two >= n (n >= 1).
[[nodiscard]] constexpr std::size_t next_power_of_two(std::size_t n) noexcept {
    std::size_t p = 1;
    while (p < n) p <<= 1;
    return p;
}

/// A precomputed plan for transforms of one length: twiddles and bit-reversal table, and for lengths
/// that are not powers of two the Bluestein chirp and its transform. A plan is immutable after
/// construction; `execute` takes caller scratch so that one plan can serve several threads.
class fft_plan {
public:
    using complex = std::complex<double>;

    /// \param n transform length (>= 1), any value
    explicit fft_plan(std::size_t n) : n_(n) {
        sss::require(n >= 1, "fft_plan.n", "transform length must be >= 1");
        if (is_power_of_two(n)) {
            init_radix2(n, twiddle_, twiddle_back_, bitrev_);
            return;
        }
        // Bluestein: X_k = w_k sum_n (x_n w_n) conj(w_{k-n}), w_j = exp(-i pi j^2 / n).
        m_ = next_power_of_two(2 * n - 1);
        init_radix2(m_, twiddle_, twiddle_back_, bitrev_);
        chirp_.resize(n);
        const std::size_t two_n = 2 * n;
        for (std::size_t j = 0; j < n; ++j) {
            // w_j is 2n-periodic in j^2: reducing j^2 mod 2n keeps the angle small (exact for n < 2^31).
            const std::size_t jj = (j * j) % two_n;
            const double angle = -pi_v<double> * static_cast<double>(jj) / static_cast<double>(n);
            chirp_[j] = complex(std::cos(angle), std::sin(angle));
        }
        kernel_.assign(m_, complex(0.0, 0.0));
        kernel_[0] = std::conj(chirp_[0]);
        for (std::size_t j = 1; j < n; ++j) kernel_[j] = kernel_[m_ - j] = std::conj(chirp_[j]);
        radix2(kernel_.data(), m_, fft_direction::forward);
    }

    /// Transform length.
    [[nodiscard]] std::size_t size() const noexcept { return n_; }

    /// Scratch length `execute` needs (0 for powers of two).
    [[nodiscard]] std::size_t scratch_size() const noexcept { return m_; }

    /// Transforms `data` (length size()) in place. `scratch` must hold scratch_size() elements.
    void execute(complex* data, fft_direction dir, complex* scratch) const noexcept {
        if (m_ == 0) {
            radix2(data, n_, dir);
            return;
        }
        // The backward transform is the conjugate of the forward transform of the conjugate.
        const bool back = dir == fft_direction::backward;
        for (std::size_t j = 0; j < n_; ++j) scratch[j] = detail::cmul(back ? std::conj(data[j]) : data[j], chirp_[j]);
        for (std::size_t j = n_; j < m_; ++j) scratch[j] = complex(0.0, 0.0);
        radix2(scratch, m_, fft_direction::forward);
        for (std::size_t j = 0; j < m_; ++j) scratch[j] = detail::cmul(scratch[j], kernel_[j]);
        radix2(scratch, m_, fft_direction::backward);
        const double inv_m = 1.0 / static_cast<double>(m_);
        for (std::size_t k = 0; k < n_; ++k) {
            const complex v = detail::cmul(scratch[k], chirp_[k]) * inv_m;
            data[k] = back ? std::conj(v) : v;
        }
    }

    /// Transforms `data` in place, allocating scratch when needed.
    void execute(std::span<complex> data, fft_direction dir) const {
        sss::require(data.size() == n_, "fft_plan.execute.data",
                        [&] { return "length " + std::to_string(data.size()) + " differs from the plan's " + std::to_string(n_); });
        std::vector<complex> scratch(m_);
        execute(data.data(), dir, scratch.data());
    }

private:
    /// Twiddles w_j = exp(-2 pi i j / n), j < n/2, laid out per stage for the radix-2 passes: the pass over
    /// butterflies of length len = 2 half uses w_{j n / len}, j < half, stored contiguously from index half - 1
    /// (n - 1 values in all); `back` holds their conjugates for the backward transform. Each value is the same
    /// cos and sin of one angle wherever it appears, so the layout changes no result.
    static void init_radix2(std::size_t n, std::vector<complex>& tw, std::vector<complex>& back,
                            std::vector<std::size_t>& rev) {
        std::vector<complex> w(n / 2);
        for (std::size_t j = 0; j < n / 2; ++j) {
            const double angle = -two_pi_v<double> * static_cast<double>(j) / static_cast<double>(n);
            w[j] = complex(std::cos(angle), std::sin(angle));
        }
        tw.resize(n > 1 ? n - 1 : 0);
        back.resize(tw.size());
        for (std::size_t half = 1; half < n; half <<= 1)
            for (std::size_t j = 0; j < half; ++j) {
                tw[half - 1 + j] = w[j * (n / (2 * half))];
                back[half - 1 + j] = std::conj(tw[half - 1 + j]);
            }
        rev.resize(n);
        std::size_t bits = 0;
        while ((std::size_t{1} << bits) < n) ++bits;
        for (std::size_t j = 0; j < n; ++j) {
            std::size_t r = 0;
            for (std::size_t b = 0; b < bits; ++b) r |= ((j >> b) & 1U) << (bits - 1 - b);
            rev[j] = r;
        }
    }

    /// Radix-2 transform of length n (the plan's power-of-two length) using the plan's tables.
    void radix2(complex* a, std::size_t n, fft_direction dir) const noexcept {
        for (std::size_t j = 0; j < n; ++j)
            if (j < bitrev_[j]) std::swap(a[j], a[bitrev_[j]]);
        // Butterflies of length 2: w_0 = 1, so hi w_0 = hi (up to the sign of a zero).
        for (std::size_t start = 0; start + 1 < n; start += 2) {
            const complex t = a[start + 1];
            a[start + 1] = a[start] - t;
            a[start] += t;
        }
        const complex* tw = dir == fft_direction::backward ? twiddle_back_.data() : twiddle_.data();
        for (std::size_t half = 2; half < n; half <<= 1) {
            const complex* w = tw + (half - 1);
            for (std::size_t start = 0; start < n; start += 2 * half) {
                complex* lo = a + start;
                complex* hi = lo + half;
                for (std::size_t j = 0; j < half; ++j) {
                    const complex t = detail::cmul(hi[j], w[j]);
                    hi[j] = lo[j] - t;
                    lo[j] += t;
                }
            }
        }
    }

    std::size_t n_;
    std::size_t m_ = 0; // Bluestein convolution length, 0 for powers of two
    std::vector<complex> twiddle_;      // per stage (init_radix2)
    std::vector<complex> twiddle_back_; // their conjugates
    std::vector<std::size_t> bitrev_;
    std::vector<complex> chirp_;
    std::vector<complex> kernel_;
};

/// One-dimensional transform of `data` in place (any length >= 1).
inline void fft(std::span<std::complex<double>> data, fft_direction dir) { fft_plan(data.size()).execute(data, dir); }

/// Two-dimensional transform in place of a row-major array, `data[iy * nx + ix]`:
/// X(kx, ky) = sum_{ix, iy} x(ix, iy) exp(-+2 pi i (ix kx / nx + iy ky / ny)), unnormalised.
/// Rows are transformed first, then columns in blocks of adjacent columns for cache locality; rows and blocks
/// are shared among the threads of shared_thread_pool() (each is transformed alone, so the result does not depend
/// on the threads).
inline void fft_2d(std::span<std::complex<double>> data, std::size_t nx, std::size_t ny, fft_direction dir) {
    sss::require(nx >= 1, "fft_2d.nx", "must be >= 1");
    sss::require(ny >= 1, "fft_2d.ny", "must be >= 1");
    sss::require(data.size() == nx * ny, "fft_2d.data",
                    [&] { return "length " + std::to_string(data.size()) + " differs from nx * ny = " + std::to_string(nx * ny); });
    using complex = std::complex<double>;
    thread_pool& pool = shared_thread_pool();
    // Small transforms are not worth a second thread.
    const unsigned threads = nx * ny >= (std::size_t(1) << 16) ? 0u : 1u;
    const fft_plan row_plan(nx);
    constexpr std::size_t rows_per_task = 32;
    pool.for_each(
        (ny + rows_per_task - 1) / rows_per_task,
        [&](std::size_t task) {
            std::vector<complex> scratch(std::max(row_plan.scratch_size(), std::size_t{1}));
            const std::size_t y1 = std::min(ny, (task + 1) * rows_per_task);
            for (std::size_t iy = task * rows_per_task; iy < y1; ++iy)
                row_plan.execute(data.data() + iy * nx, dir, scratch.data());
        },
        threads);

    const fft_plan col_plan(ny);
    constexpr std::size_t block = 16;
    pool.for_each(
        (nx + block - 1) / block,
        [&](std::size_t task) {
            const std::size_t x0 = task * block;
            const std::size_t w = std::min(block, nx - x0);
            std::vector<complex> cols(block * ny);
            std::vector<complex> scratch(std::max(col_plan.scratch_size(), std::size_t{1}));
            for (std::size_t iy = 0; iy < ny; ++iy) {
                const complex* row = data.data() + iy * nx + x0;
                for (std::size_t c = 0; c < w; ++c) cols[c * ny + iy] = row[c];
            }
            for (std::size_t c = 0; c < w; ++c) col_plan.execute(cols.data() + c * ny, dir, scratch.data());
            for (std::size_t iy = 0; iy < ny; ++iy) {
                complex* row = data.data() + iy * nx + x0;
                for (std::size_t c = 0; c < w; ++c) row[c] = cols[c * ny + iy];
            }
        },
        threads);
}

} // namespace sss::seabed

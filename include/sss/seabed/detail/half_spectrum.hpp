#pragma once
/// \file
/// Internal to the spectral synthesis of real fields (fractal surfaces, unit fractal fields): the Hermitian half
/// spectrum of a real nx x ny field held in the field's own storage, and its inverse 2D DFT in place. Not part of
/// the API.
///
/// A real field's spectrum is Hermitian, c(-kx, -ky) = conj c(kx, ky), so the columns kx = 0 .. floor(nx/2)
/// (every ky) determine it (the real-to-complex layout of e.g. Frigo & Johnson, 2005, "The design and
/// implementation of FFTW3", Proc. IEEE 93(2), 216-231). Columns 0 .. floor(nx/2) - 1 fill the nx reals of each
/// row of the field's own storage as (real, imaginary) pairs; column floor(nx/2) goes to a side array of ny
/// values. The inverse transform
///   h(x, y) = sum_{kx, ky} c(kx, ky) exp(+2 pi i (x kx / nx + y ky / ny))
/// then runs in place: first along y for each stored column (F(kx, y) = sum_ky c exp(+2 pi i y ky / ny), still
/// Hermitian in kx), then along x for rows taken two at a time, Z = F(., y) + i F(., y + 1) completed by
/// F(nx - kx, y) = conj F(kx, y), whose transform is h(., y) + i h(., y + 1) (Press et al., 2007, Numerical
/// Recipes, 3rd ed., section 12.3.2, "two real FFTs for the price of one"). Each row and column is transformed
/// in double precision and stored back in the field's type, so a float field needs its own n^2 floats plus one
/// column, not n^2 complex doubles, and differs from a transform carried out wholly in double by a few float
/// roundings of the field's RMS.

#include <algorithm>
#include <complex>
#include <cstddef>
#include <vector>

#include "sss/core/thread_pool.hpp"
#include "sss/core/types.hpp"
#include "sss/seabed/fft.hpp"

namespace sss::seabed::detail {

/// The half spectrum of a real nx x ny field in the field's storage (see the file comment); both arrays are the
/// caller's.
template <Real T> struct half_spectrum {
    T* values = nullptr;           ///< nx * ny reals; row j holds columns 0 .. nx/2 - 1 as (re, im) pairs
    std::complex<T>* last = nullptr; ///< column nx/2 (integer division) of every row: ny values
    std::size_t nx = 0;
    std::size_t ny = 0;

    /// Columns held: kx = 0 .. nx/2.
    [[nodiscard]] std::size_t columns() const noexcept { return nx / 2 + 1; }

    [[nodiscard]] std::complex<double> get(std::size_t kx, std::size_t ky) const noexcept {
        if (kx == nx / 2) return {static_cast<double>(last[ky].real()), static_cast<double>(last[ky].imag())};
        const T* p = values + ky * nx + 2 * kx;
        return {static_cast<double>(p[0]), static_cast<double>(p[1])};
    }

    void set(std::size_t kx, std::size_t ky, std::complex<double> c) const noexcept {
        if (kx == nx / 2) {
            last[ky] = {static_cast<T>(c.real()), static_cast<T>(c.imag())};
            return;
        }
        T* p = values + ky * nx + 2 * kx;
        p[0] = static_cast<T>(c.real());
        p[1] = static_cast<T>(c.imag());
    }

    /// Stores c at mode (i, j) and conj c at its Hermitian partner (pi, pj), each where it lies in the half (the
    /// store of draw_coefficients).
    void set_pair(std::size_t i, std::size_t j, std::size_t pi, std::size_t pj, std::complex<double> c) const noexcept {
        if (i <= nx / 2) set(i, j, c);
        if (pi <= nx / 2) set(pi, pj, std::conj(c));
    }
};

/// The inverse 2D DFT of half spectrum `s`, times `scale`, in place: afterwards s.values[y * nx + x] = scale h(x, y)
/// (the field of the file comment); s.last is left undefined. Columns and row pairs are shared among the threads
/// of shared_thread_pool() (each transformed alone, so the result does not depend on the threads).
template <Real T> void inverse_half_spectrum(const half_spectrum<T>& s, double scale) {
    using complex = std::complex<double>;
    const std::size_t nx = s.nx, ny = s.ny, half = s.columns();
    thread_pool& pool = shared_thread_pool();
    const unsigned threads = nx * ny >= (std::size_t(1) << 16) ? 0u : 1u; // small fields are not worth a thread

    // Along y, for blocks of adjacent columns (cache locality); the block is gathered into double precision.
    const fft_plan col_plan(ny);
    constexpr std::size_t block = 16;
    pool.for_each(
        (half + block - 1) / block,
        [&](std::size_t task) {
            const std::size_t k0 = task * block, w = std::min(block, half - k0);
            std::vector<complex> cols(w * ny);
            std::vector<complex> scratch(std::max(col_plan.scratch_size(), std::size_t{1}));
            for (std::size_t ky = 0; ky < ny; ++ky)
                for (std::size_t c = 0; c < w; ++c) cols[c * ny + ky] = s.get(k0 + c, ky);
            for (std::size_t c = 0; c < w; ++c)
                col_plan.execute(cols.data() + c * ny, fft_direction::backward, scratch.data());
            for (std::size_t y = 0; y < ny; ++y)
                for (std::size_t c = 0; c < w; ++c) s.set(k0 + c, y, cols[c * ny + y]);
        },
        threads);

    // Along x, two rows at a time: Z(kx) = F(kx, y) + i F(kx, y + 1), completed by Hermitian symmetry in kx (on
    // the self-conjugate columns kx = 0 and, for even nx, nx/2, F is real: only its real part is taken).
    const fft_plan row_plan(nx);
    constexpr std::size_t pairs_per_task = 16;
    const std::size_t pairs = (ny + 1) / 2;
    pool.for_each(
        (pairs + pairs_per_task - 1) / pairs_per_task,
        [&](std::size_t task) {
            std::vector<complex> z(nx);
            std::vector<complex> scratch(std::max(row_plan.scratch_size(), std::size_t{1}));
            const std::size_t p1 = std::min(pairs, (task + 1) * pairs_per_task);
            for (std::size_t p = task * pairs_per_task; p < p1; ++p) {
                const std::size_t y = 2 * p;
                const bool second = y + 1 < ny;
                for (std::size_t kx = 0; kx < half; ++kx) {
                    const complex a = s.get(kx, y), b = second ? s.get(kx, y + 1) : complex(0.0, 0.0);
                    const std::size_t mirror = (nx - kx) % nx;
                    if (mirror == kx) {
                        z[kx] = {a.real(), b.real()};
                        continue;
                    }
                    z[kx] = {a.real() - b.imag(), a.imag() + b.real()};     // a + i b
                    z[mirror] = {a.real() + b.imag(), b.real() - a.imag()}; // conj(a) + i conj(b)
                }
                row_plan.execute(z.data(), fft_direction::backward, scratch.data());
                T* row = s.values + y * nx;
                for (std::size_t x = 0; x < nx; ++x) row[x] = static_cast<T>(scale * z[x].real());
                if (second)
                    for (std::size_t x = 0; x < nx; ++x) row[nx + x] = static_cast<T>(scale * z[x].imag());
            }
        },
        threads);
}

} // namespace sss::seabed::detail

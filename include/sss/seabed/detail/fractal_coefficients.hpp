#pragma once
/// \file
/// Internal to the fractal surfaces (seabed/fractal.hpp): the directional spectral density, the variance of each
/// grid mode and the draw of Hermitian-symmetric random Fourier coefficients. Not part of the API.

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <span>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/core/thread_pool.hpp"
#include "sss/core/types.hpp"
#include "sss/seabed/fractal_params.hpp"
#include "sss/seabed/random.hpp"

namespace sss::seabed::detail {

/// W(K_eff) with the direction's cosine and sine and the outer scale evaluated once.
struct directional_density {
    double c, s, a, k0sq, w2, half_gamma;
    [[nodiscard]] double operator()(double kx, double ky) const noexcept {
        const double ku = kx * c + ky * s;
        const double kv = -kx * s + ky * c;
        return w2 * std::pow(a * ku * ku + kv * kv / a + k0sq, -half_gamma);
    }
};

template <Real T> [[nodiscard]] directional_density make_density(const fractal_params<T>& p) noexcept {
    const double l0 = static_cast<double>(p.spectrum.outer_scale_m);
    const double k0 = l0 > 0.0 ? two_pi_v<double> / l0 : 0.0;
    return {std::cos(static_cast<double>(p.direction_rad)),
            std::sin(static_cast<double>(p.direction_rad)),
            static_cast<double>(p.anisotropy),
            k0 * k0,
            static_cast<double>(p.spectrum.w2_si),
            0.5 * static_cast<double>(p.spectrum.gamma)};
}

/// Signed wavenumber (rad/m) of FFT index i on an n-point axis of spacing dk.
[[nodiscard]] inline double wavenumber(std::size_t i, std::size_t n, double dk) noexcept {
    return i <= n / 2 ? static_cast<double>(i) * dk : -static_cast<double>(n - i) * dk;
}

/// W dKx dKy for grid mode (i, j) of an nx x ny grid. Modes on a Nyquist line (index n/2 of an even
/// axis) alias +K and -K; they take the mean of W at both, which makes the value symmetric under
/// (i, j) -> (-i, -j) as Hermitian symmetry needs. 0 at K = 0.
[[nodiscard]] inline double mode_variance(const directional_density& w, std::size_t i, std::size_t j, std::size_t nx,
                                          std::size_t ny, double dkx, double dky) noexcept {
    if (i == 0 && j == 0) return 0.0;
    const double kx = wavenumber(i, nx, dkx);
    const double ky = wavenumber(j, ny, dky);
    const bool nyq_x = nx % 2 == 0 && i == nx / 2;
    const bool nyq_y = ny % 2 == 0 && j == ny / 2;
    double d = 0.0;
    if (nyq_x && nyq_y)
        d = w(kx, ky); // self-conjugate: any alias will do
    else if (nyq_x)
        d = 0.5 * (w(kx, ky) + w(-kx, ky));
    else if (nyq_y)
        d = 0.5 * (w(kx, ky) + w(kx, -ky));
    else
        d = w(kx, ky);
    return d * dkx * dky;
}

/// Random deviates one mode draws from each generator: two normals for a Gaussian mode, one for a self-conjugate
/// Gaussian one (real), and one uniform for a random-phase mode (its phase) or a self-conjugate one (its sign).
[[nodiscard]] inline std::size_t mode_deviates(bool gaussian, bool self_conjugate) noexcept {
    return gaussian && !self_conjugate ? 2 : 1;
}

/// One mode's random coefficient of variance `var` from its deviates `d` (mode_deviates of them, drawn as
/// generator.normal() for Gaussian amplitudes, generator.uniform() otherwise): real for a self-conjugate mode.
[[nodiscard]] inline std::complex<double> mode_coefficient(double var, bool self_conjugate, bool gaussian,
                                                           const double* d) noexcept {
    if (self_conjugate) return {std::sqrt(var) * (gaussian ? d[0] : (d[0] < 0.5 ? -1.0 : 1.0)), 0.0};
    if (gaussian) {
        const double sd = std::sqrt(0.5 * var);
        return {sd * d[0], sd * d[1]};
    }
    return std::polar(std::sqrt(var), two_pi_v<double> * d[0]);
}

/// A mode (i, j) and its Hermitian partner (pi, pj) = (-i mod nx, -j mod ny), with their flat indices
/// own = j nx + i and partner = pj nx + pi of the row-major nx x ny grid.
struct mode_pair {
    std::size_t i, j, pi, pj, own, partner;
};

/// Draws Hermitian-symmetric random coefficients of the spectrum for an nx x ny grid in the fixed order (rows of
/// modes, each mode with its partner), from every generator of `gens` in step (each generator draws the same
/// sequence as alone), calling store(m, v) with the mode_pair m and v[k] from gens[k] for each pair
/// (m.partner == m.own for a self-conjugate mode, v then real): the caller sets c[own] = v and
/// c[partner] = conj(v), or combines them. Returns the sum of the modes' variances, the band variance of the grid.
///
/// Work: the rows go in chunks, each in three stages: (a) the generators draw, in the fixed order (for Gaussian
/// amplitudes only the polar method's uniform pairs, rng::draw_polar_pairs); (b) the pairs become normal
/// deviates (rng::polar_normals); (c) the rows' spectral densities and coefficients are evaluated and stored.
/// The stages of successive chunks overlap on the threads of shared_thread_pool() (a of one chunk, b of the one
/// before, c of the one before that), so the sequential draws cost little more than their share: `store` is
/// called concurrently for different pairs (each element of the spectrum belongs to one pair). The
/// coefficients, and the band variance (summed in the fixed order), are those of drawing mode by mode, bit for
/// bit.
template <Real T, std::size_t N, class Store>
double draw_coefficients(std::size_t nx, std::size_t ny, double cell_m, const fractal_params<T>& p,
                         std::array<rng*, N> gens, Store&& store) {
    const double dkx = two_pi_v<double> / (static_cast<double>(nx) * cell_m);
    const double dky = two_pi_v<double> / (static_cast<double>(ny) * cell_m);
    const directional_density w = make_density(p);
    const bool gaussian = p.amplitudes == spectral_amplitudes::gaussian;
    thread_pool& pool = shared_thread_pool();
    const unsigned threads = nx * ny >= (std::size_t(1) << 16) ? 0u : 1u; // small grids are not worth a thread
    // Mode (i, j) is drawn with its partner (-i, -j) when the partner's flat index is not below its own.
    const auto mirror = [](std::size_t i, std::size_t n) { return i == 0 ? i : n - i; }; // -i mod n
    const std::size_t chunk_rows = std::min(ny, std::max<std::size_t>(1, (std::size_t(1) << 16) / nx));
    const std::size_t chunks = (ny + chunk_rows - 1) / chunk_rows;
    constexpr std::size_t piece = 8192; // deviates per task of stage b (even)

    struct chunk {
        std::size_t j0 = 0, rows = 0, pieces = 0;
        std::vector<std::size_t> deviate_at;      // first deviate of each row, and the total
        std::array<std::vector<double>, N> deviates;
        std::array<rng::polar_span, N> pairs{};
        std::vector<double> contribution;         // each mode's share of the band variance, 0 if not drawn
    };
    std::array<chunk, 3> buffers; // chunk c lives in buffers[c % 3]

    const auto draw = [&](std::size_t c) { // stage a: sequential
        chunk& b = buffers[c % 3];
        b.j0 = c * chunk_rows;
        b.rows = std::min(chunk_rows, ny - b.j0);
        b.deviate_at.assign(b.rows + 1, 0);
        for (std::size_t r = 0; r < b.rows; ++r) {
            const std::size_t j = b.j0 + r, pj = mirror(j, ny);
            std::size_t count = 0;
            for (std::size_t i = 0; i < nx; ++i) {
                const std::size_t own = j * nx + i, partner = pj * nx + mirror(i, nx);
                if (partner >= own) count += mode_deviates(gaussian, partner == own);
            }
            b.deviate_at[r + 1] = b.deviate_at[r] + count;
        }
        for (std::size_t k = 0; k < N; ++k) {
            b.deviates[k].resize(b.deviate_at[b.rows]);
            if (gaussian)
                b.pairs[k] = gens[k]->draw_polar_pairs(b.deviates[k]);
            else
                for (double& d : b.deviates[k]) d = gens[k]->uniform();
        }
        b.pieces = gaussian ? (b.deviate_at[b.rows] + piece - 1) / piece : 0;
    };
    const auto transform = [&](std::size_t c, std::size_t task) { // stage b: one piece of one generator's pairs
        chunk& b = buffers[c % 3];
        const std::size_t k = task / b.pieces;
        const std::size_t at = b.pairs[k].begin + (task % b.pieces) * piece;
        if (at < b.pairs[k].end)
            rng::polar_normals(std::span<double>(b.deviates[k]).subspan(at, std::min(piece, b.pairs[k].end - at)));
    };
    const auto evaluate = [&](std::size_t c, std::size_t r) { // stage c: one row
        chunk& b = buffers[c % 3];
        const std::size_t j = b.j0 + r, pj = mirror(j, ny);
        std::size_t d = b.deviate_at[r];
        std::array<std::complex<double>, N> v;
        for (std::size_t i = 0; i < nx; ++i) {
            const std::size_t pi_ = mirror(i, nx);
            const mode_pair m{i, j, pi_, pj, j * nx + i, pj * nx + pi_};
            double& share = b.contribution[r * nx + i];
            share = 0.0;
            if (m.partner < m.own) continue; // set together with its partner
            const bool self = m.partner == m.own;
            const double var = mode_variance(w, i, j, nx, ny, dkx, dky);
            share = self ? var : 2.0 * var;
            for (std::size_t k = 0; k < N; ++k)
                v[k] = mode_coefficient(var, self, gaussian, b.deviates[k].data() + d);
            d += mode_deviates(gaussian, self);
            store(m, v);
        }
    };

    for (chunk& b : buffers) b.contribution.resize(chunk_rows * nx);
    double band = 0.0;
    for (std::size_t c = 0; c < chunks + 2; ++c) {
        // Tasks of this step: [draw chunk c] [transform chunk c - 1] [evaluate chunk c - 2], each where it exists.
        const std::size_t n_draw = c < chunks ? 1 : 0;
        const std::size_t n_transform = c >= 1 && c - 1 < chunks ? N * buffers[(c - 1) % 3].pieces : 0;
        const std::size_t n_evaluate = c >= 2 && c - 2 < chunks ? buffers[(c - 2) % 3].rows : 0;
        pool.for_each(
            n_draw + n_transform + n_evaluate,
            [&](std::size_t task) {
                if (task < n_draw)
                    draw(c);
                else if (task < n_draw + n_transform)
                    transform(c - 1, task - n_draw);
                else
                    evaluate(c - 2, task - n_draw - n_transform);
            },
            threads);
        if (n_evaluate > 0) {
            const chunk& b = buffers[(c - 2) % 3];
            for (std::size_t m = 0; m < b.rows * nx; ++m) band += b.contribution[m];
        }
    }
    return band;
}

} // namespace sss::seabed::detail

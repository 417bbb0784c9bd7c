#pragma once
/// \file
/// The line stage that turns mean power into a record's statistics: seabed speckle (receiver/speckle.hpp),
/// volume reverberation (receiver/volume_reverberation.hpp) and noise (receiver/noise.hpp), each optional.
///
/// The three add as complex amplitudes before detection, so sample k records
///
///     I_k = | s_k + sqrt(V_k) v_k + sqrt(N) n_k |^2,
///
/// s_k the seabed's speckled amplitude (E|s_k|^2 = the ray tracer's mean power; without speckle the real
/// sqrt(mean)), V_k the volume reverberation's mean power and N the noise power per sample, v_k and n_k unit
/// circular complex Gaussians. The noise is keyed by (seed, the ping's pose, side, sample), the volume's
/// scatterers likewise (the water column moves between pings); the seabed's by where they lie on the seabed.
/// Volume reverberation fills the beam's shell before the seabed's range and the part of it above the seabed beyond
/// (receiver/volume_reverberation.hpp: the simulator gives the beam). Its expectation is mean + V + N; every draw
/// is a function of the seed and what it belongs to, so a render gives the same bytes on any number of threads and
/// for any split of its pings.

#include <bit>
#include <complex>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/receiver/detail/counter_random.hpp"
#include "sss/receiver/line_stage.hpp"
#include "sss/receiver/noise.hpp"
#include "sss/receiver/speckle.hpp"
#include "sss/receiver/volume_reverberation.hpp"

namespace sss {

struct echo_statistics_params {
    std::uint64_t seed = 1;                          ///< another seed, other speckle and noise
    std::optional<speckle_params> speckle = speckle_params{}; ///< seabed speckle; none: the mean amplitude
    std::optional<noise_params> noise{};             ///< ambient and electronic noise; none: noiseless
    std::optional<volume_params> volume{};           ///< volume reverberation; none: a clear water column
};

class echo_statistics {
public:

    echo_statistics() : echo_statistics(echo_statistics_params{}) {}
    explicit echo_statistics(echo_statistics_params p) : p_(std::move(p)) {
        if (p_.speckle) speckle_ = seabed_speckle(*p_.speckle, p_.seed);
        if (p_.noise) p_.noise->validate();
        if (p_.volume) p_.volume->validate();
    }

    [[nodiscard]] const echo_statistics_params& params() const noexcept { return p_; }

    /// True when the simulator must say which material dominates each sample (a K shape per material).
    [[nodiscard]] bool needs_materials() const noexcept { return p_.speckle && !p_.speckle->k_shape_by_material.empty(); }
    /// True when the simulator must give its beam's elevation share: volume reverberation is cut by the seabed.
    [[nodiscard]] bool needs_beam() const noexcept { return p_.volume.has_value(); }

    /// Mean noise power per sample on the render's reference (0 without noise), in a line received with `received`
    /// (a compressed chirp's matched filter passes less: noise.hpp).
    [[nodiscard]] double noise_power_per_sample(double dt_s, double render_source_level_db,
                                                const pulse& received = pulse{}) const {
        if (!p_.noise) return 0.0;
        return noise_power(*p_.noise, dt_s, received) * std::pow(10.0, render_source_level_db / 10.0);
    }

    template <Real T> void process(std::vector<T>& line, const line_context<T>& ctx) const {
        const std::size_t n = line.size();
        std::vector<std::complex<double>> s;
        if (p_.speckle) {
            speckle_.amplitudes(line, ctx, s);
        } else {
            s.resize(n);
            for (std::size_t k = 0; k < n; ++k) s[k] = std::sqrt(std::max(0.0, double(line[k])));
        }
        if (p_.noise || p_.volume) {
            const auto& table = sss::detail::half_normal_table();
            const std::uint64_t ping = ping_key(ctx);
            const double noise = noise_power_per_sample(ctx.dt_s, ctx.source_level_db, ctx.pulse);
            const double sqrt_noise = std::sqrt(noise);
            const std::uint64_t noise_key = sss::detail::mix(ping, 0x0015eULL);
            const std::uint64_t volume_key = sss::detail::mix(ping, 0x7011eULL);
            const double sl = std::pow(10.0, ctx.source_level_db / 10.0);
            const double pulse_energy_s = p_.volume ? ctx.pulse.energy_s() : 0.0; // tau of c tau / 2
            // Psi: the parameter, or the beam's own; cut by the seabed beyond its range where the beam is known.
            double psi_sr = 0.0;
            if (p_.volume) {
                psi_sr = p_.volume->psi_sr > 0.0 ? p_.volume->psi_sr : ctx.beam ? ctx.beam->psi_sr : 0.0;
                sss::require(psi_sr > 0.0, "volume.psi_sr",
                             "is 0 (the beam's own) but the line comes without a beam: give Psi, or render with a simulator");
            }
            const double H = ctx.altitude_m, roll = double(ctx.pose.roll_rad);
            for (std::size_t k = 0; k < n; ++k) {
                if (p_.noise)
                    s[k] += sqrt_noise * std::complex<double>(sss::detail::complex_gaussian(sss::detail::mix(noise_key, k), table));
                if (p_.volume) {
                    const double r = 0.5 * ctx.c_mps * (double(k) + 0.5) * ctx.dt_s;
                    const double share = ctx.beam ? water_share(*ctx.beam, ctx.line_side, r, H, roll) : 1.0;
                    const double v = sl * volume_reverberation(*p_.volume, r, ctx.c_mps, pulse_energy_s, psi_sr * share);
                    s[k] += std::sqrt(v) * std::complex<double>(sss::detail::complex_gaussian(sss::detail::mix(volume_key, k), table));
                }
            }
        }
        for (std::size_t k = 0; k < n; ++k) line[k] = static_cast<T>(std::norm(s[k]));
    }

private:
    /// The ping and side, from the pose's bits: a key that no thread or call order changes.
    template <Real T> [[nodiscard]] std::uint64_t ping_key(const line_context<T>& ctx) const noexcept {
        std::uint64_t key = sss::detail::mix(p_.seed, 0x9179ULL);
        key = sss::detail::mix(key, std::bit_cast<std::uint64_t>(double(ctx.pose.time_s)));
        key = sss::detail::mix(key, std::bit_cast<std::uint64_t>(double(ctx.pose.position.x)));
        key = sss::detail::mix(key, std::bit_cast<std::uint64_t>(double(ctx.pose.position.y)));
        key = sss::detail::mix(key, std::bit_cast<std::uint64_t>(double(ctx.pose.position.z)));
        return sss::detail::mix(key, ctx.line_side == side::starboard ? 1U : 0U);
    }

    echo_statistics_params p_;
    seabed_speckle speckle_{};
};

static_assert(LineStage<echo_statistics, float> && LineStage<echo_statistics, double>);

} // namespace sss

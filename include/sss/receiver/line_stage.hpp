#pragma once
/// \file
/// Line stages: what the receiver does to a line after the time sampler has rendered its mean power.
///
/// A simulator's last template parameter names a stage; it is called once per ping and side with the line of
/// mean powers and the context below, and may rewrite the line in place (speckle, noise, gain, digitisation).
/// The default, `no_line_stage`, is never called: a simulator that asks for nothing pays nothing and renders
/// the mean power exactly as without stages.
///
///   | expression                          | meaning                                                    |
///   |-------------------------------------|------------------------------------------------------------|
///   | `st.process(line, ctx)` (const)     | rewrite `line` (std::vector<T>&, sample k over [k dt, (k+1) dt)) |
///   | `st.needs_materials()` (optional)   | true: `ctx.materials` names each sample's dominant material  |
///   | `st.needs_beam()` (optional)        | true: `ctx.beam` holds the line's side of the beam's elevation share |
///
/// A stage must give the same result for the same inputs whatever thread calls it (render runs pings in
/// parallel): randomness is keyed by what it belongs to (the seabed, the ping's pose), never drawn from a
/// generator's state.

#include <concepts>
#include <cstdint>
#include <span>
#include <tuple>
#include <utility>
#include <vector>

#include "sss/beam/elevation_share.hpp"
#include "sss/core/pose.hpp"
#include "sss/core/types.hpp"
#include "sss/receiver/pulse.hpp"

namespace sss {

/// What a line stage knows about the line it processes.
template <Real T> struct line_context {
    sss::pose<T> pose{};          ///< the ping's pose
    side line_side = side::port;  ///< which line
    double dt_s = 0.0;            ///< sample interval (s)
    double c_mps = 1500.0;        ///< reference sound speed turning two-way time into range (m/s)
    double altitude_m = 0.0;      ///< towfish height above the seabed straight below it (m)
    sss::pulse pulse{};           ///< transmitted pulse
    double source_level_db = 0.0; ///< the render's source level reference (receiver_params::source_level_db)
    std::span<const std::uint32_t> materials{}; ///< per sample, the material of its strongest echo: filled only
                                                ///< for a stage whose `needs_materials()` is true (else empty)
    const elevation_share* beam = nullptr; ///< the beam's Psi and its share in depression on this side (body frame):
                                           ///< given to a stage whose `needs_beam()` is true (else null)
};

/// A line stage (table above).
template <class St, class T>
concept LineStage = Real<T> && requires(const St& st, std::vector<T>& line, const line_context<T>& ctx) {
    st.process(line, ctx);
};

/// A stage that may ask the simulator which material's echo dominates each sample (`line_context::materials`),
/// e.g. to give each material its own speckle statistics: `needs_materials()` says whether it does (the
/// bookkeeping costs a little per ray tube, so it is done only then).
template <class St>
concept LineStageWithMaterials = requires(const St& st) {
    { st.needs_materials() } -> std::convertible_to<bool>;
};

/// A stage that may ask the simulator for its beam's elevation share (`line_context::beam`), e.g. for the volume
/// reverberation of the water above the seabed: `needs_beam()` says whether it does (the simulator tabulates it
/// once, when it is built).
template <class St>
concept LineStageWithBeam = requires(const St& st) {
    { st.needs_beam() } -> std::convertible_to<bool>;
};

/// The stage that does nothing, and is never called.
struct no_line_stage {
    template <Real T> void process(std::vector<T>&, const line_context<T>&) const noexcept {}
};

/// Stages applied in order: e.g. `line_chain<echo_statistics, tvg>` speckles and adds noise, then applies the
/// time-varied gain, as a receiver does.
template <class... Stages> class line_chain {
public:
    /// Asks for the materials when any of its stages does.
    [[nodiscard]] bool needs_materials() const {
        return std::apply([](const Stages&... st) { return (needs(st) || ...); }, stages_);
    }
    /// Asks for the beam when any of its stages does.
    [[nodiscard]] bool needs_beam() const {
        return std::apply([](const Stages&... st) { return (needs_beam_of(st) || ...); }, stages_);
    }

    line_chain() = default;
    explicit line_chain(Stages... stages) : stages_(std::move(stages)...) {}

    [[nodiscard]] const std::tuple<Stages...>& stages() const noexcept { return stages_; }

    template <Real T> void process(std::vector<T>& line, const line_context<T>& ctx) const {
        std::apply([&](const Stages&... st) { (st.process(line, ctx), ...); }, stages_);
    }

private:
    template <class St> [[nodiscard]] static bool needs(const St& st) {
        if constexpr (LineStageWithMaterials<St>) return bool(st.needs_materials());
        else return false;
    }
    template <class St> [[nodiscard]] static bool needs_beam_of(const St& st) {
        if constexpr (LineStageWithBeam<St>) return bool(st.needs_beam());
        else return false;
    }

    std::tuple<Stages...> stages_;
};

} // namespace sss

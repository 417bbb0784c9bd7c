#pragma once
/// \file
/// Ground truth per sample: what each sample of a rendered line saw, from the provenance of the echo energy and
/// the geometry of the shadows.
///
/// Per ping and side, the simulator's rays are traced twice through `simulator::trace` (its public visitor):
/// 1. through the scene: every tube of echo energy is spread over the samples the receiver shows it in (its two-way
///    times, smeared over the pulse: a burst's length, a Hann burst's echo peaking half of it after its arrival; a
///    compressed chirp's main lobe; detail::echo_smear), kept apart by the hit it came from: the seabed (by region and
///    material) and each object (by id). So a highlight covers the samples its echo shows in, and a shadow starts
///    where the echo before it has died away. render_labelled takes these echoes from the trace that renders the
///    image (simulator::ping with an observer), so image and labels cost two traces, not three;
/// 2. through the seabed alone (`scene.seabed()`), with the rays of the first pass (`simulator::trace_seabed_alone`:
///    the same launch angles, which follow the top of the seabed and of the objects the side can reach): the echo
///    the seabed would return if no object were there.
///    For each such tube, the ray of its first end (`tube_echo::launch`) is traced again through the objects alone,
///    by the simulator's own propagation, up to the time it took to meet the seabed (`tube_echo::first_leg_s`): an
///    object it meets first blocks that energy, and the blocked energy is counted against that object. So shadows
///    follow the rays as they bend in refracting water, and are the straight-segment ones in isovelocity water.
///    (A bounced path is tested on its first leg, up to the bounce.) Where no object reaches over the side's area
///    (`simulator::side_area`), this pass
///    would trace the very rays and hits of the first, so it is not traced: its sums are the first pass's, bit for
///    bit. Nor is it where objects reach over the area but no ray of the first pass met one (behind the beam, beyond
///    the range, between the rays): the objects block nothing there that the image shows. Along a survey with sparse
///    targets most sides are such, and labels then cost little more than the image.
/// A sample is then, in this order:
/// - `highlight` of object k: k returns the largest share of the sample's echo energy among objects, and at
///   least `highlight_fraction` of it;
/// - `shadow` of object k: objects block at least `shadow_fraction` of the bare seabed's energy in the sample,
///   k the most;
/// - `seabed`: the seabed returns energy there (region and material of the largest contribution);
/// - `water_column`: before the first return of the bare seabed;
/// - `seabed_shadow`: after it and before its last direct return, but the bare seabed returns nothing there:
///   seabed that the seabed itself hides from the towfish (behind a ridge, in a ripple's trough). It carries the
///   region and material of the nearest lit seabed sample before it, the slope that casts it;
/// - `no_coverage`: anything else (beyond the last direct seabed return, or outside the beam; a bounced echo that
///   arrives later makes its own samples `seabed`, not the gap before them a shadow).
/// Labels share the waterfall's geometry (receiver/image.hpp): rows are pings, port mirrored on the left.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "sss/core/checked_size.hpp"
#include "sss/core/error.hpp"
#include "sss/core/hit.hpp"
#include "sss/core/pose.hpp"
#include "sss/core/ray.hpp"
#include "sss/core/render_control.hpp"
#include "sss/labels/detail/label_accumulator.hpp"
#include "sss/receiver/image.hpp"
#include "sss/scene/scene.hpp"
#include "sss/simulator.hpp"

namespace sss {

/// What a sample saw (values as written to label images).
enum class sample_class : std::uint8_t {
    no_coverage = 0,
    water_column = 1,
    seabed = 2,
    highlight = 3,
    shadow = 4,       ///< an object's
    seabed_shadow = 5 ///< the seabed's own (file comment)
};

/// The label of one sample.
struct sample_label {
    sample_class kind = sample_class::no_coverage;
    std::uint32_t object = no_object; ///< highlight, shadow: the object's id; else no_object
    std::uint32_t label = 0;          ///< highlight, shadow: the object's class id; seabed, seabed_shadow: region id; else 0
    std::uint32_t material = 0;       ///< highlight, seabed: the material of the largest echo; seabed_shadow: of the lit
                                      ///< seabed before it; else 0

    friend bool operator==(const sample_label&, const sample_label&) = default;
};

/// Labels in the waterfall's geometry: pings x (2 samples), port mirrored on the left.
struct label_image {
    std::size_t pings = 0;
    std::size_t samples = 0; ///< per side
    double dt_s = 0.0;
    std::vector<sample_label> values;

    [[nodiscard]] std::size_t width() const noexcept { return 2 * samples; }
    [[nodiscard]] const sample_label& at(std::size_t ping, std::size_t column) const noexcept { return values[ping * width() + column]; }
};

/// Thresholds of the classification (see the file comment).
struct label_params {
    double highlight_fraction = 0.5; ///< an object's least share of a sample's echo energy to label it, in (0, 1]
    double shadow_fraction = 0.5;    ///< least share of the bare seabed's energy blocked for a shadow, in (0, 1]
    unsigned threads = 0;            ///< label_render: pings labelled on this many threads (0: hardware concurrency)
};

} // namespace sss

namespace sss {

namespace detail {

/// The objects of a scene as a Scene of their own, without a seabed: the labels' second pass traces the bare
/// seabed's rays through them to find what blocks each ray (file comment).
template <Real T> struct objects_alone {
    using value_type = T;
    const scene::object_set<T>* objects = nullptr;
    T top = -std::numeric_limits<T>::infinity(); ///< world z above which no object the rays can reach rises (m)

    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max_m) const noexcept {
        return objects->intersect(r, t_max_m);
    }
    [[nodiscard]] T seabed_height_m(T, T) const noexcept { return -std::numeric_limits<T>::infinity(); }
    [[nodiscard]] T top_m() const noexcept { return top; }
    [[nodiscard]] T clear_length_m(const ray<T>& r, T t_max_m, T band_m) const noexcept {
        return objects->clear_length_m(r, t_max_m, band_m);
    }
};

/// True for a piece of a direct path's echo: its two-way time at its first end is twice that end's one-way time (the
/// simulator computes both from one traced time); a bounced path's is longer by its second leg.
template <Real T> [[nodiscard]] bool direct_echo(const tube_echo<T>& e) noexcept {
    return e.t0_s <= 2.0 * double(e.first_leg_s) * (1.0 + 1e-9);
}

/// The first pass (file comment): one piece of the scene's echo, kept apart by the hit it came from.
template <Real T> void label_scene_echo(label_accumulator& acc, const tube_echo<T>& e) {
    if (e.surface.object != no_object) acc.met_object = true; // even without echo power: a dark object casts shadows
    if (!(e.power > 0.0)) return;
    const hit<T>& h = e.surface;
    if (h.object == no_object) {
        acc.first_seabed_s = std::min(acc.first_seabed_s, std::min(e.t0_s, e.t1_s));
        if (direct_echo(e)) acc.last_seabed_s = std::max(acc.last_seabed_s, std::max(e.t0_s, e.t1_s));
        acc.spread(e.t0_s, e.t1_s, [&](std::size_t k, double share) {
            if (acc.add(acc.seabed, acc.seabed_best, k, share * e.power)) {
                acc.seabed_region[k] = h.label;
                acc.seabed_material[k] = h.material;
            }
        });
    } else {
        const std::size_t s = acc.slot(h.object, h.label);
        acc.spread(e.t0_s, e.t1_s, [&](std::size_t k, double share) {
            if (acc.add(acc.echo[s], acc.best_echo[s], k, share * e.power)) acc.echo_material[s][k] = h.material;
        });
    }
}

inline void check_label_params(const label_params& lp) {
    sss::require(lp.highlight_fraction > 0.0 && lp.highlight_fraction <= 1.0, "label_params.highlight_fraction", "must lie in (0, 1]");
    sss::require(lp.shadow_fraction > 0.0 && lp.shadow_fraction <= 1.0, "label_params.shadow_fraction", "must lie in (0, 1]");
}

/// True when the second pass would trace exactly what the first traced: both launch the same rays
/// (simulator::trace_seabed_alone), and where no object reaches over the side's area the first pass asked the
/// seabed alone (scene/area_view.hpp). Then nothing is blocked, and the bare seabed's echo is the scene's, sum for
/// sum. (finish_labels also takes the first pass's sums where objects reach over the area but no ray met one.)
template <class Sim, class Seabed>
[[nodiscard]] bool bare_pass_repeats_first(const Sim& sim, const scene::scene<Seabed>& sc, const pose<typename Sim::value_type>& p,
                                           side sd) {
    const auto area = sim.side_area(p, sd);
    return area.has_value() && !std::isfinite(sc.objects().top_m(area->lo, area->hi));
}

/// The second pass (the bare seabed, and what the objects block of it) over the first pass's `acc`, and the
/// labels. Where the second pass would repeat the first (bare_pass_repeats_first), its sums are the first's.
template <class Sim, class Seabed>
[[nodiscard]] std::vector<sample_label> finish_labels(const Sim& sim, const scene::scene<Seabed>& sc,
                                                      const pose<typename Sim::value_type>& p, side sd,
                                                      label_accumulator& acc, const label_params& lp) {
    using T = typename Sim::value_type;
    const std::size_t n = acc.n;
    const auto& objects = sc.objects();
    // No ray of the first pass met an object: every ray reached the seabed (or nothing) as if the objects were not
    // there, so the bare seabed's echo is the scene's (the second pass would differ only where its own refinement
    // met an object the first pass's rays all missed, which no image shows either).
    if (!acc.met_object || bare_pass_repeats_first(sim, sc, p, sd)) {
        acc.bare = acc.seabed;
        acc.bare_best = acc.seabed_best;
        acc.bare_region = acc.seabed_region;
        acc.bare_material = acc.seabed_material;
        acc.first_bare_s = acc.first_seabed_s;
        acc.last_bare_s = acc.last_seabed_s;
    } else {
        // The objects as the side's rays see them: with the top of those over the side's area, as in the first pass.
        const auto area = sim.side_area(p, sd);
        const T area_top = area ? objects.top_m(area->lo, area->hi) : objects.top_m();
        const objects_alone<T> blockers{&objects, std::isfinite(area_top) ? area_top : objects.top_m()};
        constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
        // A bounced piece's ray is its direct piece's, just traced: its blocker is remembered.
        vec3<T> last_launch{};
        T last_leg_s = T(-1);
        std::size_t last_blocker = none;
        sim.trace_seabed_alone(sc, p, sd, [&](const tube_echo<T>& e) {
            if (!(e.power > 0.0)) return;
            const hit<T>& h = e.surface;
            acc.first_bare_s = std::min(acc.first_bare_s, std::min(e.t0_s, e.t1_s));
            if (direct_echo(e)) acc.last_bare_s = std::max(acc.last_bare_s, std::max(e.t0_s, e.t1_s));
            std::size_t blocker = none;
            if (!objects.empty() && e.first_leg_s > T(0)) {
                if (e.launch == last_launch && e.first_leg_s == last_leg_s) {
                    blocker = last_blocker;
                } else {
                    // Short of the seabed by a ten-thousandth, so that an object resting on it does not block its
                    // own contact point.
                    if (const auto o = sim.propagation().trace(ray<T>{p.position, e.launch}, blockers,
                                                               e.first_leg_s * T(0.9999)))
                        blocker = acc.slot(o->surface.object, o->surface.label);
                    last_launch = e.launch;
                    last_leg_s = e.first_leg_s;
                    last_blocker = blocker;
                }
            }
            acc.spread(e.t0_s, e.t1_s, [&](std::size_t k, double share) {
                const double w = share * e.power;
                if (acc.add(acc.bare, acc.bare_best, k, w)) {
                    acc.bare_region[k] = h.label;
                    acc.bare_material[k] = h.material;
                }
                if (blocker != none) acc.blocked[blocker][k] += w;
            });
        });
    }
    // The bare seabed's first and last echoes as the line shows them (smeared over the pulse).
    const double shown_first_s = acc.smear != nullptr
                                     ? acc.first_bare_s - acc.smear->delay_s() + acc.smear->window_begin_s()
                                     : acc.first_bare_s;
    const double shown_last_s = acc.smear != nullptr
                                    ? acc.last_bare_s - acc.smear->delay_s() + acc.smear->window_end_s()
                                    : acc.last_bare_s;
    std::vector<sample_label> out(n);
    std::size_t lit = n; // the last sample before k that the bare seabed lights (n: none yet)
    for (std::size_t k = 0; k < n; ++k) {
        sample_label& l = out[k];
        if (k > 0 && acc.bare[k - 1] > 0.0) lit = k - 1;
        double total = acc.seabed[k], best = 0.0, blocked = 0.0, most_blocked = 0.0;
        std::size_t top = 0, shade = 0;
        for (std::size_t s = 0; s < acc.ids.size(); ++s) {
            total += acc.echo[s][k];
            blocked += acc.blocked[s][k];
            if (acc.echo[s][k] > best) { best = acc.echo[s][k]; top = s; }
            if (acc.blocked[s][k] > most_blocked) { most_blocked = acc.blocked[s][k]; shade = s; }
        }
        if (best > 0.0 && best >= lp.highlight_fraction * total) {
            l = {sample_class::highlight, acc.ids[top], acc.classes[top], acc.echo_material[top][k]};
        } else if (acc.bare[k] > 0.0 && blocked >= lp.shadow_fraction * acc.bare[k]) {
            l = {sample_class::shadow, acc.ids[shade], acc.classes[shade], 0};
        } else if (acc.seabed[k] > 0.0) {
            l = {sample_class::seabed, no_object, acc.seabed_region[k], acc.seabed_material[k]};
        } else if (acc.bare[k] > 0.0) { // lit in the bare seabed, unlit here, too little blocked for a shadow
            l = {sample_class::seabed, no_object, acc.bare_region[k], acc.bare_material[k]};
        } else if (double(k + 1) * acc.dt <= shown_first_s) {
            l = {sample_class::water_column, no_object, 0, 0};
        } else if (double(k) * acc.dt < shown_last_s && lit != n) {
            l = {sample_class::seabed_shadow, no_object, acc.bare_region[lit], acc.bare_material[lit]};
        }
    }
    return out;
}

/// Row i of img from one ping's port and starboard labels (near range first), port mirrored on the left.
inline void set_label_row(label_image& img, std::size_t i, const std::vector<sample_label>& port,
                          const std::vector<sample_label>& starboard) {
    sample_label* row = img.values.data() + i * img.width();
    for (std::size_t k = 0; k < img.samples; ++k) {
        row[img.samples - 1 - k] = port[k];
        row[img.samples + k] = starboard[k];
    }
}

} // namespace detail

/// The labels of one side of one ping (see the file comment): `samples_per_line()` labels, near range first.
template <class Sim, class Seabed>
[[nodiscard]] std::vector<sample_label> label_line(const Sim& sim, const scene::scene<Seabed>& sc, const pose<typename Sim::value_type>& p,
                                                   side sd, const label_params& lp = {}) {
    using T = typename Sim::value_type;
    detail::check_label_params(lp);
    const detail::echo_smear shown(sim.receiver().pulse);
    detail::label_accumulator acc(sim.samples_per_line(), sim.dt_s(), &shown);
    sim.trace(sc, p, sd, [&](const tube_echo<T>& e) { detail::label_scene_echo(acc, e); });
    return detail::finish_labels(sim, sc, p, sd, acc, lp);
}

/// The labels of pings [first, first + count) at the simulator's motion poses, in the waterfall's geometry, on
/// `lp.threads` threads (the result does not depend on their number).
template <class Sim, class Seabed>
[[nodiscard]] label_image label_render(const Sim& sim, const scene::scene<Seabed>& sc, std::size_t first, std::size_t count,
                                       const label_params& lp = {}) {
    detail::check_label_params(lp);
    sss::require(count <= std::numeric_limits<std::size_t>::max() - first, "render.first", "first + count overflows the ping index");
    label_image img;
    img.pings = count;
    img.samples = sim.samples_per_line();
    img.dt_s = sim.dt_s();
    img.values.resize(checked_elements(count, img.width(), "render.count"));
    // On the shared pool, one ping at a time per thread, as render (the rows do not depend on the threads).
    run_pings(count, render_control{.threads = lp.threads}, [&](std::size_t i) {
        const auto p = sim.motion().pose_at(first + i);
        detail::set_label_row(img, i, label_line(sim, sc, p, side::port, lp), label_line(sim, sc, p, side::starboard, lp));
    });
    return img;
}

/// A waterfall and its labels, rendered together (render_labelled).
template <Real T> struct labelled_waterfall {
    waterfall<T> image;
    label_image labels;
};

namespace detail {

/// Ping `ping`'s image and labels, into row `row` of `out` (sized for it): render_labelled's work for one ping, one
/// trace per side for both.
template <class Sim, class Seabed>
void labelled_ping(const Sim& sim, const scene::scene<Seabed>& sc, std::size_t ping, std::size_t row,
                   labelled_waterfall<typename Sim::value_type>& out, const label_params& lp) {
    using T = typename Sim::value_type;
    const std::size_t n = sim.samples_per_line();
    const echo_smear shown(sim.receiver().pulse);
    label_accumulator port(n, sim.dt_s(), &shown), starboard(n, sim.dt_s(), &shown);
    out.image.set_row(row, sim.ping(sc, ping, [&](side sd, const tube_echo<T>& e) {
        label_scene_echo(sd == side::port ? port : starboard, e);
    }));
    const auto p = sim.motion().pose_at(ping);
    set_label_row(out.labels, row, finish_labels(sim, sc, p, side::port, port, lp),
                  finish_labels(sim, sc, p, side::starboard, starboard, lp));
}

} // namespace detail

/// simulator::render and label_render of pings [first, first + count) in one pass: each side of each ping is
/// traced once through the scene, and its echoes make both the line and the labels' first pass (file comment);
/// only the bare seabed's pass is traced again. The image is the one sim.render(sc, first, count, control) returns
/// and the labels those of label_render(sim, sc, first, count, lp), to the bit; threads, pool, progress and
/// cancellation follow `control` as in render (lp.threads is not used). For a scene with objects this saves one of
/// the three traces per side that render and label_render make between them.
template <class Sim, class Seabed>
[[nodiscard]] labelled_waterfall<typename Sim::value_type> render_labelled(const Sim& sim, const scene::scene<Seabed>& sc,
                                                                           std::size_t first, std::size_t count,
                                                                           const render_control& control = {},
                                                                           const label_params& lp = {}) {
    using T = typename Sim::value_type;
    detail::check_label_params(lp);
    sss::require(count <= std::numeric_limits<std::size_t>::max() - first, "render.first", "first + count overflows the ping index");
    labelled_waterfall<T> out;
    const std::size_t n = sim.samples_per_line();
    out.image.pings = out.labels.pings = count;
    out.image.samples = out.labels.samples = n;
    out.image.dt_s = out.labels.dt_s = sim.dt_s();
    out.image.values.assign(checked_elements(count, out.image.width(), "render.count"), T(0));
    out.labels.values.resize(out.image.values.size());
    run_pings(count, control, [&](std::size_t i) { detail::labelled_ping(sim, sc, first + i, i, out, lp); });
    return out;
}

/// Labels on a ground-range grid, by the flat-bottom mapping: ground cell j of width `cell_m` (centre
/// y = (j + 1/2) cell_m) takes the label of the slant-range sample at r = sqrt(y^2 + H^2), H the towfish's
/// altitude at that ping (`altitude_m[i]`, m), r in samples of c dt / 2 (`sound_speed_mps`, m/s). Columns: `cells`
/// per side, port mirrored on the left as in the slant-range image. A cell takes the sample whose centre is nearest
/// (k = floor(r)); cells beyond the last sample's centre (r - 1/2 > samples - 1), where the ground-range image
/// (receiver/ground_range.hpp, interpolating between sample centres) has no value, are no_coverage, so that labels
/// and image cover the same cells. Every cell is seabed by construction, so a cell whose sample is water column
/// (seabed between nadir and the first return: a beam that does not reach steep angles) is no_coverage too.
struct ground_range_params {
    double cell_m = 0.05;            ///< ground-range cell (m), > 0
    std::size_t cells = 0;           ///< cells per side; 0: enough for the slant range at zero altitude
    double sound_speed_mps = 1500.0; ///< (m/s), > 0
};

[[nodiscard]] inline label_image ground_range_labels(const label_image& slant, const std::vector<double>& altitude_m,
                                                     const ground_range_params& g) {
    sss::require_positive(g.cell_m, "ground_range_params.cell_m");
    sss::require_positive(g.sound_speed_mps, "ground_range_params.sound_speed_mps");
    sss::require_positive(slant.dt_s, "label_image.dt_s");
    sss::require(slant.samples <= std::numeric_limits<std::size_t>::max() / 2 &&
                     slant.values.size() == checked_elements(slant.pings, 2 * slant.samples, "label_image.values"),
                 "label_image.values", "must hold pings x 2 x samples labels");
    sss::require(altitude_m.size() == slant.pings, "altitude_m", "must hold one altitude per ping");
    // An infinite altitude (no seabed under the towfish) leaves its row no_coverage, as the image's is empty.
    for (const double h : altitude_m)
        sss::require(h >= 0.0, "altitude_m", [&] { return "must be >= 0 (or +infinity), got " + std::to_string(h); });
    const double dr = 0.5 * g.sound_speed_mps * slant.dt_s;
    label_image out;
    out.pings = slant.pings;
    out.dt_s = slant.dt_s;
    if (g.cells != 0) {
        out.samples = g.cells;
    } else {
        const double cells = std::ceil(double(slant.samples) * dr / g.cell_m);
        sss::require(cells < double(max_elements), "ground_range_params.cell_m",
                     "gives more cells than a label image can hold");
        out.samples = static_cast<std::size_t>(cells);
    }
    sss::require(out.samples <= std::numeric_limits<std::size_t>::max() / 2, "ground_range_params.cells",
                 "overflows the size type");
    out.values.resize(checked_elements(out.pings, out.width(), "ground_range_params.cells"));
    const auto on_ground = [](const sample_label& l) { return l.kind == sample_class::water_column ? sample_label{} : l; };
    for (std::size_t i = 0; i < out.pings; ++i) {
        const double h = altitude_m[i];
        for (std::size_t j = 0; j < out.samples; ++j) {
            const double y = (double(j) + 0.5) * g.cell_m;
            const double r = std::sqrt(y * y + h * h) / dr;
            if (!(r - 0.5 <= double(slant.samples) - 1.0)) continue; // as to_ground_range: past the last centre
            const double k = std::floor(r);
            const auto s = static_cast<std::size_t>(k);
            out.values[i * out.width() + out.samples - 1 - j] = on_ground(slant.at(i, slant.samples - 1 - s));
            out.values[i * out.width() + out.samples + j] = on_ground(slant.at(i, slant.samples + s));
        }
    }
    return out;
}

} // namespace sss

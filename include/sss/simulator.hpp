#pragma once
/// \file
/// The simulator: composes scattering, propagation, beam and motion policies into sidescan pings.
///
/// Per ping and side: motion gives the pose; the beam's volume is cut into along-track columns and each
/// column into depression angles spaced evenly in nominal return time (sampling/launch_angles.hpp: over the level
/// seabed under the towfish, or where the seabed slopes across the line a plane fitted to it, sloping_launch); each
/// column's rays are propagated to the scene together (sss::trace_all: a propagation policy or scene with a batch
/// method shares work among them, others go ray by ray); each ray's return power per unit depression angle is
///
///     I = SL b(along, e) sigma(theta) S_out S_back A_1^2 dOmega_col / (S_out sin theta_g)
///       = SL b sigma S_back A_1^2 dOmega_col / sin theta_g,
///
/// i.e. source level x two-way beam weight x two-way loss (spreading out and back, absorption A_1 squared) x
/// scattering cross section x footprint area (the outgoing ray tube's cross-section 1/S_out per steradian,
/// spread over the facet by 1/sin of the angle between ray and facet). S_back is the propagation's `spreading`. Adjacent rays on the same surface form a tube whose
/// energy, integrated by the trapezoid rule over depression, is spread evenly over the two-way times between
/// their returns; the time sampler then convolves with the pulse and averages over each sample exactly
/// (receiver/time_sampler.hpp). Where two adjacent rays are not neighbours on one surface (an occlusion, an
/// object's silhouette), the launch angle between them is bisected until the edge is located to 1/16 of a sample,
/// and where the surface's echo changes too fast between them until the tubes span half a sample (an eighth across
/// the seabed's facets' edges: ray_density.refine_facets) (sampling/detail/tube_refinement.hpp):
/// each side of an edge then keeps its energy up to it, and shadows stay empty (with a GuidedPropagation each new
/// ray is traced beside the steeper of the two, whose first hit it cannot meet anything of the seabed before:
/// scene/height_field_beside.hpp; the same hits, sooner). Where a column's objects' edges
/// disagree with a neighbour's (an edge crossing the beam obliquely), the launch angles between the disagreeing
/// edges are traced again as narrower columns, in thirds where they still disagree (ray_density.along_split, deeper
/// where the beam weights a column more: sampling/division_depths.hpp; the seabed's own shadow edges too with
/// ray_density.along_split_seabed; the narrowest at every other launch angle: ray_density.along_split_sparse), and
/// so are the columns over a small target (narrower than three columns, or a piece of a thin cylinder oblique to
/// them), which two columns passing either side of it would both miss, and within a column two rays either side of
/// it (sampling/target_spans.hpp; ray_density.along_split_targets), and near the first return, over a seabed that is not
/// one plane there, every column, and over a plane the columns across which the first return moves by more than a
/// fraction of a sample (ray_density.along_split_nadir). On an open flat seabed under a beam a few degrees wide along
/// track and a level towfish nothing is refined and the line is unchanged.
/// The result is the mean received power in each time sample, relative to the source level reference.
/// An optional line stage (last template parameter, receiver/line_stage.hpp) then rewrites each line: speckle,
/// noise and the water column (receiver/echo_statistics.hpp). The default stage is never called.

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <optional>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "sss/beam/concept.hpp"
#include "sss/beam/ideal_fan.hpp"
#include "sss/core/decibel.hpp"
#include "sss/core/checked_size.hpp"
#include "sss/core/detail/force_inline.hpp"
#include "sss/core/error.hpp"
#include "sss/core/render_control.hpp"
#include "sss/core/thread_pool.hpp"
#include "sss/motion/concept.hpp"
#include "sss/motion/straight_line.hpp"
#include "sss/propagation/concept.hpp"
#include "sss/propagation/straight.hpp"
#include "sss/receiver/image.hpp"
#include "sss/receiver/line_stage.hpp"
#include "sss/receiver/receiver.hpp"
#include "sss/receiver/time_sampler.hpp"
#include "sss/sampling/column_edges.hpp"
#include "sss/sampling/detail/tube_refinement.hpp"
#include "sss/sampling/division_depths.hpp"
#include "sss/sampling/launch_angles.hpp"
#include "sss/sampling/reach.hpp"
#include "sss/sampling/target_spans.hpp"
#include "sss/scattering/concept.hpp"
#include "sss/scattering/lambertian.hpp"
#include "sss/scattering/specular_bounce.hpp"
#include "sss/scene/concept.hpp"
#include "sss/scene/area_view.hpp"

namespace sss {

/// How many rays a ping launches.
struct ray_density {
    std::size_t along = 8;         ///< along-track columns per side, at least (a beam may ask for more: Beam concept)
    /// Rays per column; 0: `per_sample` rays per time sample of the column's span. Either way a column has at least
    /// as many as `max_launch_step_deg` needs (a 40 deg fan: 41), and more where a step in range is over a twentieth
    /// of the range (sampling/launch_angles.hpp, column_density::max_range_step): near the towfish, or anywhere
    /// within 20 steps of it when a column has few rays.
    std::size_t across = 0;
    double per_sample = 1.0;       ///< rays per time sample when `across` is 0
    /// Refine across track where adjacent rays are not neighbours on one surface (an occlusion, an object's edge,
    /// the end of coverage): bisect the launch angle up to `refine_depth` times (0: never), and at most
    /// `refine_rays` extra rays per column, so that each side of the edge keeps its energy up to it
    /// (sampling/detail/tube_refinement.hpp). Where the echo changes fast between two rays on one surface (the seabed's
    /// facets' edges, a curved object's shading), and beside a located edge whose ray meets its facet near grazing
    /// incidence (so that its echo lies where that facet does), up to 8 times as many rays as the column has are spent
    /// apart from those (`refine_rays` bounds only the edges'), so that rough relief never leaves an edge unlocated;
    /// and as many as for edges, apart again, to halve launch intervals over small targets (along_split_targets).
    std::size_t refine_depth = 12;
    std::size_t refine_rays = 64;  ///< extra rays per column for edges at most, on top of half the column's own rays
    /// Refine across the seabed's facets' edges too (sampling/detail/tube_refinement.hpp): between two seabed rays on
    /// different plane facets whose echoes per radian differ by more than 5 %, down to an eighth of a sample, where
    /// the footprint jumps from one facet to the next. On the rippled survey of bench/bench_survey_accuracy.cpp it
    /// lowers the error against a converged render by about a third for a few % more time; an open flat seabed is
    /// unchanged bit for bit.
    bool refine_facets = true;
    /// Across a facet's edge (refine_facets), where halving the step would take more than three rays, trace the two
    /// just either side of where the edge lies instead: from the two facets' planes and the sheet of rays through
    /// their hits (sampling/detail/tube_refinement.hpp, facet_edge_crossing), once the seabed there shows that the two
    /// facets meet; where the two rays straddle an edge whose stretch jumps more than sixfold, that edge goes to the
    /// along-track check (with along_split_seabed), where halving would have located it as an edge by chance
    /// (facet_edge_marks_line). The tubes' tolerance is the same;
    /// on the 1 km survey of bench/bench_survey.cpp about 9 % fewer rays and 0.97 times the time per ping, for a
    /// little less error (71 lines: 0.175 against 0.188 dB RMS of their RMS, docs/design/along-track.md); false
    /// halves the step at every level.
    bool bracket_facet_edges = true;
    /// Where a column's located edges between surfaces (objects' silhouettes, against the seabed or against open water
    /// where the rays past them meet nothing within the line, and the far ends of their shadows) differ from a
    /// neighbour's (an edge crossing the beam obliquely), the stretch of the column between them is
    /// divided into thirds along track: the middle third is centred where the column is, so it keeps the column's
    /// rays and its share of their echo; the outer two are traced. A third whose edges still disagree with its
    /// neighbouring third's is divided again, down to columns 1/along_split as wide (rounded down to a power of
    /// three; below 3: never divided; at most 3^8). With `along_split_by_weight`, that is the depth for a column of
    /// even weight, and a beam whose pattern weights its columns unevenly shares it among them. On the survey of
    /// bench/bench_survey_accuracy.cpp, 9 takes about twice the time per line of 3 and about halves the 99th
    /// percentile of the error (the bench prints both).
    std::size_t along_split = 9;
    /// Share the along-track check's division among a side's columns by the beam's weight on each
    /// (sampling/division_depths.hpp): one level deeper per factor 9 of weight, normalised to the cost of dividing
    /// every column to 1/along_split, the heaviest at most one level deeper, every one at least into thirds, and none
    /// a level below the heaviest until its weight is a factor 9 below it. Under a beam that weights its columns alike
    /// (an ideal fan up to 150 degrees wide along track) nothing changes; under the survey's 100 kHz array the two
    /// columns on its axis and the two beside them go to 1/27, the six faint ones to thirds: on the 256 m copy of
    /// bench/bench_survey_accuracy.cpp that takes the worst line's 99th percentile error against a converged render
    /// from 2.5 to 0.9 dB for 1.3 times the time of even division (both with refine_facets), on the 1 km survey of
    /// bench/bench_survey.cpp from 2.6 to 2.1 dB for 1.2 times its time (docs/design/along-track.md).
    bool along_split_by_weight = true;
    /// The seabed's own shadow edges (behind crests, ridges, ripples) take part in the along-track check too:
    /// true, false, or (unset) where the columns are more than two range samples apart at the end of the line.
    /// There, an edge crossing the beam obliquely moves by more than a sample from one column to the next, and
    /// each column alone would put it where its centre sees it; where the columns are closer, the check costs
    /// rays and changes little (bench/bench_survey_accuracy.cpp and bench/bench_rough_accuracy.cpp measure both).
    std::optional<bool> along_split_seabed{};
    /// The last level of the along-track division traces every other launch angle of the column it divides: those
    /// narrow columns each carry a third (faint columns, or along_split = 3) to a 27th of their column's weight, so
    /// their tubes' errors across track average out over them, while along track they are what resolves the scene.
    /// Edges between such rays, two launch intervals apart, are judged so that a shadow the column's own spacing
    /// would reveal is revealed (the time gap need exceed the prediction only by twice one interval's,
    /// sampling/detail/tube_refinement.hpp), and located to the same fraction of a sample. On the 256 m copy of the survey (bench/bench_survey_accuracy.cpp) a fifth fewer rays for
    /// the same error, on the 1 km survey (bench/bench_survey.cpp) a tenth fewer and 0.92 times the time for 0.006 dB
    /// more RMS (docs/design/along-track.md); false traces every launch angle there too.
    bool along_split_sparse = true;
    /// A small target (a sphere or cylinder of the scene's objects whose launch angles span at most three columns
    /// along track, or a piece of a longer thin cylinder oblique to the columns, sampling/target_spans.hpp) divides
    /// the columns over it along track, over the launch intervals that can meet it, whatever their edges agree on,
    /// until the narrowest columns there are a quarter of its angular thickness wide (at most two levels past
    /// along_split's depth, 1/81 of a column by default): two columns whose launch cones pass either side of a target
    /// both miss it and agree, and it vanished from the line (a sphere 0.16 m across between cones 0.42 m apart), and a
    /// thin one (a cable, a tether) met by one narrow column is that column's width wide. Within a column, a launch
    /// interval over it wider than a fraction of its width in depression is halved, as for an edge: two rays on the seabed
    /// either side of a cable oblique to the track agree and step over it. Nothing changes where no object lies
    /// within the beam. Like the rest of the along-track check, it needs refinement (refine_depth > 0), along_split >= 3
    /// and at least two columns.
    bool along_split_targets = true;
    /// Near the first return (echoes that begin before the two-way time of a slant range of sqrt(2) times the towfish's
    /// altitude: 45 degrees from the vertical over a level seabed), a column over a seabed that is not one plane there
    /// is divided into thirds along track, whatever its edges agree on (deeper, to the column's depth, where the
    /// thirds' edges disagree). There the time along a column turns at every facet the rays meet square on (dt/de = 0,
    /// where the echo per sample peaks as a caustic, and Jackson's model its Kirchhoff term), each column at its own
    /// time: summed, a few columns make a comb of such peaks a sample or two apart that the along-track integral
    /// smooths, and no edge marks it. On the 1 km survey of bench/bench_survey.cpp (72 lines against a converged
    /// render) it takes the line of the worst 99th percentile from 0.45 to 0.15 dB RMS and 2.9 to 0.6 dB there, the RMS
    /// of the lines' RMS from 0.182 to 0.155 dB and the lines above 0.3 dB RMS or 1 dB at the 99th percentile from 9 to
    /// 5, no line worse, for about 3 % more time (docs/design/along-track.md). Where the line ends before that time (a
    /// range under 1.4 times the altitude) the whole of each column's launch intervals is divided so. A level or
    /// sloping plane seabed (its facets' normals agreeing to rounding: any plane in double; in float, heights within
    /// about 250 m of zero at 0.05 m cells, as for refine_facets) is divided only where one column's first return
    /// moves: a column across whose width the first return (over the plane its echoes lie on, along straight rays)
    /// moves by more than a quarter of a range sample, or where it holds the side's nearest first return a twentieth,
    /// or a quarter of the part of its first sample after its earliest onset if that is less, is divided into thirds
    /// from its earliest echo from the seabed for as long as that movement and two samples more (where the seabed's
    /// echoes there are one plane too), and the four launch intervals either side share its echo with its thirds' in
    /// even steps: each column's echo begins where its centre's first return lies, and just after it the echo rises as
    /// the square root of the time, so the column's first sample misstated the beam's. Under an ideal fan 20 degrees
    /// wide along track the first sample after the nadir time goes from 0.46 to 0.04 dB off the quadrature of the sonar
    /// equation, under 120 degrees from 0.73 dB (and 0.073 dB RMS over the line) to 0.03 dB (0.006 dB RMS), for 8 to 9
    /// % more rays at 30 m of range and 10 m altitude; under a beam a few degrees wide (the default fan, the default
    /// 100 kHz planar array) over a level plane and a level towfish 10 m up sampled at 20 kHz the line is the same bit
    /// for bit, but pitched or sampled finely such a beam's nearest columns divide too, and so they do over a plane
    /// sloping along track (0.15 across and 0.075 along, 4 degrees, water bending rays down: the first sample from 24
    /// dB low to 0.5 dB against 512 columns; docs/design/along-track.md). Like the rest of the along-track check, it
    /// needs refinement (refine_depth > 0), along_split >= 3 and at least two columns.
    bool along_split_nadir = true;
    /// Where a column's echo, sample by sample, departs from what its two neighbours' echoes make likely, the launch
    /// intervals that put echo into those samples are divided into thirds along track whatever the edges agree on
    /// (deeper, to the column's depth, where the thirds' edges disagree). Each column's echo per unit of the beam's
    /// weight on it is compared with the mean of its neighbours' (the one neighbour's at the side's ends); where the
    /// difference, times the column's weight, exceeds `along_split_echo` times the three columns' echo in that sample
    /// (a lower bound of the line there), the column's value is not its width's: the scene changes across it faster
    /// than linearly (a shadow ending in its outer part, a facet's glint). Only samples within 50 dB of the three
    /// columns' strongest are compared, and nothing where all three see one plane and nothing else (a level or
    /// sloping seabed is unchanged bit for bit by it). This catches what the edges miss: where
    /// the beam's axis columns are in shadow and the line is the faint columns of its skirts, an edge crossing one of
    /// them obliquely agrees within a sample with its neighbours' and left a step where the along-track integral
    /// ramps. Where such a faint column (one that along_split_by_weight divides less deeply than a column of even
    /// weight) departs in a sample where it carries more than a fifth of the line, those intervals divide to an even
    /// column's depth; the line there is the side's columns' first echoes summed, so under such a beam every column of
    /// the side (up to 64) is traced and held before any is divided. On the 1 km survey of bench/bench_survey.cpp (72
    /// lines against a converged render) 0.1 takes the RMS of the lines' RMS from 0.148 to 0.133 dB and the worst
    /// 99th percentile from 1.74 to 1.11 dB (300 port 0.23 to 0.11 dB RMS, 448 port 0.21 to 0.09, 900 starboard 0.21
    /// to 0.10), the shadow samples missed from 50 to 33, for 4.7 % more echo pieces and about 7 % more time
    /// (docs/design/along-track.md). It compares only where the columns are more than two range samples apart at the
    /// end of the line (where along_split_seabed takes part by default): closer, facet by facet the columns' echoes
    /// differ more than the line does (fractal relief under a fan 1 deg wide at 30 m, bench/bench_rough_accuracy.cpp:
    /// 1.5 times the rays for no less error). 0 switches it off. Like the rest of the along-track check, it needs
    /// refinement (refine_depth > 0), along_split >= 3 and at least two columns.
    double along_split_echo = 0.1;
    /// How far (in range samples) the first return over a level seabed may move across one along-track column near
    /// the nearest first return, a quarter of that where it turns within a column, and more farther out
    /// (sampling/column_edges.hpp): where it moves further (a beam wide along track), the columns there are
    /// narrower, up to 4096 per side. A column puts all it sees at its centre's times, so across a wide column the
    /// onset of the echo was one step where the beam's integral ramps (8 dB in single samples under a 1 mm element
    /// at 100 kHz; with this, 0.3 dB, for about 14 times the time per ping). Where the first return moves by less
    /// than half the tolerance across every even column, nothing changes, bit for bit: the survey's 100 kHz array
    /// under its towfish at 10 m (bench/bench_survey.cpp). A beam a few degrees wide narrows its columns under a
    /// pitched towfish at a high sample rate, and that is accuracy, not waste: the default 100 kHz planar array (5.6
    /// deg along track) sampled at 100 kHz over a level seabed, against the same simulator at 256 even columns, is
    /// 1.3 dB off in the first samples with even columns 10 m up at 10 deg of pitch and 0.11 dB with 24 columns (2.4
    /// times the time); 2.4 dB against 0.16 dB 30 m up at 5 deg (3.4 times). (Those figures leave along_split_nadir
    /// off; with it, which divides the columns near the first return over a plane, 0.10 and 0.06 dB at 10 deg.) A
    /// tolerance counted in pulse lengths rather than samples would keep those columns even, and the error: the first
    /// samples are a sum of few columns whose beam weights grow fast across the beam. 0: evenly spaced columns,
    /// whatever the beam's width.
    double along_onset = 1.0;
    /// Largest step (deg) between adjacent launch angles of a column across track. Rays are spaced evenly in
    /// nominal return time, so where the returns crowd together in range (close to the towfish's altitude, and
    /// everywhere when it is low) one tube can span many degrees, and its trapezoid misses how the beam, the
    /// scattering and the footprint change across it. Steps wider than this are divided evenly in angle (and steps
    /// in range wider than a twentieth of the range geometrically: column_density::max_range_step). Against the
    /// quadrature of the sonar equation over a level seabed, with neither rule, with the range's alone, and with
    /// both: a 20 to 60 deg fan 1 mm up, which returns within three samples, 17.5 % high in energy (2.2 dB in its
    /// samples), 0.03 %, 0.001 %; 0.5 m up, the worst sample 0.57, 0.13, 0.10 dB; 10 m up under a coarse receiver
    /// (134 samples over 100 m, a 5 to 55 deg fan), 0.44, 0.10, 0.02 dB. With both, a column 10 m up with 100 m of
    /// range has about 0.5 % more rays than with neither, one at 0.5 m about 3 %; the survey of
    /// bench/bench_survey.cpp, whose array's steepest rays have steps below a degree, renders the same bit for bit.
    /// 0: no cap.
    double max_launch_step_deg = 1.0;
    /// Launch a side's rays for a plane fitted to the seabed over the area they reach, with the clearance above what
    /// rises over that area, where that spaces them over much less range than the level seabed under the towfish with
    /// the clearance above the whole seabed's top (simulator::sloping_launch; only over a scene that bounds its rise
    /// above a plane, PlaneBoundedScene). Over the plane z = 0.15 (x + 0.5 y) of tests/seabed/test_rough_accuracy.cpp
    /// (64 m by 8 m, a towfish 10 m up, 30 m of range) the rays of a ping go from 20,432 to 7,128 (a level plane takes
    /// 6,880); over ripples on it (bench/bench_rough_accuracy.cpp, scene "slope") from 19,838 to 13,965, and the time
    /// from 6.3 to 4.7 ms, 0.045 dB RMS off the converged reference where it was 0.028. Over a field of 72 m by 24 m,
    /// with ripples, the time fell by 11 to 22 % (on a plane sloping 0.08, from 13 % more to 13 % less), the error
    /// within 0.06 dB of before at the 99th percentile either way. Where nothing rises near the line (a flat seabed),
    /// nothing changes; the 1 km survey of bench/bench_survey.cpp renders the same bit for bit.
    bool sloping_launch = true;
};

/// One piece of echo energy handed to a visitor of `simulator::trace`: the power of a ray tube (or of one
/// ray's half of a tube whose other end is missing or on another surface) spread evenly over two-way times
/// [t0_s, t1_s] (t0_s == t1_s for a point).
template <Real T> struct tube_echo {
    double t0_s{};       ///< two-way time at one end (s): the first, whose ray `surface`, `launch`, `first_leg_s` describe
    double t1_s{};       ///< two-way time at the other end (s)
    double power{};      ///< echo power (relative to the source level reference)
    hit<T> surface{};    ///< what the (first) end of the tube met: material, object, label
    vec3<T> launch{};    ///< unit launch direction (world) of the first end's ray, which leaves the pose's position
    T first_leg_s{};     ///< that ray's one-way time (s) to the first surface it met: `surface`, or a bounce's point
};

/// The echo observer of simulator::ping that does nothing: ping(scene, index) is ping(scene, index, no_echo_observer{}).
struct no_echo_observer {
    template <class Echo> constexpr void operator()(side, const Echo&) const noexcept {}
};

template <Scattering S = scattering::lambertian<double>, Propagation P = propagation::straight<double>,
          Beam B = beam::ideal_fan<double>, Motion M = motion::straight_line<double>, class Stage = no_line_stage>
class simulator {
public:
    using value_type = typename S::value_type;
    using T = value_type;
    static_assert(std::is_same_v<T, typename P::value_type> && std::is_same_v<T, typename B::value_type> &&
                      std::is_same_v<T, typename M::value_type>,
                  "sss::simulator: all policies must share one scalar type");
    static_assert(LineStage<Stage, T>, "sss::simulator: the line stage needs process(std::vector<T>&, const line_context<T>&) const");

    explicit simulator(S scattering = S{}, P propagation = P{}, B beam = B{}, M motion = M{},
                       receiver_params receiver = {}, ray_density density = {}, Stage stage = Stage{})
        : scattering_(std::move(scattering)), propagation_(std::move(propagation)), beam_(std::move(beam)),
          motion_(std::move(motion)), receiver_(receiver), density_(density), stage_(std::move(stage)) {
        receiver_.validate();
        sss::require(density_.along >= 1, "ray_density.along", "must be >= 1");
        sss::require(density_.along <= 4096, "ray_density.along", "must be <= 4096");
        sss::require(density_.across == 0 || density_.across >= 2, "ray_density.across", "must be 0 (automatic) or >= 2");
        if (density_.across == 0) sss::require_positive(density_.per_sample, "ray_density.per_sample");
        sss::require(density_.along_split <= 6561, "ray_density.along_split", "must be <= 6561 (3^8)");
        sss::require_non_negative(density_.along_split_echo, "ray_density.along_split_echo");
        sss::require_non_negative(density_.along_onset, "ray_density.along_onset");
        sss::require_non_negative(density_.max_launch_step_deg, "ray_density.max_launch_step_deg");
        c_ref_ = double(propagation_.reference_speed_mps());
        samples_ = receiver_.samples(c_ref_);
        sss::require(samples_ >= 1 && samples_ <= (std::size_t(1) << 26), "receiver.max_range_m",
                        [&] { return "gives " + std::to_string(samples_) + " samples per line; must be between 1 and 2^26"; });
        dt_ = 1.0 / receiver_.sample_rate_hz;
        sss::require(receiver_.pulse.length_s * receiver_.sample_rate_hz <= double(std::size_t(1) << 20),
                             "pulse.length_s", "spans more than 2^20 samples at receiver.sample_rate_hz");
        source_level_ = db_to_power(receiver_.source_level_db);
        sampler_ = time_sampler(samples_, dt_, receiver_.pulse);
        if constexpr (LineStageWithBeam<Stage>) {
            if (stage_.needs_beam())
                for (side sd : {side::port, side::starboard}) elevation_[sd == side::starboard ? 1 : 0] = elevation_share_of(beam_, sd);
        }
    }

    [[nodiscard]] const S& scattering() const noexcept { return scattering_; }
    [[nodiscard]] const P& propagation() const noexcept { return propagation_; }
    [[nodiscard]] const B& beam() const noexcept { return beam_; }
    [[nodiscard]] const M& motion() const noexcept { return motion_; }
    [[nodiscard]] const receiver_params& receiver() const noexcept { return receiver_; }
    [[nodiscard]] const ray_density& density() const noexcept { return density_; }
    [[nodiscard]] const Stage& stage() const noexcept { return stage_; }
    [[nodiscard]] std::size_t samples_per_line() const noexcept { return samples_; }
    [[nodiscard]] double dt_s() const noexcept { return dt_; }

    /// Renders ping `index`: one port and one starboard line. Throws invalid_parameter naming the ping when the
    /// towfish is not at least `min_clearance_m` above the seabed there (a sonar in or under the seabed records
    /// nothing meaningful).
    template <Scene Sc> [[nodiscard]] ping_lines<T> ping(const Sc& scene, std::size_t index) const {
        return ping(scene, index, no_echo_observer{});
    }

    /// ping, and `observe(side, const tube_echo<T>&)` called with every piece of echo as the lines gather it (the
    /// echoes `trace` visits), so that whatever else is built from them (labels: labels/ground_truth.hpp) needs no
    /// second trace. The lines are those of ping(scene, index).
    template <Scene Sc, class Observer>
    [[nodiscard]] ping_lines<T> ping(const Sc& scene, std::size_t index, Observer&& observe) const {
        static_assert(std::is_same_v<typename Sc::value_type, T>, "sss::simulator: scene scalar type differs");
        const pose<T> p = motion_.pose_at(index);
        const T seabed_z = scene.seabed_height_m(p.position.x, p.position.y);
        if (!(double(p.position.z) - double(seabed_z) >= min_clearance_m))
            throw invalid_parameter("ping[" + std::to_string(index) + "]",
                                    "the towfish at (" + std::to_string(p.position.x) + ", " +
                                        std::to_string(p.position.y) + ", " + std::to_string(p.position.z) +
                                        ") m is not at least 1 mm above the seabed (z = " + std::to_string(seabed_z) +
                                        " m)");
        return ping_at(scene, p, observe);
    }

    /// The least height of the towfish above the seabed under it for `ping` (m). Much closer, the nearest echoes'
    /// spreading (1/r^2) and footprint (r^2) leave the scalar's range (in float below about 1e-19 m), and their
    /// product is not a number.
    static constexpr double min_clearance_m = 1e-3;

    /// Renders one ping from an explicit pose.
    template <Scene Sc> [[nodiscard]] ping_lines<T> ping_at(const Sc& scene, const pose<T>& p) const {
        return ping_at(scene, p, no_echo_observer{});
    }

    /// ping_at, with an observer of the echoes as in ping(scene, index, observe).
    template <Scene Sc, class Observer>
    [[nodiscard]] ping_lines<T> ping_at(const Sc& scene, const pose<T>& p, Observer&& observe) const {
        time_sampler sampler = sampler_; // the pulse kernels are built once, in the constructor
        ping_lines<T> lines;
        lines.dt_s = dt_;
        for (side sd : {side::port, side::starboard}) {
            sampler.clear();
            std::vector<T>& line = sd == side::port ? lines.port : lines.starboard;
            if constexpr (LineStageWithMaterials<Stage>) {
                if (stage_.needs_materials()) {
                    std::vector<std::uint32_t> materials;
                    accumulate_with_materials(scene, p, sd, sampler, materials, observe);
                    sampler.render(line);
                    line_context<T> ctx = line_context_for(scene, p, sd);
                    ctx.materials = materials;
                    stage_.process(line, ctx);
                    continue;
                }
            }
            accumulate(scene, p, sd, sampler, observe);
            sampler.render(line);
            if constexpr (has_stage) stage_.process(line, line_context_for(scene, p, sd));
        }
        return lines;
    }

    /// Renders pings [first, first + count) into a waterfall, on `threads` threads (0: hardware concurrency), on
    /// the shared pool. The result does not depend on the number of threads.
    template <Scene Sc>
    [[nodiscard]] waterfall<T> render(const Sc& scene, std::size_t first, std::size_t count, unsigned threads = 0) const {
        return render(scene, first, count, render_control{.threads = threads});
    }

    /// Renders pings [first, first + count) into a waterfall as `control` says (core/render_control.hpp): threads
    /// take pings one at a time from a persistent pool (dynamic scheduling), a progress callback may cancel, and a
    /// stop flag stops the pings under way between columns (then render throws render_cancelled). The result does
    /// not depend on the number of threads or the pool.
    /// Throws invalid_parameter naming `render.count` when the image would hold more than sss::max_elements values
    /// (or `render.first` when first + count overflows), before anything is allocated.
    template <Scene Sc>
    [[nodiscard]] waterfall<T> render(const Sc& scene, std::size_t first, std::size_t count,
                                      const render_control& control) const {
        sss::require(count <= std::numeric_limits<std::size_t>::max() - first, "render.first",
                     "first + count overflows the ping index");
        waterfall<T> w;
        w.pings = count;
        w.samples = samples_;
        w.dt_s = dt_;
        w.values.assign(checked_elements(count, w.width(), "render.count"), T(0));
        run_pings(count, control, [&](std::size_t i) { w.set_row(i, ping(scene, first + i)); });
        return w;
    }

    /// Traces every ray of one side of one ping and calls `visit(const tube_echo<T>&)` for each piece of echo.
    /// With refinement on, where a column's located edges between surfaces (an object's silhouette, its shadow's
    /// far end: sampling/detail/tube_refinement.hpp) are not all within a sample of a neighbour's (an edge or crest
    /// crossing the beam obliquely), the stretch of the column between the disagreeing edges is divided into
    /// thirds over the same launch angles, which share its solid angle exactly, and thirds that still disagree
    /// again (`divide`, ray_density::along_split); their echoes replace its own there, and the rest of the column
    /// stands.
    ///
    /// Where the scene can bound its geometry over a rectangle (AreaScene) and the propagation how far its rays
    /// reach (ReachBoundedPropagation), the rays see the scene over the rectangle they can reach
    /// (sampling/reach.hpp, scene/area_view.hpp): the same geometry, with the top of what lies there; and where that
    /// view can narrow (area_view::within), each column's rays see the objects only where the rectangle of that
    /// column reaches one. The rays launch (sampling/launch_angles.hpp) for the higher of the whole seabed's top and
    /// the top of the objects over the rectangle (launch_top_m): an object no ray of the side can reach (a moored
    /// mine elsewhere in a large scene) changes no ray, as if it were not there. Where the scene bounds its rise above
    /// a sloping plane (PlaneBoundedScene) and a plane fitted to the seabed over the rectangle spaces the side's rays
    /// over much less range, they launch for that plane instead (sloping_launch, sloping_launch_share).
    template <Scene Sc, class Visitor>
    void trace(const Sc& scene, const pose<T>& p, side sd, Visitor&& visit) const {
        if constexpr (std::is_function_v<std::remove_reference_t<Visitor>>) { // a plain function: through an object
            auto call = [&visit](const tube_echo<T>& e) { visit(e); };
            trace(scene, p, sd, call);
        } else if constexpr (AreaScene<Sc> && ReachBoundedPropagation<P>) {
            const plane_rectangle<T> r = *side_area(p, sd);
            const scene::area_view<Sc> view(scene, r.lo, r.hi);
            const scene::object_set<T>* objects = objects_of(scene);
            if constexpr (requires { view.objects_near(); })
                if (!view.objects_near()) objects = nullptr;
            trace_over(view, launch_top_m(scene, r), sloping_launch(scene, p, sd), p, sd, objects, visit);
        } else {
            trace_over(scene, scene.top_m(), std::nullopt, p, sd, objects_of(scene), visit);
        }
    }

    /// trace over the seabed of `sc` alone, with the rays trace(sc, p, sd, visit) launches: the echo the seabed
    /// would return along the same rays if the objects were taken away (labels/ground_truth.hpp compares the two).
    /// The launch angles follow the top trace(sc, ...) launches for (launch_top_m), and the plane (sloping_launch).
    template <Scene Seabed, class Visitor>
    void trace_seabed_alone(const scene::scene<Seabed>& sc, const pose<T>& p, side sd, Visitor&& visit) const {
        // The columns over a small target divide as trace(sc, ...) divides them (ray_density::along_split_targets),
        // so that the rays the labels test against the objects include those that meet it.
        // A scene::scene is an AreaScene whatever its seabed (scene.hpp): trace(sc, ...) launches for launch_top_m
        // wherever the propagation bounds its reach, and so does this, over the seabed's own view where it has one.
        if constexpr (std::is_function_v<std::remove_reference_t<Visitor>>) { // a plain function: through an object
            auto call = [&visit](const tube_echo<T>& e) { visit(e); };
            trace_seabed_alone(sc, p, sd, call);
        } else if constexpr (ReachBoundedPropagation<P>) {
            const plane_rectangle<T> r = *side_area(p, sd);
            const bool near = std::isfinite(sc.objects().top_m(r.lo, r.hi));
            const scene::object_set<T>* objects = near ? &sc.objects() : nullptr;
            if constexpr (AreaScene<Seabed>)
                trace_over(scene::area_view<Seabed>(sc.seabed(), r.lo, r.hi), launch_top_m(sc, r), sloping_launch(sc, p, sd),
                           p, sd, objects, visit);
            else
                trace_over(sc.seabed(), launch_top_m(sc, r), sloping_launch(sc, p, sd), p, sd, objects, visit);
        } else {
            trace_over(sc.seabed(), sc.top_m(), std::nullopt, p, sd, &sc.objects(), visit);
        }
    }

    /// The horizontal rectangle every ray of side sd at pose p stays over while the line lasts
    /// (sampling/reach.hpp), where the propagation bounds how far its rays reach (ReachBoundedPropagation);
    /// std::nullopt otherwise. `trace` sees an AreaScene over this rectangle (scene/area_view.hpp).
    [[nodiscard]] std::optional<plane_rectangle<T>> side_area(const pose<T>& p, side sd) const {
        if constexpr (ReachBoundedPropagation<P>) {
            const double reach_m = double(one_way_limit_s()) * double(propagation_.reach_speed_mps(p.position.z));
            return side_reach(p, sd, beam_.extent(sd), reach_m, !bouncing);
        } else {
            return std::nullopt;
        }
    }

    /// Along-track columns on one side: the requested count, or more where the beam's pattern needs them; evenly
    /// spaced. A trace narrows them where the first return moves across them (ray_density::along_onset), and then
    /// traces more.
    [[nodiscard]] std::size_t along_columns(const beam_extent<T>& ext, side sd) const noexcept {
        std::size_t n = density_.along;
        if constexpr (AlongResolvedBeam<B>) {
            const double step = double(beam_.along_resolution_rad(sd));
            const double width = double(ext.along_max_rad) - double(ext.along_min_rad);
            if (step > 0.0 && width > 0.0) n = std::max(n, static_cast<std::size_t>(std::min(4096.0, std::ceil(width / step))));
        }
        return n;
    }

private:
    /// Where the tracing below hands each piece of echo: a reference to the caller's visitor object (or to a column's
    /// record of its echoes), its type erased. The tracing is then compiled once per scene type, not once per
    /// visitor as well (trace, render, the labels and the held columns each have their own): one or two indirect
    /// calls per echo piece (two where a column's record keeps it first), a few nanoseconds against the microseconds
    /// a ray costs. Refers to the visitor, which must outlive it; it binds to no temporary.
    class echo_sink {
    public:
        template <class F>
            requires(std::is_object_v<F> && !std::same_as<std::remove_cv_t<F>, echo_sink> &&
                     std::invocable<F&, const tube_echo<T>&>)
        echo_sink(F& f) noexcept // NOLINT(google-explicit-constructor): a visitor converts where it is passed
            : target_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))),
              call_([](void* t, const tube_echo<T>& e) { (*static_cast<F*>(t))(e); }) {}
        template <class F>
            requires(!std::same_as<std::remove_cv_t<F>, echo_sink>)
        echo_sink(const F&&) = delete; // a const temporary would bind to F& above and dangle
        void operator()(const tube_echo<T>& e) const { call_(target_, e); }

    private:
        void* target_;
        void (*call_)(void*, const tube_echo<T>&);
    };

    /// The objects of a scene that has them (scene::scene), else none.
    template <Scene Sc> [[nodiscard]] static const scene::object_set<T>* objects_of(const Sc& s) noexcept {
        if constexpr (requires { { s.objects() } -> std::same_as<const scene::object_set<T>&>; })
            return &s.objects();
        else
            return nullptr;
    }

    /// The top the rays of one side launch for, where they stay over rectangle r: a scene with a seabed and objects
    /// (scene::scene, or a wrapper that shows both: seabed() and objects()), the higher of its whole seabed's top and
    /// the top of its objects whose bounds reach over r (one moored mine in a 1 km field had made every ping launch
    /// rays for its height); any other scene, its own top (correct, but an object elsewhere then adds rays).
    template <Scene Sc> [[nodiscard]] static T launch_top_m(const Sc& s, const plane_rectangle<T>& r) {
        if constexpr (requires { s.seabed(); { s.objects() } -> std::same_as<const scene::object_set<T>&>; }) {
            const T seabed = s.seabed().top_m(), objects = s.objects().top_m(r.lo, r.hi);
            return std::isfinite(objects) ? std::max(seabed, objects) : seabed;
        } else {
            return s.top_m();
        }
    }

    /// A side launches for the plane of sloping_launch where it spaces the side's centre column over less than this
    /// share of the nominal range the level seabed spaces it over (with ray_density::per_sample, the rays launched
    /// grow with that range; with a fixed count, ray_density::across, only where they go changes). Where the plane
    /// saves less, the level seabed stands.
    static constexpr double sloping_launch_share = 0.8;

    /// The plane a side's rays may launch for instead of the level seabed through the towfish's nadir (trace_over
    /// chooses, sloping_launch_share; ray_density::sloping_launch): the plane through the seabed under the towfish
    /// whose gradient fits, by least squares, the seabed's heights at 16 x 16 points spread over the rectangle that the
    /// first legs of the side's rays reach (sampling/reach.hpp, as for rays that keep their heading: a bounce does
    /// not change what a ray meets first); the towfish's distance from it, and the clearance left by how far the scene
    /// rises above it over that rectangle (PlaneBoundedScene). Where the seabed slopes across the track, the level
    /// seabed's clearance is set by the upslope end of the line (the whole seabed's top), and most rays would be
    /// launched at ranges the seabed never lets them reach: a plane sloping 0.15 took 3 times the rays of a level one.
    /// None where the density or the scene does not allow it, the propagation does not bound its reach, nothing lies
    /// over the rectangle, or the towfish is not above the seabed.
    template <Scene Sc>
    [[nodiscard]] std::optional<nominal_seabed> sloping_launch(const Sc& s, const pose<T>& p, side sd) const {
        if constexpr (PlaneBoundedScene<Sc> && ReachBoundedPropagation<P>) {
            if (!density_.sloping_launch) return std::nullopt;
            const double reach_m = double(one_way_limit_s()) * double(propagation_.reach_speed_mps(p.position.z));
            const plane_rectangle<T> r = side_reach(p, sd, beam_.extent(sd), reach_m, true);
            const double x0 = double(p.position.x), y0 = double(p.position.y), z0 = double(p.position.z);
            const double below = double(s.seabed_height_m(p.position.x, p.position.y));
            if (!(z0 - below > 0.0) || !std::isfinite(z0 - below)) return std::nullopt;
            // Least squares over a regular grid of points: dz/dx from the x moments, dz/dy from the y moments.
            constexpr int n = 16;
            const double lx = double(r.lo.x), ly = double(r.lo.y), wx = double(r.hi.x) - lx, wy = double(r.hi.y) - ly;
            if (!(wx > 0.0) || !(wy > 0.0) || !std::isfinite(wx * wy)) return std::nullopt;
            double sum = 0.0, sxh = 0.0, syh = 0.0, sxx = 0.0, syy = 0.0; // sum: to see a height that is not finite
            for (int j = 0; j < n; ++j)
                for (int i = 0; i < n; ++i) {
                    const double u = (double(i) + 0.5) / n - 0.5, v = (double(j) + 0.5) / n - 0.5; // centred
                    const double h = double(s.seabed_height_m(static_cast<T>(lx + wx * (u + 0.5)),
                                                              static_cast<T>(ly + wy * (v + 0.5))));
                    sum += h;
                    sxh += u * h;
                    syh += v * h;
                    sxx += u * u;
                    syy += v * v;
                }
            const scene::sloping_plane plane{.at = vec2<double>{x0, y0}, .z_m = below,
                                             .gradient = vec2<double>{sxh / (sxx * wx), syh / (syy * wy)}};
            if (!std::isfinite(sum) || !std::isfinite(plane.gradient.x) || !std::isfinite(plane.gradient.y))
                return std::nullopt;
            const double rise = s.rise_above_m(r.lo, r.hi, plane);
            if (!std::isfinite(rise)) return std::nullopt;
            const vec3<double> up = plane.up();
            return nominal_seabed{.up = up, .altitude_m = (z0 - below) * up.z, .clearance_m = (z0 - below - rise) * up.z};
        } else {
            return std::nullopt;
        }
    }

    /// `n` with its clearance lowered by how far a ray bends down from its straight line on its way to the longest
    /// range (RangeHeightPropagation; straight rays: `n` itself), times bent_down_margin. The launch's cut (a ray
    /// reaches geometry within the range only if its component against the plane's normal is at least the clearance
    /// over the range) holds for straight rays; in water that bends rays down, a ray launched just above the cut still
    /// comes down onto the seabed within the range. Measured on the column at `along` for the ray at the cut, at the
    /// horizontal distance its straight line reaches the range (its height there with no scene, looked for within
    /// four times the one-way time, so that slow water does not hide the bend). Over a plane sloping 0.08 with
    /// ripples, in water going from 1500 m/s 15 m above the seabed to 1470 m/s at it (the ray at the cut 0.6 m below
    /// its straight line at 30 m), the cut without it left the line 0.21 dB RMS and 0.86 dB at the 99th percentile off
    /// the converged reference (tests/seabed/test_rough_accuracy.cpp; 0.023 and 0.069 dB with it). It is measured on
    /// one ray, not a bound over every ray of the side; a propagation that bends rays but cannot say where they pass a
    /// range gets none. (The level seabed's cut, with the clearance above the whole seabed's top, has no such
    /// allowance.)
    [[nodiscard]] nominal_seabed bent_down(nominal_seabed n, side sd, T along, const beam_extent<T>& ext,
                                           const pose<T>& p, T max_range_m, T t_max_one_way_s) const {
        if constexpr (RangeHeightPropagation<P>) {
            const detail::launch_geometry lg =
                detail::launch_pieces(sd, along, double(ext.depression_min_rad), double(ext.depression_max_rad),
                                      p.body_to_world, n, double(max_range_m));
            double drop_m = 0.0;
            for (const detail::launch_piece& piece : lg.pieces) {
                if (piece.far_is_edge) continue; // not cut by the reach
                const double c = std::clamp((n.altitude_m / piece.r_far - lg.A) / lg.rho, -1.0, 1.0);
                const double e = piece.increasing_g ? piece.centre - std::acos(c) : piece.centre + std::acos(c);
                const vec3<T> d = p.to_world(beam_direction(sd, along, static_cast<T>(e)));
                const double range_m = double(max_range_m) * std::hypot(double(d.x), double(d.y));
                if (!(range_m > 0.0)) continue;
                const std::optional<T> z = propagation_.height_at_range_m(ray<T>{p.position, d}, static_cast<T>(range_m),
                                                                          T(4) * t_max_one_way_s);
                if (!z) continue;
                const double straight_z = double(p.position.z) + double(d.z) * double(max_range_m);
                if (std::isfinite(double(*z))) drop_m = std::max(drop_m, straight_z - double(*z));
            }
            n.clearance_m -= bent_down_margin * drop_m * n.up.z;
        }
        return n;
    }
    /// How much of the bend bent_down allows for: the ray at the lowered cut goes a little further, and bends a little
    /// more.
    static constexpr double bent_down_margin = 1.5;

    /// trace over `scene` (the whole scene or the area its rays reach), launching for geometry up to `top_m` over the
    /// level seabed under the towfish, or for the plane `sloping` (sloping_launch) where that saves rays; the
    /// small targets among `objects` (none: nullptr) divide the columns over them (ray_density::along_split_targets), and
    /// the stretch of each column near the first return over a seabed that is not one plane, or over a plane where the
    /// first return moves across the column (ray_density::along_split_nadir).
    template <Scene Sc>
    void trace_over(const Sc& scene, T top_m, const std::optional<nominal_seabed>& sloping, const pose<T>& p, side sd,
                    const scene::object_set<T>* objects, echo_sink visit) const {
        const beam_extent<T> ext = beam_.extent(sd);
        const double t_max_s = line_reach_s();
        trace_frame f{p, sd, ext, T{}, T{}, T{}, {}, {}, nullptr};
        f.t_max_one_way = one_way_limit_s();
        f.max_range_m = static_cast<T>(0.5 * t_max_s * c_ref_);
        f.altitude = p.position.z - scene.seabed_height_m(p.position.x, p.position.y);
        f.launch = nominal_seabed{.altitude_m = double(f.altitude), .clearance_m = double(p.position.z - top_m)};
        if (density_.across != 0) f.cd.rays = density_.across;
        else f.cd.rays_per_m = density_.per_sample * 2.0 / (c_ref_ * dt_);
        f.cd.max_step_rad = deg_to_rad(density_.max_launch_step_deg);
        const double a0 = ext.along_min_rad, a1 = ext.along_max_rad;
        if (sloping) { // the sloping plane where it spaces the centre column's rays over much less range than the level
            const T centre = static_cast<T>(0.5 * (a0 + a1));
            const nominal_seabed plane = bent_down(*sloping, sd, centre, ext, p, f.max_range_m, f.t_max_one_way);
            const auto span = [&](const nominal_seabed& n) {
                return launch_span_m(sd, centre, ext.depression_min_rad, ext.depression_max_rad, p.body_to_world, n,
                                     f.max_range_m);
            };
            // Only a plane that spaces the rays in range (above the towfish's clearance: not the even angles).
            if (plane.clearance_m > 0.0 && span(plane) < sloping_launch_share * span(f.launch)) f.launch = plane;
        }
        const buffer_lease lease(*buffers_);
        trace_buffers& b = *lease.buffers;
        // The columns' edges: evenly spaced, or narrower where the first return moves across them (column_edges.hpp).
        std::vector<double>& edges = b.edges;
        const double onset_tolerance_m = density_.along_onset * 0.5 * c_ref_ * dt_;
        const double altitude_m = double(f.altitude);
        const std::size_t n_even = along_columns(ext, sd);
        const auto nearest = [&](double a) {
            return nearest_range_m(sd, a, double(ext.depression_min_rad), double(ext.depression_max_rad),
                                   p.body_to_world, altitude_m);
        };
        column_edges(edges, a0, a1, n_even, onset_tolerance_m, double(f.max_range_m), nearest);
        const std::size_t n_along = edges.size() - 1;
        auto bounds = [&](std::size_t j) { return std::pair<double, double>{edges[j], edges[j + 1]}; };
        // The side's nearest first return (m) over a plane, at the columns' edges and centres.
        const auto side_first_m = [&](auto&& nearest_on_plane) {
            double r = std::numeric_limits<double>::infinity();
            for (std::size_t j = 0; j <= n_along; ++j) {
                r = std::min(r, nearest_on_plane(edges[j]));
                if (j < n_along) r = std::min(r, nearest_on_plane(0.5 * (edges[j] + edges[j + 1])));
            }
            return r;
        };
        // That over a level seabed.
        const double first_m =
            density_.along_split_nadir ? side_first_m(nearest) : std::numeric_limits<double>::infinity();
        // How long a column between lo and hi counts as near the first return over the plane a seabed echo `on` lies on
        // (plane_nadir_reach_s): the level seabed's first returns where that plane is the level one under the towfish
        // (to 1e-6 of the altitude and the coordinates' rounding), else the plane's own (nearest_range_to_plane_m), at
        // its distance d from the towfish. A plane's first returns are d times those of its normal's plane at unit
        // distance: the last normal asked about is kept with the side's nearest first return at unit distance, and
        // stands for any within 1e-3 rad of it (same_normal, as planarity is judged), so that the column's first
        // returns and the side's nearest come from one plane.
        struct plane_onset {
            vec3<T> normal{};
            vec3<double> unit_normal{};
            double first_per_m = 0.0;
        };
        std::optional<plane_onset> last_plane;
        const auto plane_reach_s = [&](double lo, double hi, const hit<T>& on, double first_s) {
            const vec3<double> towards = vec3<double>(p.position) - vec3<double>(on.point);
            const double rounding = 16.0 * double(std::numeric_limits<T>::epsilon()) *
                                    (std::abs(double(p.position.z)) + std::abs(double(on.point.z)));
            if (on.normal.x == T(0) && on.normal.y == T(0) && std::isfinite(altitude_m) &&
                std::abs(double(on.normal.z) * towards.z - altitude_m) <= 1e-6 * std::abs(altitude_m) + rounding)
                return plane_nadir_reach_s(lo, hi, nearest, first_m, first_s);
            const auto at_unit = [&](double a) {
                return nearest_range_to_plane_m(sd, a, double(ext.depression_min_rad), double(ext.depression_max_rad),
                                                p.body_to_world, last_plane->unit_normal, 1.0);
            };
            if (!last_plane || !same_normal(last_plane->normal, on.normal)) {
                last_plane = plane_onset{on.normal, vec3<double>(on.normal), 0.0};
                last_plane->first_per_m = side_first_m(at_unit);
            }
            const double d = glm::dot(last_plane->unit_normal, towards);
            if (!(d > 0.0)) return 0.0; // the towfish not above the plane: no first return from it
            return plane_nadir_reach_s(lo, hi, [&](double a) { return d * at_unit(a); }, d * last_plane->first_per_m,
                                       first_s);
        };
        double widest = (a1 - a0) / double(n_along); // the widest column (rad): every one where they are even
        if (n_along != n_even)
            for (std::size_t j = 0; j < n_along; ++j) widest = std::max(widest, edges[j + 1] - edges[j]);
        column_scratch& scratch = b.scratch;
        const std::size_t levels = division_levels();
        if (density_.refine_depth == 0 || levels == 0 || n_along < 2) {
            for (std::size_t j = 0; j < n_along; ++j) {
                detail::ping_stop_point(); // a stopped render ends its pings here (core/render_control.hpp)
                const auto [lo, hi] = bounds(j);
                in_column(scene, f, lo, hi, [&](const Sc& col) { trace_column(col, f, lo, hi, scratch, nullptr, visit); });
            }
            return;
        }
        // Columns j - 1, j and j + 1, in turn. Column j's echoes wait until column j + 1 is traced.
        // Three columns in turn; or, where a faint column's share of the line decides how deep it divides
        // (ray_density::along_split_echo), every column of the side, traced before any is divided (set below).
        std::vector<column_record>& records = b.records;
        bool hold_all = false;
        auto rec = [&](std::size_t j) -> column_record& { return records[hold_all ? j : j % 3]; };
        // The columns' spacing at the end of the line against the range sample.
        const bool coarse = double(f.max_range_m) * widest > 2.0 * 0.5 * c_ref_ * dt_;
        // The columns' echoes compared sample by sample there too (ray_density::along_split_echo).
        const bool echo_check = density_.along_split_echo > 0.0 && coarse;
        auto trace_into = [&](std::size_t j) {
            detail::ping_stop_point(); // a stopped render ends its pings here (core/render_control.hpp)
            column_record& r = rec(j);
            r.echoes.clear();
            r.edges.clear();
            const auto [lo, hi] = bounds(j);
            auto keep = [&r](const tube_echo<T>& t) { r.echoes.push_back(t); };
            in_column(scene, f, lo, hi, [&](const Sc& col) { trace_column(col, f, lo, hi, scratch, &r, keep); });
            std::swap(r.angles, scratch.angles);
            std::sort(r.edges.begin(), r.edges.end(), [](const column_edge& e0, const column_edge& e1) { return e0.t < e1.t; });
            if (echo_check) echo_per_sample(r);
        };
        // How deep each column may be divided: by its weight under the beam, or alike.
        std::vector<std::size_t>& depths = b.depths;
        depths.assign(n_along, levels);
        std::vector<double>& weights = b.weights;
        if (density_.along_split_by_weight || echo_check) {
            weights.assign(n_along, 0.0);
            for (std::size_t j = 0; j < n_along; ++j) weights[j] = column_weight(f.ext, sd, bounds(j));
        }
        if (density_.along_split_by_weight) division_depths(weights, levels, depths);
        hold_all = echo_check && n_along <= max_held_columns &&
                   std::any_of(depths.begin(), depths.end(), [&](std::size_t d) { return d < levels; });
        if (records.size() < (hold_all ? n_along : 3)) records.resize(hold_all ? n_along : 3);
        for (column_record& r : records) r.seabed_edges = density_.along_split_seabed.value_or(coarse);
        const std::size_t deepest = *std::max_element(depths.begin(), depths.end());
        if (b.divisions.size() + 1 < deepest) b.divisions.resize(deepest - 1); // before divide takes references
        std::vector<redo_range>& windows = b.windows;
        std::vector<std::pair<std::size_t, std::size_t>>& runs = b.runs;
        std::vector<std::ptrdiff_t>& cover = b.cover;
        std::vector<target_span>& targets = b.targets;
        targets.clear();
        if (objects && density_.along_split_targets && !objects->empty())
            target_spans(propagation_, *objects, p, sd, ext, widest, f.t_max_one_way,
                         double(f.max_range_m), targets);
        if (!targets.empty()) f.targets = &targets;
        std::vector<double>& line = b.line;
        if (hold_all) {
            line.assign(samples_, 0.0);
            for (std::size_t j = 0; j < n_along; ++j) {
                trace_into(j);
                for (std::size_t k = 0; k < samples_; ++k) line[k] += rec(j).per_sample[k];
            }
        } else {
            trace_into(0);
        }
        std::vector<redo_range>& deep = b.deep;
        for (std::size_t j = 0; j < n_along; ++j) {
            detail::ping_stop_point(); // also where every column was traced first (hold_all): column j's division
            if (!hold_all && j + 1 < n_along) trace_into(j + 1);
            const column_record& here = rec(j);
            windows.clear();
            deep.clear();
            if (j > 0) disagreements(here.edges, rec(j - 1).edges, windows);
            if (j + 1 < n_along) disagreements(here.edges, rec(j + 1).edges, windows);
            if (!targets.empty()) {
                const auto [lo, hi] = bounds(j);
                target_windows(targets, lo, hi, here.angles, windows);
            }
            // Near the first return; over a plane, the intervals beyond those windows are tapered (below).
            std::vector<redo_range>& nadir = b.nadir;
            nadir.clear();
            if (density_.along_split_nadir) {
                const auto [lo, hi] = bounds(j);
                const auto reach = [&](const hit<T>& on, double first_s) { return plane_reach_s(lo, hi, on, first_s); };
                const bool plane = nadir_windows(here, nadir_end_s(f), reach, nadir);
                windows.insert(windows.end(), nadir.begin(), nadir.end());
                if (!plane) nadir.clear(); // only a plane's are tapered
            }
            if (echo_check)
                echo_windows(here, j > 0 ? &rec(j - 1) : nullptr, j + 1 < n_along ? &rec(j + 1) : nullptr, weights, j,
                             n_along == n_even ? 0.5 : toward_right(edges, j), b.flags, windows,
                             hold_all && depths[j] < levels ? &line : nullptr, deep);
            if (windows.empty()) {
                for (const tube_echo<T>& t : here.echoes) visit(t);
                continue;
            }
            // The launch intervals within a window (between two launched rays) are traced again; the others stand.
            // cover[k]: how many windows interval k lies in, from their ends' differences.
            const std::size_t intervals = here.first.empty() ? 0 : here.first.size() - 1;
            cover.assign(intervals + 1, 0);
            for (const redo_range& w : windows) {
                if (w.k0 >= intervals) continue;
                ++cover[w.k0];
                --cover[std::min(w.k1 + 1, intervals)];
            }
            // Within the faint column's stretches where it carries a share of the line (`deep`), the runs divide to an
            // even column's depth (deep_runs).
            std::vector<std::ptrdiff_t>& deep_cover = b.deep_cover;
            std::vector<std::pair<std::size_t, std::size_t>>& deep_runs = b.deep_runs;
            deep_cover.assign(intervals + 1, 0);
            for (const redo_range& w : deep) {
                if (w.k0 >= intervals) continue;
                ++deep_cover[w.k0];
                --deep_cover[std::min(w.k1 + 1, intervals)];
            }
            runs.clear();
            deep_runs.clear();
            std::ptrdiff_t within = 0, deep_within = 0;
            std::vector<double>& tau = b.tau; // each interval's share of its thirds' echo: 1 where divided
            tau.assign(intervals, 0.0);
            for (std::size_t k = 0; k < intervals; ++k) {
                within += cover[k];
                deep_within += deep_cover[k];
                const bool redo = within > 0 && !std::isnan(here.angles[k]) && !std::isnan(here.angles[k + 1]);
                if (!redo) continue;
                tau[k] = 1.0;
                auto& into = deep_within > 0 ? deep_runs : runs;
                if (!into.empty() && into.back().second + 1 == k) into.back().second = k;
                else into.emplace_back(k, k);
            }
            // Either side of a stretch divided near the first return over a plane, the column's echo goes over to its
            // thirds' in steps (nadir_taper): where the stretch ends, the thirds' last tubes end at their own times, a
            // third of the echo each, and left a step up and down a third high, a fraction of a sample wide, at the
            // column's. The steps begin where the divided run holding the window ends.
            for (const redo_range& w : nadir) {
                if (w.k0 >= intervals) continue;
                std::size_t ends[2] = {w.k0, std::min(w.k1, intervals - 1)};
                while (ends[0] > 0 && tau[ends[0] - 1] >= 1.0) --ends[0];
                while (ends[1] + 1 < intervals && tau[ends[1] + 1] >= 1.0) ++ends[1];
                for (std::size_t d = 1; d <= nadir_taper; ++d) {
                    const double share = 1.0 - double(d) / double(nadir_taper + 1);
                    for (const std::size_t q : {ends[0] - d, ends[1] + d}) {
                        if (q >= intervals || tau[q] >= 1.0) continue; // past either end, or divided
                        if (std::isnan(here.angles[q]) || std::isnan(here.angles[q + 1])) continue;
                        tau[q] = std::max(tau[q], share);
                    }
                }
            }
            auto& taper_runs = b.taper_runs;
            taper_runs.clear();
            for (std::size_t k = 0; k < intervals; ++k) {
                if (tau[k] >= 1.0) continue;
                if (tau[k] > 0.0) {
                    if (!taper_runs.empty() && taper_runs.back().second + 1 == k) taper_runs.back().second = k;
                    else taper_runs.emplace_back(k, k);
                    continue;
                }
                for (std::size_t i = here.first[k]; i < here.first[k + 1]; ++i) visit(here.echoes[i]);
            }
            for (std::size_t i = here.first.empty() ? 0 : here.first.back(); i < here.echoes.size(); ++i)
                visit(here.echoes[i]);
            const auto [lo, hi] = bounds(j);
            if (!taper_runs.empty()) taper(scene, f, lo, hi, here, taper_runs, tau, b, visit);
            if (runs.empty() && deep_runs.empty()) continue;
            // A small target lies over the column: its launch intervals divide on until the narrowest columns are a
            // quarter of its angular thickness wide (a sphere's diameter, a cylinder's), two levels past along_split's
            // depth at most (1/81 of a column by default, whatever the column's weight).
            std::size_t target_depth = depths[j];
            for (const target_span& t : targets) {
                if (!t.along || !(t.along_hi > lo && t.along_lo < hi)) continue;
                const double need = std::ceil(std::log(4.0 * (hi - lo) / std::max(t.thickness_rad, 1e-12)) / std::log(3.0));
                if (need > double(target_depth)) target_depth = std::min(levels + 2, static_cast<std::size_t>(need));
            }
            if (b.divisions.size() + 1 < std::max(target_depth, levels)) b.divisions.resize(std::max(target_depth, levels) - 1);
            if (!runs.empty()) divide(scene, f, lo, hi, here.angles, here, 1.0, runs, 0, depths[j], target_depth, b, visit);
            if (!deep_runs.empty())
                divide(scene, f, lo, hi, here.angles, here, 1.0, deep_runs, 0, levels, std::max(target_depth, levels), b,
                       visit);
        }
    }

    /// True when the scattering policy switches on one specular bounce (scattering/specular_bounce.hpp).
    /// The member's value decides, not its presence: a policy declaring it false does not bounce.
    static constexpr bool bouncing = [] {
        if constexpr (requires { { S::specular_bounce_enabled } -> std::convertible_to<bool>; })
            return bool(S::specular_bounce_enabled);
        else
            return false;
    }();
    /// True when a line stage is asked for.
    static constexpr bool has_stage = !std::is_same_v<Stage, no_line_stage>;

    /// The latest two-way time (s) whose echo reaches the line: its length, and the receiver clock's delay (a
    /// compressed chirp's T: the line holds the envelope that late, time_sampler). The refinement's comparisons per
    /// sample (samples_of) and the labels place echoes by arrival within the line's own times: an echo arriving in
    /// the last T reaches the last samples through its leading sidelobes and lobe only, and is not refined for them.
    [[nodiscard]] double line_reach_s() const noexcept {
        return double(samples_) * dt_ + receiver_.pulse.filter_delay_s();
    }
    /// How long a ray is followed, one way (s): slightly past line_reach_s, so that the ray placed exactly at the
    /// last range is not lost to rounding (the sampler drops whatever falls beyond the line).
    [[nodiscard]] T one_way_limit_s() const noexcept { return static_cast<T>(0.5 * line_reach_s() * (1.0 + 1e-5)); }

    template <Scene Sc> [[nodiscard]] line_context<T> line_context_for(const Sc& scene, const pose<T>& p, side sd) const {
        const elevation_share& e = elevation_[sd == side::starboard ? 1 : 0];
        return line_context<T>{p, sd, dt_, c_ref_,
                               double(p.position.z - scene.seabed_height_m(p.position.x, p.position.y)),
                               receiver_.pulse, receiver_.source_level_db, {}, e.shallower.empty() ? nullptr : &e};
    }

    struct ray_end {
        bool valid = false;
        double e = 0.0, t = 0.0, power_per_rad = 0.0;
        double stretch = 0.0; ///< dt/de the ray's facet predicts for its neighbours: t cot(angle to the facet) (s/rad)
        double gain = 0.0;    ///< sigma x loss / sin(angle to the facet): the echo per radian, beam pattern aside
        hit<T> surface{}; ///< where the echo comes from
        hit<T> via{};     ///< for a bounced path: where it bounced
        vec3<T> launch{}; ///< the launched ray's unit direction (world)
        T leg_s{};        ///< one-way time (s) from the transducer to the first surface (surface, or via)
        T clear_range_m{}; ///< horizontal distance within which the ray met nothing (m): path::clear_range_m

        /// The echo piece of this end's ray, spread over two-way times [t, t1].
        [[nodiscard]] tube_echo<T> piece(double t1, double power) const noexcept {
            return {t, t1, power, surface, launch, leg_s};
        }
    };

    /// What every column of one side of one ping shares.
    struct trace_frame {
        const pose<T>& p;
        side sd;
        beam_extent<T> ext;
        T t_max_one_way, max_range_m, altitude;
        nominal_seabed launch; ///< the plane the columns launch for (sampling/launch_angles.hpp)
        column_density cd;
        const std::vector<target_span>* targets; ///< the side's small targets (none: null)
    };

    /// A small target's launch depressions over one column (rad), and the widest launch interval there that cannot
    /// step over it, or sample it too coarsely (target_span::depression_step_rad).
    struct thin_window {
        double lo, hi, step;
    };

    /// Buffers reused from column to column.
    struct column_scratch {
        std::vector<T> angles;
        std::vector<ray<T>> rays;
        std::vector<std::optional<path<T>>> paths;
        std::vector<thin_window> thin;
    };

    /// One end of a located edge between surfaces: its two-way time (s) and the launch interval it lies in.
    struct column_edge {
        double t;
        std::size_t k;
    };

    /// One column, traced and waiting: its launch angles, its echoes in the order of their launch intervals
    /// (interval k: the rays at angles[k] and angles[k + 1] and what refinement traced between them), where each
    /// interval's echoes begin (`first`, one entry per angle: the last is where the continuation beyond the last
    /// angle begins), and the ends of its located edges between surfaces (by time). `interval` is the launch
    /// interval being refined while tracing.
    struct column_record {
        std::vector<T> angles;
        std::vector<tube_echo<T>> echoes;
        std::vector<std::size_t> first;
        std::vector<column_edge> edges;
        std::size_t interval = 0;
        bool seabed_edges = false; ///< the seabed's own edges are recorded too
        std::vector<double> per_sample; ///< its echo in each time sample (ray_density::along_split_echo)
        bool planar = false;            ///< every echo from the seabed, all with one facet normal: `normal`
        vec3<T> normal{};
    };

    /// What a divided column traces again: the launch intervals k0 to k1.
    struct redo_range {
        std::size_t k0, k1;
    };

    /// What one level of divide keeps while the levels below it work: the outer thirds, traced; the middle
    /// third's edges; which launch intervals the stretch spans (`inside`), where the thirds disagree (`cover`,
    /// `windows`), and the stretches each third divides again (`runs`: left, middle, right).
    struct division {
        column_record outer[2];
        std::vector<column_edge> middle_edges;
        std::vector<unsigned char> inside;
        std::vector<std::ptrdiff_t> cover;
        std::vector<std::ptrdiff_t> forced; ///< each third's launch intervals over a small target (differences)
        std::vector<unsigned char> marks;   ///< past the column's depth: the launch intervals over a small target
        std::vector<std::pair<std::size_t, std::size_t>> rest, deeper; ///< past the depth: runs ending, going on
        std::vector<redo_range> windows;
        std::vector<std::pair<std::size_t, std::size_t>> runs[3];
    };

    /// The buffers of one trace call.
    struct trace_buffers {
        column_scratch scratch;
        std::vector<column_record> records = std::vector<column_record>(3); ///< three columns in turn, or the side's
        std::vector<double> line;        ///< the side's columns' echoes summed, per sample (a faint column's share)
        std::vector<redo_range> deep;    ///< the stretches a faint column divides to an even column's depth
        std::vector<std::ptrdiff_t> deep_cover;
        std::vector<std::pair<std::size_t, std::size_t>> deep_runs;
        std::vector<redo_range> windows;
        std::vector<std::pair<std::size_t, std::size_t>> runs;
        std::vector<std::ptrdiff_t> cover;
        std::vector<division> divisions; ///< one per level of divide but the last
        std::vector<std::size_t> depths; ///< how deep each column of the side may be divided
        std::vector<double> weights;     ///< the beam's weight on each column
        std::vector<target_span> targets; ///< the side's small targets (ray_density::along_split_targets)
        std::vector<unsigned char> flags; ///< the samples where a column's echo departs (ray_density::along_split_echo)
        std::vector<double> edges;        ///< the side's columns' along-track edges (rad): sampling/column_edges.hpp
        std::vector<redo_range> nadir;    ///< a column's windows near the first return (ray_density::along_split_nadir)
        std::vector<double> tau;          ///< each launch interval's share of its thirds' echo (1: divided)
        std::vector<std::pair<std::size_t, std::size_t>> taper_runs; ///< the intervals that share some
        column_record taper_outer[2];     ///< their outer thirds
    };

    /// Buffers kept between trace calls, so that a ping reuses the memory of the pings before it instead of
    /// allocating (and, for large buffers, mapping and unmapping pages, which threads pay for together). A trace
    /// call takes one set for its duration: concurrent calls, and a visitor that traces again, each get their own.
    /// Copies of a simulator share the pool.
    class buffer_pool {
    public:
        [[nodiscard]] std::unique_ptr<trace_buffers> take() {
            const std::lock_guard<std::mutex> hold(lock_);
            if (free_.empty()) return std::make_unique<trace_buffers>();
            std::unique_ptr<trace_buffers> b = std::move(free_.back());
            free_.pop_back();
            return b;
        }
        void give(std::unique_ptr<trace_buffers> b) noexcept {
            const std::lock_guard<std::mutex> hold(lock_);
            try {
                free_.push_back(std::move(b));
            } catch (...) { // out of memory: the buffers are freed instead of kept
            }
        }

    private:
        std::mutex lock_;
        std::vector<std::unique_ptr<trace_buffers>> free_;
    };

    /// One set of buffers, taken from the pool and given back.
    struct buffer_lease {
        explicit buffer_lease(buffer_pool& p) : pool(p), buffers(p.take()) {}
        ~buffer_lease() { pool.give(std::move(buffers)); }
        buffer_lease(const buffer_lease&) = delete;
        buffer_lease& operator=(const buffer_lease&) = delete;
        buffer_pool& pool;
        std::unique_ptr<trace_buffers> buffers;
    };

    /// The small targets of f over the column between along-track angles lo and hi (rad) that a launch interval can
    /// step over (a finite width in depression), into `out`; null where there are none.
    static const std::vector<thin_window>* thin_windows(const trace_frame& f, double lo, double hi,
                                                        std::vector<thin_window>& out) {
        out.clear();
        if (!f.targets) return nullptr;
        for (const target_span& t : *f.targets)
            if (t.along_hi > lo && t.along_lo < hi && std::isfinite(t.depression_step_rad))
                out.push_back({t.depression_lo, t.depression_hi, t.depression_step_rad});
        return out.empty() ? nullptr : &out;
    }

    /// Whether the launch interval between depressions e0 and e1 (rad) is wider than a small target of `thin` it
    /// overlaps allows (thin_window::step).
    static bool steps_over(const std::vector<thin_window>& thin, double e0, double e1) noexcept {
        const double lo = std::min(e0, e1), hi = std::max(e0, e1);
        for (const thin_window& w : thin)
            if (hi >= w.lo && lo <= w.hi && hi - lo > w.step) return true;
        return false;
    }

    /// The launch intervals of the column between along-track angles lo and hi (rad), launched at depressions
    /// `angles`, that can meet a small target of `targets` lying over it, added to `out` (one range per target, one
    /// interval more either way); with `finest` > 0 (rad: the narrowest columns there unless these intervals divide
    /// again), only the targets less than four times that thick.
    static void target_windows(const std::vector<target_span>& targets, double lo, double hi,
                               const std::vector<T>& angles, std::vector<redo_range>& out, double finest = 0.0) {
        const std::size_t intervals = angles.empty() ? 0 : angles.size() - 1;
        if (intervals == 0) return;
        for (const target_span& t : targets) {
            if (!t.along || !(t.along_hi > lo && t.along_lo < hi)) continue;
            if (finest > 0.0 && !(4.0 * finest > t.thickness_rad)) continue;
            std::size_t k0 = intervals, k1 = 0;
            for (std::size_t k = 0; k < intervals; ++k) {
                const double e0 = double(angles[k]), e1 = double(angles[k + 1]);
                if (std::isnan(e0) || std::isnan(e1)) continue;
                if (std::max(e0, e1) >= t.depression_lo && std::min(e0, e1) <= t.depression_hi) {
                    k0 = std::min(k0, k);
                    k1 = k;
                }
            }
            if (k0 <= k1) out.push_back({k0 - std::min<std::size_t>(k0, 1), k1 + 1});
        }
    }

    /// Splits `runs` (launch intervals [k0, k1]) into those within `windows` (`deeper`) and the others (`rest`), over
    /// `intervals` launch intervals; `marks` is scratch.
    static void split_runs(const std::vector<std::pair<std::size_t, std::size_t>>& runs, const std::vector<redo_range>& windows,
                           std::size_t intervals, std::vector<unsigned char>& marks,
                           std::vector<std::pair<std::size_t, std::size_t>>& rest,
                           std::vector<std::pair<std::size_t, std::size_t>>& deeper) {
        marks.assign(intervals, 0);
        for (const redo_range& w : windows)
            for (std::size_t k = w.k0; k <= std::min(w.k1, intervals - 1); ++k) marks[k] = 1;
        rest.clear();
        deeper.clear();
        for (const auto& [k0, k1] : runs)
            for (std::size_t k = k0; k <= k1; ++k) {
                auto& into = marks[k] ? deeper : rest;
                if (!into.empty() && into.back().second + 1 == k) into.back().second = k;
                else into.emplace_back(k, k);
            }
    }

    /// The two-way time (s) up to which a column's echoes count as near the first return (ray_density::along_split_nadir):
    /// a slant range of sqrt(2) times the towfish's altitude, at the reference speed; none where no seabed lies under
    /// the towfish (height -infinity).
    [[nodiscard]] double nadir_end_s(const trace_frame& f) const noexcept {
        if (!std::isfinite(f.altitude)) return 0.0;
        return 2.0 * std::sqrt(2.0) * std::max(0.0, double(f.altitude)) / c_ref_;
    }

    /// Over a plane seabed, a column is divided near the first return where that return moves across it by more than
    /// this many range samples; a column holding the side's nearest first return, by more than nadir_first_spread.
    static constexpr double nadir_plane_spread = 0.25;
    static constexpr double nadir_first_spread = 0.05;
    /// Or, for the column holding the nearest first return, by more than this share of the part of its first sample
    /// after its earliest onset (a sliver s): just after the onset the echo rises as the square root of the time, so a
    /// column whose centre's onset lags by d takes about 1.5 d / s of that sample's echo away.
    static constexpr double nadir_first_sliver = 0.25;
    /// Either side of a stretch divided near the first return over a plane, this many launch intervals share the
    /// column's echo with its thirds', in even steps.
    static constexpr std::size_t nadir_taper = 4;

    /// How long (two-way, s) after its earliest echo from the seabed, at two-way time first_s (its centre's onset), the
    /// column between along-track angles lo and hi (rad) counts as near the first return over a plane seabed: the time
    /// its first return moves across it, plus two range samples, where that movement exceeds nadir_plane_spread
    /// samples; where the column holds the side's nearest first return (`first_m`), nadir_first_spread samples or
    /// nadir_first_sliver of the part of the first sample after the column's earliest onset (first_s less the
    /// centre's lag), whichever is less; else 0. First returns are those of the plane the column's echoes lie on
    /// (nearest(a): the slant range, m, of its nearest point at along-track angle a, along straight rays), sampled at
    /// the column's edges and centre: they tell how far the return moves, the column's echoes where it begins.
    template <class Nearest>
    [[nodiscard]] double plane_nadir_reach_s(double lo, double hi, Nearest&& nearest, double first_m,
                                             double first_s) const {
        double r_min = std::numeric_limits<double>::infinity(), r_max = 0.0;
        const double r_mid = nearest(0.5 * (lo + hi));
        for (const double r : {nearest(lo), r_mid, nearest(hi)}) {
            if (!std::isfinite(r)) continue;
            r_min = std::min(r_min, r);
            r_max = std::max(r_max, r);
        }
        const double sample_m = 0.5 * c_ref_ * dt_;
        double limit = nadir_plane_spread;
        if (r_min <= first_m * (1.0 + 1e-9)) {
            // The column's earliest onset: its centre's, less how much later the centre's first return lies.
            const double lag_s = std::isfinite(r_mid) ? 2.0 * (r_mid - r_min) / c_ref_ : 0.0;
            const double x = (first_s - lag_s) / dt_, sliver = std::isfinite(x) ? 1.0 - (x - std::floor(x)) : 1.0;
            limit = std::min(nadir_first_spread, nadir_first_sliver * sliver);
        }
        if (!(r_max - r_min > limit * sample_m)) return 0.0;
        return 2.0 * (r_max - r_min + 2.0 * sample_m) / c_ref_;
    }

    /// The launch intervals of a traced column whose echoes begin before two-way time `t_end_s` (near the first return),
    /// as windows for the along-track division, where the seabed's facets met there are not all one plane (their
    /// geometric normals more than 1e-3 rad apart, as between facets whose edges are refined: detail::facet_edge).
    /// Where they are one plane (or none is met there): where the time `plane_reach_s(h, first_s)` gives for the plane
    /// of a seabed hit h (theirs, or else the column's earliest) and the column's earliest echo from the seabed, at
    /// first_s, is > 0 (plane_nadir_reach_s), and every seabed echo that begins within it of first_s lies on that plane
    /// too, those launch intervals whose echoes begin within it, and true; else none (ray_density::along_split_nadir).
    template <class Reach>
    static bool nadir_windows(const column_record& rec, double t_end_s, Reach&& plane_reach_s,
                              std::vector<redo_range>& out) {
        if (rec.first.size() < 2) return false;
        const std::size_t intervals = rec.first.size() - 1;
        const auto begins = [](const tube_echo<T>& e) { return std::min(e.t0_s, e.t1_s); };
        double end_s = t_end_s;
        auto near = [&](std::size_t k) {
            for (std::size_t i = rec.first[k]; i < rec.first[k + 1]; ++i)
                if (begins(rec.echoes[i]) < end_s) return true;
            return false;
        };
        auto windows = [&] {
            for (std::size_t k = 0; k < intervals; ++k) {
                if (!near(k)) continue;
                if (!out.empty() && out.back().k1 + 1 == k) out.back().k1 = k;
                else out.push_back({k, k});
            }
        };
        // One plane: every seabed echo of the launch intervals near the first return has the first one's normal.
        const hit<T>* plane = nullptr;
        bool planar = true;
        if (t_end_s > 0.0)
            for (std::size_t k = 0; k < intervals && planar; ++k) {
                if (!near(k)) continue;
                for (std::size_t i = rec.first[k]; i < rec.first[k + 1]; ++i) {
                    const hit<T>& h = rec.echoes[i].surface;
                    if (h.object != no_object || !(begins(rec.echoes[i]) < t_end_s)) continue;
                    if (!plane) {
                        plane = &h;
                    } else if (!same_normal(h.normal, plane->normal)) {
                        planar = false;
                        break;
                    }
                }
            }
        if (!planar) {
            windows();
            return false;
        }
        // One plane (or nothing met) there: the plane's rule, where the first return moves across the column, over
        // every seabed echo it reaches.
        double first_s = std::numeric_limits<double>::infinity();
        const hit<T>* earliest = nullptr;
        for (const tube_echo<T>& e : rec.echoes)
            if (e.surface.object == no_object && begins(e) < first_s) {
                first_s = begins(e);
                earliest = &e.surface;
            }
        if (!earliest) return false;
        if (!plane) plane = earliest;
        const double reach_s = plane_reach_s(*plane, first_s);
        if (!(reach_s > 0.0)) return false;
        end_s = first_s + reach_s;
        for (const tube_echo<T>& e : rec.echoes) {
            if (e.surface.object != no_object || !(begins(e) < end_s)) continue;
            if (!same_normal(e.surface.normal, plane->normal)) return false;
        }
        windows();
        return true;
    }

    /// The most columns per side whose echoes are held at once, so that a faint column's share of the line can decide
    /// how deep it divides (ray_density::along_split_echo); under a beam that needs more, three are held in turn.
    static constexpr std::size_t max_held_columns = 64;
    /// A column divided less deeply than an even column, by its weight, whose echo departs in a sample where it carries
    /// more than this share of the line (the side's columns' first echoes summed) divides there to an even column's
    /// depth: where the beam's axis is in shadow, the faint columns make the line.
    static constexpr double faint_share = 0.2;

    /// Two facet normals the same to 1e-3 rad (as ray_density::along_split_nadir judges one plane).
    static bool same_normal(const vec3<T>& a, const vec3<T>& b) noexcept {
        const double dx = double(a.x) - double(b.x), dy = double(a.y) - double(b.y), dz = double(a.z) - double(b.z);
        return dx * dx + dy * dy + dz * dz <= 1e-6;
    }

    /// The samples [k0, k1] an echo piece between two-way times t0 and t1 (s) falls in, within the line; false where
    /// it falls outside.
    [[nodiscard]] bool samples_of(const tube_echo<T>& e, std::size_t& k0, std::size_t& k1) const noexcept {
        const double x = std::min(e.t0_s, e.t1_s) / dt_, y = std::max(e.t0_s, e.t1_s) / dt_;
        if (!(x < double(samples_)) || !(y >= 0.0)) return false;
        k0 = static_cast<std::size_t>(std::max(0.0, x));
        k1 = static_cast<std::size_t>(std::min(y, double(samples_ - 1)));
        return true;
    }

    /// A column's echo in each time sample, into `rec.per_sample`: each piece's power spread evenly over its times.
    void echo_per_sample(column_record& rec) const {
        rec.per_sample.assign(samples_, 0.0);
        rec.planar = true;
        for (const tube_echo<T>& e : rec.echoes) {
            if (e.surface.object != no_object) {
                rec.planar = false;
                break;
            }
            if (&e == &rec.echoes.front()) rec.normal = e.surface.normal;
            else if (!same_normal(e.surface.normal, rec.normal)) {
                rec.planar = false;
                break;
            }
        }
        for (const tube_echo<T>& e : rec.echoes) {
            std::size_t k0 = 0, k1 = 0;
            if (!samples_of(e, k0, k1)) continue;
            const double x = std::min(e.t0_s, e.t1_s) / dt_, y = std::max(e.t0_s, e.t1_s) / dt_;
            if (!(y > x)) { // a point
                rec.per_sample[k0] += e.power;
                continue;
            }
            for (std::size_t k = k0; k <= k1; ++k) { // its share of each sample, none beyond the line
                const double lo = std::max(x, double(k)), hi = std::min(y, double(k + 1));
                if (hi > lo) rec.per_sample[k] += e.power * (hi - lo) / (y - x);
            }
        }
    }

    /// How far column j's centre lies from its left neighbour's toward its right one's, as a fraction of the distance
    /// between them (0.5 where the three are alike wide), from the side's column edges; 0.5 at either end of the side.
    [[nodiscard]] static double toward_right(const std::vector<double>& edges, std::size_t j) noexcept {
        if (j == 0 || j + 2 >= edges.size()) return 0.5;
        const double left = 0.5 * (edges[j - 1] + edges[j]), centre = 0.5 * (edges[j] + edges[j + 1]),
                     right = 0.5 * (edges[j + 1] + edges[j + 2]);
        return right > left ? std::clamp((centre - left) / (right - left), 0.0, 1.0) : 0.5;
    }

    /// Where column j's echo departs from what its neighbours' make likely (ray_density::along_split_echo), the launch
    /// intervals whose echoes fall in those samples, added to `out`. With I the echo per unit of the beam's weight,
    /// a sample departs where w_j |I_j - ((1 - f) I_left + f I_right)| > along_split_echo (S_left + S_j + S_right),
    /// S the columns' echoes there, f how far column j's centre lies from the left one's toward the right one's
    /// (toward_right: 0.5 for even columns; the one neighbour's I at the side's ends): the midpoint rule's value for
    /// the column is then not its width's, and thirds sample it where it changes.
    void echo_windows(const column_record& here, const column_record* left, const column_record* right,
                      const std::vector<double>& weights, std::size_t j, double f, std::vector<unsigned char>& flags,
                      std::vector<redo_range>& out, const std::vector<double>* line, std::vector<redo_range>& deep) const {
        // One plane under all three (a level or sloping seabed and nothing else): nothing to divide.
        auto on_plane = [&](const column_record* r) {
            return !r || r->echoes.empty() || (r->planar && (here.echoes.empty() || same_normal(r->normal, here.normal)));
        };
        if (here.planar && on_plane(left) && on_plane(right)) return;
        const double wj = weights[j];
        const double wl = left ? weights[j - 1] : 0.0, wr = right ? weights[j + 1] : 0.0;
        if (!(wj > 0.0) || (!(wl > 0.0) && !(wr > 0.0))) return;
        const bool both = wl > 0.0 && wr > 0.0;
        auto three = [&](std::size_t k) {
            return here.per_sample[k] + (left ? left->per_sample[k] : 0.0) + (right ? right->per_sample[k] : 0.0);
        };
        double strongest = 0.0;
        for (std::size_t k = 0; k < samples_; ++k) strongest = std::max(strongest, three(k));
        const double floor = 1e-5 * strongest; // 50 dB
        flags.assign(samples_, 0);
        bool any = false;
        for (std::size_t k = 0; k < samples_; ++k) {
            const double s3 = three(k);
            if (!(s3 > floor)) continue;
            const double il = wl > 0.0 ? left->per_sample[k] / wl : 0.0, ir = wr > 0.0 ? right->per_sample[k] / wr : 0.0;
            const double expected = both ? (1.0 - f) * il + f * ir : (wl > 0.0 ? il : ir);
            if (std::abs(here.per_sample[k] - wj * expected) > density_.along_split_echo * s3) {
                flags[k] = line && here.per_sample[k] > faint_share * (*line)[k] ? 2 : 1;
                any = true;
            }
        }
        if (!any) return;
        const std::size_t intervals = here.first.empty() ? 0 : here.first.size() - 1;
        for (std::size_t k = 0; k < intervals; ++k) {
            unsigned char departs = 0; // 2: where the column carries a share of the line
            for (std::size_t i = here.first[k]; i < here.first[k + 1] && departs < 2; ++i) {
                std::size_t k0 = 0, k1 = 0;
                if (!samples_of(here.echoes[i], k0, k1)) continue;
                for (std::size_t q = k0; q <= k1 && departs < 2; ++q) departs = std::max(departs, flags[q]);
            }
            if (departs == 0) continue;
            for (std::vector<redo_range>* into : {&out, departs == 2 ? &deep : nullptr}) {
                if (!into) continue;
                if (!into->empty() && into->back().k1 + 1 == k) into->back().k1 = k;
                else into->push_back({k, k});
            }
        }
    }

    /// Where two neighbouring columns' edges disagree, added to `out`. The edges are paired one to one in order of
    /// time (each with the earliest unpaired edge of the other within a sample of two-way time), so that where one
    /// column has two edges and the other one, one of the two is unpaired even if both lie within a sample of it
    /// (matching an edge with any of the other's within a sample hides such disagreements where edges are dense:
    /// on the 1 km survey's 72 lines one to one takes the RMS of the lines' RMS from 0.155 to 0.148 dB, no line
    /// worse, for 3 % more echo pieces). An unpaired edge moved between them, by about the distance to the
    /// other's nearest edge, so within a column it lies within that distance of where the column's centre sees it,
    /// either way: that stretch of launch intervals (the columns' launch angles nearly coincide), one interval more,
    /// is traced again. If the other column has no edge at all (an object ending between them), the stretch spans
    /// every edge of the column that has them. (Intervals whose echoes merely arrive at the same times, from
    /// elsewhere in the column, were traced again too once: that changed no error on the rough scenes of
    /// bench/bench_rough_accuracy.cpp by more than 0.01 dB, and leaving them out lowered the survey scene's a little
    /// (0.74 to 0.70 dB RMS over twelve lines), while they cost up to a quarter more rays.)
    void disagreements(const std::vector<column_edge>& x, const std::vector<column_edge>& y,
                       std::vector<redo_range>& out) const {
        const double tol = dt_;
        auto span = [&](const column_edge& a, const column_edge& b) {
            const std::size_t dk = (a.k > b.k ? a.k - b.k : b.k - a.k) + 1;
            out.push_back({a.k - std::min(a.k, dk), a.k + dk});
        };
        if (x.empty() != y.empty()) { // an object ending between them: every edge of the column that has them
            const std::vector<column_edge>& a = x.empty() ? y : x;
            for (const column_edge& u : a) {
                span(u, a.front());
                span(u, a.back());
            }
            return;
        }
        // One to one: each edge pairs with at most one of the other's, the earliest within a sample (both by time).
        auto nearest = [](const column_edge& t, const std::vector<column_edge>& b) -> const column_edge& {
            const auto it = std::lower_bound(b.begin(), b.end(), t.t,
                                             [](const column_edge& e, double v) { return e.t < v; });
            if (it == b.end()) return b.back();
            if (it != b.begin() && std::abs((it - 1)->t - t.t) < std::abs(it->t - t.t)) return *(it - 1);
            return *it;
        };
        std::size_t i = 0, j = 0;
        while (i < x.size() || j < y.size()) {
            if (i < x.size() && j < y.size() && std::abs(x[i].t - y[j].t) <= tol) {
                ++i;
                ++j;
            } else if (j == y.size() || (i < x.size() && x[i].t < y[j].t)) {
                const column_edge& u = nearest(x[i], y);
                span(x[i], u);
                span(u, x[i]);
                ++i;
            } else {
                const column_edge& u = nearest(y[j], x);
                span(y[j], u);
                span(u, y[j]);
                ++j;
            }
        }
    }

    /// Calls fn with the scene that the rays of the column between along-track angles lo and hi (rad) see: where
    /// `scene` is an area view that can narrow (area_view::within) and rays keep their heading, the view over the
    /// rectangle they stay over (sampling/reach.hpp, for the column's along-track angle and the side's depressions),
    /// so that a column passing beside every object does not ask the objects; else the scene itself. The rays are
    /// followed as they are through `scene`, so the echoes are the same.
    template <Scene Sc, class Fn> void in_column(const Sc& scene, const trace_frame& f, double lo, double hi, Fn&& fn) const {
        if constexpr (ReachBoundedPropagation<P> && !bouncing &&
                      requires(const vec2<T>& v) { { scene.within(v, v) } -> std::same_as<Sc>; }) {
            const T along = static_cast<T>(0.5 * (lo + hi));
            const double reach_m = double(one_way_limit_s()) * double(propagation_.reach_speed_mps(f.p.position.z));
            const beam_extent<T> column{along, along, f.ext.depression_min_rad, f.ext.depression_max_rad};
            const plane_rectangle<T> r = side_reach(f.p, f.sd, column, reach_m, true);
            fn(scene.within(r.lo, r.hi));
        } else {
            fn(scene);
        }
    }

    /// Traces the column between along-track angles lo and hi (rad) and visits its echoes; with a record given, the
    /// two-way times of the edges its refinement located go to its `edges`, and its `interval` follows the launch
    /// interval being refined.
    template <Scene Sc>
    void trace_column(const Sc& scene, const trace_frame& f, double lo, double hi, column_scratch& s,
                      column_record* record, echo_sink visit) const {
        const pose<T>& p = f.p;
        const side sd = f.sd;
        const T along = static_cast<T>(0.5 * (lo + hi));
        // Solid angle per unit depression of the column: int cos(a) da over the column.
        const double column_sr = std::sin(hi) - std::sin(lo);
        std::vector<T>& angles = s.angles;
        depression_angles<T>(angles, sd, along, f.ext.depression_min_rad, f.ext.depression_max_rad, p.body_to_world,
                             f.launch, f.max_range_m, f.cd);
        // The column's rays, traced together (sss::trace_all: a propagation and scene that share work among
        // the rays of a column do so; others go ray by ray).
        s.rays.resize(angles.size());
        std::size_t n_rays = 0;
        for (const T e : angles)
            if (!std::isnan(e)) s.rays[n_rays++] = ray<T>{p.position, p.to_world(beam_direction(sd, along, e))};
        s.rays.resize(n_rays);
        s.paths.resize(s.rays.size());
        trace_all(propagation_, std::span<const ray<T>>(s.rays), scene, f.t_max_one_way,
                  std::span<std::optional<path<T>>>(s.paths));
        ray_end prev, prev_bounce;
        bool in_run = false;
        std::size_t k = 0;
        const column_context col{p,
                                 sd,
                                 along,
                                 f.t_max_one_way,
                                 column_sr,
                                 density_.refine_depth == 0 ? 0 : s.rays.size() / 2 + density_.refine_rays,
                                 density_.refine_depth == 0 ? 0 : shading_budget(s.rays.size()),
                                 record,
                                 thin_windows(f, lo, hi, s.thin)};
        refine_budget budget{col.max_extra, col.max_shading, col.max_extra};
        if (record) record->first.resize(angles.size());
        for (std::size_t i = 0; i < angles.size(); ++i) {
            const T e = angles[i];
            if (std::isnan(e)) {
                if (record) record->first[i] = record->echoes.size();
                in_run = false;
                continue;
            }
            ray_end bounce;
            const ray_end cur = echo(scene, sd, along, e, s.rays[k].direction, s.paths[k], f.t_max_one_way, column_sr, bounce);
            ++k;
            if (in_run) {
                if (record) record->interval = i - 1;
                refine(scene, col, prev, prev_bounce, cur, bounce, 0, budget, visit);
            }
            if (record) record->first[i] = record->echoes.size(); // interval i begins (if it is one)
            prev = cur;
            prev_bounce = bounce;
            in_run = true;
        }
        // The spacing assumed straight rays to a flat seabed; bent rays (or a scene rising towards the far end)
        // may still return in time beyond the last angle. Continue at the last angular step while they do.
        if (in_run && prev.valid && angles.size() >= 2 && !std::isnan(angles[angles.size() - 2])) {
            const double step = double(angles[angles.size() - 2]) - prev.e;
            for (std::size_t extra = 0; step > 0.0 && extra < angles.size(); ++extra) {
                const double e = prev.e - step;
                if (e < double(f.ext.depression_min_rad)) break;
                ray_end bounce;
                const ray_end cur = shoot(scene, p, sd, along, static_cast<T>(e), f.t_max_one_way, column_sr, bounce,
                                          prev.valid ? &prev : nullptr);
                if (cur.valid) {
                    emit_tube(prev, cur, step, visit);
                    if constexpr (bouncing) emit_tube(prev_bounce, bounce, step, visit);
                } else {
                    // The far edge of coverage lies within this step: located by refinement as any edge is
                    // (detail::judge_tube), so that the last ray's echo does not stand for the whole part of the
                    // step within the line (here, in refracting water, neighbours may land two samples apart).
                    // No edge is recorded for the along-track check: these rays lie past the column's launch
                    // intervals, which the check divides and compares.
                    refine(scene, col, prev, prev_bounce, cur, bounce, 0, budget, visit, /*recorded=*/true);
                }
                if (!cur.valid && !bounce.valid) break;
                prev = cur;
                prev_bounce = bounce;
            }
        }
    }

    /// How many times a disagreeing stretch of a column may be divided into thirds: ray_density::along_split,
    /// rounded down to a power of three.
    [[nodiscard]] std::size_t division_levels() const noexcept {
        std::size_t levels = 0;
        for (std::size_t w = 3; w <= density_.along_split; w *= 3) {
            ++levels;
            if (w > density_.along_split / 3) break;
        }
        return levels;
    }

    /// The beam's two-way weight on the column between along-track angles `bounds` (rad) of side sd: its weight at
    /// the column's centre, summed over eight depressions across the extent (the along-track pattern of a planar
    /// array hardly depends on depression), times the column's solid angle per unit depression.
    [[nodiscard]] double column_weight(const beam_extent<T>& ext, side sd, std::pair<double, double> bounds) const noexcept {
        const T along = static_cast<T>(0.5 * (bounds.first + bounds.second));
        const double e0 = double(ext.depression_min_rad), e1 = double(ext.depression_max_rad);
        double w = 0.0;
        for (int q = 0; q < 8; ++q)
            w += double(beam_.weight(sd, along, static_cast<T>(e0 + (e1 - e0) * (double(q) + 0.5) / 8.0)));
        return w * (std::sin(bounds.second) - std::sin(bounds.first));
    }

    /// Replaces the column between along-track angles lo and hi, over the launch intervals `runs`, by its thirds.
    /// The middle third is centred where the column is, so its rays are the column's own: its echoes are `rec`'s
    /// (the column's, with powers `scale` times `rec`'s), times the third's share of the column's solid angle. The
    /// outer two are traced. Where a third's located edges disagree with its neighbouring third's (as columns'
    /// do in trace_over), the stretch is divided again, `depth` levels deep at most (the column's depth from
    /// trace_over); elsewhere the third's echoes stand.
    template <Scene Sc>
    void divide(const Sc& scene, const trace_frame& f, double lo, double hi, const std::vector<T>& angles,
                const column_record& rec, double scale, const std::vector<std::pair<std::size_t, std::size_t>>& runs_in,
                std::size_t level, std::size_t depth, std::size_t target_depth, trace_buffers& b, echo_sink visit) const {
        const double width = (hi - lo) / 3.0;
        const double a = lo + width, c = hi - width;
        const double middle = scale * (std::sin(c) - std::sin(a)) / (std::sin(hi) - std::sin(lo));
        auto emit_middle = [&](std::size_t k) {
            for (std::size_t i = rec.first[k]; i < rec.first[k + 1]; ++i) {
                tube_echo<T> e = rec.echoes[i];
                e.power *= middle;
                visit(e);
            }
        };
        const std::vector<std::pair<std::size_t, std::size_t>>* body_runs = &runs_in;
        if (level + 1 >= depth) {
            // The last level, but over a small target (down to target_depth): those launch intervals go on dividing.
            const std::vector<std::pair<std::size_t, std::size_t>>* rest = &runs_in;
            if (level + 1 < target_depth) {
                division& d = b.divisions[level];
                d.windows.clear();
                target_windows(b.targets, lo, hi, angles, d.windows, (hi - lo) / 3.0);
                if (!d.windows.empty()) {
                    split_runs(runs_in, d.windows, angles.size() - 1, d.marks, d.rest, d.deeper);
                    rest = &d.rest;
                    body_runs = &d.deeper;
                }
            }
            const std::size_t stride = density_.along_split_sparse ? 2 : 1;
            if (!rest->empty()) {
                in_column(scene, f, lo, a, [&](const Sc& col) {
                    trace_runs(col, f, lo, a, angles, *rest, b.scratch, nullptr, visit, stride);
                });
                in_column(scene, f, c, hi, [&](const Sc& col) {
                    trace_runs(col, f, c, hi, angles, *rest, b.scratch, nullptr, visit, stride);
                });
                for (const auto& [k0, k1] : *rest)
                    for (std::size_t k = k0; k <= k1; ++k) emit_middle(k);
            }
            if (body_runs == &runs_in || body_runs->empty()) return;
        }
        const std::vector<std::pair<std::size_t, std::size_t>>& runs = *body_runs;
        division& d = b.divisions[level];
        for (std::size_t s = 0; s < 2; ++s) {
            column_record& r = d.outer[s];
            r.echoes.clear();
            r.edges.clear();
            r.first.assign(angles.size(), 0);
            r.seabed_edges = rec.seabed_edges;
            auto keep = [&r](const tube_echo<T>& t) { r.echoes.push_back(t); };
            const double s_lo = s == 0 ? lo : c, s_hi = s == 0 ? a : hi;
            in_column(scene, f, s_lo, s_hi, [&](const Sc& col) { trace_runs(col, f, s_lo, s_hi, angles, runs, b.scratch, &r, keep); });
            std::sort(r.edges.begin(), r.edges.end(), [](const column_edge& x, const column_edge& y) { return x.t < y.t; });
        }
        // The middle third's edges: the column's, within the runs.
        const std::size_t intervals = angles.size() - 1;
        d.inside.assign(intervals, 0);
        for (const auto& [k0, k1] : runs)
            for (std::size_t k = k0; k <= k1; ++k) d.inside[k] = 1;
        d.middle_edges.clear();
        for (const column_edge& e : rec.edges)
            if (e.k < intervals && d.inside[e.k]) d.middle_edges.push_back(e);
        // Where the left third disagrees with the middle (the first half of cover) and the middle with the right
        // (the second), as differences of the windows' ends.
        d.cover.assign(2 * (intervals + 1), 0);
        for (std::size_t pair = 0; pair < 2; ++pair) {
            d.windows.clear();
            disagreements(pair == 0 ? d.outer[0].edges : d.middle_edges, pair == 0 ? d.middle_edges : d.outer[1].edges,
                          d.windows);
            std::ptrdiff_t* cover = d.cover.data() + pair * (intervals + 1);
            for (const redo_range& w : d.windows) {
                if (w.k0 >= intervals) continue;
                ++cover[w.k0];
                --cover[std::min(w.k1 + 1, intervals)];
            }
        }
        // Each third over a small target divides again there, whatever the edges say.
        const std::vector<target_span>& targets = b.targets;
        const bool any_target = std::any_of(targets.begin(), targets.end(), [&](const target_span& t) {
            return t.along_hi > lo && t.along_lo < hi;
        });
        if (any_target) {
            d.forced.assign(3 * (intervals + 1), 0);
            const double third_lo[3] = {lo, a, c}, third_hi[3] = {a, c, hi};
            for (std::size_t t = 0; t < 3; ++t) {
                d.windows.clear();
                // Past the column's depth, only the targets the third is still too wide for.
                target_windows(targets, third_lo[t], third_hi[t], angles, d.windows,
                               level + 1 >= depth ? third_hi[t] - third_lo[t] : 0.0);
                std::ptrdiff_t* forced = d.forced.data() + t * (intervals + 1);
                for (const redo_range& w : d.windows) {
                    ++forced[w.k0];
                    --forced[std::min(w.k1 + 1, intervals)];
                }
            }
        }
        for (auto& r : d.runs) r.clear();
        std::ptrdiff_t left = 0, right = 0;
        std::ptrdiff_t over[3] = {0, 0, 0};
        std::size_t next = 0; // the next interval whose cover is summed
        for (const auto& [k0, k1] : runs) {
            for (; next < k0; ++next) {
                left += d.cover[next];
                right += d.cover[intervals + 1 + next];
                if (any_target)
                    for (std::size_t t = 0; t < 3; ++t) over[t] += d.forced[t * (intervals + 1) + next];
            }
            for (std::size_t k = k0; k <= k1; ++k, ++next) {
                left += d.cover[k];
                right += d.cover[intervals + 1 + k];
                if (any_target)
                    for (std::size_t t = 0; t < 3; ++t) over[t] += d.forced[t * (intervals + 1) + k];
                const bool redo[3] = {left > 0 || over[0] > 0, left > 0 || right > 0 || over[1] > 0, right > 0 || over[2] > 0};
                for (std::size_t t = 0; t < 3; ++t) {
                    if (redo[t]) {
                        auto& sub = d.runs[t];
                        if (!sub.empty() && sub.back().second + 1 == k) sub.back().second = k;
                        else sub.emplace_back(k, k);
                    } else if (t == 1) {
                        emit_middle(k);
                    } else {
                        const column_record& r = d.outer[t / 2];
                        for (std::size_t i = r.first[k]; i < r.first[k + 1]; ++i) visit(r.echoes[i]);
                    }
                }
            }
        }
        if (!d.runs[0].empty())
            divide(scene, f, lo, a, angles, d.outer[0], 1.0, d.runs[0], level + 1, depth, target_depth, b, visit);
        if (!d.runs[1].empty())
            divide(scene, f, a, c, angles, rec, middle, d.runs[1], level + 1, depth, target_depth, b, visit);
        if (!d.runs[2].empty())
            divide(scene, f, c, hi, angles, d.outer[1], 1.0, d.runs[2], level + 1, depth, target_depth, b, visit);
    }

    /// Visits the echoes of the launch intervals `truns` of the column between along-track angles lo and hi (rad),
    /// traced as `here`, each shared with its thirds: interval k's echo is tau[k] times the thirds' (the outer two
    /// traced here, the middle the column's own scaled to its solid angle) plus 1 - tau[k] times the column's.
    template <Scene Sc>
    void taper(const Sc& scene, const trace_frame& f, double lo, double hi, const column_record& here,
               const std::vector<std::pair<std::size_t, std::size_t>>& truns, const std::vector<double>& tau,
               trace_buffers& b, echo_sink visit) const {
        const double width = (hi - lo) / 3.0;
        const double a = lo + width, c = hi - width;
        const double middle = (std::sin(c) - std::sin(a)) / (std::sin(hi) - std::sin(lo));
        for (std::size_t s = 0; s < 2; ++s) {
            column_record& r = b.taper_outer[s];
            r.echoes.clear();
            r.edges.clear();
            r.first.assign(here.angles.size(), 0);
            r.seabed_edges = here.seabed_edges;
            auto keep = [&r](const tube_echo<T>& t) { r.echoes.push_back(t); };
            const double s_lo = s == 0 ? lo : c, s_hi = s == 0 ? a : hi;
            in_column(scene, f, s_lo, s_hi,
                      [&](const Sc& col) { trace_runs(col, f, s_lo, s_hi, here.angles, truns, b.scratch, &r, keep); });
        }
        for (const auto& [k0, k1] : truns)
            for (std::size_t k = k0; k <= k1; ++k) {
                const double t = tau[k];
                for (std::size_t i = here.first[k]; i < here.first[k + 1]; ++i) {
                    tube_echo<T> e = here.echoes[i];
                    e.power *= t * middle + 1.0 - t;
                    visit(e);
                }
                for (const column_record& r : b.taper_outer)
                    for (std::size_t i = r.first[k]; i < r.first[k + 1]; ++i) {
                        tube_echo<T> e = r.echoes[i];
                        e.power *= t;
                        visit(e);
                    }
            }
    }

    /// Traces the launch intervals `runs` (each [k0, k1]: the rays at angles[k0] to angles[k1 + 1]) of a column
    /// between along-track angles lo and hi (rad), over the launch angles of the column it divides, with that
    /// column's refinement budget, and visits their echoes. With a record given, as trace_column: the located
    /// edges go to its `edges`, and where interval k's echoes begin to its `first[k]` (and where the last
    /// interval of a run ends to `first[k1 + 1]`). Without one, `stride` > 1 traces every stride-th angle of each
    /// run and its last (ray_density::along_split_sparse).
    template <Scene Sc>
    void trace_runs(const Sc& scene, const trace_frame& f, double lo, double hi, const std::vector<T>& angles,
                    const std::vector<std::pair<std::size_t, std::size_t>>& runs, column_scratch& s,
                    column_record* record, echo_sink visit, std::size_t stride = 1) const {
        const T along = static_cast<T>(0.5 * (lo + hi));
        const double column_sr = std::sin(hi) - std::sin(lo);
        if (record || stride < 1) stride = 1; // a record's intervals each need their own rays
        // The launch angle traced after angles[k] in the run ending at interval k1.
        const auto next = [stride](std::size_t k, std::size_t k1) { return std::min(k + stride, k1 + 1); };
        std::size_t n_rays = 0;
        for (const auto& [k0, k1] : runs)
            for (std::size_t k = k0;; k = next(k, k1)) {
                ++n_rays;
                if (k == k1 + 1) break;
            }
        s.rays.resize(n_rays);
        std::size_t r = 0;
        for (const auto& [k0, k1] : runs)
            for (std::size_t k = k0;; k = next(k, k1)) {
                s.rays[r++] = ray<T>{f.p.position, f.p.to_world(beam_direction(f.sd, along, angles[k]))};
                if (k == k1 + 1) break;
            }
        s.paths.resize(s.rays.size());
        trace_all(propagation_, std::span<const ray<T>>(s.rays), scene, f.t_max_one_way,
                  std::span<std::optional<path<T>>>(s.paths));
        const column_context col{f.p,
                                 f.sd,
                                 along,
                                 f.t_max_one_way,
                                 column_sr,
                                 angles.size() / 2 + density_.refine_rays,
                                 shading_budget(angles.size()),
                                 record,
                                 thin_windows(f, lo, hi, s.thin)};
        refine_budget budget{col.max_extra, col.max_shading, col.max_extra};
        std::size_t q = 0;
        for (const auto& [k0, k1] : runs) {
            ray_end prev, prev_bounce;
            std::size_t k_prev = k0;
            for (std::size_t k = k0;; k = next(k, k1)) {
                ray_end bounce;
                const ray_end cur = echo(scene, f.sd, along, angles[k], s.rays[q].direction, s.paths[q], f.t_max_one_way,
                                         column_sr, bounce);
                ++q;
                if (k > k0) {
                    if (record) record->interval = k - 1;
                    refine(scene, col, prev, prev_bounce, cur, bounce, 0, budget, visit, false, k - k_prev);
                }
                if (record) record->first[k] = record->echoes.size();
                prev = cur;
                prev_bounce = bounce;
                k_prev = k;
                if (k == k1 + 1) break;
            }
        }
    }

    /// What refining one column needs to trace a ray between two others.
    struct column_context {
        const pose<T>& p;
        side sd;
        T along;
        T t_max_one_way;
        double column_sr;
        std::size_t max_extra;       ///< extra rays this column may trace to locate edges (and, apart, over targets)
        std::size_t max_shading;     ///< and to follow an echo that changes fast (facets' edges)
        column_record* record;       ///< where located edges go (none: not recorded)
        const std::vector<thin_window>* thin; ///< the small targets over the column (none: null)
    };

    /// The extra rays a column has left: for edges, for echoes that change fast, and for launch intervals over small
    /// targets. Apart, so that the many facets' edges of rough relief (or a field of boulders) never leave an
    /// occlusion's edge unlocated.
    struct refine_budget {
        std::size_t edges;
        std::size_t shading;
        std::size_t targets; ///< and to halve launch intervals over small targets (thin_window), as many as for edges
    };
    /// The extra rays a column of `rays` rays may spend on echoes that change fast: 8 per ray. A tube of a ray per
    /// sample across a facet's edge takes about 3 to reach the eighth of a sample that facets' edges are refined to
    /// (sampling/detail/tube_refinement.hpp), and only tubes holding such an edge are refined, so it seldom binds; a
    /// budget that ran out part of the way along a column would leave its refined and unrefined stretches biased
    /// differently (on rippled relief at 0.05 m cells, a budget of the column's own rays doubled the error it was spent
    /// to lower).
    [[nodiscard]] static std::size_t shading_budget(std::size_t rays) noexcept {
        return rays <= std::numeric_limits<std::size_t>::max() / 8 ? 8 * rays : rays;
    }

    /// The energy between adjacent rays a and b (and their bounced paths): one tube where they are neighbours on
    /// one surface (and their interval is narrow enough for the small targets over the column: thin_window); else,
    /// while the depth and the column's budgets allow and the edge between them is not yet located to
    /// `edge_tolerance` of a sample, the ray between them is traced and each half refined in turn.
    /// A located edge closes the tube on each side: each end keeps its own half of the (now tiny) angular step; where
    /// one end meets its facet near grazing incidence, so that its half step still spans more than the edge's
    /// tolerance, the rays between them are traced on (from the shading budget) for where its echo lies, the edge
    /// being recorded once, where it was located (`recorded`: it is, for the pairs within; a pair within that finds
    /// another edge draws on the edges' budget, as any edge). `intervals`: the launch intervals between a and b at
    /// depth 0 (more than one in a sparse column, ray_density::along_split_sparse). `bracket`: whether a pair across a
    /// facet's edge may be bracketed (facet_bracket) rather than halved; not within a bracket's own pairs.
    template <Scene Sc>
    void refine(const Sc& scene, const column_context& col, const ray_end& a, const ray_end& a_bounce, const ray_end& b,
                const ray_end& b_bounce, std::size_t depth, refine_budget& budget, echo_sink visit,
                bool recorded = false, std::size_t intervals = 1, const ray_end* outer = nullptr,
                bool bracket = true) const {
        // The guide of a ray launched between a and b: the steeper of the two (the steeper end of the interval refined
        // at depth 0, `outer`, where neither met anything), and `outer` again where the nearer one is too close for a
        // propagation's bound.
        if (depth == 0) outer = steeper(a, b);
        const ray_end* near = steeper(a, b);
        const ray_end* guide = near ? near : outer;
        const ray_end* fallback = outer != guide ? outer : nullptr;
        const double de = std::abs(b.e - a.e);
        detail::tube_verdict v =
            detail::judge_tube(as_tube_end(a), as_tube_end(b), de, dt_, depth == 0 ? intervals : 1);
        // Two rays on one surface either side of a small target they both missed agree: where the interval is wider
        // than a target over the column allows, it is halved until it is not (trace_column, thin_window).
        const bool over_target =
            v == detail::tube_verdict::continuous && col.thin && steps_over(*col.thin, a.e, b.e);
        if (over_target) v = detail::tube_verdict::split;
        const double mid = 0.5 * (a.e + b.e);
        const T e_mid = static_cast<T>(mid);
        std::size_t& left = over_target ? budget.targets
                            : v == detail::tube_verdict::coarse ? budget.shading
                                                                : budget.edges;
        const bool can_split = v != detail::tube_verdict::located && depth < density_.refine_depth && left > 0 &&
                               double(e_mid) != a.e && double(e_mid) != b.e;
        if (v == detail::tube_verdict::continuous || (over_target && !can_split)) {
            emit_tube(a, b, de, visit);
            if constexpr (bouncing) emit_tube(a_bounce, b_bounce, de, visit);
            return;
        }
        if (!can_split) {
            if ((depth == 0 && v == detail::tube_verdict::split) || v == detail::tube_verdict::coarse)
                emit_tube(a, b, de, visit); // not refined: as before
            else {                                                                            // a located edge
                // Recorded for the along-track check: the edges between surfaces (objects' silhouettes), and with
                // along_split_seabed the seabed's own (the far ends of its shadows); and an object's silhouette against
                // open water, where the rays past it meet nothing within the line (a moored target at far range:
                // left out, its silhouette was never compared, and a sphere's front between two columns was lost).
                if (!recorded && col.record && a.valid && b.valid &&
                    (col.record->seabed_edges || !same_surface(a.surface, b.surface))) {
                    col.record->edges.push_back({a.t, col.record->interval});
                    col.record->edges.push_back({b.t, col.record->interval});
                } else if (!recorded && col.record && a.valid != b.valid) {
                    const ray_end& lit = a.valid ? a : b;
                    if (lit.surface.object != no_object) col.record->edges.push_back({lit.t, col.record->interval});
                }
                if (v == detail::tube_verdict::located && budget.shading > 0 && depth < density_.refine_depth &&
                    double(e_mid) != a.e && double(e_mid) != b.e &&
                    detail::ends_unresolved(as_tube_end(a), as_tube_end(b), de, dt_)) {
                    --budget.shading; // a grazing end: where its echo lies, not where the edge is
                    ray_end m_bounce;
                    const ray_end m = shoot(scene, col.p, col.sd, col.along, e_mid, col.t_max_one_way, col.column_sr,
                                            m_bounce, guide, fallback);
                    refine(scene, col, a, a_bounce, m, m_bounce, depth + 1, budget, visit, true, 1, outer, bracket);
                    refine(scene, col, m, m_bounce, b, b_bounce, depth + 1, budget, visit, true, 1, outer, bracket);
                    return;
                }
                emit_ends(a, b, de, visit);
            }
            if constexpr (bouncing) emit_tube(a_bounce, b_bounce, de, visit);
            return;
        }
        if (v == detail::tube_verdict::coarse && bracket) {
            // Across a facet's edge: the rays just either side of where the edge lies, rather than the middle one
            // (facet_bracket). The pair they make spans the edge within the tube's tolerance and the pairs outside it
            // lie on one facet each: two rays where halving takes four or more. A poor estimate costs two rays: the
            // pairs are then judged, and halved, as a halving's would be.
            T at[2];
            const std::size_t count = facet_bracket(scene, col, a, b, at);
            if (count > 0 && left >= count) {
                left -= count;
                ray_end m_bounce[2];
                ray_end m[2];
                for (std::size_t k = 0; k < count; ++k)
                    m[k] = shoot(scene, col.p, col.sd, col.along, at[k], col.t_max_one_way, col.column_sr, m_bounce[k],
                                 guide, fallback);
                // Where the two rays straddle the edge, it goes to the along-track check as halving would have
                // located it (facet_edge_marks_line). The pairs within are halved, not bracketed again: where the
                // estimate missed (a grazing end, whose facet the sheet of rays meets nearly edge-on, leaves a
                // first-order error in the step wider than the bracket), the edge lies in an outer pair, and another
                // bracket from the same estimate would miss again.
                const bool straddled =
                    count == 2 && detail::facet_edge(as_tube_end(m[0]), as_tube_end(m[1]));
                bool marked = recorded;
                if (straddled && !recorded && col.record && col.record->seabed_edges &&
                    detail::facet_edge_marks_line(as_tube_end(a), as_tube_end(b))) {
                    col.record->edges.push_back({m[0].t, col.record->interval});
                    col.record->edges.push_back({m[1].t, col.record->interval});
                    marked = true;
                }
                refine(scene, col, a, a_bounce, m[0], m_bounce[0], depth + 1, budget, visit, recorded, 1, outer, false);
                if (count == 2)
                    refine(scene, col, m[0], m_bounce[0], m[1], m_bounce[1], depth + 1, budget, visit, marked, 1, outer,
                           false);
                refine(scene, col, m[count - 1], m_bounce[count - 1], b, b_bounce, depth + 1, budget, visit, recorded, 1,
                       outer, false);
                return;
            }
        }
        --left;
        ray_end m_bounce;
        const ray_end m =
            shoot(scene, col.p, col.sd, col.along, e_mid, col.t_max_one_way, col.column_sr, m_bounce, guide, fallback);
        refine(scene, col, a, a_bounce, m, m_bounce, depth + 1, budget, visit, recorded, 1, outer, bracket);
        refine(scene, col, m, m_bounce, b, b_bounce, depth + 1, budget, visit, recorded, 1, outer, bracket);
    }

    /// The launch angles (into `at`, in order from a to b; returns how many) at which to trace across the edge between
    /// the seabed's facets that valid rays a and b met: either side of where the edge lies (facet_edge_crossing), a
    /// sixteenth of a sample apart in time by the larger of the two ends' stretches (half the tolerance a tube across
    /// a facet's edge is refined to, judge_tube); one where the other would lie at or beyond an end of the step. None,
    /// and the middle ray is traced instead, where halving would take at most three rays (a span of at most a sample)
    /// or the estimate does not apply: not two facets of the seabed, no crossing between the hits, or the seabed not
    /// showing the two facets meeting there (facet_reaches_crossing: other facets between them, or too far from the
    /// grid's origin for its heights to tell).
    template <Scene Sc>
    [[nodiscard]] std::size_t facet_bracket(const Sc& scene, const column_context& col, const ray_end& a,
                                            const ray_end& b, T (&at)[2]) const {
        if (!density_.bracket_facet_edges || !a.valid || !b.valid) return 0;
        const detail::tube_end ta = as_tube_end(a), tb = as_tube_end(b);
        // Halving locates the edge to the tolerance (an eighth of a sample) in about log2(span / tolerance) rays: the
        // bracket's two rays, and the checks below, pay where that is more than three.
        if (!detail::facet_edge(ta, tb) || !(detail::tube_span(ta, tb, std::abs(b.e - a.e)) > dt_)) return 0;
        const auto d3 = [](const vec3<T>& v) { return std::array<double, 3>{double(v.x), double(v.y), double(v.z)}; };
        const std::array<double, 3> pa = d3(a.surface.point), pb = d3(b.surface.point);
        const detail::facet_crossing x =
            detail::facet_edge_crossing(d3(col.p.position), pa, ta.normal, pb, tb.normal);
        const double stretch = std::max(a.stretch, b.stretch);
        if (!(x.fraction > 0.0) || !(stretch > 0.0) || !std::isfinite(stretch)) return 0;
        const double angle = std::sqrt((ta.normal[0] - tb.normal[0]) * (ta.normal[0] - tb.normal[0]) +
                                       (ta.normal[1] - tb.normal[1]) * (ta.normal[1] - tb.normal[1]) +
                                       (ta.normal[2] - tb.normal[2]) * (ta.normal[2] - tb.normal[2]));
        const auto height = [&](double x_m, double y_m) {
            return double(scene.seabed_height_m(static_cast<T>(x_m), static_cast<T>(y_m)));
        };
        const double eps = double(std::numeric_limits<T>::epsilon());
        if (!detail::facet_reaches_crossing(x.point, pa, ta.normal, angle, eps, height) ||
            !detail::facet_reaches_crossing(x.point, pb, tb.normal, angle, eps, height))
            return 0;
        const double step = b.e - a.e;
        const double half = dt_ / (32.0 * stretch) * (step > 0.0 ? 1.0 : -1.0);
        const double edge = a.e + x.fraction * step;
        const auto inside = [&](T e) { return (double(e) - a.e) * step > 0.0 && (b.e - double(e)) * step > 0.0; };
        std::size_t count = 0;
        if (const T e1 = static_cast<T>(edge - half); inside(e1)) at[count++] = e1;
        if (const T e2 = static_cast<T>(edge + half); inside(e2) && (count == 0 || e2 != at[0])) at[count++] = e2;
        return count;
    }

    [[nodiscard]] detail::tube_end as_tube_end(const ray_end& r) const noexcept {
        return {r.valid,
                r.t,
                r.stretch,
                r.gain,
                r.surface.object,
                r.surface.material,
                r.valid && density_.refine_facets && r.surface.object == no_object,
                {double(r.surface.normal.x), double(r.surface.normal.y), double(r.surface.normal.z)}};
    }

    /// Two rays on either side of an edge: each keeps its half of the step as a point.
    static void emit_ends(const ray_end& a, const ray_end& b, double de, echo_sink visit) {
        if (a.valid) visit(a.piece(a.t, 0.5 * a.power_per_rad * de));
        if (b.valid) visit(b.piece(b.t, 0.5 * b.power_per_rad * de));
    }

    /// The energy between two adjacent rays: a tube spread over their times when both ends meet the same surface
    /// (and bounced on the same surface), else each end's half as a point.
    static void emit_tube(const ray_end& a, const ray_end& b, double de, echo_sink visit) {
        const bool joined = a.valid && b.valid && same_surface(a.surface, b.surface) && same_surface(a.via, b.via);
        if (joined) {
            visit(a.piece(b.t, 0.5 * (a.power_per_rad + b.power_per_rad) * de));
        } else {
            if (a.valid) visit(a.piece(a.t, 0.5 * a.power_per_rad * de));
            if (b.valid) visit(b.piece(b.t, 0.5 * b.power_per_rad * de));
        }
    }

    /// Of two traced ends, the valid one whose ray descends faster (world frame): the guide for a ray launched
    /// between them (GuidedPropagation); null when neither is valid.
    [[nodiscard]] static const ray_end* steeper(const ray_end& a, const ray_end& b) noexcept {
        if (!a.valid || !b.valid) return a.valid ? &a : (b.valid ? &b : nullptr);
        const auto tau = [](const vec3<T>& d) { return -d.z / std::sqrt(d.x * d.x + d.y * d.y); };
        return tau(a.launch) >= tau(b.launch) ? &a : &b;
    }

    /// One ray: its two-way time and return power per radian of depression, or invalid if it meets nothing.
    /// With the specular bounce on, `bounce` receives the echo of the bounced path (else it stays invalid).
    /// `guide`, a valid end traced from the same pose, tells a GuidedPropagation where that ray met its first
    /// surface (the result is the same, sooner); `fallback`, another, is offered to a propagation that takes two
    /// (its trace_beside with two guides: propagation/concept.hpp).
    template <Scene Sc>
    [[nodiscard]] ray_end shoot(const Sc& scene, const pose<T>& p, side sd, T along, T e, T t_max_one_way,
                                double column_sr, ray_end& bounce, const ray_end* guide = nullptr,
                                const ray_end* fallback = nullptr) const {
        const vec3<T> dir = p.to_world(beam_direction(sd, along, e));
        const ray<T> r{p.position, dir};
        if constexpr (GuidedPropagation<P, Sc>) {
            if constexpr (requires { propagation_.trace_beside(r, scene, t_max_one_way, dir, T(0), dir, T(0)); }) {
                if (guide && fallback && fallback->valid)
                    return echo(scene, sd, along, e, dir,
                                propagation_.trace_beside(r, scene, t_max_one_way, guide->launch, guide->clear_range_m,
                                                          fallback->launch, fallback->clear_range_m),
                                t_max_one_way, column_sr, bounce);
            }
            if (guide)
                return echo(scene, sd, along, e, dir,
                            propagation_.trace_beside(r, scene, t_max_one_way, guide->launch, guide->clear_range_m),
                            t_max_one_way, column_sr, bounce);
        }
        return echo(scene, sd, along, e, dir, propagation_.trace(r, scene, t_max_one_way), t_max_one_way, column_sr,
                    bounce);
    }

    /// The echo of the ray launched at (along, e) that followed `traced` (none: it met nothing). Always inlined: left
    /// to its own choice, GCC 12 at -O3 kept it out of line once the simulator grew, and a ping over an open flat
    /// seabed (bench/bench_rough_accuracy.cpp) took 7 % longer.
    template <Scene Sc>
    [[nodiscard]] SSS_FORCE_INLINE ray_end echo(const Sc& scene, side sd, T along, T e, const vec3<T>& launch,
                               const std::optional<path<T>>& traced, T t_max_one_way, double column_sr,
                               ray_end& bounce) const {
        ray_end r;
        r.e = bounce.e = double(e);
        r.launch = bounce.launch = launch;
        if (!traced) return r;
        const hit<T>& h = traced->surface;
        const T sin_facet = -glm::dot(traced->arrival, h.normal);
        const T sin_graze = std::min(T(1), -glm::dot(traced->arrival, h.shading_normal));
        if (!(sin_facet > T(0)) || !(sin_graze > T(0))) return r;
        const T graze = std::asin(sin_graze);
        const double w = source_level_ * double(beam_.weight(sd, along, e)) * column_sr;
        const double sigma = double(scattering_.backscatter(graze, h.material));
        const double loss = double(traced->spreading) * double(traced->absorption) * double(traced->absorption);
        r.valid = true;
        r.t = 2.0 * double(traced->time_s);
        r.leg_s = traced->time_s;
        r.clear_range_m = traced->clear_range_m;
        r.gain = sigma * loss / double(sin_facet);
        r.power_per_rad = w * r.gain;
        r.stretch = detail::time_stretch(r.t, double(sin_facet));
        r.surface = h;
        if constexpr (bouncing) bounce_leg(scene, *traced, graze, t_max_one_way, w, bounce);
        return r;
    }

    /// The second leg of a specular bounce: reflected about the shading normal, traced on with the time left.
    /// Spreading continues the ray tube through the bounce (image source: 1/(r1 + r2)^2 in isovelocity water);
    /// the echo carries the coherent intensity reflection coefficient twice (out and back).
    template <Scene Sc>
    void bounce_leg(const Sc& scene, const path<T>& first, T graze, T t_max_one_way, double weight, ray_end& out) const {
        const hit<T>& h = first.surface;
        const T remaining = t_max_one_way - first.time_s;
        if (!(remaining > T(0))) return;
        const vec3<T> n = h.shading_normal;
        const vec3<T> d2 = first.arrival - T(2) * glm::dot(first.arrival, n) * n;
        const T offset = std::max(T(1e-4), h.distance_m * T(1e-5)); // leave the surface without meeting it again
        const auto second = propagation_.trace(ray<T>{h.point + h.normal * offset, d2}, scene, remaining);
        if (!second) return;
        const hit<T>& h2 = second->surface;
        const T sin_facet = -glm::dot(second->arrival, h2.normal);
        const T sin_graze = std::min(T(1), -glm::dot(second->arrival, h2.shading_normal));
        if (!(sin_facet > T(0)) || !(sin_graze > T(0))) return;
        const double reflection = double(scattering_.bounce_reflection(graze, h.material));
        const double legs = 1.0 / std::sqrt(double(first.spreading)) + 1.0 / std::sqrt(double(second->spreading));
        const double absorption = double(first.absorption) * double(second->absorption);
        const double sigma = double(scattering_.backscatter(std::asin(sin_graze), h2.material));
        out.valid = true;
        out.t = 2.0 * (double(first.time_s) + double(second->time_s));
        out.power_per_rad =
            weight * sigma * reflection * reflection * absorption * absorption / (legs * legs) / double(sin_facet);
        out.surface = h2;
        out.via = h;
        out.leg_s = first.time_s;
    }

    template <Scene Sc, class Observer>
    void accumulate(const Sc& scene, const pose<T>& p, side sd, time_sampler& sampler, Observer& observe) const {
        trace(scene, p, sd, [&](const tube_echo<T>& t) {
            sampler.add_span(t.t0_s, t.t1_s, t.power);
            observe(sd, t);
        });
    }

    /// accumulate, and the material of the strongest echo arriving in each sample (by the tube's mid time);
    /// samples no echo arrives in take the material of the sample before (the pulse carries it on).
    template <Scene Sc, class Observer>
    void accumulate_with_materials(const Sc& scene, const pose<T>& p, side sd, time_sampler& sampler,
                                   std::vector<std::uint32_t>& materials, Observer& observe) const {
        materials.assign(samples_, 0);
        std::vector<double> strongest(samples_, 0.0);
        trace(scene, p, sd, [&](const tube_echo<T>& t) {
            sampler.add_span(t.t0_s, t.t1_s, t.power);
            observe(sd, t);
            const double k = 0.5 * (t.t0_s + t.t1_s) / dt_;
            if (!(k >= 0.0) || !(k < double(samples_))) return;
            const auto i = static_cast<std::size_t>(k);
            if (t.power > strongest[i]) {
                strongest[i] = t.power;
                materials[i] = t.surface.material;
            }
        });
        for (std::size_t k = 1; k < samples_; ++k)
            if (!(strongest[k] > 0.0)) materials[k] = materials[k - 1];
    }

    S scattering_;
    P propagation_;
    B beam_;
    M motion_;
    receiver_params receiver_;
    ray_density density_;
    [[no_unique_address]] Stage stage_;
    std::array<elevation_share, 2> elevation_{}; ///< port, starboard: tabulated only for a stage that needs the beam
    double c_ref_ = 1500.0;
    std::size_t samples_ = 0;
    double dt_ = 0.0;
    double source_level_ = 1.0;
    time_sampler sampler_{1, 1.0, pulse{}};
    std::shared_ptr<buffer_pool> buffers_ = std::make_shared<buffer_pool>(); ///< shared by copies
};

} // namespace sss

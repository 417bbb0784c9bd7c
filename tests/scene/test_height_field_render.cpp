// A flat height field renders the flat-seabed oracle as closely as the plane does: the seabed is one interface.

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "support/compare.hpp"
#include "support/flat_seabed_oracle.hpp"
#include "support/fused.hpp"
#include <sss/sss.hpp>
#include <sss/scene/height_field.hpp>

TEST_CASE_TEMPLATE("a flat height field matches the quadrature oracle as closely as the flat plane", T, float, double) {
    sss::receiver_params rx;
    rx.max_range_m = 40.0;
    sss::motion::perturbed_params<T> tow; // rolled and pitched: rays cross the grid obliquely
    tow.start_m = {T(3.3), T(-7.1)};
    tow.heading_deg = T(33);
    tow.altitude_m = T(12);
    tow.roll_deg = {T(3), T(7), T(90)};
    tow.pitch_deg = {T(2), T(5), T(90)};
    const sss::simulator<sss::scattering::lambertian<T>, sss::propagation::straight<T>, sss::beam::ideal_fan<T>,
                         sss::motion::perturbed<T>>
        sim({}, {}, {}, sss::motion::perturbed<T>{tow}, rx);

    // 257 x 257 vertices at 0.4 m around the towfish, all at z = 2 m.
    const std::size_t n = 257;
    const T cell = T(0.4);
    const sss::scene::height_field<T> grid({.nx = n, .ny = n, .cell_m = cell, .origin_m = {T(-48), T(-55)}, .heights_m = std::vector<T>(n * n, T(2))});
    const sss::scene::flat_seabed<T> plane(T(2));
    const auto from_grid = sim.ping(grid, 0);
    const auto from_plane = sim.ping(plane, 0);

    const auto pose = sim.motion().pose_at(0);
    sss_test::oracle_setup o;
    o.altitude_m = double(pose.position.z) - 2.0;
    o.roll_rad = double(pose.roll_rad);
    o.pitch_rad = double(pose.pitch_rad);
    o.yaw_rad = double(pose.yaw_rad);
    o.absorption_db_per_km = 60.0;
    o.dt_s = sim.dt_s();
    o.samples = sim.samples_per_line();
    o.pulse_length_s = rx.pulse.length_s;
    const sss::beam::ideal_fan<double> fan;
    const sss::scattering::lambertian<double> lambert;
    for (sss::side sd : {sss::side::port, sss::side::starboard}) {
        const auto expected = sss_test::oracle_line(o, fan, lambert, sd);
        const auto e_grid = sss_test::compare_db(sd == sss::side::port ? from_grid.port : from_grid.starboard, expected);
        const auto e_plane = sss_test::compare_db(sd == sss::side::port ? from_plane.port : from_plane.starboard, expected);
        INFO("grid: rms " << e_grid.rms_db << " dB, worst " << e_grid.worst_db << "; plane: rms " << e_plane.rms_db
                          << " dB, worst " << e_plane.worst_db);
        CHECK(e_grid.compared > 200);
        CHECK(e_grid.rms_db <= 0.2);
        CHECK(std::abs(e_grid.worst_db) <= 1.0);
        CHECK(e_grid.rms_db <= e_plane.rms_db + 0.01);
    }
}

namespace {
/// A scene with every optional method of `Inner` but the guide (GuidedScene, ResumableScene), or with it and a count of
/// the guide's uses.
template <class Inner, bool guided> struct guide_probe {
    using value_type = typename Inner::value_type;
    using T = value_type;
    const Inner* inner;
    std::atomic<long>* guided_calls = nullptr;
    [[nodiscard]] std::optional<sss::hit<T>> intersect(const sss::ray<T>& r, T t) const { return inner->intersect(r, t); }
    void intersect_many(std::span<const sss::ray<T>> rays, T t, std::span<std::optional<sss::hit<T>>> hits) const {
        inner->intersect_many(rays, t, hits);
    }
    [[nodiscard]] T clear_length_m(const sss::ray<T>& r, T t, T band) const { return inner->clear_length_m(r, t, band); }
    [[nodiscard]] std::optional<sss::hit<T>> intersect_beside(const sss::ray<T>& r, T t, const sss::ray<T>& a, T a_clear) const
        requires guided
    {
        guided_calls->fetch_add(1, std::memory_order_relaxed);
        return inner->intersect_beside(r, t, a, a_clear);
    }
    [[nodiscard]] std::optional<sss::hit<T>> intersect_after(const sss::ray<T>& r, T t, T clear) const
        requires guided
    {
        return inner->intersect_after(r, t, clear);
    }
    [[nodiscard]] T clear_range_beside_m(const sss::scene::beside_rays<T>& b) const
        requires guided
    {
        const T d = inner->clear_range_beside_m(b);
        if (d > T(0)) guided_calls->fetch_add(1, std::memory_order_relaxed);
        return d;
    }
    // Arcs met by the seabed itself, guided or not (the walk's start is what the guide changes), the objects by chords.
    [[nodiscard]] std::optional<sss::scene::arc_surface_hit<T>> intersect_arc(const sss::scene::vertical_arc<T>& a, T x_clear,
                                                                              T x_end) const {
        return inner->intersect_arc(a, x_clear, x_end);
    }
    [[nodiscard]] auto arc_others() const { return inner->arc_others(); }
    [[nodiscard]] T seabed_height_m(T x, T y) const { return inner->seabed_height_m(x, y); }
    [[nodiscard]] T top_m() const { return inner->top_m(); }
    [[nodiscard]] T top_m(const sss::vec2<T>& lo, const sss::vec2<T>& hi) const { return inner->top_m(lo, hi); }
    // Its seabed and objects, as a scene::scene shows them, and its rise above a plane: the simulator launches for
    // their tops, and for a sloping seabed's plane, as over `Inner`.
    [[nodiscard]] const auto& seabed() const { return inner->seabed(); }
    [[nodiscard]] const auto& objects() const { return inner->objects(); }
    [[nodiscard]] double rise_above_m(const sss::vec2<T>& lo, const sss::vec2<T>& hi,
                                      const sss::scene::sloping_plane& plane) const {
        return inner->rise_above_m(lo, hi, plane);
    }
};

/// The same scene without its batch method: the simulator then traces every ray alone.
template <class Inner> struct one_ray_at_a_time {
    using value_type = typename Inner::value_type;
    const Inner* inner;
    [[nodiscard]] std::optional<sss::hit<value_type>> intersect(const sss::ray<value_type>& r, value_type t) const {
        return inner->intersect(r, t);
    }
    [[nodiscard]] value_type seabed_height_m(value_type x, value_type y) const { return inner->seabed_height_m(x, y); }
    [[nodiscard]] value_type top_m() const { return inner->top_m(); }
    // Its bounds over an area and against a plane, so that its rays launch as the scene's do.
    [[nodiscard]] value_type top_m(const sss::vec2<value_type>& lo, const sss::vec2<value_type>& hi) const {
        return inner->top_m(lo, hi);
    }
    [[nodiscard]] double rise_above_m(const sss::vec2<value_type>& lo, const sss::vec2<value_type>& hi,
                                      const sss::scene::sloping_plane& plane) const {
        return inner->rise_above_m(lo, hi, plane);
    }
};
/// Lambert, straight rays (or the given water) and an ideal fan on a towfish heading -21 deg at 9 m, rolling and
/// pitching a few degrees: rays cross a grid obliquely, in columns that are not vertical planes.
template <class T, class Water = sss::propagation::straight<T>> auto rolling_towfish(Water water = {}) {
    sss::receiver_params rx;
    rx.max_range_m = 40.0;
    sss::motion::perturbed_params<T> tow;
    tow.start_m = {T(1.7), T(-3.1)};
    tow.heading_deg = T(-21);
    tow.altitude_m = T(9);
    tow.roll_deg = {T(4), T(6), T(90)};
    tow.pitch_deg = {T(2), T(4), T(90)};
    return sss::simulator<sss::scattering::lambertian<T>, Water, sss::beam::ideal_fan<T>, sss::motion::perturbed<T>>(
        {}, std::move(water), {}, sss::motion::perturbed<T>{tow}, rx);
}
} // namespace

TEST_CASE_TEMPLATE("a ping over rough relief is the same whether its columns are traced together or ray by ray", T, float,
                   double) {
    const auto sim = rolling_towfish<T>();
    const std::size_t n = 241;
    std::vector<T> h(n * n);
    for (std::size_t iy = 0; iy < n; ++iy)
        for (std::size_t ix = 0; ix < n; ++ix) {
            const double x = 0.4 * double(ix), y = 0.4 * double(iy);
            h[iy * n + ix] = T(1.5 * std::sin(0.09 * x + 0.04 * y) + 0.3 * std::sin(1.3 * x - 0.7 * y) +
                               0.2 * std::sin(0.5 * y) * std::cos(2.2 * x));
        }
    const sss::scene::height_field<T> relief({.nx = n, .ny = n, .cell_m = T(0.4), .origin_m = {T(-46), T(-50)}, .heights_m = std::move(h)});
    static_assert(sss::BatchScene<sss::scene::height_field<T>>);
    static_assert(!sss::BatchScene<one_ray_at_a_time<sss::scene::height_field<T>>>);
    for (std::size_t i = 0; i < 3; ++i) {
        const auto together = sim.ping(relief, i);
        const auto alone = sim.ping(one_ray_at_a_time<sss::scene::height_field<T>>{&relief}, i);
        for (sss::side sd : {sss::side::port, sss::side::starboard}) {
            const auto& a = sd == sss::side::port ? together.port : together.starboard;
            const auto& b = sd == sss::side::port ? alone.port : alone.starboard;
            REQUIRE(a.size() == b.size());
            double peak = 0, worst = 0, total_a = 0, total_b = 0;
            for (std::size_t k = 0; k < a.size(); ++k) peak = std::max(peak, double(b[k]));
            for (std::size_t k = 0; k < a.size(); ++k) {
                worst = std::max(worst, std::abs(double(a[k]) - double(b[k])));
                total_a += double(a[k]);
                total_b += double(b[k]);
            }
            INFO("ping " << i << ": worst difference " << worst / peak << " of the peak");
            CHECK(peak > 0);
            CHECK(worst <= 1e-3 * peak);
            CHECK(std::abs(total_a - total_b) <= 1e-4 * total_b);
        }
    }
}

namespace {
/// Ripples across the track (their lee sides shadowed at low grazing) and a trench, a lying cylinder and a sphere
/// above the seabed: edges everywhere for the refinement to bisect.
template <class T> auto ripples_trench_and_targets() {
    const std::size_t n = 241;
    std::vector<T> h(n * n);
    for (std::size_t iy = 0; iy < n; ++iy)
        for (std::size_t ix = 0; ix < n; ++ix) {
            const double x = -46 + 0.4 * double(ix), y = -50 + 0.4 * double(iy);
            double z = 0.35 * std::sin(1.1 * x + 0.2 * y) + 0.5 * std::sin(0.07 * y);
            if (std::abs(x + 22) < 1.2) z -= 1.0;
            h[iy * n + ix] = T(z);
        }
    using sss::scene::cylinder;
    using sss::scene::object;
    using sss::scene::sphere;
    std::vector<object<T>> objs{object<T>({}, {cylinder<T>(sss::vec3<T>{T(15), T(-8), T(0.9)}, sss::vec3<T>{T(17), T(4), T(0.9)}, T(0.5), {1, 2, 3})}),
                                object<T>({sphere<T>(sss::vec3<T>{T(-12), T(2), T(3)}, T(0.6), {2, 3, 4})}, {})};
    return sss::scene::scene(sss::scene::height_field<T>({.nx = n, .ny = n, .cell_m = T(0.4), .origin_m = {T(-46), T(-50)}, .heights_m = std::move(h)}),
                             sss::scene::object_set<T>(std::move(objs)));
}

/// Water under a surface 30 m above z = 0 whose speed falls 20 m/s over the 12 m above the seabed: rays bend down, in
/// chords of about a metre.
template <class T> sss::propagation::layered<T> bending_water() {
    sss::propagation::layered_params<T> p;
    p.surface_z_m = T(30);
    return sss::propagation::layered<T>(
        sss::propagation::sound_speed_profile<T>({T(0), T(18), T(30), T(40)}, {T(1500), T(1500), T(1480), T(1478)}), p);
}

/// Two lines that take the same arithmetic: the same bit for bit; where multiply-adds are fused
/// (tests/support/fused.hpp), the same to rounding: the hits move by ulps, and a refinement's decision near its
/// threshold may go either way, so each sample is compared against the line's peak and the energies in total.
template <class V> void check_same_line(const V& a, const V& b) {
    if constexpr (!sss_test::fused) {
        CHECK(a == b);
    } else {
        REQUIRE(a.size() == b.size());
        double peak = 0, worst = 0, total_a = 0, total_b = 0;
        for (std::size_t k = 0; k < a.size(); ++k) {
            peak = std::max(peak, double(b[k]));
            worst = std::max(worst, std::abs(double(a[k]) - double(b[k])));
            total_a += double(a[k]);
            total_b += double(b[k]);
        }
        // GCC 12 at -O3 -mfma: at most 3e-7 of the peak and 1e-9 of the total, in float.
        INFO("fused: worst " << worst / peak << " of the peak, total " << std::abs(total_a - total_b) / total_b);
        CHECK(worst <= 1e-4 * peak);
        CHECK(std::abs(total_a - total_b) <= 1e-5 * total_b);
    }
}

/// Pings 0, 3, 6 and 9 of `sim` over `sc` with and without the guide: the same lines, bit for bit; the guide's uses.
template <class Sim, class Sc> long guided_against_plain(const Sim& sim, const Sc& sc) {
    static_assert(!sss::GuidedScene<guide_probe<Sc, false>> && sss::GuidedScene<guide_probe<Sc, true>>);
    std::atomic<long> calls{0};
    for (std::size_t i = 0; i < 4; ++i) {
        const auto guided = sim.ping(guide_probe<Sc, true>{&sc, &calls}, 3 * i);
        const auto plain = sim.ping(guide_probe<Sc, false>{&sc}, 3 * i);
        check_same_line(guided.port, plain.port);
        check_same_line(guided.starboard, plain.starboard);
    }
    return calls.load();
}
} // namespace

TEST_CASE_TEMPLATE("Refinement rays guided by their steeper neighbours give the same lines, bit for bit, over relief "
                   "with objects",
                   T, float, double) {
    const auto sc = ripples_trench_and_targets<T>();
    using Sc = std::remove_cvref_t<decltype(sc)>;
    static_assert(sss::GuidedScene<Sc> && sss::GuidedPropagation<sss::propagation::straight<T>, Sc>);
    const long calls = guided_against_plain(rolling_towfish<T>(), sc);
    MESSAGE(calls << " refinement rays guided");
    CHECK(calls > 1000);
}

TEST_CASE_TEMPLATE("Bent rays guided by their steeper neighbours, in the first pass and the refinement, give the same "
                   "lines, bit for bit, over relief with objects",
                   T, float, double) {
    const auto sc = ripples_trench_and_targets<T>();
    using Sc = std::remove_cvref_t<decltype(sc)>;
    static_assert(sss::GuidedPropagation<sss::propagation::layered<T>, Sc>);
    const long calls = guided_against_plain(rolling_towfish<T>(bending_water<T>()), sc);
    MESSAGE(calls << " bent rays guided");
    CHECK(calls > 20000);
}

TEST_CASE_TEMPLATE("Columns see the scene over the rectangle their rays stay over: the same lines, bit for bit, as "
                   "through the side's view, in straight and layered water",
                   T, float, double) {
    const auto sc = ripples_trench_and_targets<T>();
    using Sc = std::remove_cvref_t<decltype(sc)>;
    // The side's view of `sc` narrows per column (area_view::within); the probe's view cannot (its objects are asked
    // wherever the side's rectangle holds one), and is as guided.
    static_assert(requires(const sss::scene::area_view<Sc>& v, const sss::vec2<T>& p) { v.within(p, p); });
    static_assert(!requires(const sss::scene::area_view<guide_probe<Sc, true>>& v, const sss::vec2<T>& p) { v.within(p, p); });
    std::atomic<long> calls{0};
    const auto straight_sim = rolling_towfish<T>();
    const auto layered_sim = rolling_towfish<T>(bending_water<T>());
    for (std::size_t i = 0; i < 4; ++i) {
        const auto a = straight_sim.ping(sc, 3 * i), b = straight_sim.ping(guide_probe<Sc, true>{&sc, &calls}, 3 * i);
        check_same_line(a.port, b.port);
        check_same_line(a.starboard, b.starboard);
        const auto c = layered_sim.ping(sc, 3 * i), d = layered_sim.ping(guide_probe<Sc, true>{&sc, &calls}, 3 * i);
        check_same_line(c.port, d.port);
        check_same_line(c.starboard, d.starboard);
    }
    // Some columns pass beside both targets, some meet one.
    const auto pose = straight_sim.motion().pose_at(0);
    std::size_t beside = 0, meeting = 0;
    for (const sss::side sd : {sss::side::port, sss::side::starboard}) {
        const auto area = straight_sim.side_area(pose, sd);
        REQUIRE(area);
        const sss::scene::area_view<Sc> view(sc, area->lo, area->hi);
        const auto ext = sss::beam::ideal_fan<T>{}.extent(sd);
        for (int k = 0; k <= 20; ++k) {
            const T along = ext.along_min_rad + (ext.along_max_rad - ext.along_min_rad) * T(k) / T(20);
            const auto r = sss::side_reach(pose, sd, sss::beam_extent<T>{along, along, ext.depression_min_rad, ext.depression_max_rad},
                                           40.0 * 1.0001, true);
            (view.within(r.lo, r.hi).objects_near() ? meeting : beside)++;
        }
    }
    MESSAGE(beside << " of " << beside + meeting << " columns beside every target");
    CHECK(beside > 0);
    CHECK(meeting > 0);
}

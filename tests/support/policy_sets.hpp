#pragma once
// The shipped policies, as type lists per family, and their product: the policy matrix.
// Every policy the library ships joins its family's list here, so that every combination is compared with the
// flat-seabed oracle. Each family also says how to build the policy for the matrix scene and how the oracle
// sees it (the water model the oracle integrates for a propagation policy, the pose for a motion policy).

#include <tuple>
#include <type_traits>
#include <vector>

#include <sss/sss.hpp>
#include <sss/propagation/layered.hpp>

#include "flat_seabed_oracle.hpp"
#include "layered_oracle.hpp"

namespace sss_test {

template <class... Ts> struct type_list {};

template <class A, class B> struct concat;
template <class... As, class... Bs> struct concat<type_list<As...>, type_list<Bs...>> { using type = type_list<As..., Bs...>; };

template <class L> struct flatten;
template <> struct flatten<type_list<>> { using type = type_list<>; };
template <class H, class... Rest> struct flatten<type_list<H, Rest...>> {
    using type = typename concat<H, typename flatten<type_list<Rest...>>::type>::type;
};

template <class S, class P, class B, class M> struct matrix_of;
template <class... Ss, class... Ps, class... Bs, class... Ms>
struct matrix_of<type_list<Ss...>, type_list<Ps...>, type_list<Bs...>, type_list<Ms...>> {
    template <class S1, class P1, class B1> using row = type_list<std::tuple<S1, P1, B1, Ms>...>;
    template <class S1, class P1> using plane = typename flatten<type_list<row<S1, P1, Bs>...>>::type;
    template <class S1> using cube = typename flatten<type_list<plane<S1, Ps>...>>::type;
    using type = typename flatten<type_list<cube<Ss>...>>::type;
};

// The same policy over another scalar type: policy<float> -> policy<double>.
template <class Policy, class U> struct rebind;
template <template <class> class Policy, class T, class U> struct rebind<Policy<T>, U> { using type = Policy<U>; };
template <class Policy, class U> using rebind_t = typename rebind<Policy, U>::type;
template <class Seabed, class Targets, class U> struct rebind<sss::scattering::by_material<Seabed, Targets>, U> {
    using type = sss::scattering::by_material<rebind_t<Seabed, U>, rebind_t<Targets, U>>;
};

template <class L> struct as_tuple;
template <class... Ts> struct as_tuple<type_list<Ts...>> { using type = std::tuple<Ts...>; };

template <class T> using scattering_policies = type_list<sss::scattering::lambertian<T>, sss::scattering::jackson<T>>;
template <class T> using propagation_policies = type_list<sss::propagation::straight<T>, sss::propagation::layered<T>>;
template <class T> using beam_policies = type_list<sss::beam::ideal_fan<T>, sss::beam::planar_array<T>>;
template <class T>
using motion_policies = type_list<sss::motion::straight_line<T>, sss::motion::perturbed<T>, sss::motion::trajectory<T>>;

// The scattering policies for objects (hard_target, and by_material, which gives the seabed's materials and the
// objects' their own models) are not crossed with every other policy: each joins the combinations of
// target_matrix, which together take every other family's policies at least once
// (tests/foundation/test_policy_matrix_targets.cpp).
template <class T> using target_scattering = sss::scattering::by_material<sss::scattering::jackson<T>, sss::scattering::hard_target<T>>;
template <class T>
using target_matrix = std::tuple<
    std::tuple<sss::scattering::hard_target<T>, sss::propagation::straight<T>, sss::beam::ideal_fan<T>, sss::motion::straight_line<T>>,
    std::tuple<sss::scattering::hard_target<T>, sss::propagation::layered<T>, sss::beam::planar_array<T>, sss::motion::perturbed<T>>,
    std::tuple<sss::scattering::hard_target<T>, sss::propagation::straight<T>, sss::beam::planar_array<T>, sss::motion::trajectory<T>>,
    std::tuple<target_scattering<T>, sss::propagation::straight<T>, sss::beam::ideal_fan<T>, sss::motion::straight_line<T>>,
    std::tuple<target_scattering<T>, sss::propagation::layered<T>, sss::beam::planar_array<T>, sss::motion::perturbed<T>>,
    std::tuple<target_scattering<T>, sss::propagation::straight<T>, sss::beam::planar_array<T>, sss::motion::trajectory<T>>>;

template <class T>
using policy_matrix = typename as_tuple<typename matrix_of<scattering_policies<T>, propagation_policies<T>, beam_policies<T>,
                                                           motion_policies<T>>::type>::type;

// The part of the matrix with one propagation policy: the matrix test has one translation unit per propagation
// policy (tests/foundation/test_policy_matrix_<name>.cpp); a new propagation policy adds one.
template <class T, class Propagation>
using policy_matrix_with = typename as_tuple<typename matrix_of<scattering_policies<T>, type_list<Propagation>,
                                                                beam_policies<T>, motion_policies<T>>::type>::type;

} // namespace sss_test

namespace sss_test {

// How the matrix builds each policy, and what the oracle must know of it. A new policy adds a specialisation.
template <class Policy> struct matrix_policy;

template <class T> struct matrix_policy<sss::scattering::lambertian<T>> {
    static sss::scattering::lambertian<T> make() { return sss::scattering::lambertian<T>{T(-27)}; }
    static void describe(oracle_setup&, const sss::scattering::lambertian<T>&) {}
};
template <class T> struct matrix_policy<sss::propagation::straight<T>> {
    static sss::propagation::straight<T> make() { return sss::propagation::straight<T>{{T(1500), T(60)}}; }
    static void describe(oracle_setup& o, const sss::propagation::straight<T>& p) {
        o.c_mps = double(p.params().sound_speed_mps);
        o.absorption_db_per_km = double(p.params().absorption_db_per_km);
    }
    // The oracle line of a combination with this water (propagation policies choose their oracle).
    template <class Beam, class Scattering>
    static std::vector<double> oracle_line(const oracle_setup& o, const Beam& beam, const Scattering& scat, sss::side sd) {
        return sss_test::oracle_line(o, beam, scat, sd);
    }
};
template <class T> struct matrix_policy<sss::propagation::layered<T>> {
    // A summer thermocline around the towfish: 1500 m/s at the surface, 1499 at 44 m, down 20 m/s to 54 m, then the
    // pressure gradient (+0.0165 1/s). The sea surface is 60 m above the seabed (world z 0), so the towfish (about
    // 10 m up) sits inside the thermocline and its rays bend down. Francois-Garrison absorption at 300 kHz.
    static sss::propagation::layered<T> make() {
        sss::propagation::layered_params<T> p;
        p.surface_z_m = T(60);
        p.frequency_hz = T(300000);
        return sss::propagation::layered<T>{
            sss::propagation::sound_speed_profile<T>({T(0), T(44), T(54), T(200)}, {T(1500), T(1499), T(1479), T(1481.409)}), p};
    }
    static void describe(oracle_setup& o, const sss::propagation::layered<T>& p) { o.c_mps = double(p.reference_speed_mps()); }
    // The layered oracle over the same water (seen through the double-precision twin).
    template <class Beam, class Scattering>
    static std::vector<double> oracle_line(const oracle_setup& o, const Beam& beam, const Scattering& scat, sss::side sd) {
        const auto water = matrix_policy<sss::propagation::layered<double>>::make();
        layered_water w;
        w.depth_m.assign(water.profile().depths_m().begin(), water.profile().depths_m().end());
        w.speed_mps.assign(water.profile().speeds_mps().begin(), water.profile().speeds_mps().end());
        w.seabed_depth_m = water.params().surface_z_m; // the matrix's seabed is world z = 0
        w.absorption_db_per_km = [water](double z) { return water.absorption_db_per_km(z); };
        return oracle_line_layered(o, w, beam, scat, sd);
    }
};
template <class T> struct matrix_policy<sss::beam::ideal_fan<T>> {
    static sss::beam::ideal_fan<T> make() { return sss::beam::ideal_fan<T>{{T(1), T(50), T(20)}}; }
    static void describe(oracle_setup&, const sss::beam::ideal_fan<T>&) {}
};
template <class T> struct matrix_policy<sss::motion::straight_line<T>> {
    static sss::motion::straight_line<T> make() {
        return sss::motion::straight_line<T>{{{T(0), T(0)}, T(30), T(2), T(10), T(0.1)}};
    }
    static void describe(oracle_setup&, const sss::motion::straight_line<T>&) {}
};

template <class T> struct matrix_policy<sss::scattering::jackson<T>> {
    // Medium sand at 100 kHz: the Kirchhoff peak, the composite-roughness and volume terms all contribute.
    static sss::scattering::jackson<T> make() {
        return sss::scattering::jackson<T>({.frequency_hz = T(100000),
                                            .sound_speed_mps = T(1500),
                                            .materials = {sss::scattering::sediment_preset<T>("medium sand")}});
    }
    static void describe(oracle_setup&, const sss::scattering::jackson<T>&) {}
};
template <class T> struct matrix_policy<sss::scattering::hard_target<T>> {
    // Steel (|R| 0.94, RMS facet slope 0.1) with its diffuse part at -15 dB: the Kirchhoff highlight lies near
    // normal incidence, so over the matrix's grazing angles the line is mostly the diffuse part.
    static sss::scattering::hard_target<T> make() {
        return sss::scattering::hard_target<T>({sss::scattering::hard_target_params<T>{.diffuse_db = T(-15)}});
    }
    static void describe(oracle_setup&, const sss::scattering::hard_target<T>&) {}
};
template <class T> struct matrix_policy<target_scattering<T>> {
    // Medium sand as material 0 (the flat seabed's), a steel casing as material 1.
    static target_scattering<T> make() {
        return target_scattering<T>(matrix_policy<sss::scattering::jackson<T>>::make(),
                                    matrix_policy<sss::scattering::hard_target<T>>::make());
    }
    static void describe(oracle_setup&, const target_scattering<T>&) {}
};
template <class T> struct matrix_policy<sss::beam::planar_array<T>> {
    // A 300 kHz array of 32 x 2 elements (0.5 m by 4 cm), shaded along track, tilted 15 degrees down.
    static sss::beam::planar_array<T> make() {
        sss::beam::planar_array_params<T> p;
        p.frequency_hz = T(300000);
        p.depression_deg = T(15);
        p.transmit.along = {32, T(0.0150), T(0.0156), {}};
        p.transmit.vertical = {2, T(0.0190), T(0.0200), {}};
        p.threshold_db = T(-30);
        return sss::beam::planar_array<T>{p};
    }
    static void describe(oracle_setup&, const sss::beam::planar_array<T>&) {}
};
template <class T> struct matrix_policy<sss::motion::perturbed<T>> {
    // Roll, pitch, yaw, heave and sway all at once, sampled at a ping where none of them is zero.
    static sss::motion::perturbed<T> make() {
        sss::motion::perturbed_params<T> p;
        p.heading_deg = T(75);
        p.altitude_m = T(9);
        p.roll_deg = {T(4), T(7), T(30)};
        p.pitch_deg = {T(3), T(5), T(60)};
        p.yaw_deg = {T(2), T(11), T(10)};
        p.heave_m = {T(0.4), T(6), T(20)};
        p.sway_m = {T(0.5), T(9), T(45)};
        return sss::motion::perturbed<T>{p};
    }
    static void describe(oracle_setup&, const sss::motion::perturbed<T>&) {}
};
template <class T> struct matrix_policy<sss::motion::trajectory<T>> {
    // A gently curving, climbing track with its own roll and pitch channels.
    static sss::motion::trajectory<T> make() {
        sss::motion::trajectory_samples<T> s;
        for (int i = 0; i <= 20; ++i) {
            const double t = 0.5 * i;
            s.time_s.push_back(t);
            s.position_m.push_back({T(3.0 * t), T(0.05 * t * t), T(11.0 + 0.02 * t)});
            s.roll_rad.push_back(T(0.05 * std::sin(0.7 * t)));
            s.pitch_rad.push_back(T(-0.03 * std::cos(0.4 * t)));
        }
        return sss::motion::trajectory<T>{s};
    }
    static void describe(oracle_setup&, const sss::motion::trajectory<T>&) {}
};

} // namespace sss_test

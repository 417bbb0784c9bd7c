// Objects in rendered sidescan lines: the acoustic shadow of a cylinder lying on the seabed ends where the ray
// grazing its top meets the seabed, and a sphere in the water column returns its highlight at its nearest
// range, before the first seabed return, and shadows the seabed between the ranges its tangent rays predict.
// Every sample index is compared with geometry to within one sample; the echoes carry the object's labels.
//
// Geometry: the towfish heads north (+y) at altitude H over a flat seabed z = 0; starboard is east (+x).
// "Across track" in the sidescan sense: a cylinder whose axis is parallel to the track (along y) presents
// the same circular section to every ping, and its shadow extends in range (x). In that vertical section
// the transducer O = (0, H) sees the circle of radius a centred at C = (x0, c_z) at depression
// beta = atan((H - c_z) / x0) with angular radius alpha = asin(a / |OC|); the ray grazing its far side,
// at depression beta - alpha, meets the seabed at slant range R = H / sin(beta - alpha), where the shadow
// ends. Treating the cylinder as a point of height 2a at x0 gives the usual estimate of the shadow's ground
// length, x0 2a / (H - 2a).

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include <sss/core/pose.hpp>
#include <sss/scene/flat_seabed.hpp>
#include <sss/scene/scene.hpp>
#include <sss/simulator.hpp>

namespace {

using sss::vec3;
using sss::scene::cylinder;
using sss::scene::flat_seabed;
using sss::scene::object;
using sss::scene::object_set;
using sss::scene::sphere;
using sss::scene::surface_ids;

constexpr double c_mps = 1500.0, fs_hz = 20000.0, dt_s = 1.0 / fs_hz, pulse_s = 100e-6, H = 10.0;

template <class T> auto make_simulator() {
    using namespace sss;
    receiver_params rp;
    rp.sample_rate_hz = fs_hz;
    rp.max_range_m = 40.0;
    rp.pulse.length_s = pulse_s;
    ray_density density;
    density.along = 8;
    density.per_sample = 4.0;
    beam::ideal_fan_params<T> fan;
    fan.along_width_deg = T(1);
    fan.vertical_width_deg = T(90); // depressions 0 to 90 deg: from the horizon to nadir
    fan.depression_deg = T(45);
    propagation::straight_params<T> water;
    water.sound_speed_mps = T(c_mps);
    return simulator<scattering::lambertian<T>, propagation::straight<T>, beam::ideal_fan<T>, motion::straight_line<T>>(
        scattering::lambertian<T>({.mu_db = {T(-27), T(-10)}}), propagation::straight<T>(water), beam::ideal_fan<T>(fan),
        motion::straight_line<T>(), rp, density);
}

template <class T> sss::pose<T> towfish() {
    return sss::make_pose<T>(T(0), vec3<T>{T(0), T(0), T(H)}, T(0), T(0), T(0));
}

// Sample index (fractional) of a two-way time.
double sample_of(double two_way_s) { return two_way_s / dt_s; }

// Depression (rad) of the ray from O = (0, H) grazing a circle of radius a centred at (x0, cz), far (-1) or
// near (+1) side.
double tangent_depression(double x0, double cz, double a, int side) {
    const double beta = std::atan2(H - cz, x0), alpha = std::asin(a / std::hypot(x0, H - cz));
    return beta + side * alpha;
}

// Index of the first sample at or after `from` whose value exceeds `floor`.
template <class V> std::size_t first_above(const V& line, std::size_t from, double floor) {
    for (std::size_t k = from; k < line.size(); ++k)
        if (double(line[k]) > floor) return k;
    return line.size();
}

} // namespace

TEST_CASE_TEMPLATE("A cylinder lying along the track casts a shadow that ends where the ray grazing its top meets the seabed",
                   T, float, double) {
    const double a = 0.5, x0 = 20.0;
    const surface_ids ids{1, 5, 3};
    std::vector<object<T>> objs{object<T>({}, {cylinder<T>(vec3<T>{T(x0), T(-15), T(a)}, vec3<T>{T(x0), T(15), T(a)}, T(a), ids)})};
    const sss::scene::scene sc(flat_seabed<T>(T(0)), object_set<T>(std::move(objs)));
    const auto sim = make_simulator<T>();
    const auto lines = sim.ping_at(sc, towfish<T>());
    const auto& stbd = lines.starboard;

    const double e_far = tangent_depression(x0, a, a, -1);
    const double r_end = H / std::sin(e_far), x_end = H / std::tan(e_far);
    const double k_end = sample_of(2 * r_end / c_mps);
    // Echoes stop one pulse after the later of the cylinder's far tangent point (range sqrt(|OC|^2 - a^2))
    // and the last lit seabed point in front of it, where the near tangent ray lands.
    const double r_top = std::sqrt(x0 * x0 + (H - a) * (H - a) - a * a);
    const double r_front = H / std::sin(tangent_depression(x0, a, a, +1));
    const double k_echo_end = sample_of(2 * std::max(r_top, r_front) / c_mps + pulse_s);
    double peak = 0;
    for (auto v : stbd) peak = std::max(peak, double(v));
    const double floor = 1e-9 * peak;
    // The zero run: from the end of those echoes to the end of the shadow.
    const auto k0 = static_cast<std::size_t>(std::ceil(k_echo_end));
    CHECK(double(stbd[k0 - 3]) > floor);
    REQUIRE(k0 + 10 < static_cast<std::size_t>(k_end));
    for (std::size_t k = k0; k + 1 < static_cast<std::size_t>(k_end); ++k) CHECK(double(stbd[k]) <= floor);
    const std::size_t k_first = first_above(stbd, k0, floor);
    MESSAGE("shadow ends at sample " << k_first << ", geometry " << k_end << " (ground range " << x_end
                                     << " m; point-object estimate " << x0 * H / (H - 2 * a) << " m)");
    CHECK(std::abs(double(k_first) - k_end) <= 1.0);
    // The estimate x0 2a / (H - 2a) of the ground length is close to the exact tangent (22.35 m vs 22.22 m).
    CHECK(x_end - x0 == doctest::Approx(x0 * 2 * a / (H - 2 * a)).epsilon(0.07));
    // And the shadow is on the starboard side only: port sees a plain seabed there.
    CHECK(double(lines.port[static_cast<std::size_t>(k_end) - 5]) > floor);
}

TEST_CASE_TEMPLATE("A sphere in the water column returns its highlight at its nearest range, before the seabed, and "
                   "shadows the seabed between its tangent rays",
                   T, float, double) {
    const double a = 0.5, x0 = 5.0, cz = 6.0;
    const surface_ids ids{1, 8, 4};
    std::vector<object<T>> objs{object<T>({sphere<T>(vec3<T>{T(x0), T(0), T(cz)}, T(a), ids)}, {})};
    const sss::scene::scene sc(flat_seabed<T>(T(0), 0, 2), object_set<T>(std::move(objs)));
    const auto sim = make_simulator<T>();
    const auto lines = sim.ping_at(sc, towfish<T>());
    const auto& stbd = lines.starboard;
    double peak = 0;
    for (auto v : stbd) peak = std::max(peak, double(v));
    const double floor = 1e-9 * peak;

    const double D = std::hypot(x0, H - cz);
    const double k_highlight = sample_of(2 * (D - a) / c_mps);
    const double k_seabed = sample_of(2 * H / c_mps);
    const std::size_t k_first = first_above(stbd, 0, floor);
    MESSAGE("highlight at sample " << k_first << ", geometry " << k_highlight << "; first seabed return " << k_seabed);
    CHECK(std::abs(double(k_first) - k_highlight) <= 1.0);
    // Between the sphere's echo and the first seabed return (nadir) the water column is silent.
    const double k_echo_end = sample_of(2 * std::sqrt(D * D - a * a) / c_mps + pulse_s);
    const std::size_t k_gap = first_above(stbd, static_cast<std::size_t>(std::ceil(k_echo_end)) + 1, floor);
    CHECK(std::abs(double(k_gap) - k_seabed) <= 1.0);

    // Shadow on the seabed: from the near tangent's seabed range (+ pulse) to the far tangent's. Off the beam's
    // centre the rays cross the sphere |OC| sin(along) from its centre, where its section is smaller: at the
    // beam's edge (along = 0.5 deg) the seabed is lit a little further, so the shadow may start up to there.
    const double r1 = H / std::sin(tangent_depression(x0, cz, a, +1));
    const double r2 = H / std::sin(tangent_depression(x0, cz, a, -1));
    const double off_centre = D * std::sin(0.5 * 3.14159265358979 / 180.0);
    const double r1_edge = H / std::sin(tangent_depression(x0, cz, std::sqrt(a * a - off_centre * off_centre), +1));
    const double k_shadow_start = sample_of(2 * r1 / c_mps + pulse_s), k_shadow_end = sample_of(2 * r2 / c_mps);
    const double k_shadow_start_edge = sample_of(2 * r1_edge / c_mps + pulse_s);
    std::size_t k_last_lit = static_cast<std::size_t>(k_shadow_start) - 6;
    while (k_last_lit + 1 < stbd.size() && double(stbd[k_last_lit + 1]) > floor) ++k_last_lit;
    const std::size_t k_lit_again = first_above(stbd, k_last_lit + 1, floor);
    MESSAGE("seabed shadow over samples " << k_last_lit + 1 << " to " << k_lit_again << ", geometry " << k_shadow_start
                                          << " (" << k_shadow_start_edge << " at the beam's edge) to " << k_shadow_end);
    CHECK(double(k_last_lit + 1) >= k_shadow_start - 1.0);
    CHECK(double(k_last_lit + 1) <= k_shadow_start_edge + 1.0);
    CHECK(std::abs(double(k_lit_again) - k_shadow_end) <= 1.0);
}

TEST_CASE("The echoes of an object carry its object id and class label, the seabed's its region") {
    const surface_ids ids{1, 8, 4};
    std::vector<object<double>> objs{object<double>({sphere<double>(vec3<double>{5, 0, 6}, 0.5, ids)}, {})};
    const sss::scene::scene sc(flat_seabed<double>(0.0, 0, 2), object_set<double>(std::move(objs)));
    const auto sim = make_simulator<double>();
    std::size_t object_echoes = 0, seabed_echoes = 0, wrong = 0;
    const double t_sphere_end = 2 * std::sqrt(41.0 - 0.25) / c_mps;
    sim.trace(sc, towfish<double>(), sss::side::starboard, [&](const sss::tube_echo<double>& e) {
        if (e.surface.object == 8u) {
            ++object_echoes;
            wrong += e.surface.label != 4u || e.surface.material != 1u || e.t0_s > t_sphere_end + 1e-9;
        } else {
            ++seabed_echoes;
            wrong += e.surface.object != sss::no_object || e.surface.label != 2u || e.t0_s < 2 * H / c_mps - 1e-9;
        }
    });
    CHECK(object_echoes > 20u);
    CHECK(seabed_echoes > 1000u);
    CHECK(wrong == 0u);
}

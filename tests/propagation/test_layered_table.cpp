// The launch table of layered water: rays looked up above the geometry and traced exactly below it agree with
// rays traced exactly all the way, to the table's validation tolerance; rays it does not cover are traced exactly;
// and a result depends on the ray alone, not on what was traced before or on which thread.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <vector>

#include "sss/propagation/launch_table.hpp"
#include "sss/propagation/layered.hpp"
#include "sss/scene/flat_seabed.hpp"

using namespace sss;
using namespace sss::propagation;

namespace {

constexpr double deg = 3.14159265358979323846 / 180;

template <class T> layered_params<T> params(T surface_z, bool table) {
    layered_params<T> p;
    p.surface_z_m = surface_z;
    p.launch_table = table;
    return p;
}

template <class T> ray<T> launch(T z, double graze, double az) {
    return ray<T>{vec3<T>{T(1), T(2), z},
                  vec3<T>{T(std::cos(graze) * std::cos(az)), T(std::cos(graze) * std::sin(az)), T(-std::sin(graze))}};
}

double rel(double a, double b) { return b == 0 ? std::abs(a) : std::abs(a / b - 1); }

struct difference {
    double range = 0, time = 0, spreading = 0, absorption = 0, position = 0, arrival = 0;
    int rays = 0, misses = 0;
    double worst() const { return std::max({range, time, spreading, absorption, position, arrival}); }
};

// Table against exact over a fan of launch angles (0.05 .. 90 deg) and azimuths, from world z = z_fish.
template <class T, class Scene>
difference compare(const sound_speed_profile<T>& profile, T surface_z, T z_fish, const Scene& scene, T t_max) {
    const layered<T> table(profile, params(surface_z, true)), exact(profile, params(surface_z, false));
    difference d;
    for (int i = 0; i < 2000; ++i) {
        const double graze = (0.05 + 89.95 * std::pow(double((i * 739) % 2000) / 1999.0, 2.0)) * deg;
        const auto r = launch<T>(z_fish, graze, 0.01 * i);
        const auto a = table.trace_path(r, scene, t_max), b = exact.trace_path(r, scene, t_max);
        if (a.has_value() != b.has_value()) { ++d.misses; continue; }
        if (!a) continue;
        ++d.rays;
        d.range = std::max(d.range, std::abs(double(a->range_m - b->range_m)) / double(b->path_length_m));
        d.time = std::max(d.time, rel(double(a->result.time_s), double(b->result.time_s)));
        d.spreading = std::max(d.spreading, rel(double(a->result.spreading), double(b->result.spreading)));
        d.absorption = std::max(d.absorption, rel(double(a->result.absorption), double(b->result.absorption)));
        d.position = std::max(d.position, double(glm::length(a->result.surface.point - b->result.surface.point)) /
                                              double(b->path_length_m));
        d.arrival = std::max(d.arrival, double(glm::length(a->result.arrival - b->result.arrival)));
    }
    return d;
}

// A tilted plane hit from above, cut off above top (no geometry above top_m).
template <class T> struct slope_scene {
    using value_type = T;
    vec3<T> n = glm::normalize(vec3<T>{T(0.2), T(-0.1), T(1)});
    T d = T(0);
    T top = T(6);
    [[nodiscard]] std::optional<hit<T>> intersect(const ray<T>& r, T t_max) const {
        const T denom = glm::dot(n, r.direction);
        if (!(denom < T(0))) return std::nullopt;
        const T s = (d - glm::dot(n, r.origin)) / denom;
        if (!(s > T(0) && s <= t_max)) return std::nullopt;
        hit<T> h;
        h.distance_m = s;
        h.point = r.at(s);
        if (h.point.z > top) return std::nullopt;
        h.normal = n;
        h.shading_normal = n;
        return h;
    }
    [[nodiscard]] T seabed_height_m(T, T) const { return T(0); }
    [[nodiscard]] T top_m() const { return top; }
};

} // namespace

TEST_CASE("rays looked up in the launch table agree with exact tracing to 1e-9 (double)") {
    struct water { std::string name; sound_speed_profile<double> profile; };
    std::vector<double> d, c;
    for (int k = 0; k <= 1000; ++k) {
        d.push_back(0.1 * k);
        c.push_back(1490.0 - 10.0 * std::tanh((0.1 * k - 49.0) / 3.0));
    }
    const std::vector<water> waters{
        {"uniform", sound_speed_profile<double>({0, 20, 44, 54, 200}, std::vector<double>(5, 1500.0))},
        {"thermocline", sound_speed_profile<double>({0, 44, 54, 200}, {1500, 1499, 1479, 1481.409})},
        {"strong thermocline", sound_speed_profile<double>({0, 48, 52, 200}, {1500, 1500, 1440, 1442})},
        {"speed rising with depth", sound_speed_profile<double>({0, 200}, {1480, 1520})},
        {"1000 knots", sound_speed_profile<double>(d, c)},
    };
    const scene::flat_seabed<double> seabed(0);
    const slope_scene<double> slope;
    for (const auto& w : waters) {
        const auto flat = compare(w.profile, 60.0, 10.0, seabed, 0.2);
        const auto tilted = compare(w.profile, 60.0, 12.0, slope, 0.2);
        MESSAGE(w.name << ": flat " << flat.rays << " rays, worst " << flat.worst() << " (range " << flat.range << ", time "
                       << flat.time << ", spreading " << flat.spreading << ", absorption " << flat.absorption
                       << "); slope " << tilted.rays << " rays, worst " << tilted.worst() << " (range " << tilted.range << ", time " << tilted.time << ", spreading " << tilted.spreading << ", absorption " << tilted.absorption << ", position " << tilted.position << ", arrival " << tilted.arrival << ")");
        CHECK(flat.misses == 0);
        CHECK(tilted.misses == 0);
        CHECK(flat.rays > 1000);
        CHECK(tilted.rays > 1000);
        CHECK(flat.worst() < 1e-9);
        CHECK(tilted.worst() < 1e-9);
    }
}

TEST_CASE("rays looked up in the launch table agree with exact tracing to float precision (float)") {
    const sound_speed_profile<float> profile({0.f, 44.f, 54.f, 200.f}, {1500.f, 1499.f, 1479.f, 1481.409f});
    const auto flat = compare(profile, 60.f, 10.f, scene::flat_seabed<float>(0.f), 0.2f);
    MESSAGE("float thermocline: " << flat.rays << " rays, range " << flat.range << ", time " << flat.time << ", spreading "
                                  << flat.spreading << ", absorption " << flat.absorption);
    CHECK(flat.misses == 0);
    CHECK(flat.range < 2e-5);
    CHECK(flat.time < 2e-5);
    CHECK(flat.spreading < 1e-4);
    CHECK(flat.absorption < 2e-5);
}

TEST_CASE("rays the table does not cover are traced exactly: upward, grazing below 1e-3 rad, outside the water's reach") {
    const sound_speed_profile<double> profile({0, 44, 54, 200}, {1500, 1499, 1479, 1481.409});
    const layered<double> table(profile, params(60.0, true)), exact(profile, params(60.0, false));
    const scene::flat_seabed<double> seabed(0);
    for (double graze : {-20.0, -3.0, 0.0, 0.02, 0.05}) {
        const auto r = launch<double>(10.0, graze * deg, 0.3);
        const auto a = table.trace_path(r, seabed, 0.5), b = exact.trace_path(r, seabed, 0.5);
        REQUIRE(a.has_value() == b.has_value());
        if (!a) continue;
        CHECK(a->result.time_s == b->result.time_s);
        CHECK(a->result.spreading == b->result.spreading);
        CHECK(a->result.surface.point == b->result.surface.point);
    }
    // A towfish below the scene's top (inside the geometry's depth band): no table at all.
    const scene::flat_seabed<double> high(20);
    const auto r = launch<double>(10.0, -30 * deg, 0.0);
    const auto a = table.trace_path(r, high, 0.5), b = exact.trace_path(r, high, 0.5);
    CHECK(a.has_value() == b.has_value());
}

TEST_CASE("a launch-table result depends on the ray alone: not on the rays before it, nor on the thread") {
    const sound_speed_profile<double> profile({0, 44, 54, 200}, {1500, 1499, 1479, 1481.409});
    const layered<double> water(profile, params(60.0, true));
    const scene::flat_seabed<double> seabed(0);
    const auto r = launch<double>(10.0, 17 * deg, 0.4);
    const auto first = water.trace(r, seabed, 0.2);
    REQUIRE(first);
    // Rays from other depths (a table is built for each, more of them than a thread keeps, so that the first is
    // rebuilt), then the same ray again.
    for (double z : {9.0, 11.0, 10.5, 9.5, 12.0}) (void)water.trace(launch<double>(z, 30 * deg, 0.0), seabed, 0.2);
    const auto again = water.trace(r, seabed, 0.2);
    REQUIRE(again);
    CHECK(again->time_s == first->time_s);
    CHECK(again->spreading == first->spreading);
    CHECK(again->surface.point == first->surface.point);
    // Another water object of the same profile, and another thread.
    const layered<double> twin(profile, params(60.0, true));
    CHECK(twin.trace(r, seabed, 0.2)->time_s == first->time_s);
    double from_thread = 0;
    std::thread([&] { from_thread = water.trace(r, seabed, 0.2)->time_s; }).join();
    CHECK(from_thread == first->time_s);
}

TEST_CASE_TEMPLATE("trace_many gives every ray exactly what trace gives it: table or not, hit or miss, mixed origins", T,
                   float, double) {
    static_assert(BatchPropagation<layered<T>, scene::flat_seabed<T>>);
    const sound_speed_profile<T> profile({T(0), T(44), T(54), T(200)}, {T(1500), T(1499), T(1479), T(1481.409)});
    const scene::flat_seabed<T> seabed(T(0));
    const slope_scene<T> slope;
    std::vector<ray<T>> rays;
    // A column from one origin, upward to vertical (upward, horizontal and 0.02 deg: no table), then rays from other
    // origins in between (the start is worked out again for each change of origin).
    for (int i = 0; i <= 40; ++i) rays.push_back(launch<T>(T(10), (-10.0 + 2.5 * i) * deg, 0.3));
    rays.push_back(launch<T>(T(10), 0.02 * deg, 0.3));
    for (double z : {11.0, 11.0, 10.0, 25.0}) rays.push_back(launch<T>(T(z), 25 * deg, 0.1 * z));
    for (const bool table : {true, false}) {
        const layered<T> water(profile, params(T(60), table));
        for (const T t_max : {T(0.2), T(0.012)}) { // the short time limit loses the longer paths
            std::vector<std::optional<path<T>>> batch(rays.size()), batch_slope(rays.size());
            trace_all(water, std::span<const ray<T>>(rays), seabed, t_max, std::span<std::optional<path<T>>>(batch));
            water.trace_many(std::span<const ray<T>>(rays), slope, t_max, std::span<std::optional<path<T>>>(batch_slope));
            int hits = 0, misses = 0;
            for (std::size_t k = 0; k < rays.size(); ++k) {
                for (const bool tilted : {false, true}) {
                    const auto one = tilted ? water.trace(rays[k], slope, t_max) : water.trace(rays[k], seabed, t_max);
                    const auto& many = tilted ? batch_slope[k] : batch[k];
                    REQUIRE(one.has_value() == many.has_value());
                    if (!one) { ++misses; continue; }
                    ++hits;
                    CHECK(one->time_s == many->time_s);
                    CHECK(one->spreading == many->spreading);
                    CHECK(one->absorption == many->absorption);
                    CHECK(one->surface.point == many->surface.point);
                    CHECK(one->surface.distance_m == many->surface.distance_m);
                    CHECK(one->arrival == many->arrival);
                }
            }
            CHECK(hits > 20);
            CHECK(misses > 5);
        }
    }
}

TEST_CASE("the launch table interpolates smooth ray families to 1e-11 and marks the intervals it cannot") {
    // Uniform water 10 m deep: range 10 cot(phi0), time 10/(c sin phi0), ... known exactly.
    const double H = 10, c = 1500;
    auto uniform = [&](double s, double co) -> std::optional<descent_state<double>> {
        const double path = H / s;
        return descent_state<double>{H * co / s, path / c, path, 0.06 * path, c * path, c * path / s};
    };
    const launch_table<double> smooth(uniform, 1e-9);
    CHECK(smooth.usable_intervals() == smooth.intervals());
    double worst = 0;
    for (int i = 1; i < 5000; ++i) {
        const double phi = 2e-3 + (1.5707 - 2e-3) * i / 5000.0;
        const auto got = smooth.lookup(std::sin(phi), std::cos(phi));
        REQUIRE(got);
        const auto want = uniform(std::sin(phi), std::cos(phi));
        worst = std::max({worst, std::abs(got->range_m - want->range_m) / want->path_m, rel(got->time_s, want->time_s),
                          rel(got->q_sum, want->q_sum), rel(got->k_sum, want->k_sum)});
    }
    MESSAGE("uniform water: worst interpolation error " << worst << " over " << smooth.intervals() << " intervals");
    CHECK(worst < 1e-11);
    CHECK_FALSE(smooth.lookup(std::sin(5e-4), std::cos(5e-4))); // below the table's shallowest launch
    CHECK_FALSE(smooth.lookup(-0.1, std::sqrt(0.99)));           // upward

    // Rays below 20 deg never arrive, and range has a kink at 40 deg: the intervals there are marked.
    auto broken = [&](double s, double co) -> std::optional<descent_state<double>> {
        if (s < std::sin(20 * deg)) return std::nullopt;
        auto st = uniform(s, co);
        st->range_m += 3 * std::max(0.0, s - std::sin(40 * deg));
        return st;
    };
    const launch_table<double> marked(broken, 1e-9);
    CHECK(marked.usable_intervals() < marked.intervals());
    CHECK_FALSE(marked.lookup(std::sin(10 * deg), std::cos(10 * deg)));
    CHECK_FALSE(marked.lookup(std::sin(40 * deg), std::cos(40 * deg)));
    CHECK(marked.lookup(std::sin(60 * deg), std::cos(60 * deg)));
}

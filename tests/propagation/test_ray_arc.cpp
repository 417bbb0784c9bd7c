// Exact ray stepping through constant-gradient layers, checked against the published example,
// independent long double numerical integration (quadrature in depth and an ODE in arc length),
// the straight-line limit, and stacks of thin layers.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "sss/core/constants.hpp"
#include "sss/propagation/profile.hpp"
#include "sss/propagation/ray_arc.hpp"

using namespace sss::propagation;
using ld = long double;

namespace {

constexpr double deg = 3.14159265358979323846 / 180;
constexpr double inf = std::numeric_limits<double>::infinity();

double rel(double got, long double want) {
    return want == 0 ? std::abs(got) : static_cast<double>(std::abs((static_cast<ld>(got) - want) / want));
}

// Oracle 1: quadrature in depth for a ray that does not turn between z0 and z1. With xi = cos(theta0)/c0
// and sin(theta) = sqrt(1 - xi^2 c(z)^2): dx = cot(theta) |dz|, ds = |dz|/sin(theta), dt = ds/c.
struct zquad_result { ld x, t, s, graze1; };
zquad_result zquad(ld c0, ld g, ld z0, ld z1, ld graze0) {
    const ld xi = std::cos(graze0) / c0;
    const auto c = [&](ld z) { return c0 + g * (z - z0); };
    const auto sin_t = [&](ld z) { const ld q = xi * c(z); return std::sqrt((1 - q) * (1 + q)); };
    static const ld xn[5] = {-0.906179845938663992797626878299392965L, -0.538469310105683091036314420700208805L, 0.0L,
                             0.538469310105683091036314420700208805L, 0.906179845938663992797626878299392965L};
    static const ld wn[5] = {0.236926885056189087514264040719917363L, 0.478628670499366468041291514835638192L,
                             0.568888888888888888888888888888888889L, 0.478628670499366468041291514835638192L,
                             0.236926885056189087514264040719917363L};
    const int n = 64;
    const ld h = (z1 - z0) / n;
    zquad_result r{0, 0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const ld m = z0 + (i + 0.5L) * h;
        for (int k = 0; k < 5; ++k) {
            const ld z = m + 0.5L * h * xn[k];
            const ld st = sin_t(z), w = wn[k] * std::abs(h) / 2;
            r.x += w * xi * c(z) / st;
            r.s += w / st;
            r.t += w / (st * c(z));
        }
    }
    const ld q = xi * c(z1);
    r.graze1 = std::atan2(std::sqrt((1 - q) * (1 + q)), q);
    return r;
}

// Oracle 2: the ray equations integrated in arc length (RK4, long double):
// dz/ds = sin phi, dx/ds = cos phi, dphi/ds = -g cos(phi)/c(z), dt/ds = 1/c(z).
struct ode_state { ld z, x, phi, t; };
ode_state ode(ld c0, ld g, ld z0, ld phi0, ld s_end, int n) {
    const auto f = [&](const ode_state& y) {
        const ld c = c0 + g * (y.z - z0);
        return ode_state{std::sin(y.phi), std::cos(y.phi), -g * std::cos(y.phi) / c, 1 / c};
    };
    const auto axpy = [](const ode_state& y, ld a, const ode_state& k) {
        return ode_state{y.z + a * k.z, y.x + a * k.x, y.phi + a * k.phi, y.t + a * k.t};
    };
    ode_state y{z0, 0, phi0, 0};
    const ld h = s_end / n;
    for (int i = 0; i < n; ++i) {
        const auto k1 = f(y), k2 = f(axpy(y, h / 2, k1)), k3 = f(axpy(y, h / 2, k2)), k4 = f(axpy(y, h, k3));
        y.z += h / 6 * (k1.z + 2 * k2.z + 2 * k3.z + k4.z);
        y.x += h / 6 * (k1.x + 2 * k2.x + 2 * k3.x + k4.x);
        y.phi += h / 6 * (k1.phi + 2 * k2.phi + 2 * k3.phi + k4.phi);
        y.t += h / 6 * (k1.t + 2 * k2.t + 2 * k3.t + k4.t);
    }
    return y;
}

// A ray followed layer by layer through a profile between depths z_min and z_max (surface, seabed).
struct traced {
    double x = 0, t = 0, s = 0, z = 0, graze = 0;
    vertical_direction heading = vertical_direction::down;
    int steps = 0;
    double worst_invariant = 0; // largest relative drift of cos(graze)/c at the boundaries
};
traced trace(const sound_speed_profile<double>& p, double z0, double graze0, vertical_direction h, double z_min,
             double z_max) {
    traced r;
    r.z = z0;
    r.graze = graze0;
    r.heading = h;
    const double xi0 = std::cos(graze0) / p.speed_mps(z0);
    for (int guard = 0; guard < 100000; ++guard) {
        auto layer = p.layer(p.layer_index(r.z, r.heading));
        layer.z_top_m = std::max(layer.z_top_m, z_min);
        layer.z_bottom_m = std::min(layer.z_bottom_m, z_max);
        const auto st = step_through_layer(layer, r.z, r.graze, r.heading);
        if (st.boundary == layer_exit::none) break;
        r.x += st.exit.range_m;
        r.t += st.exit.time_s;
        r.s += st.exit.arc_m;
        r.z = st.exit.depth_m;
        r.graze = st.exit.graze_rad();
        r.heading = st.boundary == layer_exit::bottom ? vertical_direction::down : vertical_direction::up;
        ++r.steps;
        r.worst_invariant = std::max(r.worst_invariant, std::abs(std::cos(r.graze) / p.speed_mps(r.z) / xi0 - 1));
        if ((r.z <= z_min && r.heading == vertical_direction::up) || (r.z >= z_max && r.heading == vertical_direction::down))
            break;
    }
    return r;
}

} // namespace

TEST_CASE("Constant-gradient arc reproduces the reference example: c0 1500 m/s, g 0.1 1/s, 20 deg down to 100 m") {
    const gradient_layer<double> layer{0, 100, 0, 1500, 0.1};
    const auto st = step_through_layer(layer, 0.0, 20 * deg, vertical_direction::down);
    REQUIRE(st.boundary == layer_exit::bottom);
    CHECK_FALSE(st.turned);
    CHECK(st.exit.depth_m == 100.0);
    // Printed values, to their printed precision.
    CHECK(std::abs(st.exit.graze_rad() / deg - 18.922649) <= 5e-7);
    CHECK(std::abs(st.exit.range_m - 282.998) <= 5e-4);
    CHECK(std::abs(st.exit.time_s - 0.1994308) <= 5e-8);
    CHECK(std::abs(st.exit.arc_m - 300.151) <= 5e-4);
    // Against numerical integration in long double, to 1e-9 relative (in practice ~1e-16).
    const auto ref = zquad(1500, 0.1L, 0, 100, 20 * static_cast<ld>(deg));
    const double e = std::max({rel(st.exit.range_m, ref.x), rel(st.exit.time_s, ref.t), rel(st.exit.arc_m, ref.s),
                               rel(st.exit.graze_rad(), ref.graze1)});
    MESSAGE("reference example: worst relative error vs quadrature " << e);
    CHECK(e < 1e-9);
    // And against the textbook closed forms, evaluated in long double (no cancellation at g = 0.1).
    const ld th0 = 20 * static_cast<ld>(deg), th1 = ref.graze1, r = 1500 / (0.1L * std::cos(th0));
    CHECK(rel(st.exit.range_m, r * (std::sin(th0) - std::sin(th1))) < 1e-13);
    CHECK(rel(st.exit.arc_m, r * (th0 - th1)) < 1e-13);
    CHECK(rel(st.exit.time_s, std::log(((1 + std::sin(th0)) / std::cos(th0)) / ((1 + std::sin(th1)) / std::cos(th1))) / 0.1L) <
          1e-13);
    // The arc is the same piece of path.
    CHECK(st.arc.length_m == st.exit.arc_m);
    CHECK(st.arc.start_incline_rad == doctest::Approx(20 * deg).epsilon(1e-15));
}

TEST_CASE("Arc results stay exact as the gradient goes from 1e-1 to 1e-12 1/s (both signs, both directions)") {
    double worst = 0, worst_straight = 0;
    for (double angle : {20.0, 45.0, 80.0}) {
        for (int p = 1; p <= 12; ++p) {
            for (double sign : {1.0, -1.0}) {
                const double g = sign * std::pow(10.0, -p);
                const ld th = static_cast<ld>(angle * deg);
                // Down from 0 to 100 m, and up from 100 m to 0.
                const gradient_layer<double> down_layer{0, 100, 0, 1500, g};
                const auto d = step_through_layer(down_layer, 0.0, angle * deg, vertical_direction::down);
                const auto rd = zquad(1500, g, 0, 100, th);
                const gradient_layer<double> up_layer{0, 100, 100, 1500, g};
                const auto u = step_through_layer(up_layer, 100.0, angle * deg, vertical_direction::up);
                const auto ru = zquad(1500, g, 100, 0, th);
                REQUIRE(d.boundary == layer_exit::bottom);
                REQUIRE(u.boundary == layer_exit::top);
                for (const auto& [st, r] : {std::pair{d, rd}, std::pair{u, ru}}) {
                    worst = std::max({worst, rel(st.exit.range_m, r.x), rel(st.exit.time_s, r.t), rel(st.exit.arc_m, r.s),
                                      rel(st.exit.graze_rad(), r.graze1)});
                }
                if (p == 12) { // the straight-line limit: x = 100 cot, s = 100/sin, t = s/c0
                    const ld s = 100 / std::sin(th);
                    worst_straight = std::max({worst_straight, rel(d.exit.range_m, 100 / std::tan(th)), rel(d.exit.arc_m, s),
                                               rel(d.exit.time_s, s / 1500), rel(d.exit.graze_rad(), th)});
                }
            }
        }
    }
    MESSAGE("worst relative error vs quadrature over g = +-1e-1..1e-12: " << worst);
    MESSAGE("worst relative difference from the straight line at g = 1e-12: " << worst_straight);
    CHECK(worst < 1e-9);
    CHECK(worst < 1e-14); // what is actually achieved; a cancellation would show here first
    CHECK(worst_straight < 1e-12);
}

TEST_CASE("A zero-gradient layer gives exactly the straight line") {
    const gradient_layer<double> layer{10, 110, 10, 1490, 0.0};
    for (double angle : {0.5, 10.0, 33.0, 89.9}) {
        const auto st = step_through_layer(layer, 10.0, angle * deg, vertical_direction::down);
        const double s = 100 / std::sin(angle * deg);
        CHECK(st.exit.range_m == doctest::Approx(100 / std::tan(angle * deg)).epsilon(1e-15));
        CHECK(st.exit.arc_m == doctest::Approx(s).epsilon(1e-15));
        CHECK(st.exit.time_s == doctest::Approx(s / 1490).epsilon(1e-15));
        CHECK(st.exit.graze_rad() == doctest::Approx(angle * deg).epsilon(1e-15));
    }
    // Horizontal in a uniform layer: never leaves.
    const auto h = step_through_layer(layer, 50.0, 0.0, vertical_direction::down);
    CHECK(h.boundary == layer_exit::none);
    CHECK(h.exit.depth_m == 50.0);
    CHECK(h.exit.range_m == inf);
    CHECK(h.arc.length_m == inf);
    const auto mid = arc_point(h.arc, 1000.0);
    CHECK(mid.depth_m == 50.0);
    CHECK(mid.range_m == doctest::Approx(1000.0).epsilon(1e-15));
    CHECK(mid.time_s == doctest::Approx(1000.0 / 1490).epsilon(1e-15));
}

TEST_CASE("A turning ray matches the closed form and the ray equations integrated numerically") {
    // 5 deg down from the top of a 100 m layer with g = 0.1: turns at c0 (1/cos - 1)/g = 57.2 m, back to the top.
    const double c0 = 1500, g = 0.1, th = 5 * deg;
    const gradient_layer<double> layer{0, 100, 0, c0, g};
    const auto st = step_through_layer(layer, 0.0, th, vertical_direction::down);
    REQUIRE(st.boundary == layer_exit::top);
    CHECK(st.turned);
    const ld thl = static_cast<ld>(th), r = c0 / (g * std::cos(thl));
    CHECK(st.exit.depth_m == 0.0);
    CHECK(rel(st.exit.range_m, 2 * r * std::sin(thl)) < 1e-14);
    CHECK(rel(st.exit.arc_m, 2 * r * thl) < 1e-14);
    CHECK(rel(st.exit.time_s, 2 * std::atanh(std::sin(thl)) / g) < 1e-14);
    CHECK(st.exit.incline_rad == doctest::Approx(-th).epsilon(1e-14));
    const auto y = ode(c0, g, 0, thl, st.exit.arc_m, 4000);
    CHECK(std::abs(static_cast<double>(y.z)) < 1e-9);
    CHECK(rel(st.exit.range_m, y.x) < 1e-13);
    CHECK(rel(st.exit.time_s, y.t) < 1e-13);
    // The turning point.
    const auto tp = arc_turning_point(st.arc);
    REQUIRE(tp.has_value());
    CHECK(rel(tp->depth_m, c0 * (1 / std::cos(thl) - 1) / g) < 1e-13);
    CHECK(rel(tp->range_m, r * std::sin(thl)) < 1e-14);
    CHECK(rel(tp->arc_m, r * thl) < 1e-14);
    CHECK(tp->incline_rad == 0.0);
    // A ray that cannot turn in its layer has no turning point.
    CHECK_FALSE(arc_turning_point(step_through_layer(layer, 0.0, 20 * deg, vertical_direction::down).arc).has_value());
}

TEST_CASE("A nearly horizontal ray turning in a nearly uniform layer keeps full precision") {
    // theta0 = 1e-5 rad, g = 1e-9 1/s: radius 1.5e12 m, turns 75 m down after 15,000 km.
    const double c0 = 1500, g = 1e-9, th = 1e-5;
    const gradient_layer<double> layer{0, 100, 0, c0, g};
    const auto st = step_through_layer(layer, 0.0, th, vertical_direction::down);
    REQUIRE(st.boundary == layer_exit::top);
    CHECK(st.turned);
    const ld thl = th, r = c0 / (g * std::cos(thl));
    CHECK(rel(st.exit.range_m, 2 * r * std::sin(thl)) < 1e-13);
    CHECK(rel(st.exit.arc_m, 2 * r * thl) < 1e-13);
    CHECK(rel(st.exit.time_s, 2 * std::atanh(std::sin(thl)) / static_cast<ld>(g)) < 1e-13);
    const auto tp = arc_turning_point(st.arc);
    REQUIRE(tp.has_value());
    CHECK(rel(tp->depth_m, c0 * 2 * std::pow(std::sin(thl / 2), 2) / (g * std::cos(thl))) < 1e-12);
    const auto y = ode(c0, g, 0, thl, st.exit.arc_m / 2, 2000);
    CHECK(rel(tp->depth_m, y.z) < 1e-10);
    CHECK(rel(tp->range_m, y.x) < 1e-12);
}

TEST_CASE("A horizontal launch bends the way the gradient says, whatever heading is asked for") {
    // From 50 m in a layer [0, 100] with c(50) = 1505.
    for (double g : {0.1, -0.1}) {
        const gradient_layer<double> layer{0, 100, 0, 1500, g};
        const auto a = step_through_layer(layer, 50.0, 0.0, vertical_direction::down);
        const auto b = step_through_layer(layer, 50.0, 0.0, vertical_direction::up);
        CHECK(a.boundary == b.boundary);
        CHECK(a.exit.range_m == b.exit.range_m);
        CHECK_FALSE(a.turned);
        // g > 0: speed grows downward, the ray rises to 0 m; g < 0: it sinks to 100 m.
        const double z_exit = g > 0 ? 0.0 : 100.0;
        CHECK(a.boundary == (g > 0 ? layer_exit::top : layer_exit::bottom));
        CHECK(a.exit.depth_m == z_exit);
        // Closed form: R = c(50)/|g|, cos(theta1) = c(50)/c(z_exit), x = R sin(theta1), s = R theta1.
        const ld c_start = 1500 + static_cast<ld>(g) * 50;
        const ld c_end = 1500 + static_cast<ld>(g) * z_exit;
        const ld th1 = std::acos(c_end / c_start), r = c_start / std::abs(static_cast<ld>(g));
        CHECK(rel(a.exit.graze_rad(), th1) < 1e-12);
        CHECK(rel(a.exit.range_m, r * std::sin(th1)) < 1e-12);
        CHECK(rel(a.exit.arc_m, r * th1) < 1e-12);
        const auto y = ode(c_start, g, 50, 0, a.exit.arc_m, 4000);
        CHECK(std::abs(static_cast<double>(y.z) - z_exit) < 1e-9);
        CHECK(rel(a.exit.time_s, y.t) < 1e-13);
    }
}

TEST_CASE("A ray whose turning depth is the layer bottom leaves it exactly horizontal, and continues correctly") {
    const double c0 = 1500, g = 0.1, th = 5 * deg;
    // Place the bottom on the turning depth, c0 (1/cos theta - 1)/g, computed in long double.
    const ld thl = static_cast<ld>(th);
    const double z_turn = static_cast<double>(c0 * (1 / std::cos(thl) - 1) / g);
    const gradient_layer<double> upper{0, z_turn, 0, c0, g};
    const auto a = step_through_layer(upper, 0.0, th, vertical_direction::down);
    REQUIRE(a.boundary == layer_exit::bottom);
    CHECK_FALSE(a.turned);
    CHECK(a.exit.graze_rad() == 0.0);
    const ld r = c0 / (g * std::cos(thl));
    CHECK(rel(a.exit.range_m, r * std::sin(thl)) < 1e-13);
    CHECK(rel(a.exit.arc_m, r * thl) < 1e-13);
    CHECK(rel(a.exit.time_s, std::atanh(std::sin(thl)) / g) < 1e-13);
    // The layer below has the same gradient: the horizontal ray is sent straight back up (zero-length step) ...
    const gradient_layer<double> lower{z_turn, 2 * z_turn, 0, c0, g};
    const auto b = step_through_layer(lower, z_turn, 0.0, vertical_direction::down);
    CHECK(b.boundary == layer_exit::top);
    CHECK(b.exit.arc_m == 0.0);
    // ... and climbs back to the surface, as in one thick layer.
    const auto c = step_through_layer(upper, z_turn, 0.0, vertical_direction::up);
    REQUIRE(c.boundary == layer_exit::top);
    const auto whole = step_through_layer(gradient_layer<double>{0, 2 * z_turn, 0, c0, g}, 0.0, th, vertical_direction::down);
    REQUIRE(whole.turned);
    CHECK(rel(a.exit.range_m + c.exit.range_m, whole.exit.range_m) < 1e-13);
    CHECK(rel(a.exit.time_s + c.exit.time_s, whole.exit.time_s) < 1e-13);
    CHECK(rel(a.exit.arc_m + c.exit.arc_m, whole.exit.arc_m) < 1e-13);
    CHECK(c.exit.graze_rad() == doctest::Approx(th).epsilon(1e-13));

    // A micrometre deeper bottom: the ray turns inside and comes back to the top.
    const auto deeper = step_through_layer(gradient_layer<double>{0, z_turn + 1e-6, 0, c0, g}, 0.0, th, vertical_direction::down);
    CHECK(deeper.turned);
    CHECK(deeper.boundary == layer_exit::top);
    CHECK(rel(deeper.exit.range_m, whole.exit.range_m) < 1e-13);
    // A micrometre shallower: it leaves through the bottom at the small angle sqrt(2 g dz / c) (to first order).
    const auto shallower =
        step_through_layer(gradient_layer<double>{0, z_turn - 1e-6, 0, c0, g}, 0.0, th, vertical_direction::down);
    CHECK_FALSE(shallower.turned);
    CHECK(shallower.boundary == layer_exit::bottom);
    CHECK(shallower.exit.graze_rad() == doctest::Approx(std::sqrt(2 * g * 1e-6 / (c0 + g * z_turn))).epsilon(1e-4).scale(0));
}

TEST_CASE("A constant-speed profile reproduces straight lines to 1e-12") {
    std::vector<double> z, c;
    for (int i = 0; i <= 20; ++i) {
        z.push_back(5.0 * i);
        c.push_back(1487.5);
    }
    const sound_speed_profile<double> p(z, c);
    for (double angle : {1.0, 30.0, 75.0}) {
        const double th = angle * deg;
        const auto down = trace(p, 0.0, th, vertical_direction::down, 0.0, 100.0);
        const auto up = trace(p, 100.0, th, vertical_direction::up, 0.0, 100.0);
        for (const auto& r : {down, up}) {
            CHECK(r.steps == 20);
            CHECK(rel(r.x, 100 / std::tan(static_cast<ld>(th))) < 1e-12);
            CHECK(rel(r.s, 100 / std::sin(static_cast<ld>(th))) < 1e-12);
            CHECK(rel(r.t, 100 / std::sin(static_cast<ld>(th)) / 1487.5L) < 1e-12);
            CHECK(rel(r.graze, th) < 1e-12);
        }
        CHECK(down.z == 100.0);
        CHECK(up.z == 0.0);
    }
}

TEST_CASE("A ray crossing 1000 thin layers matches one layer with the same linear profile") {
    // c = 1500 + z/16 from 0 to 1000 m, as 1000 one-metre layers.
    std::vector<double> z, c;
    for (int i = 0; i <= 1000; ++i) {
        z.push_back(i);
        c.push_back(1500 + 0.0625 * i); // exactly representable: the thin layers are exactly linear
    }
    const sound_speed_profile<double> p(z, c);
    const gradient_layer<double> thick{0, 1000, 0, 1500, 0.0625};
    // Straight through (30 deg reaches the bottom) and a turning ray (10 deg turns at 370.2 m).
    for (double angle : {30.0, 10.0}) {
        const double th = angle * deg;
        const auto many = trace(p, 0.0, th, vertical_direction::down, 0.0, 1000.0);
        const auto one = step_through_layer(thick, 0.0, th, vertical_direction::down);
        CHECK(one.turned == (angle == 10.0));
        CHECK(many.z == one.exit.depth_m);
        const double e = std::max({rel(many.x, one.exit.range_m), rel(many.t, one.exit.time_s), rel(many.s, one.exit.arc_m),
                                   rel(many.graze, one.exit.graze_rad())});
        MESSAGE(angle << " deg through " << many.steps << " layers: worst relative difference " << e
                      << ", Snell invariant drift " << many.worst_invariant);
        CHECK(e < 1e-13);
        CHECK(many.worst_invariant < 1e-14);
    }
}

TEST_CASE("Points along an arc agree with its exit and with the integrated ray equations") {
    const double c0 = 1510, g = -0.07;
    const gradient_layer<double> layer{0, 400, 0, c0, g};
    // Up from 300 m at 6 deg with speed increasing upward: the ray turns and goes down to 400 m.
    const auto st = step_through_layer(layer, 300.0, 6 * deg, vertical_direction::up);
    REQUIRE(st.boundary == layer_exit::bottom);
    CHECK(st.turned);
    const auto end = arc_point(st.arc, st.arc.length_m);
    CHECK(end.depth_m == doctest::Approx(st.exit.depth_m).epsilon(1e-14));
    CHECK(end.range_m == doctest::Approx(st.exit.range_m).epsilon(1e-14));
    CHECK(end.time_s == doctest::Approx(st.exit.time_s).epsilon(1e-14));
    CHECK(end.incline_rad == doctest::Approx(st.exit.incline_rad).epsilon(1e-12));
    const ld c_start = c0 + static_cast<ld>(g) * 300;
    for (double frac : {0.1, 0.37, 0.5, 0.81, 1.0}) {
        const double s = frac * st.arc.length_m;
        const auto pt = arc_point(st.arc, s);
        const auto y = ode(c_start, g, 300, -6 * static_cast<ld>(deg), s, 4000);
        CHECK(rel(pt.depth_m, y.z) < 1e-13);
        CHECK(rel(pt.range_m, y.x) < 1e-13);
        CHECK(rel(pt.time_s, y.t) < 1e-13);
        CHECK(std::abs(pt.incline_rad - static_cast<double>(y.phi)) < 1e-13);
        // Inverse lookups.
        const auto by_range = arc_point_at_range(st.arc, pt.range_m);
        REQUIRE(by_range.has_value());
        CHECK(rel(by_range->arc_m, s) < 1e-13);
        CHECK(rel(by_range->depth_m, pt.depth_m) < 1e-13);
    }
    CHECK_FALSE(arc_point_at_range(st.arc, st.exit.range_m * 1.001).has_value());
    CHECK_FALSE(arc_point_at_range(st.arc, -1.0).has_value());
    // First crossing of a depth: 290 m (above the start) is reached before the turn, 350 m after it.
    const auto tp = arc_turning_point(st.arc);
    REQUIRE(tp.has_value());
    const auto at290 = arc_point_at_depth(st.arc, 290.0);
    const auto at350 = arc_point_at_depth(st.arc, 350.0);
    REQUIRE(at290.has_value());
    REQUIRE(at350.has_value());
    CHECK(at290->arc_m < tp->arc_m);
    CHECK(at350->arc_m > tp->arc_m);
    CHECK(arc_point(st.arc, at290->arc_m).depth_m == doctest::Approx(290.0).epsilon(1e-13));
    CHECK(arc_point(st.arc, at350->arc_m).depth_m == doctest::Approx(350.0).epsilon(1e-13));
    CHECK_FALSE(arc_point_at_depth(st.arc, tp->depth_m - 1.0).has_value()); // above the turning depth: never
}

TEST_CASE("Arc points keep full precision as the gradient vanishes") {
    for (double g : {1e-3, 1e-6, 1e-9, 1e-12, 0.0}) {
        const gradient_layer<double> layer{0, 1000, 0, 1500, g};
        const auto st = step_through_layer(layer, 0.0, 25 * deg, vertical_direction::down);
        const ld th = 25 * static_cast<ld>(deg);
        const auto y = ode(1500, g, 0, th, 700, 2000);
        const auto pt = arc_point(st.arc, 700.0);
        CHECK(rel(pt.depth_m, y.z) < 1e-13);
        CHECK(rel(pt.range_m, y.x) < 1e-13);
        CHECK(rel(pt.time_s, y.t) < 1e-13);
    }
}

TEST_CASE("A vertical ray goes straight down, with travel time ln(c1/c0)/g") {
    const gradient_layer<double> layer{0, 200, 0, 1480, 0.2};
    const auto st = step_through_layer(layer, 20.0, sss::half_pi_v<double>, vertical_direction::down);
    REQUIRE(st.boundary == layer_exit::bottom);
    CHECK(st.exit.range_m < 1e-13); // cos(double(pi/2)) = 6e-17: the ray is vertical to rounding
    CHECK(st.exit.arc_m == doctest::Approx(180.0).epsilon(1e-15));
    CHECK(rel(st.exit.time_s, std::log((1480 + 0.2L * 200) / (1480 + 0.2L * 20)) / 0.2L) < 1e-14);
    const auto up = step_through_layer(layer, 20.0, sss::half_pi_v<double>, vertical_direction::up);
    CHECK(up.boundary == layer_exit::top);
    CHECK(up.exit.arc_m == doctest::Approx(20.0).epsilon(1e-15));
    // Exactly vertical (cos = 0, as float pi/2 gives after clamping): the straight vertical branch.
    const gradient_layer<float> layer_f{0.f, 200.f, 0.f, 1480.f, 0.2f};
    const auto vf = step_through_layer(layer_f, 20.f, sss::half_pi_v<float>, vertical_direction::down);
    CHECK(vf.exit.range_m == 0.f);
    CHECK(vf.exit.arc_m == 180.f);
    CHECK(vf.exit.time_s == doctest::Approx(std::log(1520.0 / 1484.0) / 0.2).epsilon(1e-6));
    CHECK(rel(arc_point(st.arc, 90.0).time_s, std::log((1480 + 0.2L * 110) / (1480 + 0.2L * 20)) / 0.2L) < 1e-14);
}

TEST_CASE("Stepping by Snell invariant agrees with stepping by grazing angle, and conserves the invariant") {
    const gradient_layer<double> layer{0, 100, 0, 1500, 0.1};
    const double xi = snell_invariant(20 * deg, 1500.0);
    const auto a = step_through_layer_invariant(layer, 0.0, xi, vertical_direction::down);
    const auto b = step_through_layer(layer, 0.0, 20 * deg, vertical_direction::down);
    CHECK(a.exit.range_m == doctest::Approx(b.exit.range_m).epsilon(1e-14));
    CHECK(a.exit.time_s == doctest::Approx(b.exit.time_s).epsilon(1e-14));
    CHECK(snell_invariant(b.exit.graze_rad(), layer.speed_mps(100.0)) == doctest::Approx(xi).epsilon(1e-15));
    CHECK(graze_from_invariant(xi, 1500.0) == doctest::Approx(20 * deg).epsilon(1e-14));
    CHECK(graze_from_invariant(1.0 / 1400, 1500.0) == 0.0); // beyond the turning depth
}

TEST_CASE("Float arcs agree with double to single precision") {
    const gradient_layer<float> layer{0.f, 100.f, 0.f, 1500.f, 0.1f};
    const auto st = step_through_layer(layer, 0.f, 20 * static_cast<float>(deg), vertical_direction::down);
    CHECK(std::abs(st.exit.graze_rad() / static_cast<float>(deg) - 18.922649f) < 2e-5f);
    CHECK(st.exit.range_m == doctest::Approx(282.99823).epsilon(1e-5));
    CHECK(st.exit.time_s == doctest::Approx(0.19943077).epsilon(1e-5));
    CHECK(st.exit.arc_m == doctest::Approx(300.15105).epsilon(1e-5));
    const auto turn = step_through_layer(layer, 0.f, 5 * static_cast<float>(deg), vertical_direction::down);
    CHECK(turn.turned);
    CHECK(turn.exit.range_m == doctest::Approx(2 * 1500 / (0.1 * std::cos(5 * deg)) * std::sin(5 * deg)).epsilon(1e-5));
    const auto pt = arc_point(turn.arc, turn.arc.length_m / 2);
    CHECK(pt.depth_m == doctest::Approx(1500 * (1 / std::cos(5 * deg) - 1) / 0.1).epsilon(1e-4));
}

TEST_CASE("atan(w)/w and atanh(u)/u by their series agree with the functions to an ulp across the series' range, "
          "up to its ends") {
    // The arcs' closed forms divide these by w; near 0 their series (to the q^7 term for |w| <= 1/16, where the next
    // term is below 3.2e-21) replace the library calls. Against long double, over 1e-5 <= |w| <= 1/16, both signs.
    const auto check = [](auto zero) {
        using R = decltype(zero);
        const double ulp = double(std::numeric_limits<R>::epsilon());
        double worst_atan = 0.0, worst_atanh = 0.0;
        for (int i = 0; i <= 4000; ++i) {
            // Logarithmically spaced from 1e-5 to 1/16, with the switch at 1e-4 among the points.
            const long double mag = i == 4000 ? 1e-4L : 1e-5L * std::pow(6250.0L, i / 3999.0L);
            for (const long double sign : {1.0L, -1.0L}) {
                const R w = R(sign * mag);
                const long double lw = w;
                const long double ta = std::atan(lw) / lw, th = std::atanh(lw) / lw;
                worst_atan = std::max(worst_atan, double(std::abs((sss::propagation::detail::atan_ratio(w) - ta) / ta)));
                worst_atanh = std::max(worst_atanh, double(std::abs((sss::propagation::detail::atanh_ratio(w) - th) / th)));
            }
        }
        INFO("worst relative error: atan " << worst_atan / ulp << " ulp, atanh " << worst_atanh / ulp << " ulp");
        CHECK(worst_atan <= ulp);
        CHECK(worst_atanh <= ulp);
    };
    check(0.0f);
    check(0.0);
}

TEST_CASE("log(1 + e)/e by its series agrees with log1p to an ulp up to the series' end, both signs") {
    // Layer times and the harmonic mean speed divide log1p(e) by e; below |e| = 1e-4 the series 1 - e/2 + e^2/3 -
    // e^3/4 + e^4/5 stands in (its next term is below 2e-21). Without the e^3 term the error reached 2.5e-13.
    const auto check = [](auto zero) {
        using R = decltype(zero);
        const double ulp = double(std::numeric_limits<R>::epsilon());
        double worst = 0.0;
        for (int i = 0; i <= 2000; ++i) {
            const long double mag = 1e-9L * std::pow(1e5L, i / 2000.0L); // 1e-9 to 1e-4
            for (const long double sign : {1.0L, -1.0L}) {
                const R e = R(sign * mag);
                const long double le = e;
                const long double want = std::log1p(le) / le;
                worst = std::max(worst, double(std::abs((sss::propagation::detail::log1p_ratio(e) - want) / want)));
            }
        }
        INFO("worst relative error " << worst / ulp << " ulp");
        CHECK(worst <= ulp);
    };
    check(0.0f);
    check(0.0);
}

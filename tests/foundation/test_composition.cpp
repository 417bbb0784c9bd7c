// Compile-time composition: every shipped policy models its family's concept, simulator<> has working defaults, and
// rendering is deterministic whatever the number of threads.

#include <doctest/doctest.h>

#include <sss/sss.hpp>

static_assert(sss::Scattering<sss::scattering::lambertian<float>> && sss::Scattering<sss::scattering::jackson<double>>);
static_assert(sss::Propagation<sss::propagation::straight<float>>);
static_assert(sss::Beam<sss::beam::ideal_fan<double>> && sss::Beam<sss::beam::planar_array<float>>);
static_assert(sss::Motion<sss::motion::straight_line<float>> && sss::Motion<sss::motion::perturbed<double>> &&
              sss::Motion<sss::motion::trajectory<double>>);
static_assert(sss::Scene<sss::scene::flat_seabed<float>>);
static_assert(std::is_same_v<sss::simulator<>::value_type, double>);
// A type that lacks the required expressions does not model the concepts.
static_assert(!sss::Scattering<int> && !sss::Beam<sss::scattering::lambertian<double>> &&
              !sss::Motion<sss::beam::ideal_fan<double>> && !sss::Propagation<sss::motion::straight_line<double>>);

TEST_CASE("the default simulator renders one ping on a flat seabed with returns on both sides") {
    const sss::simulator<> sim;
    const auto lines = sim.ping(sss::scene::flat_seabed<double>{}, 0);
    CHECK(lines.port.size() == sim.samples_per_line());
    CHECK(lines.starboard.size() == sim.samples_per_line());
    double e = 0;
    for (double v : lines.starboard) e += v;
    CHECK(e > 0);
}

TEST_CASE("rendering is deterministic: one thread and several give identical waterfalls") {
    sss::motion::perturbed_params<float> m;
    m.roll_deg = {3.0f, 4.0f, 0.0f};
    const sss::simulator<sss::scattering::lambertian<float>, sss::propagation::straight<float>, sss::beam::ideal_fan<float>,
                         sss::motion::perturbed<float>>
        sim({}, {}, {}, sss::motion::perturbed<float>{m});
    const sss::scene::flat_seabed<float> seabed;
    const auto a = sim.render(seabed, 0, 12, 1), b = sim.render(seabed, 0, 12, 3);
    REQUIRE(a.values.size() == 12 * 2 * sim.samples_per_line());
    CHECK(a.values == b.values);
    // Port on the left mirrored: the row's middle holds both sides' first samples.
    const auto one = sim.ping(seabed, 5);
    CHECK(a.at(5, a.samples - 1) == one.port[0]);
    CHECK(a.at(5, 0) == one.port[a.samples - 1]);
    CHECK(a.at(5, a.samples + 7) == one.starboard[7]);
}

namespace {
double function_visitor_power = 0.0;
void add_power(const sss::tube_echo<double>& e) { function_visitor_power += e.power; }
} // namespace

TEST_CASE("trace hands a plain function every echo piece it hands a callable object") {
    const sss::simulator<> sim;
    const sss::scene::flat_seabed<double> seabed;
    const auto pose = sim.motion().pose_at(0);
    double object_power = 0.0;
    std::size_t pieces = 0;
    const auto visit = [&](const sss::tube_echo<double>& e) {
        object_power += e.power;
        ++pieces;
    };
    sim.trace(seabed, pose, sss::side::starboard, visit); // a const lvalue object
    function_visitor_power = 0.0;
    sim.trace(seabed, pose, sss::side::starboard, add_power);
    CHECK(pieces > 100);
    CHECK(function_visitor_power == object_power);
}

// A fixed-seed sweep of random small scenes: parameters drawn across their valid ranges render without a crash,
// with every sample finite and no energy negative; one parameter drawn just outside its range is refused with an
// sss::invalid_parameter naming it. The CI sweep is 400 scenes; SSS_SWEEP_SCENES=N runs N of them
// (tests/fuzz/run.sh --sweep N builds and runs the long one).

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <sss/sss.hpp>
#include <sss/scene/height_field.hpp>
#include <sss/seabed/fractal.hpp>

namespace {

constexpr double nan_v = std::numeric_limits<double>::quiet_NaN();
constexpr double inf_v = std::numeric_limits<double>::infinity();

enum class beam_kind { fan, array };
enum class scattering_kind { lambert, jackson };
enum class scene_kind { flat, relief };

// Everything one scene is made of, as the user would set it.
struct config {
    sss::receiver_params rx{};
    beam_kind beam = beam_kind::fan;
    sss::beam::ideal_fan_params<double> fan{};
    sss::beam::planar_array_params<double> array{};
    sss::propagation::straight_params<double> water{};
    scattering_kind scattering = scattering_kind::lambert;
    double mu_db = -27.0;
    double jackson_f_hz = 100e3;
    sss::scattering::sediment sediment = sss::scattering::sediment::medium_sand;
    sss::motion::straight_line_params<double> motion{};
    sss::ray_density density{};
    scene_kind scene = scene_kind::flat;
    double seabed_z_m = 0.0;
    double relief_rms_m = 0.0;
    double cell_m = 1.0;
    std::uint64_t relief_seed = 0;
    std::size_t first = 0, count = 2;
};

class draw {
public:
    explicit draw(std::uint64_t seed) : g_(seed) {}
    double in(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g_); }
    std::size_t index(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(g_); }
    bool chance(double p) { return in(0.0, 1.0) < p; }
    template <class V> V one_of(std::initializer_list<V> v) { return *(v.begin() + static_cast<std::ptrdiff_t>(index(v.size()))); }

private:
    std::mt19937_64 g_;
};

// Every parameter drawn inside its valid range, kept small enough that a scene renders in milliseconds.
config valid_config(draw& d) {
    config c;
    c.rx.sample_rate_hz = d.in(4e3, 30e3);
    c.rx.max_range_m = d.in(4.0, 60.0);
    c.rx.pulse.length_s = d.in(10e-6, 2e-3);
    c.rx.pulse.shape = d.chance(0.5) ? sss::pulse_shape::rectangular : sss::pulse_shape::hann;
    c.rx.source_level_db = d.in(-50.0, 230.0);
    c.beam = d.chance(0.5) ? beam_kind::fan : beam_kind::array;
    c.fan = {.along_width_deg = d.in(0.05, 20.0), .vertical_width_deg = d.in(1.0, 180.0),
             .depression_deg = d.in(-90.0, 90.0)};
    c.array.frequency_hz = d.in(30e3, 200e3);
    c.array.sound_speed_mps = d.in(1400.0, 1600.0);
    c.array.depression_deg = d.in(-10.0, 80.0);
    c.array.threshold_db = d.in(-40.0, -3.0);
    c.array.transmit.along = {.count = 1 + d.index(4), .element_m = d.in(0.05, 0.3)};
    c.array.transmit.along.pitch_m = c.array.transmit.along.element_m * d.in(1.0, 1.5);
    c.array.transmit.vertical = {.count = 1, .element_m = d.in(0.005, 0.05)};
    c.water = {.sound_speed_mps = d.in(1000.0, 2500.0), .absorption_db_per_km = d.in(0.0, 200.0)};
    c.scattering = d.chance(0.5) ? scattering_kind::lambert : scattering_kind::jackson;
    c.mu_db = d.in(-60.0, sss::scattering::lambert_max_db);
    c.jackson_f_hz = d.in(10e3, 500e3);
    c.sediment = static_cast<sss::scattering::sediment>(d.index(static_cast<std::size_t>(sss::scattering::sediment::sandy_clay) + 1));
    c.motion = {.start_m = {d.in(-100.0, 100.0), d.in(-100.0, 100.0)}, .heading_deg = d.in(-720.0, 720.0),
                .speed_mps = d.in(0.0, 6.0), .altitude_m = d.in(0.5, 40.0), .ping_interval_s = d.in(0.01, 1.0)};
    c.density = {.along = 1 + d.index(3), .across = d.chance(0.3) ? 2 + d.index(200) : 0,
                 .per_sample = d.in(0.1, 1.5)};
    c.scene = d.chance(0.5) ? scene_kind::flat : scene_kind::relief;
    c.relief_rms_m = d.in(0.0, 2.0);
    c.cell_m = d.in(0.25, 4.0);
    c.relief_seed = d.index(1u << 30);
    // The seabed lies below the towfish (by at least 0.2 m, plus the relief's reach for a rough seabed).
    const double reach = c.scene == scene_kind::relief ? 8.0 * c.relief_rms_m : 0.0;
    c.seabed_z_m = c.motion.altitude_m - reach - d.in(0.2, 40.0);
    // A rough seabed covers the first pings' footprint only; a flat one extends everywhere.
    c.first = c.scene == scene_kind::flat ? d.index(1000) : d.index(3);
    c.count = 1 + d.index(2);
    return c;
}

// One parameter moved just outside its range, and the name its error must carry.
struct mutation {
    std::string name;
    std::function<void(config&, draw&)> apply;
};

std::vector<mutation> mutations() {
    return {
        {"receiver.sample_rate_hz", [](config& c, draw& d) { c.rx.sample_rate_hz = d.one_of({0.0, -1e4, nan_v, inf_v}); }},
        {"receiver.max_range_m", [](config& c, draw& d) { c.rx.max_range_m = d.one_of({0.0, -5.0, nan_v, 1e9}); }},
        {"receiver.source_level_db", [](config& c, draw& d) { c.rx.source_level_db = d.one_of({nan_v, inf_v, -inf_v}); }},
        {"pulse.length_s", [](config& c, draw& d) { c.rx.pulse.length_s = d.one_of({0.0, -1e-4, nan_v, 1.001}); }},
        {"ideal_fan.along_width_deg", [](config& c, draw& d) {
             c.beam = beam_kind::fan;
             c.fan.along_width_deg = d.one_of({0.0, 180.0, -1.0, nan_v});
         }},
        {"ideal_fan.vertical_width_deg", [](config& c, draw& d) {
             c.beam = beam_kind::fan;
             c.fan.vertical_width_deg = d.one_of({0.0, 180.01, nan_v});
         }},
        {"ideal_fan.depression_deg", [](config& c, draw& d) {
             c.beam = beam_kind::fan;
             c.fan.depression_deg = d.one_of({-90.01, 90.01, nan_v});
         }},
        {"planar_array.frequency_hz", [](config& c, draw& d) {
             c.beam = beam_kind::array;
             c.array.frequency_hz = d.one_of({0.0, -1.0, nan_v});
         }},
        {"planar_array.depression_deg", [](config& c, draw& d) {
             c.beam = beam_kind::array;
             c.array.depression_deg = d.one_of({90.01, -90.01, nan_v});
         }},
        {"planar_array.threshold_db", [](config& c, draw& d) {
             c.beam = beam_kind::array;
             c.array.threshold_db = d.one_of({0.0, 3.0, nan_v});
         }},
        {"straight.sound_speed_mps", [](config& c, draw& d) {
             c.scattering = scattering_kind::lambert; // jackson would name its own copy, jackson.sound_speed_mps
             c.water.sound_speed_mps = d.one_of({999.9, 2500.1, nan_v});
         }},
        {"straight.absorption_db_per_km", [](config& c, draw& d) { c.water.absorption_db_per_km = d.one_of({-0.1, nan_v}); }},
        {"lambertian.mu_db[0]", [](config& c, draw& d) {
             c.scattering = scattering_kind::lambert;
             c.mu_db = d.one_of({-4.9, 0.0, nan_v});
         }},
        {"jackson.frequency_hz", [](config& c, draw& d) {
             c.scattering = scattering_kind::jackson;
             c.jackson_f_hz = d.one_of({0.0, -1.0, nan_v});
         }},
        {"straight_line.altitude_m", [](config& c, draw& d) { c.motion.altitude_m = d.one_of({0.0, -1.0, nan_v}); }},
        {"straight_line.speed_mps", [](config& c, draw& d) { c.motion.speed_mps = d.one_of({-0.1, nan_v}); }},
        {"straight_line.ping_interval_s", [](config& c, draw& d) { c.motion.ping_interval_s = d.one_of({0.0, -1.0, nan_v}); }},
        {"straight_line.heading_deg", [](config& c, draw& d) { c.motion.heading_deg = d.one_of({inf_v, nan_v}); }},
        {"ray_density.along", [](config& c, draw& d) { c.density.along = d.one_of<std::size_t>({0, 4097}); }},
        {"ray_density.across", [](config& c, draw&) { c.density.across = 1; }},
        {"ray_density.along_split", [](config& c, draw& d) { c.density.along_split = d.one_of<std::size_t>({6562, 100000}); }},
        {"ray_density.along_split_echo", [](config& c, draw& d) { c.density.along_split_echo = d.one_of({-0.5, nan_v, -inf_v}); }},
        {"ray_density.along_onset", [](config& c, draw& d) { c.density.along_onset = d.one_of({-1.0, nan_v, inf_v}); }},
        {"ray_density.max_launch_step_deg", [](config& c, draw& d) { c.density.max_launch_step_deg = d.one_of({-0.5, nan_v, inf_v}); }},
        {"ray_density.per_sample", [](config& c, draw& d) {
             c.density.across = 0;
             c.density.per_sample = d.one_of({0.0, -1.0, nan_v});
         }},
        {"flat_seabed.height_m", [](config& c, draw& d) {
             c.scene = scene_kind::flat;
             c.seabed_z_m = d.one_of({nan_v, inf_v});
         }},
        {"height_field.cell_m", [](config& c, draw& d) {
             c.scene = scene_kind::relief;
             c.cell_m = d.one_of({0.0, -1.0, nan_v});
         }},
        {"render.count", [](config& c, draw& d) { c.count = d.one_of<std::size_t>({std::size_t(1) << 40, ~std::size_t(0) >> 1}); }},
        {"ping[", [](config& c, draw& d) {
             c.scene = scene_kind::flat;
             c.seabed_z_m = c.motion.altitude_m + d.one_of({0.0, 0.5, 100.0});
         }},
    };
}

// The relief: a small fractal surface of the given RMS about seabed_z_m.
sss::scene::height_field<double> relief(const config& c) {
    constexpr std::size_t n = 48;
    std::vector<double> h(n * n, c.seabed_z_m);
    if (c.relief_rms_m > 0.0 && std::isfinite(c.cell_m) && c.cell_m > 0.0) {
        const auto f = sss::seabed::fractal_surface<double>(n, n, c.cell_m, {}, c.relief_seed);
        double ms = 0.0;
        for (double v : f.values) ms += v * v;
        const double scale = ms > 0.0 ? c.relief_rms_m / std::sqrt(ms / double(f.values.size())) : 0.0;
        for (std::size_t i = 0; i < h.size(); ++i) h[i] += scale * f.values[i];
    }
    // Centred under the first pings.
    const double half = 0.5 * double(n - 1) * c.cell_m;
    return sss::scene::height_field<double>({.nx = n,
                                             .ny = n,
                                             .cell_m = c.cell_m,
                                             .origin_m = {c.motion.start_m.x - half, c.motion.start_m.y - half},
                                             .heights_m = std::move(h)});
}

template <class Scattering, class Beam>
sss::waterfall<double> render_with(const config& c, Scattering scattering, Beam beam) {
    using sim_t = sss::simulator<Scattering, sss::propagation::straight<double>, Beam, sss::motion::straight_line<double>>;
    const sim_t sim(std::move(scattering), sss::propagation::straight<double>(c.water), std::move(beam),
                    sss::motion::straight_line<double>(c.motion), c.rx, c.density);
    if (c.scene == scene_kind::flat) return sim.render(sss::scene::flat_seabed<double>(c.seabed_z_m), c.first, c.count, 1);
    return sim.render(relief(c), c.first, c.count, 1);
}

template <class Scattering> sss::waterfall<double> render_beam(const config& c, Scattering scattering) {
    if (c.beam == beam_kind::fan) return render_with(c, std::move(scattering), sss::beam::ideal_fan<double>(c.fan));
    return render_with(c, std::move(scattering), sss::beam::planar_array<double>(c.array));
}

sss::waterfall<double> render(const config& c) {
    if (c.scattering == scattering_kind::lambert) return render_beam(c, sss::scattering::lambertian<double>(c.mu_db));
    return render_beam(c, sss::scattering::jackson<double>(
                                   {.frequency_hz = c.jackson_f_hz,
                                    .sound_speed_mps = c.water.sound_speed_mps,
                                    .materials = {sss::scattering::sediment_preset<double>(c.sediment)}}));
}

std::size_t scenes_to_run() {
    if (const char* s = std::getenv("SSS_SWEEP_SCENES"); s && *s) return std::strtoull(s, nullptr, 10);
    return 400;
}

} // namespace

TEST_CASE("random scenes in range render finite, non-negative energy; one parameter out of range is named") {
    const std::size_t scenes = scenes_to_run();
    const std::vector<mutation> table = mutations();
    draw d(20261124);
    std::size_t rendered = 0, refused = 0, samples = 0, lit = 0;
    for (std::size_t s = 0; s < scenes; ++s) {
        config c = valid_config(d);
        const mutation* m = nullptr;
        if (d.chance(0.35)) {
            m = &table[d.index(table.size())];
            m->apply(c, d);
        }
        CAPTURE(s);
        if (m) {
            CAPTURE(m->name);
            std::string named;
            try {
                (void)render(c);
            } catch (const sss::invalid_parameter& e) {
                named = e.parameter();
            }
            CHECK(named.rfind(m->name, 0) == 0); // "ping[" names the ping that follows
            ++refused;
            continue;
        }
        const sss::waterfall<double> w = render(c);
        REQUIRE(w.values.size() == w.pings * w.width());
        bool finite = true, non_negative = true;
        for (double v : w.values) {
            finite = finite && std::isfinite(v);
            non_negative = non_negative && v >= 0.0;
            lit += v > 0.0 ? 1u : 0u;
        }
        CHECK(finite);
        CHECK(non_negative);
        samples += w.values.size();
        ++rendered;
    }
    MESSAGE(scenes << " scenes: " << rendered << " rendered (" << samples << " samples, " << lit << " lit), " << refused
                   << " refused by name");
    // The sweep means something only if most scenes render and some of them see the seabed.
    CHECK(rendered > scenes / 2);
    CHECK(lit > 0);
}

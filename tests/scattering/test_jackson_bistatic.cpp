// The bistatic APL-UW model (Williams & Jackson 1998 on TR 9407): the backscatter limit, reciprocity, the
// specular lobe, and finite, continuous values over the whole bistatic domain.

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <string>

#include <sss/scattering/jackson_bistatic.hpp>

using namespace sss::scattering;
using sss::deg_to_rad;

namespace {

const double pi = sss::pi_v<double>;

// The largest step (dB) of f along [a, b] sampled every h, after refining: a step above 0.5 dB is re-sampled 100
// times finer, and only what remains there (a true jump does not shrink) is reported.
double largest_jump_db(const std::function<double(double)>& sigma, double a, double b, double h) {
    auto db = [&](double x) { return 10.0 * std::log10(sigma(x)); };
    double worst = 0.0;
    double prev = db(a);
    for (double x = a + h; x <= b + 1e-12; x += h) {
        const double v = db(x);
        double step = std::abs(v - prev);
        if (!(step <= 0.5)) { // refine (also catches NaN)
            step = 0.0;
            double p = prev;
            for (int k = 1; k <= 100; ++k) {
                const double q = db(x - h + h * k / 100.0);
                step = std::max(step, std::isfinite(q) && std::isfinite(p) ? std::abs(q - p) : 1e9);
                p = q;
            }
        }
        worst = std::max(worst, step);
        prev = v;
    }
    return worst;
}

} // namespace

TEST_CASE("the bistatic geometry gives Delta = 1 at backscatter and Delta_t = 0 in the specular direction") {
    for (double deg : {0.0, 10.0, 45.0, 90.0}) {
        const double g = deg_to_rad(deg);
        const auto back = make_bistatic_geometry(g, g, pi);
        CHECK(back.delta == doctest::Approx(1.0).epsilon(1e-15));
        CHECK(back.delta_t == doctest::Approx(std::cos(g)).epsilon(1e-15));
        CHECK(back.delta_z == doctest::Approx(std::sin(g)).epsilon(1e-15));
        const auto spec = make_bistatic_geometry(g, g, 0.0);
        CHECK(spec.delta_t == doctest::Approx(0.0));
        CHECK(spec.delta == doctest::Approx(std::sin(g)).epsilon(1e-15));
    }
}

TEST_CASE("the Williams-Jackson perturbation term reduces to TR 9407's at backscatter") {
    for (const auto& row : sediment_table) {
        const auto c = make_jackson_coefficients(sediment_preset<double>(row.id), 40e3, 1500.0);
        for (double deg : {0.0, 1.0, 15.0, 45.0, 75.0, 90.0}) {
            CAPTURE(row.name);
            CAPTURE(deg);
            const double g = deg_to_rad(deg);
            const auto local = jackson_bistatic_local_terms(c, std::sin(g), std::sin(g), -std::cos(g) * std::cos(g));
            if (deg == 0.0) {
                // At grazing incidence both terms vanish exactly, in both forms.
                CHECK(local.pr == jackson_sigma_pr(c, g));
                CHECK(local.pv == jackson_sigma_pv(c, g));
            } else {
                CHECK(local.pr == doctest::Approx(jackson_sigma_pr(c, g)).epsilon(1e-12).scale(0));
                CHECK(local.pv == doctest::Approx(jackson_sigma_pv(c, g)).epsilon(1e-12).scale(0));
            }
        }
    }
}

TEST_CASE("the bistatic model reduces to the monostatic model at backscatter, term by term, within 1e-6") {
    double worst = 0.0;
    for (const auto& row : sediment_table)
        for (double f : {10e3, 30e3, 100e3, 400e3}) {
            const auto c = make_jackson_coefficients(sediment_preset<double>(row.id), f, 1500.0);
            for (int i = 0; i <= 180; ++i) {
                const double g = i == 180 ? sss::half_pi_v<double> : deg_to_rad(0.5 * i);
                const jackson_terms<double> m = jackson_backscatter_terms(c, g);
                for (double phi : {pi, -pi, double(float(pi)), 3.0 * pi}) {
                    const jackson_terms<double> b = jackson_bistatic_terms(c, g, g, phi);
                    CAPTURE(row.name);
                    CAPTURE(f);
                    CAPTURE(0.5 * i);
                    CAPTURE(phi);
                    CHECK(b.total == doctest::Approx(m.total).epsilon(1e-6).scale(0));
                    CHECK(b.kirchhoff == doctest::Approx(m.kirchhoff).epsilon(1e-6).scale(0));
                    if (i == 0) {
                        // At grazing incidence the perturbation, large-roughness and volume terms vanish exactly.
                        CHECK(b.composite == m.composite);
                        CHECK(b.large_roughness == m.large_roughness);
                        CHECK(b.volume == m.volume);
                    } else {
                        CHECK(b.composite == doctest::Approx(m.composite).epsilon(1e-6).scale(0));
                        CHECK(b.large_roughness == doctest::Approx(m.large_roughness).epsilon(1e-6).scale(0));
                        CHECK(b.volume == doctest::Approx(m.volume).epsilon(1e-6).scale(0));
                    }
                    if (m.total > 0) worst = std::max(worst, std::abs(b.total / m.total - 1.0));
                }
            }
        }
    MESSAGE("largest relative difference bistatic(phi = pi) vs backscatter: " << worst);
    // The public entry points agree too, for float and double.
    const auto sand = sediment_preset<double>(sediment::medium_sand);
    CHECK(jackson_bistatic(sand, 30e3, 1528.0, 0.4, 0.4, pi) == doctest::Approx(jackson_backscatter(sand, 30e3, 1528.0, 0.4)).epsilon(1e-12));
    const auto sand_f = sediment_preset<float>(sediment::medium_sand);
    CHECK(jackson_bistatic(sand_f, 30e3f, 1528.0f, 0.4f, 0.4f, sss::pi_v<float>) ==
          doctest::Approx(jackson_backscatter(sand_f, 30e3f, 1528.0f, 0.4f)).epsilon(1e-6));
}

TEST_CASE("bistatic scattering is reciprocal: sigma(i -> s) = sigma(s -> i)") {
    std::mt19937 rng(20240611);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (const auto& row : sediment_table) {
        const auto c = make_jackson_coefficients(sediment_preset<double>(row.id), 60e3, 1500.0);
        for (int n = 0; n < 400; ++n) {
            double gi = u(rng) * sss::half_pi_v<double>, gs = u(rng) * sss::half_pi_v<double>;
            const double phi = u(rng) * 2.0 * pi;
            if (n % 7 == 0) gi = 0.0;
            if (n % 11 == 0) gs = sss::half_pi_v<double>;
            if (n % 13 == 0) gs = gi + 1e-7;
            CAPTURE(row.name);
            CAPTURE(gi);
            CAPTURE(gs);
            CAPTURE(phi);
            const double a = jackson_bistatic(c, gi, gs, phi), b = jackson_bistatic(c, gs, gi, phi);
            CHECK(a == doctest::Approx(b).epsilon(1e-9).scale(0));
        }
    }
}

TEST_CASE("in the specular direction the bistatic Kirchhoff term equals its geometric-optics limit") {
    // At Delta_t = 0 the Kirchhoff integral (|R|^2 Delta^4 / (8 pi Delta_z^2 Delta_t^2)) int exp(-q u^(2 alpha)) J0(u) u du,
    // q = q_c Delta_z^2 Delta_t^(-2 alpha), tends to |R(theta)|^2 Gamma(1/alpha) / (16 pi alpha q_c^(1/alpha)) Delta_z^(2 - 2/alpha):
    // the closed form must reproduce it for every incidence, not only at normal incidence.
    for (const auto& row : sediment_table) {
        const auto c = make_jackson_coefficients(sediment_preset<double>(row.id), 30e3, 1528.0);
        const double a = c.alpha;
        for (double deg : {2.0, 10.0, 30.0, 60.0, 90.0}) {
            CAPTURE(row.name);
            CAPTURE(deg);
            const double g = deg_to_rad(deg);
            const double r2 = std::norm(rayleigh_reflection(sediment_preset<double>(row.id), g));
            const double limit = r2 * std::tgamma(1.0 / a) / (16.0 * pi * a * std::pow(c.q_c, 1.0 / a)) * std::pow(std::sin(g), 2.0 - 2.0 / a);
            CHECK(jackson_bistatic_sigma_kr(c, make_bistatic_geometry(g, g, 0.0)) == doctest::Approx(limit).epsilon(1e-9));
        }
    }
}

TEST_CASE("on a smooth bed the bistatic Kirchhoff lobe peaks in the specular direction") {
    const auto c = make_jackson_coefficients(sediment_preset<double>(sediment::clay), 30e3, 1528.0);
    for (double gi_deg : {20.0, 45.0, 70.0}) {
        const double gi = deg_to_rad(gi_deg);
        const double peak = jackson_bistatic_sigma_kr(c, make_bistatic_geometry(gi, gi, 0.0));
        for (double gs_deg = 1.0; gs_deg < 90.0; gs_deg += 1.0)
            for (double phi_deg = 0.0; phi_deg <= 180.0; phi_deg += 5.0) {
                if (gs_deg == gi_deg && phi_deg == 0.0) continue;
                CAPTURE(gi_deg);
                CAPTURE(gs_deg);
                CAPTURE(phi_deg);
                CHECK(jackson_bistatic_sigma_kr(c, make_bistatic_geometry(gi, deg_to_rad(gs_deg), deg_to_rad(phi_deg))) < peak);
            }
    }
}

TEST_CASE("bistatic scattering is finite and non-negative over the whole domain, its edges included") {
    const double edges[] = {0.0, 1e-9, deg_to_rad(0.01), deg_to_rad(1.0), deg_to_rad(30.0), deg_to_rad(89.99), sss::half_pi_v<double>};
    for (const auto& row : sediment_table)
        for (double f : {10e3, 300e3}) {
            const auto c = make_jackson_coefficients(sediment_preset<double>(row.id), f, 1500.0);
            for (double gi : edges)
                for (double gs : edges)
                    for (double phi : {0.0, 1e-9, 0.5, pi / 2, pi, 4.0, 2.0 * pi, -1.0}) {
                        const jackson_terms<double> t = jackson_bistatic_terms(c, gi, gs, phi);
                        CAPTURE(row.name);
                        CAPTURE(gi);
                        CAPTURE(gs);
                        CAPTURE(phi);
                        REQUIRE(std::isfinite(t.total));
                        REQUIRE(t.total >= 0.0);
                        REQUIRE(t.kirchhoff >= 0.0);
                        REQUIRE(t.composite >= 0.0);
                        REQUIRE(t.large_roughness >= 0.0);
                        REQUIRE(t.volume >= 0.0);
                    }
            CHECK(std::isfinite(jackson_bistatic(c, std::nan(""), 0.3, std::nan(""))));
        }
}

TEST_CASE("bistatic scattering is continuous in azimuth and in scattered angle, through the specular lobe") {
    for (sediment id : {sediment::medium_sand, sediment::sandy_silt, sediment::clay, sediment::rock, sediment::rough_rock})
        for (double f : {30e3, 300e3}) {
            const auto c = make_jackson_coefficients(sediment_preset<double>(id), f, 1500.0);
            for (double gi_deg : {5.0, 30.0, 80.0}) {
                const double gi = deg_to_rad(gi_deg);
                for (double gs_deg : {5.0, 30.0, 60.0, 89.0}) {
                    const double gs = deg_to_rad(gs_deg);
                    CAPTURE(sediment_table[static_cast<std::size_t>(id)].name);
                    CAPTURE(f);
                    CAPTURE(gi_deg);
                    CAPTURE(gs_deg);
                    CHECK(largest_jump_db([&](double phi) { return jackson_bistatic(c, gi, gs, phi); }, deg_to_rad(0.01), pi,
                                          deg_to_rad(0.05)) <= 0.5);
                }
                for (double phi_deg : {0.0, 90.0, 180.0}) {
                    CAPTURE(phi_deg);
                    CHECK(largest_jump_db([&](double gs) { return jackson_bistatic(c, gi, gs, deg_to_rad(phi_deg)); }, deg_to_rad(0.5),
                                          sss::half_pi_v<double>, deg_to_rad(0.05)) <= 0.5);
                }
            }
        }
}

TEST_CASE("bistatic evaluation rejects invalid inputs, naming the parameter") {
    const auto sand = sediment_preset<double>(sediment::medium_sand);
    auto name_of = [](auto&& f) -> std::string {
        try {
            f();
        } catch (const sss::invalid_parameter& e) {
            return e.parameter();
        }
        return "";
    };
    CHECK(name_of([&] { (void)jackson_bistatic(sand, 30e3, 1500.0, -0.1, 0.3, 1.0); }) == "graze_in_rad");
    CHECK(name_of([&] { (void)jackson_bistatic(sand, 30e3, 1500.0, 0.1, 2.0, 1.0); }) == "graze_out_rad");
    CHECK(name_of([&] { (void)jackson_bistatic(sand, 30e3, 1500.0, 0.1, 0.3, std::numeric_limits<double>::infinity()); }) == "phi_rad");
    CHECK(name_of([&] { (void)jackson_bistatic(sand, -3.0, 1500.0, 0.1, 0.3, 1.0); }) == "jackson.f_hz");
}

// When two adjacent rays share their energy as one tube and when the ray between them is traced
// (sampling/detail/tube_refinement.hpp): a ray meeting its facet at angle theta predicts its neighbours' time to grow
// at dt/de = t cot theta; a gap in time beyond that hides a shadow (or another surface) between them.

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <cstddef>

#include <sss/sampling/detail/tube_refinement.hpp>

namespace {

using sss::detail::judge_tube;
using sss::detail::tube_end;
using sss::detail::tube_verdict;

constexpr double dt_s = 6.5e-5;     // a sample (s)

// A seabed ray at two-way time t_s whose facet predicts `stretch` (s/rad), with echo per radian `gain`.
tube_end seabed_end(double t_s, double stretch, double gain = 1.0, double nz = 1.0) {
    const double nx = std::sqrt(1.0 - nz * nz);
    return {.valid = true, .t_s = t_s, .stretch = stretch, .gain = gain, .object = 0, .material = 0, .faceted = true,
            .normal = {nx, 0.0, nz}};
}

using v3 = std::array<double, 3>;

v3 unit(const v3& v) {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return {v[0] / l, v[1] / l, v[2] / l};
}

double dot3(const v3& a, const v3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// Two planes through point q with normals n_a and n_b (a crest or a trough along their common line), and straight
// rays from o in the vertical plane of azimuth psi at depression e.
struct crease {
    v3 o, q, n_a, n_b;
    double psi;
    [[nodiscard]] v3 dir(double e) const {
        return {std::cos(e) * std::cos(psi), std::cos(e) * std::sin(psi), -std::sin(e)};
    }
    // Where the ray at depression e meets the plane through q of normal n.
    [[nodiscard]] v3 hit(double e, const v3& n) const {
        const v3 d = dir(e);
        const double s = dot3(n, {q[0] - o[0], q[1] - o[1], q[2] - o[2]}) / dot3(n, d);
        return {o[0] + s * d[0], o[1] + s * d[1], o[2] + s * d[2]};
    }
};

} // namespace

TEST_CASE("a shadow between rays n launch intervals apart is found exactly when adjacent rays would find it") {
    // Rays one interval de apart on a surface of stretch s span p = s de each; a shadow of time length L between
    // them adds L to the gap. Adjacent rays call it an edge for L > 2 p; rays n intervals apart (a sparse column,
    // ray_density::along_split_sparse) are judged with the ratio 1 + 2 / n, so the same L decides.
    const double stretch = 0.06, de1 = 1e-3; // p = 6e-5 s: about a sample
    const double p = stretch * de1;
    for (const std::size_t n : {std::size_t{1}, std::size_t{2}, std::size_t{4}}) {
        CAPTURE(n);
        const double de = double(n) * de1;
        const tube_end a = seabed_end(0.05, stretch);
        for (const double shadow : {1.8, 1.95}) {
            CAPTURE(shadow);
            const tube_end b = seabed_end(0.05 + double(n) * p + shadow * p, stretch);
            CHECK(judge_tube(a, b, de, dt_s, n) == tube_verdict::continuous);
        }
        for (const double shadow : {2.05, 2.5, 10.0}) {
            CAPTURE(shadow);
            const tube_end b = seabed_end(0.05 + double(n) * p + shadow * p, stretch);
            CHECK(judge_tube(a, b, de, dt_s, n) == tube_verdict::split);
        }
    }
    // Judged as adjacent rays (the ratio 3), two intervals hide a shadow up to four intervals' span.
    const tube_end a = seabed_end(0.05, stretch), b = seabed_end(0.05 + 2 * p + 3.0 * p, stretch);
    CHECK(judge_tube(a, b, 2 * de1, dt_s) == tube_verdict::continuous);
    CHECK(judge_tube(a, b, 2 * de1, dt_s, 2) == tube_verdict::split);
}

TEST_CASE("a pair about normal incidence on one plane is one tube: time grows as the square of the step there") {
    // A level seabed 10 m down, rays delta_a and delta_b from the vertical: t = 2 H / (c cos delta), and the stretch
    // t tan delta vanishes at nadir. To first order the pair (0, 5 deg) predicted no gap at all against its 0.8
    // samples, and was taken for an edge (each ray keeping half the step as a point).
    const double H = 10.0, c = 1500.0, deg = 3.141592653589793 / 180.0;
    const auto at = [&](double delta) {
        const double t = 2.0 * H / (c * std::cos(delta));
        return seabed_end(t, sss::detail::time_stretch(t, std::cos(delta)));
    };
    for (const auto& [lo, hi] : {std::array<double, 2>{0.0, 5.0}, {0.1, 3.0}, {0.0, 3.5}, {1.0, 6.0}}) {
        CAPTURE(lo);
        CAPTURE(hi);
        const tube_end a = at(lo * deg), b = at(hi * deg);
        REQUIRE(std::abs(b.t_s - a.t_s) > 0.25 * dt_s); // beyond the quarter sample that is never an edge
        CHECK(judge_tube(a, b, (hi - lo) * deg, dt_s) == tube_verdict::continuous);
        CHECK(judge_tube(b, a, (hi - lo) * deg, dt_s) == tube_verdict::continuous);
        // A shadow of three samples between them is still one.
        tube_end beyond = b;
        beyond.t_s += 3.0 * dt_s;
        CHECK(judge_tube(a, beyond, (hi - lo) * deg, dt_s) == tube_verdict::split);
    }
}

TEST_CASE("across a facet's edge, a ray grazing its facet is refined by its own stretch, not only by the time gap") {
    // The two rays return within a tenth of a sample of each other, but one meets its facet at 2e-4 rad: its
    // stretch, t cot theta, spans hundreds of samples over the step, and its echo per radian is thousands of times
    // the other's. Its facet must end within a tiny part of the step: the tube is refined on (coarse).
    const double de = 3.4e-4;
    const tube_end grazing = seabed_end(0.0266, 130.0, 0.0289, 0.467);
    const tube_end steady = seabed_end(0.0266 + 0.1 * dt_s, 0.058, 3.6e-6, 0.67);
    CHECK(judge_tube(grazing, steady, de, dt_s) == tube_verdict::coarse);
    CHECK(judge_tube(steady, grazing, de, dt_s) == tube_verdict::coarse);
    // Echoes within a factor 2 of each other: the time gap alone decides, and a tenth of a sample is below the
    // eighth the facets' edges are refined to.
    const tube_end near = seabed_end(0.0266 + 0.1 * dt_s, 0.058, 0.0289 / 1.5, 0.67);
    CHECK(judge_tube(grazing, near, de, dt_s) == tube_verdict::continuous);
    // One facet (the same normal): nothing jumps between the rays, whatever their stretches.
    const tube_end same_facet = seabed_end(0.0266 + 0.1 * dt_s, 0.058, 3.6e-6, 0.467);
    CHECK(judge_tube(grazing, same_facet, de, dt_s) == tube_verdict::continuous);
}

TEST_CASE("a located edge's grazing end stays unresolved until its stretch over the step is a sixteenth of a sample") {
    // The edge is located by the end with the smaller stretch; the other end's echo lies where its facet is, and
    // that is known to a sixteenth of a sample only once its own stretch over the step spans no more.
    const double located = sss::detail::located_fraction * dt_s;
    const tube_end lit = seabed_end(0.03, 0.05), grazing = seabed_end(0.03 + 5 * dt_s, 40.0);
    const double de_located = 0.9 * located / 0.05; // the smaller stretch spans 0.9 of the tolerance
    CHECK(sss::detail::ends_unresolved(lit, grazing, de_located, dt_s));
    CHECK(sss::detail::ends_unresolved(grazing, lit, de_located, dt_s));
    const double de_fine = 0.9 * located / 40.0;
    CHECK_FALSE(sss::detail::ends_unresolved(lit, grazing, de_fine, dt_s));
    // An end that met nothing has no echo to place.
    tube_end none;
    CHECK_FALSE(sss::detail::ends_unresolved(none, grazing, de_located, dt_s));
}

TEST_CASE("the edge between two facets lies where the sheet of rays meets their common line, as the launch angle "
          "there divides the step") {
    // Straight rays in one vertical plane over a crease (crest or trough) whose line crosses that plane obliquely: the
    // ray through the line's point in the sheet has depression e*, and the fraction of the step from e_a to e_b up to
    // it is exact but that the ratio of the angles' sines stands for theirs (off by about the square of the step's
    // angle, below 1e-6 here). World coordinates up to 1000 m, as on a survey.
    for (const double world : {0.0, 1000.0}) {
        for (const double psi : {0.0, 0.7, 2.0}) {
            for (const double turn : {0.0, 0.4, -1.1}) { // the line's heading, turned from square across the sheet
                for (const double sa : {-0.3, 0.05, 0.2}) {
                    for (const double sb : {0.25, -0.1, -0.35}) {
                        if (std::abs(sa - sb) < 0.1) continue;
                        CAPTURE(world);
                        CAPTURE(psi);
                        CAPTURE(turn);
                        CAPTURE(sa);
                        CAPTURE(sb);
                        const v3 o{world, world, 10.0};
                        const v3 h{std::cos(psi), std::sin(psi), 0.0}, side{-std::sin(psi), std::cos(psi), 0.0};
                        const v3 q{o[0] + 25.0 * h[0], o[1] + 25.0 * h[1], 0.3}; // the crease 25 m out, 0.3 m up
                        const v3 along{std::cos(turn) * side[0] + std::sin(turn) * h[0],
                                       std::cos(turn) * side[1] + std::sin(turn) * h[1], 0.0};
                        const v3 across{along[1], -along[0], 0.0}; // horizontal, square to the line, away from o
                        // Plane A (the near side) rises at slope sa away from o across the line, B at sb.
                        const v3 n_a = unit({-sa * across[0], -sa * across[1], 1.0});
                        const v3 n_b = unit({-sb * across[0], -sb * across[1], 1.0});
                        const crease c{o, q, n_a, n_b, psi};
                        const double e_star = std::atan2(o[2] - q[2], 25.0);
                        for (const double step : {1e-4, 2e-3}) {
                            for (const double at : {0.1, 0.5, 0.93}) {
                                CAPTURE(step);
                                CAPTURE(at);
                                const double e_a = e_star + at * step, e_b = e_star - (1.0 - at) * step;
                                const auto x = sss::detail::facet_edge_crossing(o, c.hit(e_a, n_a), n_a,
                                                                                c.hit(e_b, n_b), n_b);
                                CHECK(std::abs(x.fraction - at) < 2e-6);
                                CHECK(std::abs(x.point[0] - q[0]) < 1e-6 * (1.0 + world));
                                CHECK(std::abs(x.point[1] - q[1]) < 1e-6 * (1.0 + world));
                                CHECK(std::abs(x.point[2] - q[2]) < 1e-6 * (1.0 + world));
                            }
                        }
                    }
                }
            }
        }
    }
}

TEST_CASE("no edge between two facets is found where their common line does not cross the sheet between the hits") {
    const v3 o{0.0, 0.0, 10.0};
    const v3 n_a = unit({-0.2, 0.0, 1.0}), n_b = unit({0.3, 0.0, 1.0});
    const crease c{o, {25.0, 0.0, 0.3}, n_a, n_b, 0.0};
    const double e_star = std::atan2(9.7, 25.0);
    const auto fraction = [&](const v3& p_a, const v3& m_a, const v3& p_b, const v3& m_b) {
        return sss::detail::facet_edge_crossing(o, p_a, m_a, p_b, m_b).fraction;
    };
    // Both rays short of the crease, or both beyond it.
    CHECK(fraction(c.hit(e_star + 2e-3, n_a), n_a, c.hit(e_star + 1e-3, n_b), n_b) == -1.0);
    CHECK(fraction(c.hit(e_star - 1e-3, n_a), n_a, c.hit(e_star - 2e-3, n_b), n_b) == -1.0);
    // One plane twice (no common line), and two hits in line with the origin (no sheet).
    CHECK(fraction(c.hit(e_star + 1e-3, n_a), n_a, c.hit(e_star - 1e-3, n_a), n_a) == -1.0);
    const v3 p = c.hit(e_star + 1e-3, n_a);
    const v3 farther{1.5 * p[0], 1.5 * p[1], o[2] + 1.5 * (p[2] - o[2])};
    CHECK(fraction(p, n_a, farther, n_b) == -1.0);
    // The planes' common line along the sheet's own heading: it never crosses the sheet.
    const v3 m_a = unit({0.0, -0.2, 1.0}), m_b = unit({0.0, 0.3, 1.0});
    const crease d{o, {25.0, 0.0, 0.3}, m_a, m_b, 0.0};
    CHECK(fraction(d.hit(e_star + 1e-3, m_a), m_a, d.hit(e_star - 1e-3, m_b), m_b) == -1.0);
}

TEST_CASE("the edge's place along the step is the same whichever ray of the pair comes first") {
    const v3 o{300.0, -200.0, 10.0};
    const v3 n_a = unit({-0.25, 0.1, 1.0}), n_b = unit({0.2, -0.05, 1.0});
    const double psi = 0.3;
    const crease c{o, {o[0] + 25.0 * std::cos(psi), o[1] + 25.0 * std::sin(psi), 0.3}, n_a, n_b, psi};
    const double e_star = std::atan2(9.7, 25.0);
    const v3 pa = c.hit(e_star + 4e-4, n_a), pb = c.hit(e_star - 6e-4, n_b);
    const auto ab = sss::detail::facet_edge_crossing(o, pa, n_a, pb, n_b);
    const auto ba = sss::detail::facet_edge_crossing(o, pb, n_b, pa, n_a);
    REQUIRE(ab.fraction > 0.0);
    CHECK(ab.fraction == doctest::Approx(0.4).epsilon(1e-5));
    CHECK(ba.fraction == doctest::Approx(1.0 - ab.fraction).epsilon(1e-6)); // the sines' ratio, to the angle squared
    for (int k = 0; k < 3; ++k) CHECK(ba.point[std::size_t(k)] == doctest::Approx(ab.point[std::size_t(k)]).epsilon(1e-12));
}

TEST_CASE("the seabed tells whether two facets meet where their planes cross, unless a third lies between them") {
    // A crest along y at x = 20 m: facet A (z = 0.3 + 0.2 (x - 20)) before it, B (z = 0.3 - 0.25 (x - 20)) beyond. Hits
    // 4 cm either side of the crest.
    const v3 x{20.0, 1.0, 0.3};
    const v3 n_a = unit({-0.2, 0.0, 1.0}), n_b = unit({0.25, 0.0, 1.0});
    const double angle = std::sqrt((n_a[0] - n_b[0]) * (n_a[0] - n_b[0]) + (n_a[2] - n_b[2]) * (n_a[2] - n_b[2]));
    const auto crest = [](double px, double) { return px < 20.0 ? 0.3 + 0.2 * (px - 20.0) : 0.3 - 0.25 * (px - 20.0); };
    const v3 pa{19.96, 1.0, crest(19.96, 0.0)}, pb{20.04, 1.0, crest(20.04, 0.0)};
    const double eps = 2.2e-16;
    CHECK(sss::detail::facet_reaches_crossing(x, pa, n_a, angle, eps, crest));
    CHECK(sss::detail::facet_reaches_crossing(x, pb, n_b, angle, eps, crest));
    // A third facet, level, from 19.985 m to the crest, and the hit on a facet of A's slope before it: that facet's
    // plane meets B's at x = (0.2 x 19.985 + 0.25 x 20) / 0.45, short of the crest, where the seabed is level.
    const auto stepped = [](double px, double) {
        return px < 19.985 ? 0.3 + 0.2 * (px - 19.985) : px < 20.0 ? 0.3 : 0.3 - 0.25 * (px - 20.0);
    };
    const v3 qa{19.96, 1.0, stepped(19.96, 0.0)};
    const double xc = (0.2 * 19.985 + 0.25 * 20.0) / 0.45;
    const v3 xs{xc, 1.0, 0.3 + 0.2 * (xc - 19.985)};
    CHECK_FALSE(sss::detail::facet_reaches_crossing(xs, qa, n_a, angle, eps, stepped));
    // Far from the grid's origin in float, hits 4 mm apart: the heights cannot tell, so it does not claim it.
    const double far = 5000.0;
    const auto far_crest = [&](double px, double py) { return crest(px - far, py); };
    const v3 fx{x[0] + far, 1.0, 0.3}, fa{far + 19.996, 1.0, crest(19.996, 0.0)};
    CHECK_FALSE(sss::detail::facet_reaches_crossing(fx, fa, n_a, angle, 1.19e-7, far_crest));
    CHECK(sss::detail::facet_reaches_crossing(fx, fa, n_a, angle, 2.2e-16, far_crest));
}

TEST_CASE("halving never locates a facet's edge as an edge of the line below a fivefold jump in stretch, ever more "
          "often above, and the bracket's test marks every one above sixfold") {
    // Two facets along one step: times grow at stretch s_a up to the edge and s_b = R s_a beyond, the echo per radian
    // in proportion. Halving the step as the simulator does (judge_tube at every level) locates the edge as one, which
    // the along-track check then compares between columns, only where some sub-pair's time gap exceeds a quarter of a
    // sample and three times the smaller end's prediction: that depends on where in the step the edge falls. The
    // bracket leaves no such gap and records it by facet_edge_marks_line instead.
    const double t0 = 0.05, s_a = 2e4 * dt_s;
    const auto located_share = [&](double ratio, double span_samples) {
        const double s_b = ratio * s_a, de = span_samples * dt_s / s_a;
        std::size_t located = 0, places = 0;
        for (int i = 1; i < 200; ++i, ++places) {
            const double x = de * double(i) / 200.0;
            const auto end = [&](double e) {
                return e < x ? seabed_end(t0 + s_a * e, s_a, 1.0, 1.0)
                             : seabed_end(t0 + s_a * x + s_b * (e - x), s_b, ratio, 0.95);
            };
            // Depth first, as the simulator refines; true once a sub-pair is a located edge.
            const auto halve = [&](const auto& self, double e0, double e1, int depth) -> bool {
                const tube_verdict v = judge_tube(end(e0), end(e1), e1 - e0, dt_s);
                if (v == tube_verdict::located) return true;
                if (v == tube_verdict::continuous || depth > 30) return false;
                const double m = 0.5 * (e0 + e1);
                return self(self, e0, m, depth + 1) || self(self, m, e1, depth + 1);
            };
            located += halve(halve, 0.0, de, 0) ? 1 : 0;
        }
        return double(located) / double(places);
    };
    const auto marks = [&](double ratio) {
        return sss::detail::facet_edge_marks_line(seabed_end(t0, s_a, 1.0, 1.0), seabed_end(t0, ratio * s_a, ratio, 0.95));
    };
    double previous = 0.0;
    for (const double ratio : {1.5, 3.0, 5.0, 6.0, 6.5, 7.0, 10.0, 20.0, 50.0}) {
        CAPTURE(ratio);
        for (const double span : {1.5, 6.0}) {
            CAPTURE(span);
            const double share = located_share(ratio, span);
            if (ratio <= 5.0) CHECK(share == 0.0);
            else CHECK(share > previous);
            if (span == 6.0) previous = share;
        }
        CHECK(marks(ratio) == (ratio > 6.0));
    }
    CHECK(previous > 0.8); // at fiftyfold
    // One facet, or an end that met nothing: never.
    CHECK_FALSE(sss::detail::facet_edge_marks_line(seabed_end(t0, s_a), seabed_end(t0, 10 * s_a)));
    CHECK_FALSE(sss::detail::facet_edge_marks_line(tube_end{}, seabed_end(t0, 10 * s_a, 10.0, 0.95)));
}

TEST_CASE("a lit ray beside one that returned after the line's end is refined until the edge is located, as any edge") {
    // The far edge of coverage: the part of the step within the line holds echo, wherever the lit ray's facet says the
    // step would reach (its stretch is for straight rays, several times short in refracting water).
    const tube_end lit = seabed_end(0.1349, 0.06), beyond{};
    const double located = sss::detail::located_fraction * dt_s;
    for (const double de : {1e-2, 1e-3, 1e-4}) {
        CAPTURE(de);
        CHECK(judge_tube(lit, beyond, de, dt_s) == tube_verdict::split);
        CHECK(judge_tube(beyond, lit, de, dt_s) == tube_verdict::split);
    }
    const double de_located = 0.9 * located / 0.06;
    CHECK(judge_tube(lit, beyond, de_located, dt_s) == tube_verdict::located);
    CHECK(judge_tube(beyond, lit, de_located, dt_s) == tube_verdict::located);
    CHECK(judge_tube(beyond, beyond, 1e-3, dt_s) == tube_verdict::continuous); // nothing on either side
}

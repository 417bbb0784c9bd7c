// When two adjacent rays share their energy as one tube and when the ray between them is traced
// (sampling/detail/tube_refinement.hpp): a ray meeting its facet at angle theta predicts its neighbours' time to grow
// at dt/de = t cot theta; a gap in time beyond that hides a shadow (or another surface) between them.

#include <doctest/doctest.h>

#include <cmath>
#include <cstddef>

#include <sss/sampling/detail/tube_refinement.hpp>

namespace {

using sss::detail::judge_tube;
using sss::detail::tube_end;
using sss::detail::tube_verdict;

constexpr double dt_s = 6.5e-5;     // a sample (s)
constexpr double t_line_s = 0.133;  // the line's end (s)

// A seabed ray at two-way time t_s whose facet predicts `stretch` (s/rad), with echo per radian `gain`.
tube_end seabed_end(double t_s, double stretch, double gain = 1.0, double nz = 1.0) {
    const double nx = std::sqrt(1.0 - nz * nz);
    return {.valid = true, .t_s = t_s, .stretch = stretch, .gain = gain, .object = 0, .material = 0, .faceted = true,
            .normal = {nx, 0.0, nz}};
}

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
            CHECK(judge_tube(a, b, de, dt_s, t_line_s, n) == tube_verdict::continuous);
        }
        for (const double shadow : {2.05, 2.5, 10.0}) {
            CAPTURE(shadow);
            const tube_end b = seabed_end(0.05 + double(n) * p + shadow * p, stretch);
            CHECK(judge_tube(a, b, de, dt_s, t_line_s, n) == tube_verdict::split);
        }
    }
    // Judged as adjacent rays (the ratio 3), two intervals hide a shadow up to four intervals' span.
    const tube_end a = seabed_end(0.05, stretch), b = seabed_end(0.05 + 2 * p + 3.0 * p, stretch);
    CHECK(judge_tube(a, b, 2 * de1, dt_s, t_line_s) == tube_verdict::continuous);
    CHECK(judge_tube(a, b, 2 * de1, dt_s, t_line_s, 2) == tube_verdict::split);
}

TEST_CASE("across a facet's edge, a ray grazing its facet is refined by its own stretch, not only by the time gap") {
    // The two rays return within a tenth of a sample of each other, but one meets its facet at 2e-4 rad: its
    // stretch, t cot theta, spans hundreds of samples over the step, and its echo per radian is thousands of times
    // the other's. Its facet must end within a tiny part of the step: the tube is refined on (coarse).
    const double de = 3.4e-4;
    const tube_end grazing = seabed_end(0.0266, 130.0, 0.0289, 0.467);
    const tube_end steady = seabed_end(0.0266 + 0.1 * dt_s, 0.058, 3.6e-6, 0.67);
    CHECK(judge_tube(grazing, steady, de, dt_s, t_line_s) == tube_verdict::coarse);
    CHECK(judge_tube(steady, grazing, de, dt_s, t_line_s) == tube_verdict::coarse);
    // Echoes within a factor 2 of each other: the time gap alone decides, and a tenth of a sample is below the
    // eighth the facets' edges are refined to.
    const tube_end near = seabed_end(0.0266 + 0.1 * dt_s, 0.058, 0.0289 / 1.5, 0.67);
    CHECK(judge_tube(grazing, near, de, dt_s, t_line_s) == tube_verdict::continuous);
    // One facet (the same normal): nothing jumps between the rays, whatever their stretches.
    const tube_end same_facet = seabed_end(0.0266 + 0.1 * dt_s, 0.058, 3.6e-6, 0.467);
    CHECK(judge_tube(grazing, same_facet, de, dt_s, t_line_s) == tube_verdict::continuous);
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

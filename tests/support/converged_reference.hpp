#pragma once
// A converged reference for any scene: the same simulator, in double precision, at a much higher ray density
// across and along track, doubled until the next doubling changes the line by less than a tolerance; and the
// error statistics a rendered line is judged by against it.
//
// Convergence check: the reference is rendered at density d, then at 2d (twice the along-track columns and
// twice the rays per time sample, four times the rays); when the RMS difference between the two lines over the
// samples within `window_db` of the finer line's peak is below `tolerance_db` (0.05 dB), the finer line is the
// reference. Otherwise the density doubles again, up to `max_doublings`; `converged` says whether it held.
// Over a shadow the two lines are both (near) zero and do not enter the RMS; `shadow_mismatch` counts samples that
// one line shows as a shadow and the other does not, and must be zero too.
// Only the ray density doubles: what the propagation approximates on its own (layered water's chords) stays as
// the simulator under test has it, so the reference shares that error (docs/design/layered.md measures it).

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <sss/simulator.hpp>

namespace sss_test {

/// Error of a rendered line against a reference, in decibels, over the samples within `window_db` of the
/// reference's peak; and the shadow check.
struct line_error {
    double rms_db = 0.0;          // RMS of 10 log10(got / reference)
    double median_db = 0.0;       // median of |10 log10(got / reference)|
    double p99_db = 0.0;          // 99th percentile of |10 log10(got / reference)|
    std::size_t compared = 0;     // samples within the window
    std::size_t shadow_samples = 0; // samples the reference shows >= shadow_db below their lit surroundings
    std::size_t shadow_misses = 0;  // of those, samples the line does not show >= shadow_db below the same surroundings
};

/// Lit surroundings of sample k: the median of the reference over +-`radius` samples, leaving out samples below
/// 1e-6 of the line's peak (shadows and the water column before the first return).
inline std::vector<double> lit_surroundings(const std::vector<double>& ref, std::size_t radius) {
    double peak = 0.0;
    for (double v : ref) peak = std::max(peak, v);
    std::vector<double> out(ref.size(), 0.0), lit;
    for (std::size_t k = 0; k < ref.size(); ++k) {
        const std::size_t lo = k >= radius ? k - radius : 0, hi = std::min(ref.size(), k + radius + 1);
        lit.clear();
        for (std::size_t j = lo; j < hi; ++j)
            if (ref[j] > 1e-6 * peak) lit.push_back(ref[j]);
        if (lit.empty()) continue;
        std::nth_element(lit.begin(), lit.begin() + std::ptrdiff_t(lit.size() / 2), lit.end());
        out[k] = lit[lit.size() / 2];
    }
    return out;
}

/// Compares `got` with `ref`. A difference where one line is zero and the other is not counts as 100 dB.
/// Shadow samples: reference value `shadow_db` or more below the lit surroundings (+-`radius` samples), and not next
/// to a sample that is not a shadow (an edge is judged by its position, to within one sample, not here).
template <class V>
line_error compare_lines(const V& got, const std::vector<double>& ref, double window_db = 40.0,
                         double shadow_db = 40.0, std::size_t radius = 100) {
    line_error e;
    const std::size_t n = std::min(ref.size(), std::size_t(got.size()));
    double peak = 0.0;
    for (std::size_t k = 0; k < n; ++k) peak = std::max(peak, ref[k]);
    if (!(peak > 0.0)) return e;
    const double floor = peak * std::pow(10.0, -window_db / 10.0);
    std::vector<double> diffs;
    double sum2 = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
        if (!(ref[k] >= floor)) continue;
        const double g = double(got[k]);
        double d = g > 0.0 ? 10.0 * std::log10(g / ref[k]) : -100.0;
        d = std::clamp(d, -100.0, 100.0);
        sum2 += d * d;
        diffs.push_back(std::abs(d));
    }
    e.compared = diffs.size();
    if (!diffs.empty()) {
        e.rms_db = std::sqrt(sum2 / double(diffs.size()));
        std::sort(diffs.begin(), diffs.end());
        e.median_db = diffs[diffs.size() / 2];
        e.p99_db = diffs[std::min(diffs.size() - 1, static_cast<std::size_t>(std::ceil(0.99 * double(diffs.size()))) - 1)];
    }
    const std::vector<double> lit = lit_surroundings(ref, radius);
    const double below = std::pow(10.0, -shadow_db / 10.0);
    std::vector<char> shadow(n, 0);
    for (std::size_t k = 0; k < n; ++k) shadow[k] = lit[k] > 0.0 && ref[k] <= below * lit[k];
    for (std::size_t k = 1; k + 1 < n; ++k) {
        if (!shadow[k] || !shadow[k - 1] || !shadow[k + 1]) continue;
        ++e.shadow_samples;
        if (!(double(got[k]) <= below * lit[k])) ++e.shadow_misses;
    }
    return e;
}

/// One line of a ping in double.
template <class V> std::vector<double> to_double(const V& line) { return std::vector<double>(line.begin(), line.end()); }

/// A reference line and how it was reached.
struct reference_line {
    std::vector<double> values;         // mean power per sample
    sss::ray_density density{};         // the density it was rendered at
    double last_change_db = 0.0;        // RMS change from the previous doubling (within 40 dB of the peak)
    bool converged = false;             // last_change_db < tolerance
    std::size_t doublings = 0;
};

struct reference_params {
    sss::ray_density start{.along = 32, .across = 0, .per_sample = 8.0}; // first density tried
    double tolerance_db = 0.05;         // convergence: the next doubling changes the line by less (RMS)
    std::size_t max_doublings = 2;      // at most this many doublings (>= 1)
};

/// The converged reference of one side of one ping. `make(density)` returns the simulator at a given density
/// (double precision for a reference of record; float to measure a float simulator's sampling error alone);
/// `pose` is the towfish's pose, in the simulator's scalar type.
template <class Make, class Scene, class P>
reference_line converged_line(Make&& make, const Scene& scene, const sss::pose<P>& pose, sss::side sd,
                              const reference_params& rp = {}) {
    auto render = [&](const sss::ray_density& d) {
        const auto sim = make(d);
        const auto lines = sim.ping_at(scene, pose);
        return to_double(sd == sss::side::port ? lines.port : lines.starboard);
    };
    reference_line r;
    r.density = rp.start;
    std::vector<double> coarse = render(r.density);
    for (std::size_t i = 0; i < rp.max_doublings; ++i) {
        sss::ray_density finer = r.density;
        finer.along *= 2;
        finer.per_sample *= 2.0;
        std::vector<double> fine = render(finer);
        const line_error change = compare_lines(coarse, fine);
        r.values = std::move(fine);
        r.density = finer;
        r.doublings = i + 1;
        r.last_change_db = change.rms_db;
        r.converged = change.rms_db < rp.tolerance_db && change.shadow_misses == 0;
        if (r.converged) break;
        coarse = r.values;
    }
    return r;
}

} // namespace sss_test

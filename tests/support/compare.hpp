#pragma once
// Comparison of a rendered line with an expected one, in decibels, over the samples that matter.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace sss_test {

struct db_error {
    double rms_db = 0.0;       // RMS of 10 log10(got/expected) over the compared samples
    double worst_db = 0.0;     // the largest |difference| among them (signed)
    std::size_t worst_index = 0;
    std::size_t compared = 0;  // samples within the window below the expected line's peak
};

// Compares samples whose expected value lies within `window_db` of the expected line's peak.
template <class T>
db_error compare_db(const std::vector<T>& got, const std::vector<double>& expected, double window_db = 40.0) {
    db_error e;
    double peak = 0.0;
    for (double v : expected) peak = std::max(peak, v);
    if (!(peak > 0.0)) return e;
    const double floor = peak * std::pow(10.0, -window_db / 10.0);
    double sum2 = 0.0;
    for (std::size_t k = 0; k < expected.size() && k < got.size(); ++k) {
        if (expected[k] < floor) continue;
        const double d = 10.0 * std::log10(double(got[k]) / expected[k]);
        const double dd = std::isfinite(d) ? d : 1e9;
        sum2 += dd * dd;
        ++e.compared;
        if (std::abs(dd) > std::abs(e.worst_db)) { e.worst_db = dd; e.worst_index = k; }
    }
    if (e.compared) e.rms_db = std::sqrt(sum2 / double(e.compared));
    return e;
}

} // namespace sss_test

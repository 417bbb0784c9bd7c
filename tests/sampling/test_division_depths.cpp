// The along-track check's division shared among a side's columns by the beam's weight (division_depths.hpp):
// the depths that leave the least error sum_j w_j 3^-d_j for the cost sum_j 3^d_j of dividing every column alike,
// with no column more than a level below the heaviest per whole factor 9 of weight below it.

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <random>
#include <vector>

#include <sss/sampling/division_depths.hpp>

namespace {

std::vector<std::size_t> depths_for(const std::vector<double>& w, std::size_t levels) {
    std::vector<std::size_t> d(w.size(), 99);
    sss::division_depths(w, levels, d);
    return d;
}

double cost(const std::vector<std::size_t>& d) {
    double c = 0.0;
    for (const std::size_t x : d) c += std::pow(3.0, double(x));
    return c;
}

// The two-way along-track weight of a uniform line array at n columns spread over its -30 dB extent: sinc^4.
std::vector<double> sinc4_columns(std::size_t n) {
    std::vector<double> w(n);
    const double x_max = 2.6; // sinc(2.6)^4 is about -30 dB
    for (std::size_t j = 0; j < n; ++j) {
        const double x = -x_max + 2.0 * x_max * (double(j) + 0.5) / double(n);
        w[j] = std::pow(std::sin(x) / x, 4);
    }
    return w;
}

} // namespace

TEST_CASE("columns the beam weights alike are all divided as deep as along_split asks, whatever the scale") {
    for (const std::size_t levels : {std::size_t{1}, std::size_t{2}, std::size_t{3}, std::size_t{5}})
        for (const double scale : {1e-30, 1.0, 7.5, 1e30}) {
            const auto d = depths_for(std::vector<double>(10, scale), levels);
            for (const std::size_t x : d) CHECK(x == levels);
        }
}

TEST_CASE("a column nine times heavier than another is divided one level deeper") {
    // Two columns: 3^d proportional to sqrt(w), so weights 1 and 9 give depths one apart around the even depth.
    const auto d = depths_for({1.0, 9.0}, 2);
    CHECK(d[0] == 1);
    CHECK(d[1] == 2);
    // Over a wider spread, away from the bounds, each factor 81 is two levels.
    const auto e = depths_for({1.0, 81.0, 6561.0, 81.0, 1.0}, 4);
    CHECK(e[1] == e[0] + 2);
    CHECK(e[2] == e[1] + 2);
    CHECK(e[3] == e[1]);
    CHECK(e[4] == e[0]);
}

TEST_CASE("under a line array's pattern the axis columns go a level deeper and the edges shallower, no more than a "
          "level below the heaviest column per factor 9 of weight below it") {
    const auto w = sinc4_columns(10);
    const auto d = depths_for(w, 2);
    // Relative weights 1, 0.66, 0.32, 0.084, 0.0093 from the axis out: the three pairs within a factor 9 of the axis
    // go with it, the next a level shallower, the edges two.
    const std::vector<std::size_t> expected{1, 2, 3, 3, 3, 3, 3, 3, 2, 1};
    CHECK(d == expected);
    // Without the floor (the budget alone) the nearest level would leave the 0.66 and 0.32 pairs at ninths, within
    // sqrt(3) of the even cost; the floor raises them, and the cost is at most every column at the heaviest's depth.
    const double even = 10.0 * 9.0;
    CHECK(cost(d) <= 3.0 * even);
    // The error sum w 3^-d falls further than the cost rises, as against even division.
    double err_even = 0.0, err_shared = 0.0;
    for (std::size_t j = 0; j < w.size(); ++j) {
        err_even += w[j] * std::pow(3.0, -2.0);
        err_shared += w[j] * std::pow(3.0, -double(d[j]));
    }
    MESSAGE("cost " << cost(d) / even << " of even division's; error " << err_shared / err_even << " of its");
    CHECK(err_shared * cost(d) < 0.85 * err_even * even);
}

TEST_CASE("no column is divided less than the heaviest until its weight is a factor 9 below it") {
    // The survey's 100 kHz array at ten columns (bench/bench_survey.cpp): the budget alone rounds the pair beside the
    // axis, at a fifth of its weight, to one level below it.
    const std::vector<double> survey{0.003, 0.0002, 0.002, 0.212, 1.0, 1.0, 0.212, 0.002, 0.0002, 0.003};
    const auto d = depths_for(survey, 2);
    CHECK(d == std::vector<std::size_t>{1, 1, 1, 3, 3, 3, 3, 1, 1, 1});
    // Just inside a factor 9 the floor holds a column at the heaviest's depth, where the budget alone would not.
    const auto e = depths_for({1.0, 1.0 / 8.9, 1.0 / 9.1, 1.0 / 81.0}, 3);
    CHECK(e[1] == e[0]);
    CHECK(e[2] == e[0] - 1);
    CHECK(e[3] == e[0] - 2);
    // A power of 9 counts as whole factors even where its logarithm rounds below it (log 9^5 / log 9 comes out as
    // 4.999...): the column five factors down stays five levels down, not four.
    const auto f = depths_for({59049.0, 59049.0, 1.0}, 8);
    CHECK(f[0] == 8);
    CHECK(f[2] == 3);
}

TEST_CASE("depths grow with weight, stay between thirds and one level past along_split, and keep the heaviest's floor") {
    std::mt19937_64 rng(20261126);
    std::uniform_real_distribution<double> log_w(-12.0, 0.0);
    std::uniform_int_distribution<std::size_t> count(1, 40), lv(1, 8);
    for (int trial = 0; trial < 2000; ++trial) {
        std::vector<double> w(count(rng));
        for (double& x : w) x = std::exp(log_w(rng));
        const std::size_t levels = lv(rng);
        const auto d = depths_for(w, levels);
        const std::size_t top = std::size_t(std::max_element(w.begin(), w.end()) - w.begin());
        for (std::size_t i = 0; i < w.size(); ++i) {
            CHECK(d[i] >= 1);
            CHECK(d[i] <= levels + 1);
            CHECK(d[i] <= d[top]);
            const double below = std::floor(std::log(w[top] / w[i]) / std::log(9.0) + 1e-9);
            CHECK(double(d[i]) >= double(d[top]) - below);
            for (std::size_t j = 0; j < w.size(); ++j)
                if (w[i] >= w[j]) CHECK(d[i] >= d[j]);
        }
    }
}

TEST_CASE("no division asked for, or no weight anywhere, leaves every column at along_split's depth") {
    for (const std::size_t x : depths_for(sinc4_columns(8), 0)) CHECK(x == 0);
    for (const std::size_t x : depths_for(std::vector<double>(6, 0.0), 2)) CHECK(x == 2);
    // A column the beam does not reach is still divided into thirds where it disagrees.
    const auto d = depths_for({0.0, 1.0, 1.0, 0.0}, 3);
    CHECK(d[0] == 1);
    CHECK(d[3] == 1);
    CHECK(d[1] == 4);
    // Weights that are not finite positive numbers count as zero; any depth along_split can ask for is exact.
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    const auto odd = depths_for({nan, 1.0, inf, -1.0, 1.0}, 2);
    CHECK(odd == std::vector<std::size_t>{1, 3, 1, 1, 3});
    const std::size_t huge = std::numeric_limits<std::size_t>::max(), big = (std::size_t(1) << 53) + 1;
    for (const std::size_t x : depths_for(std::vector<double>(5, 2.0), huge)) CHECK(x == huge);
    for (const std::size_t x : depths_for(std::vector<double>(5, 2.0), big)) CHECK(x == big);
    CHECK(depths_for({1.0, 1e-200}, huge)[0] == huge);
    CHECK(depths_for({1.0, 1e-200}, huge)[1] == huge - 64);
}

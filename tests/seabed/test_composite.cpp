// Composite seabeds: region partitions with fractal boundaries, per-region textures, blending.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <set>
#include <vector>

#include "sss/core/error.hpp"
#include "sss/seabed/composite.hpp"

namespace {

using namespace sss::seabed;

double fit_slope(const std::vector<double>& x, const std::vector<double>& y) {
    const double n = static_cast<double>(x.size());
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (std::size_t i = 0; i < x.size(); ++i) {
        sx += x[i];
        sy += y[i];
        sxx += x[i] * x[i];
        sxy += x[i] * y[i];
    }
    return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

/// Box-counting dimension of the boundary samples (those with a right or upper neighbour in another
/// region), from boxes of 1 to 8 cells. A straight or smooth boundary reads 1.
double boundary_box_dimension(const region_raster<double>& r) {
    std::vector<char> b(r.size(), 0);
    for (std::size_t j = 0; j < r.ny; ++j)
        for (std::size_t i = 0; i < r.nx; ++i) {
            const auto v = r(i, j);
            if ((i + 1 < r.nx && r(i + 1, j) != v) || (j + 1 < r.ny && r(i, j + 1) != v)) b[j * r.nx + i] = 1;
        }
    std::vector<double> x, y;
    for (std::size_t s = 1; s <= 8; s *= 2) {
        double count = 0;
        for (std::size_t by = 0; by < r.ny; by += s)
            for (std::size_t bx = 0; bx < r.nx; bx += s) {
                bool any = false;
                for (std::size_t j = by; j < std::min(r.ny, by + s) && !any; ++j)
                    for (std::size_t i = bx; i < std::min(r.nx, bx + s) && !any; ++i) any = b[j * r.nx + i] != 0;
                count += any ? 1 : 0;
            }
        x.push_back(-std::log(static_cast<double>(s)));
        y.push_back(std::log(count));
    }
    return fit_slope(x, y);
}

/// RMS of first differences (x and y neighbours) over neighbour pairs that both have region `id`.
double difference_rms(const composite_seabed<double>& c, std::uint32_t id) {
    double s = 0, n = 0;
    const auto& h = c.height;
    for (std::size_t j = 0; j + 1 < h.ny; ++j)
        for (std::size_t i = 0; i + 1 < h.nx; ++i) {
            if (c.regions(i, j) != id) continue;
            if (c.regions(i + 1, j) == id) s += std::pow(h(i + 1, j) - h(i, j), 2), n += 1;
            if (c.regions(i, j + 1) == id) s += std::pow(h(i, j + 1) - h(i, j), 2), n += 1;
        }
    return std::sqrt(s / n);
}

/// RMS of the heights of region `id` about their mean.
double height_rms(const composite_seabed<double>& c, std::uint32_t id) {
    double s = 0, s2 = 0, n = 0;
    for (std::size_t i = 0; i < c.height.size(); ++i)
        if (c.regions.values[i] == id) {
            s += c.height.values[i];
            s2 += c.height.values[i] * c.height.values[i];
            n += 1;
        }
    return std::sqrt(s2 / n - (s / n) * (s / n));
}

region_texture<double> rough(std::uint32_t id, double w2_cm4, double mean_height_m = 0.0) {
    region_texture<double> t;
    t.id = id;
    t.mean_height_m = mean_height_m;
    t.roughness.spectrum = jackson_spectrum(w2_cm4, 3.25);
    return t;
}

} // namespace

TEST_CASE("level partition: every texture present with its requested area fraction") {
    level_partition<double> p;
    p.fractions = {0.5, 0.3, 0.2};
    p.patch_scale_m = 5.0;
    const auto r = partition<double>(256, 256, 0.05, p, 1);
    std::vector<double> count(3, 0);
    std::size_t out_of_range = 0;
    for (auto v : r.values) {
        if (v < 3)
            count[v] += 1;
        else
            ++out_of_range;
    }
    CHECK(out_of_range == 0);
    for (std::size_t k = 0; k < 3; ++k)
        CHECK(count[k] / static_cast<double>(r.size()) == doctest::Approx(p.fractions[k]).epsilon(1e-3).scale(0));
}

TEST_CASE("level-partition boundaries are fractal: box dimension near 2 - H, not 1") {
    // gamma = 3.5: H = 0.75, level sets of dimension 1.25 below the patch scale.
    level_partition<double> p;
    p.fractions = {1, 1, 1};
    p.patch_scale_m = 5.0;
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        CAPTURE(seed);
        const double d = boundary_box_dimension(partition<double>(512, 512, 0.05, p, seed));
        CHECK(d == doctest::Approx(1.25).epsilon(0.08).scale(0));
    }
    // The estimator reads 1 for straight boundaries: an unwarped Voronoi partition.
    voronoi_partition<double> v;
    v.sites = {{6, 6, 0}, {19, 7, 1}, {5, 19, 2}, {20, 18, 0}};
    CHECK(boundary_box_dimension(partition<double>(512, 512, 0.05, v, 1)) ==
          doctest::Approx(1.0).epsilon(0.03).scale(0));
}

TEST_CASE("warped Voronoi boundary departs from its straight bisector by about the warp RMS") {
    // Two sites: the unwarped boundary is the line x = 12.8 m. Each row's boundary position is read from
    // its count of region-0 samples; its RMS deviation from the fitted line is the normal component of
    // the warp field along the boundary: RMS warp_m while warp_m << warp_scale_m (4 seeds of a 2 m outer
    // scale on a 25.6 m line; larger warps fold the map and the displacement falls short of warp_m).
    voronoi_partition<double> v;
    v.sites = {{6.4, 12.8, 0}, {19.2, 12.8, 1}};
    v.warp_m = 0.1;
    v.warp_scale_m = 2.0;
    auto deviation = [&](std::uint64_t seed) {
        const auto r = partition<double>(512, 512, 0.05, v, seed);
        std::vector<double> y, x;
        for (std::size_t j = 0; j < r.ny; ++j) {
            double zeros = 0;
            for (std::size_t i = 0; i < r.nx; ++i) zeros += r(i, j) == 0 ? 1 : 0;
            y.push_back(r.y_m(j));
            x.push_back(zeros * r.cell_m);
        }
        const double b = fit_slope(y, x);
        double mx = 0, my = 0;
        for (std::size_t j = 0; j < y.size(); ++j) mx += x[j], my += y[j];
        mx /= static_cast<double>(y.size());
        my /= static_cast<double>(y.size());
        double ss = 0;
        for (std::size_t j = 0; j < y.size(); ++j) ss += std::pow(x[j] - mx - b * (y[j] - my), 2);
        return ss / static_cast<double>(y.size());
    };
    double ms = 0;
    for (std::uint64_t seed = 1; seed <= 4; ++seed) ms += deviation(seed) / 4;
    CHECK(std::sqrt(ms) == doctest::Approx(0.1).epsilon(0.2).scale(0)); // 0.90 to 1.04 times warp_m over 15 seed sets
    v.warp_m = 0.0;
    CHECK(std::sqrt(deviation(1)) < 0.05); // straight to within a cell
}

TEST_CASE("composite seabed: each region carries its id and its own texture's roughness") {
    level_partition<double> p;
    p.fractions = {1, 1, 1};
    p.patch_scale_m = 6.0;
    const auto idx = partition<double>(256, 256, 0.05, p, 11);
    std::vector<region_texture<double>> textures{rough(10, 0.000518), rough(20, 0.016), region_texture<double>{}};
    textures[2].id = 30;
    ripple_params<double> rp;
    rp.wavelength_m = 0.5;
    rp.height_m = 0.04;
    rp.crest_heading_deg = 90.0 - sss::rad_to_deg(0.4);
    textures[2].ripples.push_back(rp);
    const auto c = compose(idx, textures, 0.0, 5);
    std::set<std::uint32_t> ids(c.regions.values.begin(), c.regions.values.end());
    CHECK(ids == std::set<std::uint32_t>{10, 20, 30});
    std::size_t mismatched = 0;
    for (std::size_t i = 0; i < idx.size(); ++i)
        mismatched += c.regions.values[i] == textures[idx.values[i]].id ? 0 : 1;
    CHECK(mismatched == 0);
    // Same gamma: the RMS of first differences scales as sqrt(w2); cobble vs clay: sqrt(0.016 / 0.000518) = 5.56.
    CHECK(difference_rms(c, 20) / difference_rms(c, 10) ==
          doctest::Approx(std::sqrt(0.016 / 0.000518)).epsilon(0.08).scale(0));
    // The rippled region: RMS H / (2 sqrt 2) = 14.1 mm.
    CHECK(height_rms(c, 30) == doctest::Approx(0.04 / (2 * std::sqrt(2.0))).epsilon(0.03).scale(0));
}

TEST_CASE("blending smooths heights across boundaries without moving them") {
    level_partition<double> p;
    p.fractions = {1, 1};
    p.patch_scale_m = 6.0;
    const auto idx = partition<double>(200, 200, 0.05, p, 3);
    region_texture<double> low, high;
    low.id = 1;
    high.id = 2;
    high.mean_height_m = 1.0;
    const std::vector<region_texture<double>> textures{low, high};
    const auto sharp = compose(idx, textures, 0.0, 1);
    const auto soft = compose(idx, textures, 0.25, 1); // sigma = 5 cells
    CHECK(sharp.regions.values == soft.regions.values);
    double max_step_sharp = 0, max_step_soft = 0;
    for (std::size_t j = 0; j < 200; ++j)
        for (std::size_t i = 0; i + 1 < 200; ++i) {
            max_step_sharp = std::max(max_step_sharp, std::abs(sharp.height(i + 1, j) - sharp.height(i, j)));
            max_step_soft = std::max(max_step_soft, std::abs(soft.height(i + 1, j) - soft.height(i, j)));
        }
    CHECK(max_step_sharp == 1.0);
    // A straight edge blurred by sigma = 5 cells has a largest step of 1 / (5 sqrt(2 pi)) = 0.08;
    // curved boundaries steepen it somewhat.
    CHECK(max_step_soft < 0.15);
    // Far (> 4 sigma, the kernel's reach) from any boundary the blended heights equal the sharp ones.
    std::size_t far = 0;
    double far_diff = 0;
    for (std::size_t j = 20; j < 180; ++j)
        for (std::size_t i = 20; i < 180; ++i) {
            bool near = false;
            for (std::size_t jj = j - 20; jj <= j + 20 && !near; ++jj)
                for (std::size_t ii = i - 20; ii <= i + 20 && !near; ++ii) near = idx(ii, jj) != idx(i, j);
            if (near) continue;
            ++far;
            far_diff = std::max(far_diff, std::abs(soft.height(i, j) - sharp.height(i, j)));
        }
    CHECK(far > 0);
    CHECK(far_diff < 1e-6);
}

TEST_CASE("Voronoi partition: sites map to their textures; composites are reproducible from the seed") {
    voronoi_partition<double> v;
    v.sites = {{2, 2, 0}, {8, 3, 1}, {5, 8, 2}, {9, 9, 1}};
    v.warp_m = 0.3;
    v.warp_scale_m = 3.0;
    const auto idx = partition<double>(200, 200, 0.05, v, 4);
    for (const auto& s : v.sites) {
        CAPTURE(s.x_m);
        CHECK(idx(static_cast<std::size_t>(s.x_m / 0.05), static_cast<std::size_t>(s.y_m / 0.05)) == s.texture);
    }
    std::vector<region_texture<double>> textures{rough(1, 0.001), rough(2, 0.004), rough(3, 0.01)};
    const auto a = compose(idx, textures, 0.1, 8);
    const auto b = compose(partition<double>(200, 200, 0.05, v, 4), textures, 0.1, 8);
    const auto c = compose(idx, textures, 0.1, 9);
    CHECK(a.height.values == b.height.values);
    CHECK(a.regions.values == b.regions.values);
    CHECK(a.height.values != c.height.values);
    const auto d = partition<double>(200, 200, 0.05, v, 5);
    CHECK(d.values != idx.values); // another warp
}

TEST_CASE("composite parameters are validated, naming the field") {
    auto expect = [](auto&& f, const char* name) {
        try {
            f();
            FAIL("no exception for " << name);
        } catch (const sss::invalid_parameter& e) {
            CHECK(e.parameter() == name);
        }
    };
    level_partition<double> p;
    expect([&] { (void)partition<double>(8, 8, 0.1, p, 1); }, "partition.fractions");
    p.fractions = {1, -1};
    expect([&] { (void)partition<double>(8, 8, 0.1, p, 1); }, "partition.fractions[1]");
    p.fractions = {1, 1};
    p.boundary_gamma = 4.5;
    expect([&] { (void)partition<double>(8, 8, 0.1, p, 1); }, "partition.boundary_gamma");
    voronoi_partition<double> v;
    expect([&] { (void)partition<double>(8, 8, 0.1, v, 1); }, "partition.sites");
    v.sites = {{0, 0, 0}};
    v.warp_m = -1;
    expect([&] { (void)partition<double>(8, 8, 0.1, v, 1); }, "partition.warp_m");
    const auto idx = make_raster<std::uint32_t, double>(8, 8, 0.1, 2u);
    std::vector<region_texture<double>> one{rough(1, 0.001)};
    expect([&] { (void)compose(idx, one, 0.0, 1); }, "compose.texture_index");
    one.push_back(rough(2, 0.001));
    one.push_back(rough(3, 0.001));
    one[2].roughness.spectrum.gamma = 1.5;
    expect([&] { (void)compose(idx, one, 0.0, 1); }, "compose.textures[2].roughness.spectrum.gamma");
    one[2].roughness.spectrum.gamma = 3.25;
    expect([&] { (void)compose(idx, one, -1.0, 1); }, "compose.blend_m");
    expect([&] { (void)compose(idx, one, 25.7, 1); }, "compose.blend_m"); // 257 cells: its Gaussian, cell by cell
    one[2].ripples.push_back(ripple_params<double>{});
    one[2].ripples[0].wavelength_m = 0.1;
    expect([&] { (void)compose(idx, one, 0.0, 1); }, "compose.textures[2].ripples[0].wavelength_m");
}

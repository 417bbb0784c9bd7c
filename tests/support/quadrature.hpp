#pragma once
// Adaptive Gauss-Kronrod (7-point Gauss, 15-point Kronrod) quadrature for the test oracles.
// Independent of the library: tests compare the tracer against integrals computed here.

#include <algorithm>
#include <array>
#include <cmath>
#include <queue>
#include <vector>

namespace sss_test {

struct quad_result {
    double value = 0.0;
    double error = 0.0;
};

namespace detail {
// Nodes and weights of the 15-point Kronrod rule and its embedded 7-point Gauss rule on [-1, 1].
inline constexpr std::array<double, 8> xk{0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                                           0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                                           0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                                           0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
inline constexpr std::array<double, 8> wk{0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                                           0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                                           0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                                           0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
inline constexpr std::array<double, 4> wg{0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                                           0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

template <class F> quad_result gk15(F&& f, double a, double b) {
    const double c = 0.5 * (a + b), h = 0.5 * (b - a);
    const double fc = f(c);
    double k = fc * wk[7], g = fc * wg[3];
    for (int i = 0; i < 7; ++i) {
        const double x = h * xk[static_cast<std::size_t>(i)];
        const double s = f(c - x) + f(c + x);
        k += wk[static_cast<std::size_t>(i)] * s;
        if (i % 2 == 1) g += wg[static_cast<std::size_t>(i / 2)] * s;
    }
    return {k * h, std::abs((k - g) * h)};
}
} // namespace detail

/// Integral of f over [a, b] to |error| <= max(abs_tol, rel_tol |integral|), by global adaptive bisection.
template <class F> quad_result integrate(F&& f, double a, double b, double rel_tol = 1e-10, double abs_tol = 0.0,
                                         int max_intervals = 2000) {
    if (!(b > a)) return {};
    struct piece { double a, b; quad_result r; bool operator<(const piece& o) const { return r.error < o.r.error; } };
    std::priority_queue<piece> heap;
    const auto first = detail::gk15(f, a, b);
    heap.push({a, b, first});
    double value = first.value, error = first.error;
    int n = 1;
    while (error > std::max(abs_tol, rel_tol * std::abs(value)) && n < max_intervals) {
        const piece p = heap.top();
        heap.pop();
        const double m = 0.5 * (p.a + p.b);
        const auto l = detail::gk15(f, p.a, m), r = detail::gk15(f, m, p.b);
        value += l.value + r.value - p.r.value;
        error += l.error + r.error - p.r.error;
        heap.push({p.a, m, l});
        heap.push({m, p.b, r});
        ++n;
    }
    // Re-sum to avoid drift from the running updates.
    double v = 0.0, e = 0.0;
    while (!heap.empty()) { v += heap.top().r.value; e += heap.top().r.error; heap.pop(); }
    return {v, e};
}

/// Integral over [a, b] split at the given interior points (kinks and jumps of f).
template <class F> quad_result integrate_pieces(F&& f, double a, double b, std::vector<double> cuts, double rel_tol = 1e-10,
                                                double abs_tol = 0.0) {
    cuts.push_back(a);
    cuts.push_back(b);
    std::sort(cuts.begin(), cuts.end());
    quad_result total;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
        const double lo = std::clamp(cuts[i], a, b), hi = std::clamp(cuts[i + 1], a, b);
        if (!(hi > lo)) continue;
        const auto r = integrate(f, lo, hi, rel_tol, abs_tol * (hi - lo) / (b - a));
        total.value += r.value;
        total.error += r.error;
    }
    return total;
}

} // namespace sss_test

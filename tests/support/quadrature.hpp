// Double-precision adaptive quadrature for the tests' closed forms and airlight integrals.
#pragma once
#include <cmath>
#include <functional>

namespace obscura::test {

//! Adaptive Simpson on [a, b] to an absolute tolerance (f at the ends and middle given).
inline double adaptiveSimpson(const std::function<double(double)>& f, double a, double b, double fa, double fm, double fb,
                              double whole, double tol, int depth) {
    const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
    const double flm = f(lm), frm = f(rm);
    const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
    // Also stop where the difference is at the level of double rounding: a tolerance below it
    // could never be met and would only split further.
    const double delta = std::abs(left + right - whole);
    if (depth <= 0 || delta <= 15 * tol || delta <= 1e-14 * std::abs(left + right))
        return left + right + (left + right - whole) / 15;
    return adaptiveSimpson(f, a, m, fa, flm, fm, left, tol / 2, depth - 1) +
           adaptiveSimpson(f, m, b, fm, frm, fb, right, tol / 2, depth - 1);
}

//! Integral of f over [a, b] to a relative tolerance of the integral (estimated by a first
//! pass), over `pieces` so that sharp features (a light next to the ray, a dense channel's
//! fast decay) are not missed.
inline double integrate(const std::function<double(double)>& f, double a, double b, double relativeTolerance,
                        int pieces = 256) {
    double rough = 0.0;
    for (int i = 0; i < pieces; ++i) rough += std::abs(f(a + (b - a) * (i + 0.5) / pieces)) * (b - a) / pieces;
    const double tol = relativeTolerance * rough + 1e-300;
    double sum = 0.0;
    for (int i = 0; i < pieces; ++i) {
        const double lo = a + (b - a) * i / pieces, hi = a + (b - a) * (i + 1) / pieces;
        const double flo = f(lo), fhi = f(hi), fm = f(0.5 * (lo + hi));
        sum += adaptiveSimpson(f, lo, hi, flo, fm, fhi, (hi - lo) / 6 * (flo + 4 * fm + fhi), tol / pieces, 30);
    }
    return sum;
}

} // namespace obscura::test

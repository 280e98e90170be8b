#pragma once
// The airlight integral's table for media.analytic's Table integral (shaders/media/
// media_analytic.comp.glsl): G(u, v) = Integral_v^{pi/2} exp(-u (tan xi - tan v)) dxi, the
// tail of Sun et al.'s F(u, v) = Integral_0^v exp(-u tan xi) dxi scaled by exp(u tan v).
// With e = pi/2 - v, G has a layer where e ~ u (G ~ e above it, ~ e^2 / u below), whose place
// moves with u: a grid uniform in v misses it at small u (33 % off at u = 0.01). So the table
// holds G / (e^2 / (e + u)), which is 1 on both sides of the layer, on columns u = maxU t^4 (t
// uniform in [0, 1]: dense at small u, where the layer is thinnest) and rows y = [e / (e + c)] / [(pi/2) / (pi/2 + c)], c = u + the first
// column's u (y uniform in [0, 1]): the layer sits at the same rows in every column. Lookups
// take e itself (the shader computes it without cancellation). No GL: the unit tests measure
// the error with the shader's own lookup.
#include <vector>

namespace obscura::detail {

//! u of the table's last column: past it the shader takes the asymptotic series.
constexpr double kAirlightTableMaxU = 64.0;

//! G(u, v) in double, to about 1e-12 relative: Simpson's rule on the substitution
//! s = tan xi - tan v, G = Integral_0^inf exp(-u s) / (1 + (s + tan v)^2) ds.
double airlightTail(double u, double v);
//! Three terms of G's asymptotic series in 1/u (Watson's lemma), as the shader takes past maxU.
double airlightTailAsymptotic(double u, double v);
//! e = pi/2 - v of row coordinate y in [0, 1] in column u, for a table of `size` rows.
double airlightTableEpsilon(double u, double y, int size);
//! The table, `size` x `size`, row-major with u along x.
std::vector<float> airlightTable(int size);
//! The shader's lookup of G(u, pi/2 - epsilon): bilinear interpolation in float of `table`
//! times the scale, or the series past maxU.
double airlightTableLookup(const std::vector<float>& table, int size, double u, double epsilon);

} // namespace obscura::detail

#include "media/airlight_table.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura::detail {
namespace {

constexpr double kHalfPi = 0.5 * std::numbers::pi;

// Simpson's rule with n (even) intervals.
template <class F>
double simpson(F f, double a, double b, int n) {
    const double h = (b - a) / n;
    double sum = f(a) + f(b);
    for (int i = 1; i < n; ++i) sum += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
    return sum * h / 3.0;
}

} // namespace

double airlightTail(double u, double v) {
    if (v >= kHalfPi) return 0.0;
    const double tanV = std::tan(v), epsilon = kHalfPi - v;
    if (u <= std::min(1.0, epsilon)) {
        // Smooth in xi on [v, pi/2]: the decay near pi/2 (exp(-u / (pi/2 - xi))) is no
        // narrower than u >= epsilon / 4096 of the range... or irrelevant below it.
        return simpson([&](double xi) { return xi >= kHalfPi ? (u > 0.0 ? 0.0 : 1.0) : std::exp(-u * (std::tan(xi) - tanV)); },
                       v, kHalfPi, 4096);
    }
    // In s = tan xi - tan v the exponential sets the scale: 40 / u covers all but e^-40, and the
    // rational factor varies on the scale 1 + tan v >= 1 / epsilon > 1 / u.
    return simpson([&](double s) { return std::exp(-u * s) / (1.0 + (s + tanV) * (s + tanV)); }, 0.0, 40.0 / u, 4096);
}

double airlightTailAsymptotic(double u, double v) {
    const double t = std::tan(std::min(v, 1.5707963)), c2 = 1.0 / (1.0 + t * t);
    return c2 / u - 2.0 * t * c2 * c2 / (u * u) + (6.0 * t * t - 2.0) * c2 * c2 * c2 / (u * u * u);
}

namespace {

// The offset that keeps the row mapping defined at u = 0: the first column's u.
double rowOffset(int size) { return kAirlightTableMaxU / std::pow(double(size - 1), 4.0); }

// G's scale: (pi/2 - v)^2 / (pi/2 - v + u), which G meets for pi/2 - v >> u (pi/2 - v) and
// << u ((pi/2 - v)^2 / u), and at v = 0 within a factor 0.4 to 1.
double tailScale(double u, double epsilon) { return epsilon > 0.0 ? epsilon * epsilon / (epsilon + u) : 0.0; }

} // namespace

double airlightTableEpsilon(double u, double y, int size) {
    const double c = u + rowOffset(size), q = y * kHalfPi / (kHalfPi + c);
    return q * c / (1.0 - q);
}

std::vector<float> airlightTable(int size) {
    std::vector<float> table(std::size_t(size) * std::size_t(size));
    for (int j = 0; j < size; ++j) {
        for (int i = 0; i < size; ++i) {
            const double t = double(i) / (size - 1), u = kAirlightTableMaxU * std::pow(t, 4.0);
            const double epsilon = std::min(airlightTableEpsilon(u, double(j) / (size - 1), size), kHalfPi);
            const double scale = tailScale(u, epsilon);
            table[std::size_t(j) * std::size_t(size) + std::size_t(i)] =
                scale > 0.0 ? float(airlightTail(u, kHalfPi - epsilon) / scale) : 1.0f;
        }
    }
    return table;
}

double airlightTableLookup(const std::vector<float>& table, int size, double u, double epsilon) {
    if (u > kAirlightTableMaxU) return airlightTailAsymptotic(u, kHalfPi - epsilon);
    // The shader's arithmetic, in float.
    const float n = float(size - 1), uf = float(u), ef = std::clamp(float(epsilon), 0.0f, float(kHalfPi));
    const float c = uf + float(rowOffset(size)), halfPi = float(kHalfPi);
    const float x = std::sqrt(std::sqrt(uf / float(kAirlightTableMaxU))) * n;
    const float y = std::clamp((ef / (ef + c)) * ((halfPi + c) / halfPi), 0.0f, 1.0f) * n;
    const int i = std::min(int(std::floor(x)), size - 2), j = std::min(int(std::floor(y)), size - 2);
    const float fx = x - float(i), fy = y - float(j);
    const auto at = [&](int a, int b) { return table[std::size_t(b) * std::size_t(size) + std::size_t(a)]; };
    const auto mix = [](float a, float b, float f) { return a + (b - a) * f; };
    const float r = mix(mix(at(i, j), at(i + 1, j), fx), mix(at(i, j + 1), at(i + 1, j + 1), fx), fy);
    return double(r * (ef > 0.0f ? ef * ef / (ef + uf) : 0.0f));
}

} // namespace obscura::detail

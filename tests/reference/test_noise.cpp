// The noise floor: halves, their stated confidence, determinism and the cache.
#include "obscura/assets.hpp"
#include "obscura/metrics.hpp"
#include "reference_helpers.hpp"

#include <catch2/catch.hpp>

#include <filesystem>

using namespace obscura;
using namespace obscura::reference;

namespace {
struct CornellAo {
    assets::LoadedScene cornell = assets::builtinScene("cornell");
    RayScene scene{cornell.scene};
    ShadingPoints points = fromCamera(scene, assets::makeCamera(cornell.camera, 32, 32), 32, 32);
    Quantity ao = reference::AmbientOcclusion{150.0, true};
};
} // namespace

TEST_CASE("The two halves agree within their stated confidence", "[reference][noise]") {
    CornellAo c;
    RenderSettings settings;
    settings.samplesPerPixel = 64;
    const Reference a = render(c.scene, c.points, c.ao, settings);
    settings.seed = 2;
    const Reference b = render(c.scene, c.points, c.ao, settings);
    const Image mask = surfaceMask(c.points);
    metrics::Options o;
    o.mask = &mask;
    // noiseMse is the estimated MSE of each render's value around the truth; two independent
    // renders then differ by noiseMse(a) + noiseMse(b) in the mean square. Each pixel adds a
    // chi-square term of one degree of freedom, so the ratio's relative spread is
    // sqrt(2 / n_eff), n_eff = (sum s_i)^2 / sum s_i^2 with s_i the pixels' variances
    // (estimated from the halves); allow 4 of those spreads.
    const double between = metrics::mse(a.value, b.value, o);
    double sum = 0, sumSq = 0;
    for (std::size_t i = 0; i < a.halfA.pixels.size(); ++i) {
        if (!c.points.points[i].surface()) continue;
        const double d = a.halfA.pixels[i] - a.halfB.pixels[i];
        sum += d * d / 4;
        sumSq += (d * d / 4) * (d * d / 4);
    }
    const double nEff = sum * sum / sumSq;
    const double spread = std::sqrt(2.0 / nEff);
    INFO("MSE between seeds " << between << ", stated noise " << a.noiseMse << " and " << b.noiseMse << ", n_eff " << nEff);
    CHECK(std::abs(between / (a.noiseMse + b.noiseMse) - 1.0) < 4 * spread);
    // The halves of one render have zero-mean differences: within 4 standard errors.
    double dsum = 0, sq = 0;
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.halfA.pixels.size(); ++i) {
        if (!c.points.points[i].surface()) continue;
        const double d = a.halfA.pixels[i] - a.halfB.pixels[i];
        dsum += d;
        sq += d * d;
        ++n;
    }
    const double mean = dsum / double(n), sd = std::sqrt(sq / double(n) - mean * mean);
    CHECK(std::abs(mean) < 4 * sd / std::sqrt(double(n)));
    CHECK(a.noiseMse == Approx(metrics::halvesNoiseMse(a.halfA, a.halfB, o)));
}

TEST_CASE("References are deterministic whatever the thread count and are cached", "[reference][noise]") {
    CornellAo c;
    RenderSettings settings;
    settings.samplesPerPixel = 16;
    settings.threads = 1;
    const Reference one = render(c.scene, c.points, c.ao, settings);
    settings.threads = 3;
    const Reference three = render(c.scene, c.points, c.ao, settings);
    CHECK(one.value.pixels == three.value.pixels);
    CHECK(one.rays == three.rays);
    CHECK(one.rays > 0);

    const auto dir = std::filesystem::temp_directory_path() / "obscura_reference_cache_test";
    std::filesystem::remove_all(dir);
    const Reference first = renderCached(dir, c.scene, c.points, c.ao, settings);
    std::size_t files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
    CHECK(files == 2); // <key>.exr and <key>.json
    const Reference cached = renderCached(dir, c.scene, c.points, c.ao, settings);
    CHECK(cached.value.pixels == first.value.pixels);
    CHECK(cached.halfB.pixels == first.halfB.pixels);
    CHECK(cached.noiseMse == first.noiseMse);
    // Another quantity is another entry.
    renderCached(dir, c.scene, c.points, reference::AmbientOcclusion{100.0, true}, settings);
    files = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) files += e.is_regular_file();
    CHECK(files == 4);
    std::filesystem::remove_all(dir);
}

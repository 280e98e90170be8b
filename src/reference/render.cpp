// The reference renderer: two independent halves per pixel over all cores, deterministic.
#include "obscura/error.hpp"
#include "reference/estimators.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <cstdio>
#include <mutex>
#include <sstream>
#include <thread>

#if defined(__SSE__) || defined(__x86_64__)
#include <pmmintrin.h>
#include <xmmintrin.h>
#endif

namespace obscura::reference {
namespace detail {

Estimator makeEstimator(const RayScene::Impl& scene, const Quantity& quantity, bool& surfaceOnly) {
    surfaceOnly = true;
    if (std::holds_alternative<AmbientOcclusion>(quantity) || std::holds_alternative<Obscurance>(quantity) ||
        std::holds_alternative<BentNormal>(quantity))
        return occlusionEstimator(scene, quantity);
    if (const auto* q = std::get_if<SingleScattering>(&quantity)) {
        surfaceOnly = false;
        return scatteringEstimator(scene, *q);
    }
    return lightingEstimator(scene, quantity);
}

namespace {

// Embree's advice: flush denormals in every thread that traces rays. The calling thread
// is the host's: its previous modes are restored when the render ends.
class FlushDenormals {
public:
    FlushDenormals() {
#if defined(__SSE__) || defined(__x86_64__)
        flush_ = _MM_GET_FLUSH_ZERO_MODE();
        denormals_ = _MM_GET_DENORMALS_ZERO_MODE();
        _MM_SET_FLUSH_ZERO_MODE(_MM_FLUSH_ZERO_ON);
        _MM_SET_DENORMALS_ZERO_MODE(_MM_DENORMALS_ZERO_ON);
#endif
    }
    ~FlushDenormals() {
#if defined(__SSE__) || defined(__x86_64__)
        _MM_SET_FLUSH_ZERO_MODE(flush_);
        _MM_SET_DENORMALS_ZERO_MODE(denormals_);
#endif
    }
    FlushDenormals(const FlushDenormals&) = delete;
    FlushDenormals& operator=(const FlushDenormals&) = delete;

private:
    unsigned flush_ = 0, denormals_ = 0;
};

class ProgressBar {
public:
    ProgressBar(bool enabled, int total) : enabled_(enabled), total_(total), start_(std::chrono::steady_clock::now()) {}
    void advance() {
        const int done = ++done_;
        if (!enabled_) return;
        const auto now = std::chrono::steady_clock::now();
        std::lock_guard<std::mutex> lock(mutex_);
        if (done < total_ && now - last_ < std::chrono::milliseconds(250)) return;
        last_ = now;
        const int width = 40, filled = width * done / total_;
        const double seconds = std::chrono::duration<double>(now - start_).count();
        std::fprintf(stderr, "\r  reference [%s%s] %3d%%  %.1f s", std::string(static_cast<std::size_t>(filled), '#').c_str(),
                     std::string(static_cast<std::size_t>(width - filled), '-').c_str(), 100 * done / total_, seconds);
        if (done == total_) std::fprintf(stderr, "\n");
    }

private:
    bool enabled_;
    int total_;
    std::atomic<int> done_{0};
    std::mutex mutex_;
    std::chrono::steady_clock::time_point start_, last_;
};

Image blank(int w, int h, int c) {
    Image img;
    img.width = w;
    img.height = h;
    img.channels = c;
    img.pixels.assign(static_cast<std::size_t>(w) * h * c, 0.0f);
    return img;
}

} // namespace
} // namespace detail

int channels(const Quantity& q) {
    if (std::holds_alternative<AmbientOcclusion>(q) || std::holds_alternative<Obscurance>(q)) return 1;
    if (std::holds_alternative<Shadow>(q)) return 2;
    if (std::holds_alternative<SingleScattering>(q)) return 4;
    return 3;
}

namespace {
template <class... Ts>
struct Overloaded : Ts... {
    using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;
} // namespace

std::string describe(const Quantity& q) {
    std::ostringstream s;
    s.precision(17);
    std::visit(Overloaded{
                   [&](const AmbientOcclusion& v) { s << "ao radius=" << v.radius << " cosine=" << v.cosineWeighted; },
                   [&](const Obscurance& v) {
                       s << "obscurance max_distance=" << v.maxDistance << " falloff=" << static_cast<int>(v.falloff);
                       // Only when uniform: cache keys of the default stay as they were.
                       if (!v.cosineWeighted) s << " cosine=0";
                   },
                   [&](const BentNormal& v) { s << "bent_normal radius=" << v.radius; },
                   [&](const DirectLight& v) { s << "direct visibility=" << v.visibility; },
                   [&](const IndirectLight& v) {
                       s << "indirect radius=" << v.radius;
                       // Only when off: cache keys of the default stay as they were.
                       if (!v.directVisibility) s << " direct_visibility=0";
                       if (v.environment) s << " environment=1";
                   },
                   [&](const Shadow& v) { s << "shadow light=" << v.light; },
                   [&](const SingleScattering& v) { s << "media medium=" << v.medium << " shadows=" << v.shadows; },
                   [&](const ImageBasedLight& v) {
                       s << "ibl irradiance=" << v.irradianceOnly << " visibility=" << v.visibility;
                       if (std::isfinite(v.radius)) s << " radius=" << v.radius; // only when limited: keys stay
                       if (v.lights) s << " lights=1";
                   },
               },
               q);
    return s.str();
}

Reference render(const RayScene& scene, const ShadingPoints& points, const Quantity& quantity,
                 const RenderSettings& settings) {
    if (settings.samplesPerPixel < 2 || settings.samplesPerPixel > (1 << 20))
        throw Error(ErrorCode::InvalidArgument, "RenderSettings::samplesPerPixel must be in [2, 1048576], got " +
                                                    std::to_string(settings.samplesPerPixel));
    if (settings.threads < 0 || settings.threads > 4096)
        throw Error(ErrorCode::InvalidArgument,
                    "RenderSettings::threads must be in [0, 4096] (0: all cores), got " + std::to_string(settings.threads));
    if (points.width < 1 || points.height < 1 ||
        points.points.size() != static_cast<std::size_t>(points.width) * static_cast<std::size_t>(points.height))
        throw Error(ErrorCode::InvalidArgument, "ShadingPoints: inconsistent size");
    bool surfaceOnly = true;
    const detail::Estimator estimate = detail::makeEstimator(scene.impl(), quantity, surfaceOnly);
    const int c = channels(quantity), perHalf = settings.samplesPerPixel / 2;
    Reference ref;
    ref.samplesPerPixel = 2 * perHalf;
    ref.halfA = detail::blank(points.width, points.height, c);
    ref.halfB = ref.halfA;
    const int threads = settings.threads > 0 ? settings.threads : std::max(1u, std::thread::hardware_concurrency());
    std::atomic<int> nextRow{0};
    std::atomic<std::uint64_t> rays{0};
    detail::ProgressBar progress(settings.progress, points.height);
    const auto start = std::chrono::steady_clock::now();
    std::exception_ptr failure;
    std::mutex failureMutex;
    const auto work = [&] {
        const detail::FlushDenormals flush;
        std::uint64_t localRays = 0;
        for (int y = nextRow++; y < points.height; y = nextRow++) {
            for (int x = 0; x < points.width; ++x) {
                const std::size_t index = static_cast<std::size_t>(y) * points.width + x;
                const ShadingPoint& p = points.points[index];
                if (surfaceOnly && !p.surface()) continue;
                // Independent streams per pixel and half: the result does not depend on threads.
                for (int half = 0; half < 2; ++half) {
                    // PCG streams that share a seed are correlated: hash the stream into the seed too.
                    const std::uint64_t stream = 2 * index + static_cast<std::uint64_t>(half);
                    detail::PixelSampler sampler(detail::mix64(settings.seed ^ detail::mix64(stream)), stream);
                    const glm::dvec4 v = estimate(p, perHalf, sampler, localRays);
                    Image& img = half == 0 ? ref.halfA : ref.halfB;
                    for (int k = 0; k < c; ++k) img.pixels[index * c + k] = static_cast<float>(v[k]);
                }
            }
            progress.advance();
        }
        rays += localRays;
    };
    // An exception in any thread stops the others (they run out of rows) and is rethrown here.
    const auto worker = [&] {
        try {
            work();
        } catch (...) {
            const std::lock_guard<std::mutex> lock(failureMutex);
            if (!failure) failure = std::current_exception();
            nextRow = points.height;
        }
    };
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
    ref.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ref.rays = rays;

    ref.value = ref.halfA;
    double sq = 0.0;
    std::size_t count = 0;
    for (std::size_t i = 0; i < ref.value.pixels.size(); ++i) {
        const double a = ref.halfA.pixels[i], b = ref.halfB.pixels[i];
        ref.value.pixels[i] = static_cast<float>(0.5 * (a + b));
        if (surfaceOnly && !points.points[i / c].surface()) continue;
        sq += (a - b) * (a - b);
        ++count;
    }
    ref.noiseMse = count ? sq / static_cast<double>(count) / 4.0 : 0.0;
    // A bent normal is a direction: the mean of the halves is normalized again.
    if (std::holds_alternative<BentNormal>(quantity))
        for (std::size_t i = 0; i + 2 < ref.value.pixels.size(); i += 3) {
            const glm::dvec3 v(ref.value.pixels[i], ref.value.pixels[i + 1], ref.value.pixels[i + 2]);
            const double len = glm::length(v);
            if (len > 0.0)
                for (int k = 0; k < 3; ++k) ref.value.pixels[i + static_cast<std::size_t>(k)] = static_cast<float>(v[k] / len);
        }
    return ref;
}

} // namespace obscura::reference

// Screen-space visibility: the texture-space march against the view-space one, Hi-Z against
// the texture-space march, depth peeling (the G-buffer's second layer and the thickness it
// gives), and bad input.
#include "gl_fixture.hpp"
#include "integrator_settings.hpp"
#include "screen_mirror.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

using namespace obscura;

namespace {

struct ScreenFixture {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    ScreenVisibility visibility{ctx};
    GBufferView view;
    Image positions, normals; // view space; positions' alpha = geometry

    //! cameraOf: the camera from the scene's own spec (default: as makeCamera gives it).
    ScreenFixture(const std::string& sceneName, int width, int height, int depthLayers = 1,
                  const std::function<Camera(const assets::CameraSpec&)>& cameraOf = {}) {
        const assets::LoadedScene s = assets::builtinScene(sceneName);
        const Camera camera = cameraOf ? cameraOf(s.camera) : assets::makeCamera(s.camera, width, height);
        GBufferSettings settings{width, height, true, {}}; // lit: indirect light gathers it
        settings.depthLayers = depthLayers;
        view = gbuffer.render(s.scene, camera, settings);
        positions = readTexture(ctx, gbuffer.positions(view));
        normals = readTexture(ctx, view.normal);
    }

    // Segments as the integrators cast them: from visible surface points, in random
    // directions (a quarter of them into the surface), of lengths up to `reach`.
    std::vector<ScreenSegment> surfaceSegments(std::size_t count, float reach, unsigned seed) const {
        std::mt19937 rng(seed);
        std::uniform_int_distribution<int> px(0, positions.width - 1), py(0, positions.height - 1);
        std::normal_distribution<float> gauss;
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::vector<ScreenSegment> out;
        while (out.size() < count) {
            const int x = px(rng), y = py(rng);
            if (positions.at(x, y, 3) == 0.0f) continue;
            const glm::vec3 p(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2));
            const glm::vec3 n(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2));
            glm::vec3 w = glm::normalize(glm::vec3(gauss(rng), gauss(rng), gauss(rng)));
            if (glm::dot(w, n) < 0.0f && unit(rng) < 0.67f) w = -w;
            out.push_back({p, p + w * (reach * unit(rng))});
        }
        return out;
    }
};

std::size_t differingSamples(const std::vector<ScreenHit>& a, const std::vector<ScreenHit>& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += a[i].sample != b[i].sample ? 1 : 0;
    return n;
}

// Whether a march's first hidden sample (hit.sample, -1: none) is what the exact arithmetic
// of the mirror gives: each sample before it visible or a tie, it hidden or a tie. `tied`
// is set when any of those samples is a tie.
bool agreesWithMirror(const test::ScreenMirror& mirror, const ScreenSegment& segment, const ScreenHit& hit,
                      const ScreenTraceSettings& s, bool& tied) {
    const glm::dvec3 from(segment.from), d = glm::dvec3(segment.to) - glm::dvec3(segment.from);
    const int first = hit.sample < 0 ? s.steps : hit.sample;
    bool agrees = true;
    for (int j = 0; j <= std::min(first, s.steps - 1); ++j) {
        const test::Verdict v = mirror.classify(from, d, j, s.steps, s.jitter, s.thickness, s.thicknessMode);
        tied = tied || v == test::Verdict::Tie;
        agrees = agrees && (j < first ? v != test::Verdict::Hidden : v != test::Verdict::Visible);
    }
    return agrees;
}

std::size_t hitCount(const std::vector<ScreenHit>& hits) {
    std::size_t n = 0;
    for (const ScreenHit& h : hits) n += h.hit ? 1 : 0;
    return n;
}

// The share of ties among the samples of 20000 rays from random surface points into their
// normals' hemispheres, of length `radius`, with random jitter: an upper bound at three
// Poisson deviations of the count (and 3 for none seen), over the samples.
double tieShareOf(const ScreenFixture& f, const test::ScreenMirror& mirror, float radius, int steps, ScreenThickness mode) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::size_t ties = 0, samples = 0;
    for (const ScreenSegment& segment : f.surfaceSegments(20000, radius, 13)) {
        const glm::dvec3 from(segment.from), d = glm::normalize(glm::dvec3(segment.to) - from) * double(radius);
        const double jitter = unit(rng);
        for (int j = 0; j < steps; ++j, ++samples)
            ties += mirror.classify(from, d, j, steps, jitter, radius, mode) == test::Verdict::Tie ? 1 : 0;
    }
    return (double(ties) + 3.0 * std::sqrt(double(ties)) + 3.0) / double(samples);
}

using CameraOf = std::function<Camera(const assets::CameraSpec&)>;

// The Cornell box's camera as perspective (empty: the scene's own), reversed-Z with an
// infinite far plane, and orthographic with depth from 0 to 1 and reversed, for a W x H image.
std::vector<std::pair<const char*, CameraOf>> projectionCases(int W, int H) {
    const float aspect = float(W) / float(H);
    return {
        {"perspective", {}},
        {"reversed-Z, infinite far", [aspect](const assets::CameraSpec& c) {
             return Camera::perspective(c.lookAt, glm::radians(c.fovyDegrees), aspect, c.nearPlane, INFINITY, DepthMode::Reversed);
         }},
        {"orthographic, zero to one", [aspect](const assets::CameraSpec& c) {
             return Camera::orthographic(c.lookAt, 330.0f, aspect, c.nearPlane, c.farPlane, DepthMode::StandardZeroToOne);
         }},
        {"orthographic, reversed", [aspect](const assets::CameraSpec& c) {
             return Camera::orthographic(c.lookAt, 330.0f, aspect, c.nearPlane, c.farPlane, DepthMode::Reversed);
         }},
    };
}

// Both marches must find the first hidden sample that the double-precision mirror of
// screenHiddenAt finds, except where a sample lies within the marches' derived float
// rounding of a decision (screen_mirror.cpp: a tie). So they can differ only on rays with a
// tie; a systematic error (a wrong pixel or depth) would differ on tens of percent.
void checkViewAndTextureAgree(ScreenFixture& f, const test::ScreenMirror& mirror,
                              const std::vector<ScreenSegment>& segments, ScreenThickness mode, float thickness) {
    ScreenTraceSettings s;
    s.steps = 24;
    s.thicknessMode = mode;
    s.thickness = thickness;
    s.march = ScreenMarch::View;
    const auto view = f.visibility.trace(f.view, segments, s);
    s.march = ScreenMarch::Texture;
    const auto texture = f.visibility.trace(f.view, segments, s);
    std::size_t viewOff = 0, textureOff = 0, tiedRays = 0;
    for (std::size_t i = 0; i < segments.size(); ++i) {
        bool tied = false;
        viewOff += agreesWithMirror(mirror, segments[i], view[i], s, tied) ? 0 : 1;
        textureOff += agreesWithMirror(mirror, segments[i], texture[i], s, tied) ? 0 : 1;
        tiedRays += tied ? 1 : 0;
    }
    const std::size_t hits = hitCount(view), differing = differingSamples(view, texture);
    INFO("mode " << int(mode) << ", thickness " << thickness << ": " << hits << " of " << segments.size()
                 << " rays hit; first hidden sample differs on " << differing << "; rays with a tie " << tiedRays
                 << "; off the mirror: view " << viewOff << ", texture " << textureOff);
    CHECK(hits > segments.size() / 10);
    CHECK(viewOff == 0);
    CHECK(textureOff == 0);
    CHECK(differing <= tiedRays);
    // The ties' margins are a few ulp; a mirror that called most samples ties would pass the
    // checks above and say nothing.
    CHECK(tiedRays < segments.size() / 100);
}
} // namespace

TEST_CASE("Texture-space and view-space marching classify every sample as exact arithmetic does, but for rounding ties",
          "[visibility]") {
    // checkViewAndTextureAgree for each thickness mode, with a thin slab (where the modes
    // differ most) and a thick one.
    const std::pair<ScreenThickness, float> modes[] = {{ScreenThickness::Constant, 0.05f},
                                                       {ScreenThickness::Constant, 10.0f},
                                                       {ScreenThickness::DepthPeeling, 0.05f},
                                                       {ScreenThickness::PeelingOrConstant, 0.05f}};
    for (const char* sceneName : {"cornell", "box_room"}) {
        ScreenFixture f(sceneName, 96, 72, 2);
        const test::ScreenMirror mirror(f.ctx, f.view);
        const float reach = std::string(sceneName) == "cornell" ? 300.0f : 2.0f;
        const std::vector<ScreenSegment> segments = f.surfaceSegments(4000, reach, 7);
        CAPTURE(sceneName);
        for (const auto& [mode, share] : modes) checkViewAndTextureAgree(f, mirror, segments, mode, share * reach);
    }
}

TEST_CASE("Texture-space and view-space marching classify alike with reversed and orthographic projections",
          "[visibility]") {
    // The same checks as above in the projections whose depth runs otherwise (reversed, an
    // infinite far plane) or whose rays are parallel: the marches derive pixel and view z from
    // the projection differently (screenRayOf's clip-space line against view-space points).
    // Two depth layers, so that the peeling modes read a second layer in these depth modes too.
    constexpr int W = 80, H = 64;
    const std::pair<ScreenThickness, float> modes[] = {{ScreenThickness::Constant, 15.0f},
                                                       {ScreenThickness::Constant, 3000.0f},
                                                       {ScreenThickness::DepthPeeling, 15.0f},
                                                       {ScreenThickness::PeelingOrConstant, 15.0f}};
    for (const auto& [name, cameraOf] : projectionCases(W, H)) {
        if (!cameraOf) continue; // the default perspective: the test above
        CAPTURE(name);
        ScreenFixture f("cornell", W, H, 2, cameraOf);
        const test::ScreenMirror mirror(f.ctx, f.view);
        const std::vector<ScreenSegment> segments = f.surfaceSegments(4000, 300.0f, 7);
        for (const auto& [mode, thickness] : modes) checkViewAndTextureAgree(f, mirror, segments, mode, thickness);
    }
}

TEST_CASE("Hi-Z finds exactly the first hidden sample of the texture-space march with fewer fetches", "[visibility]") {
    // In every projection the pyramid's bounds must hold: its level 0 bounds the view z of a
    // pixel's piece of surface from the depth (perspective) or along parallel rays
    // (orthographic), whichever way depth runs (reversed, infinite far plane).
    constexpr int W = 80, H = 64;
    for (const auto& [name, cameraOf] : projectionCases(W, H)) {
        CAPTURE(name);
        ScreenFixture f("cornell", W, H, 1, cameraOf);
        std::vector<ScreenSegment> segments = f.surfaceSegments(3000, 600.0f, 11);
        // Segments from anywhere: outside the image, behind the camera, across the near plane.
        std::mt19937 rng(5);
        std::uniform_real_distribution<float> coord(-2000.0f, 2000.0f);
        for (int i = 0; i < 1000; ++i)
            segments.push_back({{coord(rng), coord(rng), coord(rng)}, {coord(rng), coord(rng), coord(rng)}});
        for (const int steps : {8, 64, 512}) {
            ScreenTraceSettings s;
            s.steps = steps;
            s.thickness = 30.0f;
            s.march = ScreenMarch::Texture;
            const auto texture = f.visibility.trace(f.view, segments, s);
            s.march = ScreenMarch::HiZ;
            const auto hiz = f.visibility.trace(f.view, segments, s);
            std::uint64_t textureFetches = 0, hizFetches = 0;
            for (std::size_t i = 0; i < segments.size(); ++i) {
                textureFetches += texture[i].fetches;
                hizFetches += hiz[i].fetches;
            }
            INFO(steps << " steps: " << hitCount(texture) << " hits; fetches " << textureFetches << " texture-space, "
                       << hizFetches << " Hi-Z");
            CHECK(hitCount(texture) > segments.size() / 10);
            CHECK(differingSamples(texture, hiz) == 0);
            // Where rays run far past surfaces the pyramid skips runs of samples; with a few
            // samples per pixel the saving must show (with 8 steps it need not).
            if (steps >= 64) CHECK(hizFetches < textureFetches);
        }
    }
}

TEST_CASE("AO and GI march alike with view and texture samples and exactly alike with Hi-Z", "[visibility][ao][gi]") {
    constexpr int W = 96, H = 72;
    ScreenFixture f("box_room", W, H, 2);
    AmbientOcclusion ao(f.ctx);
    IndirectLight gi(f.ctx);
    const test::ScreenMirror mirror(f.ctx, f.view);
    // Few samples, so that the rounding bound below stays a small share of the pixels.
    constexpr float radius = 0.6f;
    constexpr int rays = 4, steps = 8;
    for (const ScreenThickness mode :
         {ScreenThickness::Constant, ScreenThickness::DepthPeeling, ScreenThickness::PeelingOrConstant}) {
        std::vector<Image> aoImages, giImages;
        for (const ScreenMarch march : {ScreenMarch::View, ScreenMarch::Texture, ScreenMarch::HiZ}) {
            auto a = test::integratorSettings<AmbientOcclusionSettings>(radius, rays, steps);
            a.thicknessMode = mode;
            a.march = march;
            aoImages.push_back(readTexture(f.ctx, ao.run(f.view, a).ao));
            auto g = test::integratorSettings<IndirectLightSettings>(radius, rays, steps);
            g.thicknessMode = mode;
            g.march = march;
            giImages.push_back(readTexture(f.ctx, gi.run(f.view, g).radiance));
        }
        // A pixel differs only if one of its rays met a tie (a sample within the marches'
        // rounding of a decision, screen_mirror.cpp) before its first hidden sample. The
        // share of samples that are ties, from the mirror on rays like these (from surface
        // points into the hemisphere, length the radius, random jitter), taken at its upper
        // 3-sigma bound; times the image's rays x steps samples, plus five Poisson standard
        // deviations.
        const double tieShare = tieShareOf(f, mirror, radius, steps, mode);
        const double expected = tieShare * double(W) * H * rays * steps;
        CAPTURE(static_cast<int>(mode), tieShare, expected);
        const auto differing = [](const Image& x, const Image& y) {
            std::size_t n = 0;
            for (std::size_t i = 0; i < x.pixels.size(); ++i) n += x.pixels[i] != y.pixels[i] ? 1 : 0;
            return n;
        };
        std::size_t occluded = 0, gathered = 0;
        for (const float v : aoImages[0].pixels) occluded += v < 1.0f ? 1 : 0;
        for (std::size_t i = 0; i < giImages[0].pixels.size(); i += 4) gathered += giImages[0].pixels[i] > 0.0f ? 1 : 0;
        CHECK(occluded > std::size_t(W * H / 10));
        CHECK(gathered > std::size_t(W * H / 10));
        CHECK(double(differing(aoImages[0], aoImages[1])) <= expected + 5.0 * std::sqrt(expected));
        CHECK(double(differing(giImages[0], giImages[1])) <= 4.0 * (expected + 5.0 * std::sqrt(expected))); // 4 channels
        CHECK(differing(aoImages[1], aoImages[2]) == 0);
        CHECK(differing(giImages[1], giImages[2]) == 0);
    }
}

TEST_CASE("Depth peeling gives the back of a closed box and lets rays pass behind it", "[visibility]") {
    // box_room: a closed 1 m box ([-0.5, 0.5] x [0, 1] x [-0.5, 0.5]) inside a 6 m room, seen
    // from (2.2, 1.6, 2.6) toward the box's centre (0, 0.5, 0): with an odd size the centre
    // pixel's ray is the view axis.
    ScreenFixture f("box_room", 65, 65, 2);
    REQUIRE(f.view.backDepth);
    const glm::dvec3 eye(2.2, 1.6, 2.6), target(0.0, 0.5, 0.0);
    const glm::dvec3 dir = glm::normalize(target - eye);
    // Slab intersection of the axis with the box and with the room.
    const auto slab = [&](glm::dvec3 lo, glm::dvec3 hi, bool wantExit) {
        double tEnter = -1e30, tExit = 1e30;
        for (int a = 0; a < 3; ++a) {
            const double t0 = (lo[a] - eye[a]) / dir[a], t1 = (hi[a] - eye[a]) / dir[a];
            tEnter = std::max(tEnter, std::min(t0, t1));
            tExit = std::min(tExit, std::max(t0, t1));
        }
        return wantExit ? tExit : tEnter;
    };
    const double front = slab({-0.5, 0, -0.5}, {0.5, 1, 0.5}, false), back = slab({-0.5, 0, -0.5}, {0.5, 1, 0.5}, true);
    const double wall = slab({-3, 0, -3}, {3, 3, 3}, true);
    REQUIRE(front < back);
    REQUIRE(back < wall);

    // The back layer's view z at the centre pixel is -back (the axis is the view direction).
    const Image backPositions = [&] {
        GBufferView backView = f.view;
        backView.depth = f.view.backDepth;
        return readTexture(f.ctx, f.gbuffer.positions(backView));
    }();
    REQUIRE(backPositions.at(32, 32, 3) == 1.0f);
    // 32F depth of a perspective projection with near 0.05: relative view-z error ~1e-6.
    CHECK(-backPositions.at(32, 32, 2) == Approx(back).epsilon(1e-5));
    // Where the first layer is the room (one-sided walls), nothing lies behind: no back layer.
    CHECK(backPositions.at(0, 0, 3) == 0.0f);

    // Points on the axis (view space: (0, 0, -t)) inside the box, behind it, and in front.
    const std::vector<glm::vec3> points = {{0, 0, float(-0.5 * (front + back))},
                                           {0, 0, float(-0.5 * (back + wall))},
                                           {0, 0, float(-0.5 * front)}};
    const auto hiddenWith = [&](ScreenThickness mode, float thickness) {
        ScreenTraceSettings s;
        s.thicknessMode = mode;
        s.thickness = thickness;
        return f.visibility.hidden(f.view, points, s);
    };
    using Flags = std::vector<std::uint8_t>;
    // 10 m, deeper than the whole room: constant thickness closes the gap behind the box;
    // peeling opens it; the deeper of both closes it again.
    CHECK(hiddenWith(ScreenThickness::Constant, 10.0f) == Flags{1, 1, 0});
    CHECK(hiddenWith(ScreenThickness::DepthPeeling, 10.0f) == Flags{1, 0, 0});
    CHECK(hiddenWith(ScreenThickness::PeelingOrConstant, 10.0f) == Flags{1, 1, 0});
    // 5 cm, far thinner than the box: the slab misses the box's middle; peeling and the
    // deeper of both find it.
    CHECK(hiddenWith(ScreenThickness::Constant, 0.05f) == Flags{0, 0, 0});
    CHECK(hiddenWith(ScreenThickness::DepthPeeling, 0.05f) == Flags{1, 0, 0});
    CHECK(hiddenWith(ScreenThickness::PeelingOrConstant, 0.05f) == Flags{1, 0, 0});

    // Hi-Z over the peeled bounds, and over the deeper of both, agrees with the
    // texture-space march too.
    const std::vector<ScreenSegment> segments = f.surfaceSegments(2000, 3.0f, 3);
    for (const ScreenThickness mode : {ScreenThickness::DepthPeeling, ScreenThickness::PeelingOrConstant})
        for (const float thickness : {0.05f, 10.0f}) {
            CAPTURE(int(mode), thickness);
            ScreenTraceSettings s;
            s.thicknessMode = mode;
            s.thickness = thickness;
            s.steps = 128;
            s.march = ScreenMarch::Texture;
            const auto texture = f.visibility.trace(f.view, segments, s);
            s.march = ScreenMarch::HiZ;
            CHECK(differingSamples(texture, f.visibility.trace(f.view, segments, s)) == 0);
        }
}

TEST_CASE("Segments longer than 1.8e19 units classify as exact arithmetic does", "[visibility]") {
    // The radius and the thickness range over (0, inf). Past about 1.8e19 units a sample's
    // squared length overflows float; screenHiddenAt took |s| for its rounding tolerance, which
    // became Inf, so nothing was hidden (every ray of this test missed). 1e18 is a control
    // below the overflow; 1e30, 1e37 and 3e38 (near FLT_MAX) lie above it (a segment's end
    // still finite). At 3e38 a projected extent p00 d.x can overflow to Inf, and Inf * 0 at
    // t = 0 gives a NaN texture coordinate, which screenPixelOfClip now counts as off the
    // image; on llvmpipe the earlier test, which let NaN through, classified those samples
    // the same way by chance (this case passes with either), so it guards the range, not that
    // fix.
    // Segments from surface points of the Cornell box, the slab as deep as the reach, so that
    // the far samples of rays into the image are hidden behind the walls. Random directions
    // seldom point into the image (a few percent), so half the segments run along the eye's
    // ray through another surface pixel: their far samples project near that pixel, behind
    // its surface. The marches must agree with the double-precision mirror but for ties, and
    // Hi-Z with the texture march.
    ScreenFixture f("cornell", 64, 48);
    const test::ScreenMirror mirror(f.ctx, f.view);
    const std::vector<ScreenSegment> across = f.surfaceSegments(1000, 1.0f, 17), toward = f.surfaceSegments(1000, 1.0f, 19);
    for (const float reach : {1e18f, 1e30f, 1e37f, 3e38f}) {
        CAPTURE(reach);
        std::vector<ScreenSegment> segments = f.surfaceSegments(1000, reach, 23);
        for (std::size_t i = 0; i < across.size(); ++i) {
            const glm::vec3 w = glm::normalize(toward[i].from); // the eye is the view-space origin
            const float length = reach * (0.25f + 0.75f * float(i) / float(across.size()));
            segments.push_back({across[i].from, across[i].from + w * length});
        }
        ScreenTraceSettings s;
        s.steps = 16;
        s.thickness = reach;
        std::size_t off[2] = {0, 0}, tiedRays = 0;
        std::vector<ScreenHit> marches[3];
        const ScreenMarch kinds[3] = {ScreenMarch::View, ScreenMarch::Texture, ScreenMarch::HiZ};
        for (int m = 0; m < 3; ++m) {
            s.march = kinds[m];
            marches[m] = f.visibility.trace(f.view, segments, s);
        }
        for (std::size_t i = 0; i < segments.size(); ++i) {
            bool tied = false;
            for (int m = 0; m < 2; ++m) off[m] += agreesWithMirror(mirror, segments[i], marches[m][i], s, tied) ? 0 : 1;
            tiedRays += tied ? 1 : 0;
            for (const auto& march : marches) CHECK(std::isfinite(march[i].t));
        }
        INFO(hitCount(marches[0]) << " of " << segments.size() << " rays hit; off the mirror: view " << off[0]
                                  << ", texture " << off[1] << "; rays with a tie " << tiedRays);
        CHECK(hitCount(marches[0]) > segments.size() / 10);
        CHECK(off[0] == 0);
        CHECK(off[1] == 0);
        CHECK(tiedRays < segments.size() / 100);
        CHECK(differingSamples(marches[1], marches[2]) == 0);
    }
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Points off the image or behind the camera are visible and a surface hides only its thickness",
          "[visibility]") {
    // The border policy and the radius check (screen_march.glsl): what the depth buffer does
    // not show counts as visible, and a depth sample stands for a slab `thickness` deep, not
    // for everything behind it ("extending to infinity"). The Cornell box from its camera: the
    // centre pixel shows the back wall (z = 559.2 in the world, 1059 units from the eye).
    ScreenFixture f("cornell", 33, 33);
    REQUIRE(f.positions.at(16, 16, 3) == 1.0f);
    const glm::vec3 wall(f.positions.at(16, 16, 0), f.positions.at(16, 16, 1), f.positions.at(16, 16, 2));
    const glm::vec3 ray = glm::normalize(wall); // from the eye through the wall point
    ScreenTraceSettings s;
    s.thickness = 50.0f;
    // A point behind the back wall but off the image: the same depth, moved sideways by
    // twice the distance (the field of view is 40 degrees, so 2 |z| is far outside it).
    const glm::vec3 offImage = wall + ray * 10.0f + glm::vec3(2.0f * std::abs(wall.z), 0.0f, 0.0f);
    const std::vector<glm::vec3> points = {
        wall + ray * (0.5f * s.thickness), // behind the wall, within its thickness: hidden
        wall + ray * (2.0f * s.thickness), // beyond the thickness: visible (the radius check)
        wall - ray * 10.0f,                // in front of the wall: visible
        offImage,                          // off the image: visible (nothing is known there)
        glm::vec3(0.0f, 0.0f, 100.0f),     // behind the camera: visible
        glm::vec3(0.0f, 0.0f, 0.0f),       // at the eye: visible
    };
    CHECK(f.visibility.hidden(f.view, points, s) == std::vector<std::uint8_t>{1, 0, 0, 0, 0, 0});
    // A segment from the wall point out of the image sideways, behind the wall's plane all
    // along: its samples on the image are hidden, those off it are not.
    const glm::vec3 side = wall + ray * 10.0f;
    s.steps = 64;
    s.jitter = 0.0f;
    const std::vector<ScreenHit> leaving = f.visibility.trace(f.view, {{offImage, side}}, s);
    REQUIRE(leaving.size() == 1);
    CHECK(leaving[0].hit); // it enters the image behind the wall
    CHECK(leaving[0].sample > 0); // but its first samples, off the image, are visible
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Screen visibility rejects bad settings and survives NaN segments", "[visibility]") {
    ScreenFixture f("cornell", 32, 32);
    ScreenTraceSettings s;
    const std::vector<ScreenSegment> one = {{{0, 0, -500}, {0, 0, -900}}};
    ScreenTraceSettings bad = s;
    bad.steps = 0;
    CHECK_THROWS_AS(f.visibility.trace(f.view, one, bad), Error);
    bad = s;
    bad.thickness = 0.0f;
    CHECK_THROWS_AS(f.visibility.trace(f.view, one, bad), Error);
    bad = s;
    bad.jitter = 1.0f;
    CHECK_THROWS_AS(f.visibility.trace(f.view, one, bad), Error);
    bad = s;
    bad.thicknessMode = ScreenThickness::DepthPeeling; // this G-buffer has one layer
    CHECK_THROWS_AS(f.visibility.trace(f.view, one, bad), Error);
    bad.thicknessMode = ScreenThickness::PeelingOrConstant; // so has the deeper of both
    CHECK_THROWS_AS(f.visibility.trace(f.view, one, bad), Error);
    bad.thicknessMode = static_cast<ScreenThickness>(3); // an integer outside the enumerators
    CHECK_THROWS_AS(f.visibility.trace(f.view, one, bad), Error);
    bad = s;
    bad.march = static_cast<ScreenMarch>(3); // an integer outside the enumerators
    CHECK_THROWS_AS(f.visibility.trace(f.view, one, bad), Error);

    const float nan = std::nanf("");
    const std::vector<ScreenSegment> broken = {{{nan, 0, -500}, {0, 0, -900}}, {{0, 0, -500}, {0, INFINITY, -900}}};
    for (const ScreenMarch m : {ScreenMarch::View, ScreenMarch::Texture, ScreenMarch::HiZ}) {
        s.march = m;
        for (const ScreenHit& h : f.visibility.trace(f.view, broken, s)) CHECK_FALSE(h.hit);
    }
    CHECK(test::drainGlErrors().empty());
}

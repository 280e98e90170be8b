// Ambient occlusion in a closed box room against the Embree reference at the G-buffer's own
// samples, and the screen-space marches (view, texture, Hi-Z) inside the AO integrator.
#include "gl_fixture.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"
#include "obscura/reference.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace obscura;

namespace {

struct RoomFixture {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    AmbientOcclusion ao{ctx};
    assets::LoadedScene room = assets::builtinScene("box_room");
    Camera camera;
    GBufferView view;
    Image positions, normals;

    RoomFixture(int width, int height) : camera(assets::makeCamera(room.camera, width, height)) {
        GBufferSettings settings{width, height, false, {}};
        settings.depthLayers = 2;
        view = gbuffer.render(room.scene, camera, settings);
        positions = readTexture(ctx, gbuffer.positions(view));
        normals = readTexture(ctx, view.normal);
    }

    Image run(const AmbientOcclusionSettings& s) { return readTexture(ctx, ao.run(view, s).ao); }

    // Whether the cube of half side r around the view point of pixel (x, y), and so the ball
    // of its rays, projects inside the image in front of the camera: the projection of a
    // convex set in front of the camera is the hull of its corners' projections.
    bool ballOnScreen(int x, int y, float r) const {
        const glm::vec3 p(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2));
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 c = p + r * glm::vec3(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
            const glm::vec4 clip = camera.projection * glm::vec4(c, 1.0f);
            if (!(clip.w > 0.0f) || std::abs(clip.x) >= clip.w || std::abs(clip.y) >= clip.w) return false;
        }
        return true;
    }

    // Per pixel: whether no silhouette of the small box (a pixel whose 4-neighbours are
    // partly on the box and partly not) lies in the pixel rectangle that holds the
    // projection of the ray ball. There the depth buffer and its back layer hold every
    // surface within reach.
    std::vector<bool> ballsWithoutSilhouette(const reference::ShadingPoints& points, float r) const {
        const int w = positions.width, h = positions.height;
        auto onBox = [&](int x, int y) {
            const glm::dvec3 p = points.points[std::size_t(y) * w + std::size_t(x)].position;
            return points.points[std::size_t(y) * w + std::size_t(x)].surface() && std::abs(p.x) < 0.501 &&
                   std::abs(p.z) < 0.501 && p.y < 1.001;
        };
        std::vector<bool> silhouette(std::size_t(w) * h, false);
        for (int y = 1; y + 1 < h; ++y)
            for (int x = 1; x + 1 < w; ++x) {
                const bool c = onBox(x, y);
                silhouette[std::size_t(y) * w + std::size_t(x)] =
                    onBox(x - 1, y) != c || onBox(x + 1, y) != c || onBox(x, y - 1) != c || onBox(x, y + 1) != c;
            }
        std::vector<bool> clear(std::size_t(w) * h, false);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                if (!ballOnScreen(x, y, r)) continue;
                const glm::vec3 p(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2));
                glm::vec2 lo(1e30f), hi(-1e30f);
                for (int corner = 0; corner < 8; ++corner) {
                    const glm::vec3 c = p + r * glm::vec3(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
                    const glm::vec4 clip = camera.projection * glm::vec4(c, 1.0f);
                    // Pixel coordinates, row 0 at the top as in the images.
                    const glm::vec2 q((clip.x / clip.w * 0.5f + 0.5f) * float(w), (0.5f - clip.y / clip.w * 0.5f) * float(h));
                    lo = glm::min(lo, q);
                    hi = glm::max(hi, q);
                }
                bool any = false;
                for (int v = std::max(0, int(lo.y) - 1); v <= std::min(h - 1, int(hi.y) + 1); ++v)
                    for (int u = std::max(0, int(lo.x) - 1); u <= std::min(w - 1, int(hi.x) + 1); ++u)
                        any = any || silhouette[std::size_t(v) * w + std::size_t(u)];
                clear[std::size_t(y) * w + std::size_t(x)] = !any;
            }
        return clear;
    }
};

} // namespace

TEST_CASE("AO in a box room with depth peeling matches the reference within the march and sampling bounds", "[ao][reference]") {
    constexpr int W = 96, H = 72;
    RoomFixture f(W, H);
    constexpr float radius = 0.6f;
    constexpr int rays = 256, steps = 32;
    const reference::RayScene scene(f.room.scene);
    const reference::ShadingPoints points = reference::fromGBuffer(scene, f.camera, f.positions, f.normals);
    reference::RenderSettings rs;
    rs.samplesPerPixel = 1024;
    // The march samples up to r (1 - 1/steps) at least, so it may miss exactly the hits
    // beyond that: its expectation lies between AO_r and AO_r(1-1/steps).
    const reference::Reference lo = reference::render(scene, points, reference::AmbientOcclusion{radius, true}, rs);
    const reference::Reference hi =
        reference::render(scene, points, reference::AmbientOcclusion{radius * (1.0 - 1.0 / steps), true}, rs);
    const auto clear = f.ballsWithoutSilhouette(points, radius);
    AmbientOcclusionSettings s;
    s.radius = radius;
    s.rays = rays;
    s.steps = steps;
    double meanBound = 0.0;
    for (const ScreenThickness mode : {ScreenThickness::DepthPeeling, ScreenThickness::Constant}) {
        s.thicknessMode = mode; // Constant: the thickness is the radius
        const Image ao = f.run(s);
        int checked = 0, outside = 0, clearChecked = 0, clearOutside = 0;
        double meanError = 0.0, meanWindow = 0.0, sumSigma2 = 0.0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const std::size_t i = std::size_t(y) * W + std::size_t(x);
                if (!points.points[i].surface() || !f.ballOnScreen(x, y, radius)) continue;
                const double a = lo.value.pixels[i], b = hi.value.pixels[i], value = ao.at(x, y, 0);
                // Five standard deviations of the GPU's mean of `rays` binary samples (the
                // rotated Hammersley set taken as random: conservative) and of the reference's,
                // and the 16-bit float rounding of the stored value (to nearest, roundedToHalf:
                // at most 2^-12 below 1).
                const double p = std::clamp(0.5 * (a + b), 1.0 / rays, 1.0 - 1.0 / rays);
                const double sigma = std::sqrt(p * (1.0 - p) / rays + p * (1.0 - p) / rs.samplesPerPixel);
                const double tolerance = 5.0 * sigma + std::ldexp(1.0, -12);
                const bool in = value >= a - tolerance && value <= b + tolerance;
                outside += in ? 0 : 1;
                if (clear[i]) {
                    ++clearChecked;
                    clearOutside += in ? 0 : 1;
                }
                meanError += value - 0.5 * (a + b);
                meanWindow += 0.5 * (b - a);
                sumSigma2 += sigma * sigma;
                ++checked;
            }
        meanError /= checked;
        // Independent pixels: their mean stays within the mean window plus five standard
        // deviations of a mean, plus the half-float rounding, which need not average out.
        meanBound = meanWindow / checked + 5.0 * std::sqrt(sumSigma2) / checked + std::ldexp(1.0, -12);
        INFO((mode == ScreenThickness::DepthPeeling ? "peeled" : "constant")
             << ": " << checked << " pixels, " << outside << " outside their window (" << clearOutside << " of "
             << clearChecked << " without a silhouette in reach); mean error " << meanError << ", bound " << meanBound);
        CHECK(checked > W * H / 4);
        CHECK(clearChecked > W * H / 20);
        if (mode == ScreenThickness::DepthPeeling) {
            // Where no silhouette is in reach the depth buffer and its back layer hold
            // all the geometry within the radius: every pixel is within its window. Near
            // silhouettes two things the pixel grid cannot resolve remain (a sample within
            // a pixel footprint of an edge is judged by the plane at the pixel's centre;
            // floor hidden behind the box is unknown): they are in the mean.
            CHECK(clearOutside == 0);
            CHECK(std::abs(meanError) <= meanBound);
        } else {
            // A constant thickness fills the space behind the box: rays passing behind it
            // count as occluded, which the mean shows beyond its bound.
            CHECK(meanError < -meanBound);
        }
    }
}

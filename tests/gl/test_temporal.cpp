// Temporal input: a frame index that shifts every pixel's sampling pattern, and temporal
// accumulation of AO and indirect light (reprojected history, rejected by depth and normal).
#include "gl_fixture.hpp"

#include "core/frame_uniforms.hpp"
#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <set>
#include <vector>

using namespace obscura;

namespace {

constexpr int W = 64, H = 48;

struct RoomFrames {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    AmbientOcclusion ao{ctx}, converged{ctx};
    IndirectLight gi{ctx}, giConverged{ctx};
    assets::LoadedScene room = assets::builtinScene("box_room");
    assets::CameraSpec base = room.camera; //!< panned along x by camera()

    Camera camera(float pan) const {
        assets::CameraSpec spec = base;
        spec.lookAt.eye.x += pan;
        spec.lookAt.target.x += pan;
        return assets::makeCamera(spec, W, H);
    }
    GBufferView view(const Camera& c) { return gbuffer.render(room.scene, c, {W, H, true, {}}); }
};

AmbientOcclusionSettings aoSettings(int rays, float radius = 0.6f) {
    AmbientOcclusionSettings s;
    s.radius = radius;
    s.rays = rays;
    s.steps = 16;
    return s;
}

// Root mean square of a - b over the pixels with geometry (the view's positions' alpha), in
// channel 0 (or the channels given).
double rmse(const Image& a, const Image& b, const Image& positions, int channels = 1) {
    double sum = 0.0;
    std::size_t n = 0;
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            if (positions.at(x, y, 3) == 0.0f) continue;
            for (int c = 0; c < channels; ++c) {
                const double d = double(a.at(x, y, c)) - double(b.at(x, y, c));
                sum += d * d;
                ++n;
            }
        }
    return std::sqrt(sum / double(std::max<std::size_t>(n, 1)));
}

} // namespace

TEST_CASE("A frame index shifts every pixel's sampling pattern; index 0 is the unshifted one", "[temporal]") {
    // Index 0 is no shift, so results without a frame index are those of before (the bench's
    // cells); the next indices are points of the R3 sequence, all different.
    CHECK(detail::frameSampleShift(0) == glm::vec3(0.0f));
    std::set<std::tuple<float, float, float>> shifts;
    for (std::uint32_t i = 1; i <= 64; ++i) {
        const glm::vec3 s = detail::frameSampleShift(i);
        CHECK((glm::all(glm::greaterThanEqual(s, glm::vec3(0.0f))) && glm::all(glm::lessThan(s, glm::vec3(1.0f)))));
        shifts.insert({s.x, s.y, s.z});
    }
    CHECK(shifts.size() == 64);
    const glm::vec3 last = detail::frameSampleShift(0xFFFFFFFFu);
    CHECK((glm::all(glm::greaterThanEqual(last, glm::vec3(0.0f))) && glm::all(glm::lessThan(last, glm::vec3(1.0f)))));

    RoomFrames f;
    const GBufferView view = f.view(f.camera(0.0f));
    const Image positions = readTexture(f.ctx, f.gbuffer.positions(view));
    AmbientOcclusionSettings s = aoSettings(4);
    const Image first = readTexture(f.ctx, f.ao.run(view, s).ao);
    s.frameIndex = 1;
    const Image second = readTexture(f.ctx, f.ao.run(view, s).ao);
    int differ = 0, pixels = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (positions.at(x, y, 3) == 0.0f || (first.at(x, y, 0) == 1.0f && second.at(x, y, 0) == 1.0f)) continue;
            ++pixels;
            differ += first.at(x, y, 0) != second.at(x, y, 0);
        }
    // Open pixels stay open whatever their samples (AO 1 with every ray missing): the shift
    // shows where some ray of either frame hits.
    INFO(differ << " of " << pixels << " occluded pixels differ between frames 0 and 1");
    CHECK(differ > pixels / 2);
    CHECK(test::drainGlErrors().empty());
}


TEST_CASE("Temporal accumulation of a still view divides the error of 1 frame by about the root of the frames",
          "[temporal]") {
    // AO (4 rays) and indirect light (4 rays) of the box room, accumulated over 1, 4 and 16
    // frames with frame indices 0, 1, ...: the plain mean of N frames. N independent estimates
    // would divide the RMSE against the converged value (the same method with 1024 rays) by
    // sqrt(N); the frames' rotations are spread by a low-discrepancy sequence, which does at
    // least as well (measured: 2.4x from 1 to 4 frames, 2.3x from 4 to 16). Asked here: 90 % of
    // sqrt(4) = 2 at each step.
    RoomFrames f;
    const GBufferView view = f.view(f.camera(0.0f));
    const Image positions = readTexture(f.ctx, f.gbuffer.positions(view));
    const auto check = [&](const std::function<Image(std::uint32_t)>& frame, const Image& target, int channels) {
        std::vector<double> errors;
        for (std::uint32_t i = 0; i < 16; ++i) {
            const Image accumulated = frame(i);
            if (i == 0 || i == 3 || i == 15) errors.push_back(rmse(accumulated, target, positions, channels));
        }
        INFO("RMSE after 1, 4 and 16 frames: " << errors[0] << ", " << errors[1] << ", " << errors[2]);
        CHECK(errors[1] <= errors[0] / (0.9 * 2.0));
        CHECK(errors[2] <= errors[1] / (0.9 * 2.0));
    };
    AmbientOcclusionSettings a = aoSettings(4);
    a.temporal.enabled = true;
    check([&](std::uint32_t i) {
              a.frameIndex = i;
              return readTexture(f.ctx, f.ao.run(view, a).ao);
          },
          readTexture(f.ctx, f.converged.run(view, aoSettings(1024)).ao), 1);
    IndirectLightSettings g;
    g.radius = 1.0f;
    g.rays = 1024;
    g.steps = 16;
    const Image giTarget = readTexture(f.ctx, f.giConverged.run(view, g).radiance);
    g.rays = 4;
    g.temporal.enabled = true;
    check([&](std::uint32_t i) {
              g.frameIndex = i;
              return readTexture(f.ctx, f.gi.run(view, g).radiance);
          },
          giTarget, 3);
    // The history: two RGBA16F and two RG32UI textures of the view's size; freed by
    // resetHistory, after which a run is a single frame's again.
    const std::size_t withHistory = f.ao.memoryBytes();
    f.ao.resetHistory();
    CHECK(withHistory - f.ao.memoryBytes() == std::size_t(W) * H * 32);
    AmbientOcclusionSettings single = aoSettings(4);
    single.frameIndex = 16;
    a.frameIndex = 16;
    CHECK(readTexture(f.ctx, f.ao.run(view, a).ao).pixels == readTexture(f.ctx, f.converged.run(view, single).ao).pixels);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("A panning camera's history is reprojected, and what comes into view starts afresh", "[temporal]") {
    // The camera pans 2 cm a frame before the box room's box for 15 frames (a fifth of a pixel
    // a frame at the far wall, more on the box), AO with 4 rays: the accumulation must halve
    // the last frame's RMSE against the converged AO (1024 rays). Then it jumps to 40 cm right
    // of the centre, which reveals wall beside the box. Where the history texels around a pixel's point all
    // show another surface, the history is dropped and the pixel is the jump frame's own
    // value, exactly; each test alone must drop its case:
    // - normals turned away by more than 60 degrees (cosine below 0.5, well under the 0.9
    //   threshold: the box's side where the wall now shows), with the plane test off
    //   (tolerance 1);
    // - the same normal (cosine above 0.99: the box's front against the parallel wall behind
    //   it) on a plane further than 2.5 times the tolerance (5 % of the depth) from the point,
    //   with the normal test off (threshold -1).
    // With both off (tolerance 1, threshold -1) the turned-away pixels took the other
    // surface's history: a ghost. The parallel ones stay dropped even then (the box's front
    // lies further from the wall's plane than the whole depth); with the plane test removed
    // from the shader, all 84 of them kept the box's history (checked once by hand).
    RoomFrames f;
    // Head-on at the box, whose front face is parallel to the wall behind it; a radius that
    // reaches from the box's front and the wall to the floor, so that their AO differs.
    constexpr float kRadius = 2.0f;
    f.base.lookAt = {{0.0f, 0.8f, 2.6f}, {0.0f, 0.5f, -3.0f}, {0.0f, 1.0f, 0.0f}};
    struct Run {
        Image beforeJump, afterJump;
        Image positions[2], normals[2]; // the frames before and after the jump
        Camera cameras[2];
    };
    const auto pan = [&](float depthTolerance, float normalThreshold) {
        AmbientOcclusion ao(f.ctx);
        AmbientOcclusionSettings s = aoSettings(4, kRadius);
        s.temporal.enabled = true;
        s.temporal.depthTolerance = depthTolerance;
        s.temporal.normalThreshold = normalThreshold;
        Run r;
        for (std::uint32_t i = 0; i < 16; ++i) {
            const Camera c = f.camera(i < 15 ? -0.3f + 0.02f * float(i) : 0.4f);
            const GBufferView v = f.view(c);
            s.frameIndex = i;
            const Image result = readTexture(f.ctx, ao.run(v, s).ao);
            if (i < 14) continue;
            const int k = i - 14;
            (k == 0 ? r.beforeJump : r.afterJump) = result;
            r.positions[k] = readTexture(f.ctx, f.gbuffer.positions(v));
            r.normals[k] = readTexture(f.ctx, v.normal);
            r.cameras[k] = c;
        }
        return r;
    };
    const TemporalSettings defaults;
    const Run both = pan(defaults.depthTolerance, defaults.normalThreshold);
    const Run planeOnly = pan(defaults.depthTolerance, -1.0f), normalOnly = pan(1.0f, defaults.normalThreshold);
    const Run none = pan(1.0f, -1.0f);
    const Image converged = readTexture(f.ctx, f.converged.run(f.view(both.cameras[0]), aoSettings(1024, kRadius)).ao);
    AmbientOcclusionSettings one = aoSettings(4, kRadius);
    one.frameIndex = 14;
    const Image single = readTexture(f.ctx, f.ao.run(f.view(both.cameras[0]), one).ao);
    const double accumulatedError = rmse(both.beforeJump, converged, both.positions[0]);
    const double singleError = rmse(single, converged, both.positions[0]);
    INFO("RMSE after 15 panning frames: accumulated " << accumulatedError << ", the last frame alone " << singleError);
    CHECK(accumulatedError < 0.5 * singleError);

    one.frameIndex = 15;
    const Image jumped = readTexture(f.ctx, f.ao.run(f.view(both.cameras[1]), one).ao);
    const glm::dmat4 toBefore = glm::dmat4(both.cameras[0].view) * glm::inverse(glm::dmat4(both.cameras[1].view));
    const auto texel3 = [](const Image& image, int x, int y) {
        return glm::dvec3(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
    };
    int turned = 0, parallel = 0, turnedExact = 0, parallelExact = 0, turnedGhosts = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (both.positions[1].at(x, y, 3) == 0.0f) continue;
            // The point and its normal in the view of the frame before the jump.
            const glm::dvec3 p(toBefore * glm::dvec4(texel3(both.positions[1], x, y), 1.0));
            const glm::dvec3 n = glm::dmat3(toBefore) * texel3(both.normals[1], x, y);
            const glm::dvec4 clip = glm::dmat4(both.cameras[0].projection) * glm::dvec4(p, 1.0);
            if (!(clip.w > 0.0)) continue;
            // The shader's four texels, as it finds them (GL rows, bottom up).
            const glm::dvec2 texel = (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * glm::dvec2(W, H) - 0.5;
            const glm::ivec2 base(int(std::floor(texel.x)), int(std::floor(texel.y)));
            bool allTurned = true, allParallel = true, any = false;
            for (int k = 0; k < 4; ++k) {
                const glm::ivec2 q = base + glm::ivec2(k & 1, k >> 1);
                if (q.x < 0 || q.y < 0 || q.x >= W || q.y >= H) continue;
                const int row = H - 1 - q.y;
                if (both.positions[0].at(q.x, row, 3) == 0.0f) continue;
                any = true;
                const double cosine = glm::dot(texel3(both.normals[0], q.x, row), n);
                const glm::dvec3 o = texel3(both.positions[0], q.x, row);
                allTurned = allTurned && cosine < 0.5;
                allParallel = allParallel && cosine > 0.99 && std::abs(glm::dot(o - p, n)) > 0.05 * -o.z;
            }
            if (!any) continue; // no history there at all
            const bool sameAsJump = none.afterJump.at(x, y, 0) == jumped.at(x, y, 0);
            if (allTurned) {
                ++turned;
                turnedExact += normalOnly.afterJump.at(x, y, 0) == jumped.at(x, y, 0) &&
                               both.afterJump.at(x, y, 0) == jumped.at(x, y, 0);
                turnedGhosts += !sameAsJump;
            } else if (allParallel) {
                ++parallel;
                parallelExact += planeOnly.afterJump.at(x, y, 0) == jumped.at(x, y, 0) &&
                                 both.afterJump.at(x, y, 0) == jumped.at(x, y, 0);
            }
        }
    INFO(turned << " pixels whose history texels all face away (" << turnedExact << " dropped by the normal test, "
                << turnedGhosts << " kept a ghost without the tests), " << parallel
                << " whose texels are parallel surfaces off its plane (" << parallelExact << " dropped by the plane test)");
    REQUIRE(turned > 10);
    REQUIRE(parallel > 10);
    CHECK(turnedExact == turned);
    CHECK(parallelExact == parallel);
    CHECK(turnedGhosts > turned / 2);
    CHECK(test::drainGlErrors().empty());
}

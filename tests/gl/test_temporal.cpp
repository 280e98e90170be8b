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

    Camera camera(float pan) const {
        assets::CameraSpec spec = room.camera;
        spec.lookAt.eye.x += pan;
        spec.lookAt.target.x += pan;
        return assets::makeCamera(spec, W, H);
    }
    GBufferView view(const Camera& c) { return gbuffer.render(room.scene, c, {W, H, true, {}}); }
};

AmbientOcclusionSettings aoSettings(int rays) {
    AmbientOcclusionSettings s;
    s.radius = 0.6f;
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
    // The camera pans 2 cm a frame through the box room for 15 frames (a fifth of a pixel a
    // frame at the far wall, more on the box), AO with 4 rays: the accumulation must halve the
    // last frame's RMSE against the converged AO (1024 rays). Then it jumps 25 cm sideways,
    // which reveals wall beside the box. Where all four history texels around a pixel's point
    // show a surface turned away from the point's by more than 60 degrees (normals with a
    // cosine below 0.5, well under the 0.9 threshold: the box seen where the wall now shows,
    // or background), the history is dropped and the pixel is the jump frame's own value,
    // exactly. Without the plane and normal tests (tolerance 1, threshold -1) such pixels took
    // the other surface's history: a ghost.
    RoomFrames f;
    struct Run {
        Image beforeJump, afterJump;
        Image positions[2], normals[2]; // the frames before and after the jump
        Camera cameras[2];
    };
    const auto pan = [&](bool reject) {
        AmbientOcclusion ao(f.ctx);
        AmbientOcclusionSettings s = aoSettings(4);
        s.temporal.enabled = true;
        if (!reject) {
            s.temporal.depthTolerance = 1.0f;
            s.temporal.normalThreshold = -1.0f;
        }
        Run r;
        for (std::uint32_t i = 0; i < 16; ++i) {
            const Camera c = f.camera(i < 15 ? -0.3f + 0.02f * float(i) : 0.23f);
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
    const Run with = pan(true), without = pan(false);
    const Image converged = readTexture(f.ctx, f.converged.run(f.view(with.cameras[0]), aoSettings(1024)).ao);
    AmbientOcclusionSettings one = aoSettings(4);
    one.frameIndex = 14;
    const Image single = readTexture(f.ctx, f.ao.run(f.view(with.cameras[0]), one).ao);
    const double accumulatedError = rmse(with.beforeJump, converged, with.positions[0]);
    const double singleError = rmse(single, converged, with.positions[0]);
    INFO("RMSE after 15 panning frames: accumulated " << accumulatedError << ", the last frame alone " << singleError);
    CHECK(accumulatedError < 0.5 * singleError);

    one.frameIndex = 15;
    const Image jumped = readTexture(f.ctx, f.ao.run(f.view(with.cameras[1]), one).ao);
    const glm::dmat4 toBefore = glm::dmat4(with.cameras[0].view) * glm::inverse(glm::dmat4(with.cameras[1].view));
    const glm::dmat3 beforeToWorld = glm::transpose(glm::dmat3(with.cameras[0].view));
    const glm::dmat3 afterToWorld = glm::transpose(glm::dmat3(with.cameras[1].view));
    const auto texel3 = [](const Image& image, int x, int y) {
        return glm::dvec3(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2));
    };
    int revealed = 0, exact = 0, ghosts = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (with.positions[1].at(x, y, 3) == 0.0f) continue;
            const glm::dvec4 clip = glm::dmat4(with.cameras[0].projection) * toBefore * glm::dvec4(texel3(with.positions[1], x, y), 1.0);
            if (!(clip.w > 0.0)) continue;
            // The shader's four texels, as it finds them (GL rows, bottom up).
            const glm::dvec2 texel = (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * glm::dvec2(W, H) - 0.5;
            const glm::ivec2 base(int(std::floor(texel.x)), int(std::floor(texel.y)));
            const glm::dvec3 normal = afterToWorld * texel3(with.normals[1], x, y);
            bool turnedAway = true;
            for (int k = 0; k < 4 && turnedAway; ++k) {
                const glm::ivec2 q = base + glm::ivec2(k & 1, k >> 1);
                if (q.x < 0 || q.y < 0 || q.x >= W || q.y >= H) continue;
                const int row = H - 1 - q.y;
                if (with.positions[0].at(q.x, row, 3) == 0.0f) continue;
                turnedAway = glm::dot(beforeToWorld * texel3(with.normals[0], q.x, row), normal) < 0.5;
            }
            if (!turnedAway) continue;
            ++revealed;
            exact += with.afterJump.at(x, y, 0) == jumped.at(x, y, 0);
            ghosts += without.afterJump.at(x, y, 0) != jumped.at(x, y, 0);
        }
    INFO(revealed << " pixels whose history texels all show another surface; " << exact
                  << " of them the jump frame's own value, " << ghosts << " not without the tests");
    REQUIRE(revealed > 20);
    CHECK(exact == revealed);
    CHECK(ghosts > 0);
    CHECK(test::drainGlErrors().empty());
}

// The bench's pipeline: reference evaluated at the G-buffer's own samples (mode a).
#include "gl_fixture.hpp"
#include "scene_builders.hpp"
#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"
#include "obscura/reference.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using namespace obscura;

TEST_CASE("At the G-buffer's samples the reference sees the same surfaces as from the camera", "[reference][gbuffer]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    const auto mode = GENERATE(DepthMode::Standard, DepthMode::Reversed);
    for (const char* name : {"plane", "cornell"}) {
        CAPTURE(name, static_cast<int>(mode));
        const assets::LoadedScene s = assets::builtinScene(name);
        constexpr int W = 48, H = 40;
        const Camera camera = assets::makeCamera(s.camera, W, H, mode);
        const GBufferView view = gbuffer.render(s.scene, camera, {W, H, true, {}});
        const reference::RayScene scene(s.scene);
        const reference::ShadingPoints fromGBuffer = reference::fromGBuffer(
            scene, camera, readTexture(ctx, gbuffer.positions(view)), readTexture(ctx, view.normal));
        const reference::ShadingPoints fromCamera = reference::fromCamera(scene, camera, W, H);
        int both = 0;
        for (std::size_t i = 0; i < fromCamera.points.size(); ++i) {
            const auto &a = fromGBuffer.points[i], &b = fromCamera.points[i];
            if (!a.surface() || !b.surface()) continue;
            ++both;
            // Same point within the stated uncertainties (the depth buffer's quantization for the
            // G-buffer sample), except where the pixel centre and the rasterizer disagree on which
            // triangle covers it (silhouettes and edges: different normals).
            if (glm::dot(a.normal, b.normal) < 0.999) continue;
            CHECK(glm::length(a.position - b.position) <= a.uncertainty + b.uncertainty);
        }
        CHECK(both > W * H / 2);
        // The open plane is unoccluded at its G-buffer samples: depth-buffer error must not
        // make a sample see its own surface.
        if (std::string(name) == "plane") {
            reference::RenderSettings rs;
            rs.samplesPerPixel = 32;
            const reference::Reference ao = reference::render(scene, fromGBuffer, reference::AmbientOcclusion{}, rs);
            for (std::size_t i = 0; i < fromGBuffer.points.size(); ++i)
                if (fromGBuffer.points[i].surface()) CHECK(ao.value.pixels[i] == 1.0f);
        }
    }
}

namespace {

// A rasterizer that interpolates depth from vertices snapped to 1/256 of a pixel (NVIDIA's
// GL_SUBPIXEL_BITS is 8 and its depth follows the snapped vertices; llvmpipe's follows the
// exact ones): the G-buffer's vertex shader rounds the window position itself.
const char* kSnappedPosition = R"(
    vec4 clip = frame.projection * p;
    if (clip.w > 0.0) {
        const vec2 window = round((clip.xy / clip.w * 0.5 + 0.5) * vec2(frameSize()) * 256.0) / 256.0;
        clip.xy = (window / vec2(frameSize()) * 2.0 - 1.0) * clip.w;
    }
    gl_Position = clip;
)";

// How far the reference lifted a G-buffer sample's secondary rays before it moved samples
// onto the surface: 4 float steps of the stored depth along the view ray
// (ShadingPoint::uncertainty), at least 2^-20 of the point's largest coordinate.
double quantizationLift(const Camera& camera, const glm::dvec3& view, const glm::dvec3& world, glm::dvec2 ndc) {
    const glm::dvec4 clip = glm::dmat4(camera.projection) * glm::dvec4(view, 1.0);
    const double zn = clip.z / clip.w;
    const float depth = static_cast<float>(camera.clipDepth == ClipDepth::ZeroToOne ? zn : 0.5 * zn + 0.5);
    const float next = std::nextafter(depth, 2.0f);
    const double step = std::abs(viewPositionFromDepth(camera, ndc, next).z - viewPositionFromDepth(camera, ndc, depth).z);
    const double lift = 4.0 * step * glm::length(view) / std::abs(view.z);
    return std::max(lift, std::ldexp(std::max({std::abs(world.x), std::abs(world.y), std::abs(world.z)}), -20));
}

} // namespace

TEST_CASE("G-buffer samples of a rasterizer that snaps vertices to its sub-pixel grid see no occluder in an open "
          "scene", "[reference][gbuffer]") {
    // The H100's fault on imported models (37-40 % of pixels falsely shadowed in the shadow
    // bench, AO 0 on open surfaces): their framing camera's near/far ratio of about 3.5 makes
    // the depth quantization, the old lift, far smaller than the snapped vertices' depth error.
    test::GlFixture gl;
    Context ctx(gl.desc());
    test::overrideShader(ctx, "gbuffer/gbuffer.vert.glsl", "    gl_Position = frame.projection * p;\n", kSnappedPosition);
    GBuffer gbuffer(ctx);
    Scene scene = test::quadScene({{{glm::dvec3(-2, 0, -2), {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}}}});
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0.3f, -1.0f, 0.2f};
    scene.lights.push_back(sun);
    constexpr int W = 64, H = 64;
    const auto mode = GENERATE(DepthMode::Standard, DepthMode::Reversed);
    // Framed as mesh files are (assets::framingCamera): near and far 1.5 and 2 radii from the
    // centre, here of a sphere of radius 2 about the floor's centre, seen from 45 degrees up.
    assets::CameraSpec spec;
    spec.lookAt = {{0.0f, 4.0f, 4.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    spec.fovyDegrees = 40.0f;
    spec.nearPlane = std::sqrt(32.0f) - 3.0f;
    spec.farPlane = std::sqrt(32.0f) + 4.0f;
    const Camera camera = assets::makeCamera(spec, W, H, mode);
    const GBufferView view = gbuffer.render(scene, camera, {W, H, false, {}});
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const reference::RayScene rays(scene);
    const reference::ShadingPoints points = reference::fromGBuffer(rays, camera, positions, readTexture(ctx, view.normal));
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(camera.view));
    int samples = 0, belowLift = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (positions.at(x, y, 3) == 0.0f) continue;
            ++samples;
            const glm::dvec3 v(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2));
            const glm::dvec3 w(toWorld * glm::dvec4(v, 1.0));
            belowLift += -w.y > quantizationLift(camera, v, w, test::pixelNdc(x, y, W, H));
            // Moved onto the floor, to the float error of a ray hit.
            const reference::ShadingPoint& s = points.points[std::size_t(y) * W + x];
            CHECK(std::abs(s.position.y) <= s.uncertainty);
        }
    CAPTURE(samples, belowLift);
    REQUIRE(samples > W * H / 2);
    // The emulation bites: many samples lie below the floor by more than the old lift.
    CHECK(belowLift > samples / 10);
    reference::RenderSettings rs;
    rs.samplesPerPixel = 32;
    const reference::Reference ao = reference::render(rays, points, reference::AmbientOcclusion{}, rs);
    const reference::Reference lit = reference::render(rays, points, reference::Shadow{0}, rs);
    int occluded = 0, shadowed = 0;
    for (std::size_t i = 0; i < points.points.size(); ++i) {
        if (!points.points[i].surface()) continue;
        occluded += ao.value.pixels[i] != 1.0f;
        // Channel 0: the sun's visibility; channel 1: its light reaches the front side.
        shadowed += lit.value.at(int(i) % W, int(i) / W, 0) != 1.0f || lit.value.at(int(i) % W, int(i) / W, 1) != 1.0f;
    }
    CHECK(occluded == 0);
    CHECK(shadowed == 0);
}

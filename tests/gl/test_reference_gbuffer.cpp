// The bench's pipeline: reference evaluated at the G-buffer's own samples (mode a).
#include "gl_fixture.hpp"
#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"
#include "obscura/reference.hpp"

#include <catch2/catch.hpp>

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

// prepare(): every program a call takes is compiled ahead of time, so that an engine's first
// frame does not stall on compiling. The check is that the call, run after prepare() with the
// same settings, compiles nothing more (Context::compiledPrograms is the same list), and that
// prepare() allocates nothing.
#include "gl_fixture.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>

#include <functional>

using namespace obscura;

namespace {

Camera roomCamera(int w, int h) {
    return Camera::perspective({{2.2f, 1.6f, 2.6f}, {0.0f, 0.5f, 0.0f}, {0.0f, 1.0f, 0.0f}}, 0.9f, float(w) / float(h),
                               0.05f, 50.0f);
}

struct PrepareFixture {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    Scene scene = test::cornerScene(true);
    GBufferView view;

    PrepareFixture() { view = gbuffer.render(scene, roomCamera(48, 40), {48, 40, true, {}}); }

    // Runs `prepare`, then `run`: the run compiles nothing prepare() did not; returns how many
    // programs prepare() compiled.
    std::size_t check(const std::function<void()>& prepare, const std::function<void()>& run) {
        const std::size_t before = ctx.compiledPrograms().size();
        prepare();
        const auto prepared = ctx.compiledPrograms();
        run();
        CHECK(ctx.compiledPrograms() == prepared);
        return prepared.size() - before;
    }
};

} // namespace

TEST_CASE("prepare() compiles every program a call with the same settings takes", "[prepare]") {
    PrepareFixture f;
    SECTION("ambient occlusion, every method, full and half resolution, filtered, bent normals, temporal") {
        Voxelizer voxelizer(f.ctx);
        for (const AoMethod method : {AoMethod::RayMarch, AoMethod::Points, AoMethod::Horizon, AoMethod::Voxel})
            for (const AoResolution resolution : {AoResolution::Full, AoResolution::Half})
                for (const int blur : {0, 2}) {
                    CAPTURE(static_cast<int>(method), static_cast<int>(resolution), blur);
                    AmbientOcclusion ao(f.ctx);
                    AmbientOcclusionSettings s;
                    s.method = method;
                    s.resolution = resolution;
                    s.blurRadius = blur;
                    s.rays = 4;
                    s.bentNormals = blur > 0;
                    s.temporal.enabled = blur > 0;
                    s.march = method == AoMethod::RayMarch && blur > 0 ? ScreenMarch::HiZ : ScreenMarch::View;
                    if (method == AoMethod::Voxel) s.voxels = &voxelizer.voxelize(f.scene, {});
                    f.check([&] { ao.prepare(s); }, [&] { ao.run(f.view, s); });
                    CHECK(AmbientOcclusion(f.ctx).memoryBytes() == 0);
                }
    }
    SECTION("indirect light, both methods, quarter resolution with blur") {
        Voxelizer voxelizer(f.ctx);
        for (const GiMethod method : {GiMethod::Screen, GiMethod::Hybrid}) {
            IndirectLight gi(f.ctx);
            IndirectLightSettings s;
            s.method = method;
            s.resolution = AoResolution::Quarter;
            s.blurRadius = 1;
            s.rays = 4;
            s.temporal.enabled = method == GiMethod::Screen;
            if (method == GiMethod::Hybrid) s.voxels = &voxelizer.voxelize(f.scene, {});
            CHECK(f.check([&] { gi.prepare(s); }, [&] { gi.run(f.view, s); }) > 0);
            // prepare() holds no memory of its own.
            IndirectLight fresh(f.ctx);
            fresh.prepare(s);
            CHECK(fresh.memoryBytes() == 0);
        }
    }
    SECTION("compose and drawing into the host's framebuffer") {
        GLuint colour = 0, framebuffer = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &colour);
        glTextureStorage2D(colour, 1, GL_RGBA8, 48, 40);
        glCreateFramebuffers(1, &framebuffer);
        glNamedFramebufferTexture(framebuffer, GL_COLOR_ATTACHMENT0, colour, 0);
        Composer composer(f.ctx);
        ComposeSettings s;
        CHECK(f.check([&] { composer.prepare(s); },
                      [&] {
                          const TextureView display = composer.compose({f.view, {}, {}}, s);
                          composer.drawToHost(display, {framebuffer, 0, 0, 48, 40});
                      }) == 3);
        CHECK(Composer(f.ctx).memoryBytes() == 0);
        glDeleteFramebuffers(1, &framebuffer);
        glDeleteTextures(1, &colour);
    }
    SECTION("adopting host buffers: normals from depth, or converted") {
        for (const bool normals : {false, true}) {
            GBuffer host(f.ctx);
            HostGBuffer buffers;
            buffers.depth = f.view.depth;
            if (normals) buffers.normal = f.view.normal;
            f.check([&] { host.prepareAdopt(buffers); }, [&] { host.adopt(buffers, f.view.camera); });
        }
    }
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("prepare() refuses what run() refuses", "[prepare][bad-input]") {
    PrepareFixture f;
    const auto before = f.ctx.compiledPrograms();
    AmbientOcclusion ao(f.ctx);
    AmbientOcclusionSettings s;
    s.rays = 0;
    CHECK_THROWS_WITH(ao.prepare(s), Catch::Contains("AmbientOcclusionSettings::rays"));
    s.rays = 4;
    s.method = AoMethod::Voxel;
    CHECK_THROWS_WITH(ao.prepare(s), Catch::Contains("voxels"));
    IndirectLight gi(f.ctx);
    IndirectLightSettings g;
    g.radius = -1.0f;
    CHECK_THROWS_WITH(gi.prepare(g), Catch::Contains("IndirectLightSettings::radius"));
    Composer composer(f.ctx);
    ComposeSettings c;
    c.exposure = 0.0f;
    CHECK_THROWS_WITH(composer.prepare(c), Catch::Contains("ComposeSettings::exposure"));
    HostGBuffer host;
    host.normalEncoding = static_cast<NormalEncoding>(7);
    CHECK_THROWS_WITH(f.gbuffer.prepareAdopt(host), Catch::Contains("HostGBuffer::normalEncoding"));
    CHECK(f.ctx.compiledPrograms() == before);
    CHECK(test::drainGlErrors().empty());
}

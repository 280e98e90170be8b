// Profiler: wall clock on software renderers, non-stalling timestamps otherwise, named debug
// groups and object labels.
#include "gl_fixture.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>

using namespace obscura;

namespace {
Camera floorCamera() { return Camera::perspective({{0, 2, 2}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f); }
} // namespace

TEST_CASE("On llvmpipe passes are timed by glFinish and a steady clock and that time is real", "[profiler]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    if (!ctx.info().softwareRenderer) {
        // On hardware the non-stalling timestamps are the default (next test).
        CHECK(ctx.profiler().clock() == ClockSource::GpuTimestamp);
        return;
    }
    REQUIRE(ctx.profiler().clock() == ClockSource::WallClockFinish);
    GBuffer gbuffer(ctx);
    const Scene scene = test::floorScene(1.0);
    constexpr int frames = 20;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < frames; ++i) gbuffer.render(scene, floorCamera(), {256, 256, true, {}});
    const double wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const auto stats = ctx.profiler().statistics();
    REQUIRE(stats.size() == 1);
    CHECK(stats[0].name == "gbuffer.render");
    CHECK(stats[0].samples == frames);
    CHECK(stats[0].clock == ClockSource::WallClockFinish);
    CHECK(std::string(toString(stats[0].clock)) == "wall_clock_finish");
    CHECK(stats[0].minMs > 0.0);
    CHECK(stats[0].minMs <= stats[0].medianMs);
    CHECK(stats[0].medianMs <= stats[0].maxMs);
    // The passes ran inside the measured loop: their sum cannot exceed it. And glFinish
    // makes each pass include its rasterization, which is most of the loop's time (the rest
    // is validation and state save/restore on the CPU): at least half of it here.
    const double passSum = stats[0].meanMs * frames;
    INFO("passes " << passSum << " ms of a " << wallMs << " ms loop");
    CHECK(passSum <= wallMs);
    CHECK(passSum >= 0.5 * wallMs);
    const auto latest = ctx.profiler().latest();
    REQUIRE(latest.size() == 1);
    CHECK(latest[0].ms > 0.0);
}

TEST_CASE("An engine's context times no pass unless it asks, and a software renderer's only when told to stall",
          "[profiler]") {
    // An engine's ContextDesc defaults to Profiling::Off: no queries, no glFinish. Tools ask
    // for Always (HeadlessContext::contextDesc). TimerQueries times only where the timestamps
    // are trustworthy: on llvmpipe, nothing.
    test::GlFixture gl;
    CHECK(ContextDesc{}.profiling == Profiling::Off);
    CHECK(gl.desc().profiling == Profiling::Always);
    const Scene scene = test::floorScene(1.0);
    for (const Profiling mode : {Profiling::Off, Profiling::TimerQueries, Profiling::Always}) {
        ContextDesc desc = gl.desc();
        desc.profiling = mode;
        Context ctx(desc);
        const bool trustworthy = !ctx.info().softwareRenderer && ctx.info().timestampBits > 0;
        const bool expected = mode == Profiling::Always || (mode == Profiling::TimerQueries && trustworthy);
        CAPTURE(static_cast<int>(mode), trustworthy);
        CHECK(ctx.profiler().enabled() == expected);
        GBuffer gbuffer(ctx);
        gbuffer.render(scene, floorCamera(), {32, 32, true, {}});
        CHECK(ctx.profiler().statistics(/*wait=*/true).size() == (expected ? 1u : 0u));
    }
    ContextDesc bad = gl.desc();
    bad.profiling = static_cast<Profiling>(3);
    CHECK_THROWS_WITH(Context(bad), Catch::Contains("ContextDesc::profiling"));
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("GPU timestamp queries are collected without stalling and completely when asked to wait", "[profiler]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    ctx.profiler().setClock(ClockSource::GpuTimestamp);
    GBuffer gbuffer(ctx);
    const Scene scene = test::floorScene(1.0);
    for (int i = 0; i < 25; ++i) {
        gbuffer.render(scene, floorCamera(), {64, 64, true, {}});
        for (const auto& t : ctx.profiler().latest()) CHECK((std::isfinite(t.ms) && t.ms >= 0.0));
    }
    const auto stats = ctx.profiler().statistics(/*wait=*/true);
    REQUIRE(stats.size() == 1);
    CHECK(stats[0].samples == 25);
    CHECK(stats[0].clock == ClockSource::GpuTimestamp);
    CHECK(std::string(toString(stats[0].clock)) == "gpu_timer_query");
    // llvmpipe's timestamps under-report but advance: a pass that draws takes > 0.
    CHECK(stats[0].maxMs > 0.0);
    ctx.profiler().reset();
    CHECK(ctx.profiler().statistics(true).empty());
    ctx.profiler().setEnabled(false);
    gbuffer.render(scene, floorCamera(), {64, 64, true, {}});
    CHECK(ctx.profiler().statistics(true).empty());
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Passes are KHR_debug groups and objects carry the pass names", "[profiler][debug]") {
    test::GlFixture gl(/*debug=*/true);
    struct Groups {
        std::vector<std::string> pushed;
        static void GLAD_API_PTR callback(GLenum, GLenum type, GLuint, GLenum, GLsizei length, const GLchar* message,
                                          const void* user) {
            if (type == GL_DEBUG_TYPE_PUSH_GROUP)
                static_cast<Groups*>(const_cast<void*>(user))->pushed.emplace_back(message, static_cast<std::size_t>(length));
        }
    } groups;
    glDebugMessageCallback(&Groups::callback, &groups);
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    const GBufferView v = gbuffer.render(test::floorScene(1.0), floorCamera(), {16, 16, true, {}});
    gbuffer.positions(v);
    CHECK(groups.pushed == std::vector<std::string>{"gbuffer.render", "gbuffer.positions"});
    char label[64] = {};
    GLsizei length = 0;
    glGetObjectLabel(GL_TEXTURE, v.depth.name, sizeof label, &length, label);
    CHECK(std::string(label) == "gbuffer.depth");
    glGetObjectLabel(GL_TEXTURE, v.directRadiance.name, sizeof label, &length, label);
    CHECK(std::string(label) == "gbuffer.direct");
}

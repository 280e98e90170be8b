// Shader library: lazy compilation of only the permutations used, and compile errors
// reported against the original file and line.
#include "gl_fixture.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

using namespace obscura;

namespace {
bool contains(const std::vector<std::string>& v, const std::string& needle) {
    return std::any_of(v.begin(), v.end(), [&](const std::string& s) { return s.find(needle) != std::string::npos; });
}
} // namespace

TEST_CASE("Only the shader permutations a frame uses are compiled once", "[shaders]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    CHECK(ctx.compiledPrograms().empty());
    GBuffer gbuffer(ctx);
    CHECK(ctx.compiledPrograms().empty());
    const Scene scene = test::quadScene({{{{{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}}}});
    const Camera camera = Camera::perspective({{0, 2, 2}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f);
    const GBufferView view = gbuffer.render(scene, camera, {8, 8, true, {}});
    const auto afterRender = ctx.compiledPrograms();
    REQUIRE(afterRender.size() == 1);
    CHECK(afterRender[0] == "gbuffer/gbuffer.vert.glsl + gbuffer/gbuffer.geom.glsl + gbuffer/gbuffer.frag.glsl "
                            "[HAS_NORMALS]");
    for (int i = 0; i < 3; ++i) gbuffer.render(scene, camera, {8, 8, true, {}});
    CHECK(ctx.compiledPrograms() == afterRender);
    gbuffer.positions(view);
    CHECK(ctx.compiledPrograms().size() == 2);
    CHECK(contains(ctx.compiledPrograms(), "gbuffer/positions.comp.glsl"));
    CHECK_FALSE(contains(ctx.compiledPrograms(), "normals.comp"));
}

TEST_CASE("Compile errors name the original file and line through #include", "[shaders]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    const Scene scene = test::quadScene({{{{{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}}}});
    const Camera camera = Camera::perspective({{0, 2, 2}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f);
    const GBufferView view = gbuffer.render(scene, camera, {8, 8, true, {}});
    ctx.addShaderSource("gbuffer/helpers_broken.glsl", "// line 1\n"
                                                        "float helper() {\n"
                                                        "    return undefinedSymbol;\n" // line 3
                                                        "}\n");
    ctx.addShaderSource("gbuffer/positions.comp.glsl", "layout(local_size_x = 1) in;\n"
                                                        "#include \"helpers_broken.glsl\"\n"
                                                        "void main() { helper(); }\n");
    try {
        gbuffer.positions(view);
        FAIL("a broken shader compiled");
    } catch (const Error& e) {
        INFO(e.what());
        CHECK(e.code() == ErrorCode::ShaderCompile);
        CHECK_THAT(e.what(), Catch::Contains("gbuffer/helpers_broken.glsl:3"));
        CHECK_THAT(e.what(), Catch::Contains("undefinedSymbol"));
    }
    CHECK(test::drainGlErrors().empty());
    ctx.addShaderSource("gbuffer/positions.comp.glsl", "layout(local_size_x = 1) in;\n#include \"missing.glsl\"\n");
    CHECK_THROWS_WITH(gbuffer.positions(view), Catch::Contains("gbuffer/positions.comp.glsl:2") &&
                                                   Catch::Contains("missing.glsl"));
}

TEST_CASE("Memory is allocated on first use and reported by the module", "[shaders][memory]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    CHECK(gbuffer.memoryBytes() == 0);
    CHECK(ctx.liveObjectCount() == 0);
    const Scene scene = test::quadScene({{{{{-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1}}}}});
    const Camera camera = Camera::perspective({{0, 2, 2}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f);
    const GBufferView view = gbuffer.render(scene, camera, {32, 16, true, {}});
    // Targets: 32F depth + 2 x RGBA16F + SRGB8_ALPHA8 = 24 bytes per pixel; the mesh (4
    // positions and 4 normals of 12 bytes, 6 indices of 4 = 120 bytes); one 80-byte light
    // slot (kept even without lights); the 256-byte frame block.
    CHECK(gbuffer.memoryBytes() == 32 * 16 * 24 + 120 + 80 + 256);
    const std::size_t before = gbuffer.memoryBytes();
    gbuffer.positions(view);
    CHECK(gbuffer.memoryBytes() == before + 32 * 16 * 16);
    // Same size again: nothing new is allocated (once the pending timer queries are back in
    // their pool: a GPU that runs behind would otherwise take new ones).
    ctx.profiler().statistics(/*wait=*/true);
    const std::size_t objects = ctx.liveObjectCount();
    gbuffer.render(scene, camera, {32, 16, true, {}});
    gbuffer.positions(view);
    ctx.profiler().statistics(/*wait=*/true);
    CHECK(ctx.liveObjectCount() == objects);
}

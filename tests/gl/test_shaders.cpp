// Shader library: lazy compilation of only the permutations used, compile errors reported
// against the original file and line, and shared GLSL functions run on the driver.
#include "core/sampling.hpp"
#include "frame_checks.hpp"
#include "gl_fixture.hpp"
#include "shaders/common/common_bindings.h"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

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
    // slot (kept even without lights); the 272-byte frame block (common_bindings.h's FrameData).
    CHECK(gbuffer.memoryBytes() == 32 * 16 * 24 + 120 + 80 + sizeof(shader::FrameData));
    CHECK(sizeof(shader::FrameData) == 272);
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

TEST_CASE("The GLSL tangent frame is orthonormal and finite for normals of (0, 0, +-1), signed zeros and 1000 others",
          "[shaders][sampling]") {
    // sampling.glsl's tangentFrame and toFrame as the integrators run them, on the driver: the
    // unit tests check the CPU mirror (core/sampling.hpp), this one the GLSL the integrators use.
    // A frame built by crossing with the z axis would divide by zero at (0, 0, +-1).
    test::GlFixture gl;
    constexpr int kDirections = 16;
    const GLuint program = test::libraryComputeProgram(R"(#include "common/sampling.glsl"
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Normals { vec4 normals[]; };
layout(std430, binding = 1) writeonly buffer Frames { vec4 frames[]; }; // t, b, then the directions
layout(location = 0) uniform uint count;
void main() {
    const uint i = gl_GlobalInvocationID.x;
    if (i >= count) return;
    const vec3 n = normals[i].xyz;
    vec3 t, b;
    tangentFrame(n, t, b);
    const uint at = i * 18u;
    frames[at] = vec4(t, 0.0);
    frames[at + 1u] = vec4(b, 0.0);
    for (uint k = 0u; k < 16u; ++k) frames[at + 2u + k] = vec4(toFrame(cosineHemisphere(hammersley(k, 16u)), n), 0.0);
}
)");
    std::vector<glm::vec4> normals;
    for (const glm::vec3& n : test::tangentFrameNormals()) normals.emplace_back(n, 0.0f);
    GLuint buffers[2];
    glCreateBuffers(2, buffers);
    const std::size_t outputs = normals.size() * (2 + kDirections);
    glNamedBufferStorage(buffers[0], GLsizeiptr(normals.size() * sizeof(glm::vec4)), normals.data(), 0);
    glNamedBufferStorage(buffers[1], GLsizeiptr(outputs * sizeof(glm::vec4)), nullptr, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
    glUseProgram(program);
    glUniform1ui(0, GLuint(normals.size()));
    glDispatchCompute(GLuint((normals.size() + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> frames(outputs);
    glGetNamedBufferSubData(buffers[1], 0, GLsizeiptr(outputs * sizeof(glm::vec4)), frames.data());
    glUseProgram(0);
    glDeleteProgram(program);
    glDeleteBuffers(2, buffers);
    for (std::size_t i = 0; i < normals.size(); ++i) {
        const glm::vec3 n(normals[i]), t(frames[i * 18]), b(frames[i * 18 + 1]);
        CAPTURE(i, n.x, n.y, n.z, t.x, t.y, t.z, b.x, b.y, b.z);
        test::checkTangentFrame(n, t, b);
        // The same frame as the CPU mirror the tests' closed forms use: |s + n.z| >= 1, so a is
        // within an ulp or two, and each component, of size at most 1, is off by a few ulp of 1
        // in either (fused or not): an absolute bound, 1e-6 being 8 ulp of 1.
        glm::vec3 ct, cb;
        detail::tangentFrame(n, ct, cb);
        CHECK(glm::length(t - ct) < 1e-6f);
        CHECK(glm::length(b - cb) < 1e-6f);
        // x t + y b + z n with x^2 + y^2 + z^2 = 1, z >= 0: within (|x| + |y| + |z|)^2 1e-5 <=
        // 3e-5 of unit length squared, so 2e-5 of unit length, and above the plane but for
        // (|x| + |y|) 1e-5 <= 2e-5.
        for (int k = 0; k < kDirections; ++k) {
            const glm::vec3 w(frames[i * 18 + 2 + std::size_t(k)]);
            CAPTURE(k, w.x, w.y, w.z);
            CHECK(std::isfinite(w.x + w.y + w.z));
            CHECK(std::abs(glm::length(w) - 1.0f) < 2e-5f);
            CHECK(glm::dot(w, n) >= -2e-5f);
        }
    }
    CHECK(test::drainGlErrors().empty());
}

// G-buffer in post-process mode: a host's depth (and normals) adopted, and a host's meshes
// drawn from its own buffers and VAO.
#include "gl_fixture.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <vector>

using namespace obscura;
using test::kHalfRelative;

TEST_CASE("Host depth (and normals) are adopted for post-processing", "[gbuffer]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer ours(ctx), host(ctx);
    constexpr int W = 48, H = 40;
    const Camera camera = Camera::perspective({{1, 2, 4}, {0, 0.5f, 0}, {0, 1, 0}}, 1.0f, 1.2f, 0.1f, 50.0f,
                                              DepthMode::Reversed);
    const GBufferView rendered = ours.render(test::cornerScene(false), camera, {W, H, false, {}});
    const Image expected = readTexture(ctx, rendered.normal);

    SECTION("normals reconstructed from depth alone") {
        HostGBuffer in;
        in.depth = rendered.depth;
        const GBufferView adopted = host.adopt(in, camera);
        CHECK(adopted.depth.name == rendered.depth.name);
        const Image n = readTexture(ctx, adopted.normal);
        const Image p = readTexture(ctx, ours.positions(rendered));
        // A pixel is interior when its 3x3 neighbourhood is geometry with one face normal: the
        // one-sided differences then stay on that plane. Their error is the float error of the
        // positions (relative ~1e-7, i.e. ~5e-7 units here) over a pixel step (>= 0.05 units
        // here): ~1e-5, far below the half-float storage of the result (2 half ulps, 1e-3).
        const auto sameNormal = [&](int x, int y) {
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if (expected.at(x + dx, y + dy, 3) == 0.0f ||
                        test::texel3(expected, x + dx, y + dy) != test::texel3(expected, x, y))
                        return false;
            return true;
        };
        int interior = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                // Alpha: 0 on background; on geometry the pixel's normal error in units of
                // normalError, at least 1 (test_depth_normals.cpp checks the bound).
                CHECK((n.at(x, y, 3) == 0.0f) == (expected.at(x, y, 3) == 0.0f));
                if (expected.at(x, y, 3) == 0.0f) continue;
                CHECK(n.at(x, y, 3) >= 1.0f);
                const glm::dvec3 got = test::texel3(n, x, y);
                // Everywhere: unit length, facing the camera.
                CHECK(std::abs(glm::length(got) - 1.0) < 2 * kHalfRelative);
                CHECK(glm::dot(got, -test::texel3(p, x, y)) >= 0.0);
                if (x == 0 || y == 0 || x == W - 1 || y == H - 1 || !sameNormal(x, y)) continue;
                ++interior;
                CHECK(glm::length(got - test::texel3(expected, x, y)) < 4 * kHalfRelative);
            }
        CHECK(interior > W * H / 3);
    }
    SECTION("world-space normals in an RGBA8 texture") {
        const glm::dmat3 toWorld = glm::transpose(glm::dmat3(camera.view));
        std::vector<std::uint8_t> bytes(static_cast<std::size_t>(W * H * 4));
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const glm::dvec3 w = toWorld * test::texel3(expected, x, y);
                for (int c = 0; c < 3; ++c)
                    bytes[static_cast<std::size_t>(((H - 1 - y) * W + x) * 4 + c)] =
                        static_cast<std::uint8_t>(std::lround((w[c] * 0.5 + 0.5) * 255));
            }
        GLuint tex = 0;
        glCreateTextures(GL_TEXTURE_2D, 1, &tex);
        glTextureStorage2D(tex, 1, GL_RGBA8, W, H);
        glTextureSubImage2D(tex, 0, 0, 0, W, H, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
        HostGBuffer in;
        in.depth = rendered.depth;
        in.normal = {tex, GL_RGBA8, W, H};
        in.normalSpace = NormalSpace::World;
        in.normalEncoding = NormalEncoding::Unsigned;
        const Image n = readTexture(ctx, host.adopt(in, camera).normal);
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                if (expected.at(x, y, 3) == 0.0f) continue;
                // 8-bit encoding: half a step (1/255) per component.
                CHECK(glm::length(test::texel3(n, x, y) - test::texel3(expected, x, y)) < 2.0 / 255 * std::sqrt(3.0));
            }
        glDeleteTextures(1, &tex);
    }
    SECTION("normals already in the view's contract are read in place") {
        // Another GBuffer's view normals (RGBA16F, view space, alpha 1): the identity, which
        // adopt() converted again on every call before (a pass over every pixel and a texture
        // of the view's size). In place: the view names the host's texture, no conversion
        // program is compiled, the GBuffer holds no memory, and the AO is the rendered view's,
        // value for value.
        HostGBuffer in;
        in.depth = rendered.depth;
        in.normal = rendered.normal;
        in.normalEncoding = NormalEncoding::ViewContract;
        const GBufferView adopted = host.adopt(in, camera);
        CHECK(adopted.normal.name == rendered.normal.name);
        CHECK(adopted.normalError == rendered.normalError);
        CHECK(host.memoryBytes() == 0);
        for (const std::string& program : ctx.compiledPrograms()) CHECK(program.find("normals.comp") == std::string::npos);
        AmbientOcclusion ao(ctx);
        AmbientOcclusionSettings settings;
        settings.radius = 1.0f;
        const Image fromRendered = readTexture(ctx, ao.run(rendered, settings).ao);
        const Image fromAdopted = readTexture(ctx, ao.run(adopted, settings).ao);
        CHECK(fromAdopted.pixels == fromRendered.pixels);
        // Converted first, then in place: the conversion's texture is freed.
        in.normalEncoding = NormalEncoding::Signed;
        host.adopt(in, camera);
        const std::size_t converted = host.memoryBytes();
        in.normalEncoding = NormalEncoding::ViewContract;
        host.adopt(in, camera);
        CHECK(converted - host.memoryBytes() == std::size_t(W) * H * 8); // one RGBA16F texture of the view's size
    }
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Host meshes in the host's buffers and VAO render like uploaded meshes", "[gbuffer]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    const Camera camera = Camera::perspective({{0.5f, 1, 3}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 20.0f);
    const auto data = test::quadMesh({{{-1, -1, 0}, {1, -1, 0.5}, {1, 1, 0}, {-1, 1, -0.5}}});
    Scene cpu = test::quadScene({});
    cpu.meshes.push_back({data, glm::translate(glm::mat4(1), {0.1f, 0, 0}), 0, "quad"});
    const Image expected = readTexture(ctx, gbuffer.render(cpu, camera, {32, 32, false, {}}).normal);

    // Interleaved position+normal in one host buffer, 16-bit indices in another.
    std::vector<float> interleaved;
    for (std::size_t i = 0; i < 4; ++i)
        for (const glm::vec3& v : {data->positions[i], data->normals[i]}) interleaved.insert(interleaved.end(), {v.x, v.y, v.z});
    const std::uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    GLuint buffers[2];
    glCreateBuffers(2, buffers);
    glNamedBufferData(buffers[0], static_cast<GLsizeiptr>(interleaved.size() * sizeof(float)), interleaved.data(), GL_STATIC_DRAW);
    glNamedBufferData(buffers[1], sizeof indices, indices, GL_STATIC_DRAW);

    MeshRef ref;
    ref.count = 6;
    ref.indexType = GL_UNSIGNED_SHORT;
    ref.model = glm::translate(glm::mat4(1), {0.1f, 0, 0});
    SECTION("streams") {
        ref.position = {buffers[0], 0, 24, 3, GL_FLOAT, false};
        ref.normal = {buffers[0], 12, 24, 3, GL_FLOAT, false};
        ref.indexBuffer = buffers[1];
    }
    GLuint vao = 0;
    SECTION("host VAO with its own attribute locations") {
        glCreateVertexArrays(1, &vao);
        glVertexArrayVertexBuffer(vao, 3, buffers[0], 0, 24);
        glVertexArrayAttribFormat(vao, 5, 3, GL_FLOAT, GL_FALSE, 0);
        glVertexArrayAttribFormat(vao, 7, 3, GL_FLOAT, GL_FALSE, 12);
        glVertexArrayAttribBinding(vao, 5, 3);
        glVertexArrayAttribBinding(vao, 7, 3);
        glEnableVertexArrayAttrib(vao, 5);
        glEnableVertexArrayAttrib(vao, 7);
        glVertexArrayElementBuffer(vao, buffers[1]);
        ref.vao = vao;
        ref.positionLocation = 5;
        ref.normalLocation = 7;
    }
    Scene host = test::quadScene({});
    host.meshRefs.push_back(ref);
    const Image got = readTexture(ctx, gbuffer.render(host, camera, {32, 32, false, {}}).normal);
    CHECK(got.pixels == expected.pixels);
    if (vao) glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(2, buffers);
    CHECK(test::drainGlErrors().empty());
}

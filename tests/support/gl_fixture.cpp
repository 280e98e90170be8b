#include "gl_fixture.hpp"

#include "core/shader_source.hpp"

#include <EGL/egl.h>
#include <catch2/catch.hpp>

#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace obscura::test {
namespace {

GLADapiproc loadHostGl(void*, const char* name) { return reinterpret_cast<GLADapiproc>(eglGetProcAddress(name)); }

headless::HeadlessDesc headlessDesc(bool debug) {
    headless::HeadlessDesc d;
    d.debug = debug;
    return d;
}

} // namespace

GlFixture::GlFixture(bool debug) : GlFixture(headlessDesc(debug)) {}

GlFixture::GlFixture(const headless::HeadlessDesc& desc) : egl_(desc) {
    if (!gladLoadGLUserPtr(loadHostGl, nullptr)) throw std::runtime_error("test host: gladLoadGL failed");
}

std::set<std::string> liveGlObjects(unsigned limit) {
    std::set<std::string> live;
    for (GLuint n = 1; n <= limit; ++n) {
        if (glIsTexture(n)) live.insert("texture " + std::to_string(n));
        if (glIsBuffer(n)) live.insert("buffer " + std::to_string(n));
        if (glIsFramebuffer(n)) live.insert("framebuffer " + std::to_string(n));
        if (glIsVertexArray(n)) live.insert("vertex array " + std::to_string(n));
        if (glIsSampler(n)) live.insert("sampler " + std::to_string(n));
        if (glIsQuery(n)) live.insert("query " + std::to_string(n));
        if (glIsProgram(n)) live.insert("program " + std::to_string(n));
        if (glIsShader(n)) live.insert("shader " + std::to_string(n));
        if (glIsRenderbuffer(n)) live.insert("renderbuffer " + std::to_string(n));
    }
    return live;
}

std::vector<unsigned> drainGlErrors() {
    std::vector<unsigned> errors;
    for (GLenum e = glGetError(); e != GL_NO_ERROR && errors.size() < 64; e = glGetError()) errors.push_back(e);
    return errors;
}

namespace {

GLuint compiledShader(GLenum kind, const char* source) {
    const GLuint shader = glCreateShader(kind);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    REQUIRE(ok == GL_TRUE);
    return shader;
}

} // namespace

GLuint hostRgbTexture(const Image& image, GLenum format, const std::function<glm::vec3(std::size_t, glm::vec3)>& map) {
    std::vector<float> rows(std::size_t(image.width) * image.height * 4);
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const glm::vec3 v = map(std::size_t(y) * image.width + x, {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)});
            const std::size_t i = (std::size_t(image.height - 1 - y) * image.width + x) * 4; // GL rows bottom up
            for (int c = 0; c < 3; ++c) rows[i + c] = v[c];
            rows[i + 3] = 1.0f;
        }
    GLuint texture = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &texture);
    glTextureStorage2D(texture, 1, format, image.width, image.height);
    glTextureSubImage2D(texture, 0, 0, 0, image.width, image.height, GL_RGBA, GL_FLOAT, rows.data());
    return texture;
}

GLuint hostNormalTexture(const Image& normals, const Camera& camera, GLenum format, NormalSpace space) {
    const glm::mat3 toWorld = glm::transpose(glm::mat3(camera.view));
    return hostRgbTexture(normals, format, [&](std::size_t, glm::vec3 n) {
        return (space == NormalSpace::World ? toWorld * n : n) * 0.5f + 0.5f;
    });
}

HostGBuffer unsignedNormalHost(GLuint depth, GLuint normal, GLenum format, NormalSpace space, int width, int height) {
    HostGBuffer host;
    host.depth = {depth, GL_DEPTH_COMPONENT32F, width, height};
    host.normal = {normal, format, width, height};
    host.normalSpace = space;
    host.normalEncoding = NormalEncoding::Unsigned;
    return host;
}

namespace {

GLuint linkedProgram(const char* vertex, const char* fragment) {
    const GLuint vs = compiledShader(GL_VERTEX_SHADER, vertex), fs = compiledShader(GL_FRAGMENT_SHADER, fragment);
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    REQUIRE(linked == GL_TRUE);
    return program;
}

// A host's depth pass: a new depth texture of `format`, cleared to `clear`, and `draw` run into it
// with `program`, the depth test `func`, and the clip control `origin`, `depthMode`. Sets the GL
// state the pass needs explicitly and leaves the defaults, except the viewport, which stays the
// pass's (test contexts only).
// `colour`, if not 0, is attached as the pass's one draw buffer and cleared to 0.
GLuint hostDepthPass(int width, int height, GLenum format, GLuint program, float clear, GLenum func, GLenum origin,
                     GLenum depthMode, const std::function<void()>& draw, GLuint colour = 0) {
    GLuint target = 0, fbo = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &target);
    glTextureStorage2D(target, 1, format, width, height);
    glCreateFramebuffers(1, &fbo);
    glNamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, target, 0);
    if (colour) glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, colour, 0);
    glNamedFramebufferDrawBuffer(fbo, colour ? GL_COLOR_ATTACHMENT0 : GL_NONE);
    REQUIRE(glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glViewport(0, 0, width, height);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_CULL_FACE);
    glDisable(GL_RASTERIZER_DISCARD);
    glDisable(GL_DEPTH_CLAMP);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthRange(0.0, 1.0);
    glClipControl(origin, depthMode);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(func);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &clear); // after the state that limits clears
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    if (colour) glClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero);
    glUseProgram(program);
    draw();
    glUseProgram(0);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    return target;
}

} // namespace

GLuint copyDepthAsHost(GLuint depth, int width, int height, GLenum format) {
    const GLuint program = linkedProgram(R"(#version 450
void main() { gl_Position = vec4(vec2((gl_VertexID << 1) & 2, gl_VertexID & 2) * 2.0 - 1.0, 0.0, 1.0); })",
                                         R"(#version 450
layout(binding = 0) uniform sampler2D source;
void main() { gl_FragDepth = texelFetch(source, ivec2(gl_FragCoord.xy), 0).r; })");
    GLuint vao = 0;
    glCreateVertexArrays(1, &vao);
    const GLuint target = hostDepthPass(width, height, format, program, 1.0f, GL_ALWAYS, GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE, [&] {
        glBindTextureUnit(0, depth);
        glBindVertexArray(vao);
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glBindVertexArray(0);
        glBindTextureUnit(0, 0);
    });
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(program);
    return target;
}

GLuint rasterizeDepthAsHost(const Scene& scene, const Camera& camera, int width, int height, GLenum format,
                            GLenum clipOrigin) {
    std::vector<glm::vec3> world; // every mesh's triangles in world space, as a host's vertex shader would see them
    for (const Mesh& mesh : scene.meshes) {
        const MeshData& data = *mesh.data;
        const std::size_t count = data.indices.empty() ? data.positions.size() : data.indices.size();
        for (std::size_t i = 0; i < count; ++i) {
            const glm::vec3 p = data.positions[data.indices.empty() ? i : data.indices[i]];
            world.push_back(glm::vec3(mesh.model * glm::vec4(p, 1.0f)));
        }
    }
    REQUIRE(scene.meshRefs.empty());
    const GLuint program = linkedProgram(R"(#version 450
layout(location = 0) in vec3 position;
layout(location = 0) uniform mat4 viewProjection;
void main() { gl_Position = viewProjection * vec4(position, 1.0); })",
                                         "#version 450\nvoid main() {}");
    const glm::mat4 viewProjection = camera.projection * camera.view;
    glProgramUniformMatrix4fv(program, 0, 1, GL_FALSE, &viewProjection[0][0]);
    GLuint buffer = 0, vao = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, GLsizeiptr(world.size() * sizeof(glm::vec3)), world.data(), 0);
    glCreateVertexArrays(1, &vao);
    glVertexArrayVertexBuffer(vao, 0, buffer, 0, sizeof(glm::vec3));
    glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vao, 0, 0);
    glEnableVertexArrayAttrib(vao, 0);
    const bool reversed = analyzeProjection(camera).reversedZ;
    const GLuint target = hostDepthPass(
        width, height, format, program, reversed ? 0.0f : 1.0f, reversed ? GL_GREATER : GL_LESS, clipOrigin,
        camera.clipDepth == ClipDepth::ZeroToOne ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE, [&] {
            glBindVertexArray(vao);
            glDrawArrays(GL_TRIANGLES, 0, GLsizei(world.size()));
            glBindVertexArray(0);
        });
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &buffer);
    glDeleteProgram(program);
    return target;
}

HostShadingBuffers rasterizeShadingNormalsAsHost(const Scene& scene, const Camera& camera, int width, int height) {
    std::vector<glm::vec3> vertices; // world position and world normal of each triangle corner, interleaved
    for (const Mesh& mesh : scene.meshes) {
        const MeshData& data = *mesh.data;
        REQUIRE(data.normals.size() == data.positions.size());
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(mesh.model)));
        const std::size_t count = data.indices.empty() ? data.positions.size() : data.indices.size();
        for (std::size_t i = 0; i < count; ++i) {
            const std::size_t v = data.indices.empty() ? i : data.indices[i];
            vertices.push_back(glm::vec3(mesh.model * glm::vec4(data.positions[v], 1.0f)));
            vertices.push_back(normalMatrix * data.normals[v]);
        }
    }
    REQUIRE(scene.meshRefs.empty());
    const GLuint program = linkedProgram(R"(#version 450
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) uniform mat4 viewProjection;
layout(location = 1) uniform mat4 view;
out vec3 viewNormal;
void main() {
    viewNormal = mat3(view) * normal;
    gl_Position = viewProjection * vec4(position, 1.0);
})",
                                         R"(#version 450
in vec3 viewNormal;
layout(location = 0) out vec4 outNormal;
void main() { outNormal = vec4(normalize(viewNormal), 1.0); })");
    const glm::mat4 viewProjection = camera.projection * camera.view;
    glProgramUniformMatrix4fv(program, 0, 1, GL_FALSE, &viewProjection[0][0]);
    glProgramUniformMatrix4fv(program, 1, 1, GL_FALSE, &camera.view[0][0]);
    GLuint buffer = 0, vao = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferStorage(buffer, GLsizeiptr(vertices.size() * sizeof(glm::vec3)), vertices.data(), 0);
    glCreateVertexArrays(1, &vao);
    glVertexArrayVertexBuffer(vao, 0, buffer, 0, 2 * sizeof(glm::vec3));
    for (GLuint attribute : {0u, 1u}) {
        glVertexArrayAttribFormat(vao, attribute, 3, GL_FLOAT, GL_FALSE, attribute * GLuint(sizeof(glm::vec3)));
        glVertexArrayAttribBinding(vao, attribute, 0);
        glEnableVertexArrayAttrib(vao, attribute);
    }
    HostShadingBuffers out;
    glCreateTextures(GL_TEXTURE_2D, 1, &out.normal);
    glTextureStorage2D(out.normal, 1, GL_RGBA16F, width, height);
    const bool reversed = analyzeProjection(camera).reversedZ;
    out.depth = hostDepthPass(
        width, height, GL_DEPTH_COMPONENT32F, program, reversed ? 0.0f : 1.0f, reversed ? GL_GREATER : GL_LESS,
        GL_LOWER_LEFT, camera.clipDepth == ClipDepth::ZeroToOne ? GL_ZERO_TO_ONE : GL_NEGATIVE_ONE_TO_ONE,
        [&] {
            glBindVertexArray(vao);
            glDrawArrays(GL_TRIANGLES, 0, GLsizei(vertices.size() / 2));
            glBindVertexArray(0);
        },
        out.normal);
    glDeleteVertexArrays(1, &vao);
    glDeleteBuffers(1, &buffer);
    glDeleteProgram(program);
    return out;
}

GLuint libraryComputeProgram(const std::string& source) {
    namespace fs = std::filesystem;
    const std::string self = "test/library_compute.comp.glsl";
    const detail::ResolvedSource resolved =
        detail::resolveIncludes(self, [&](const std::string& path) -> std::optional<std::string> {
            if (path == self) return source;
            std::ifstream in(fs::path(OBSCURA_SHADER_DIR) / path);
            if (!in) return std::nullopt;
            std::stringstream text;
            text << in.rdbuf();
            return text.str();
        });
    const std::string text = "#version 450 core\n" + resolved.text;
    const char* chars = text.c_str();
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &chars, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    std::string log(4096, '\0');
    glGetShaderInfoLog(shader, GLsizei(log.size()), nullptr, log.data());
    INFO(detail::mapShaderLog(log.c_str(), resolved.files));
    REQUIRE(ok == GL_TRUE);
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    REQUIRE(ok == GL_TRUE);
    return program;
}

void overrideShader(Context& ctx, const std::string& file, const std::string& call, const std::string& replacement,
                    const std::string& prelude) {
    overrideShaders(ctx, {{file, call, replacement, prelude}});
}

void overrideShaders(Context& ctx, const std::vector<ShaderEdit>& edits) {
    namespace fs = std::filesystem;
    const fs::path root = OBSCURA_SHADER_DIR;
    std::size_t applied = 0;
    for (const auto& entry : fs::recursive_directory_iterator(root)) {
        if (!entry.is_regular_file()) continue;
        std::ifstream in(entry.path());
        std::stringstream text;
        text << in.rdbuf();
        std::string source = text.str();
        const std::string path = fs::relative(entry.path(), root).generic_string();
        for (const ShaderEdit& edit : edits) {
            if (path != edit.file) continue;
            const auto at = source.find(edit.call);
            REQUIRE(at != std::string::npos);
            source.replace(at, edit.call.size(), edit.replacement);
            const auto main = source.find("void main()");
            if (!edit.prelude.empty()) {
                REQUIRE(main != std::string::npos);
                source.insert(main, edit.prelude);
            }
            ++applied;
        }
        ctx.addShaderSource(path, source);
    }
    REQUIRE(applied == edits.size());
}

} // namespace obscura::test

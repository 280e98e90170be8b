#include "host_engine.hpp"

#include "obscura/error.hpp"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

namespace obscura::examples {
namespace {

constexpr int kMaxLights = 8;

// One vertex of the engine's single buffer: world position and normal, material.
struct Vertex {
    glm::vec3 position, normal, albedo, emission;
};

const char* kVertexShader = R"(#version 450 core
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec3 albedo;
layout(location = 3) in vec3 emission;
layout(location = 0) uniform mat4 viewProjection;
layout(location = 1) uniform mat4 view;
out Surface { vec3 world; vec3 worldNormal; vec3 viewNormal; vec3 albedo; vec3 emission; } v;
void main() {
    v.world = position;
    v.worldNormal = normal;
    v.viewNormal = mat3(view) * normal;
    v.albedo = albedo;
    v.emission = emission;
    gl_Position = viewProjection * vec4(position, 1.0);
})";

// Lambert shading by point, spot and directional lights (area lights as points of their
// power), unshadowed: the engine's lit image. Writes through GL_FRAMEBUFFER_SRGB, so that the
// albedo target stores sRGB.
const char* kFragmentShader = R"(#version 450 core
in Surface { vec3 world; vec3 worldNormal; vec3 viewNormal; vec3 albedo; vec3 emission; } v;
layout(location = 0) out vec4 outNormal;
layout(location = 1) out vec4 outAlbedo;
layout(location = 2) out vec4 outLit;
layout(location = 2) uniform int lightCount;
layout(location = 3) uniform vec4 lightPosition[8];  // xyz, w: 0 point, 1 spot, 2 directional
layout(location = 11) uniform vec4 lightDirection[8]; // xyz: where it shines, w: cos(outer)
layout(location = 19) uniform vec4 lightPower[8];     // rgb: W/sr (irradiance for directional), w: cos(inner)
void main() {
    vec3 n = normalize(v.worldNormal);
    vec3 e = vec3(0.0);
    for (int i = 0; i < lightCount; ++i) {
        vec3 l = -lightDirection[i].xyz;
        float falloff = 1.0;
        if (lightPosition[i].w != 2.0) {
            const vec3 d = lightPosition[i].xyz - v.world;
            l = normalize(d);
            falloff = 1.0 / max(dot(d, d), 1e-12);
            if (lightPosition[i].w == 1.0)
                falloff *= smoothstep(lightDirection[i].w, lightPower[i].w, dot(-l, lightDirection[i].xyz));
        }
        e += lightPower[i].rgb * falloff * max(dot(n, l), 0.0);
    }
    outNormal = vec4(normalize(v.viewNormal), 1.0);
    outAlbedo = vec4(v.albedo, 1.0);
    outLit = vec4(v.albedo / 3.14159265 * e + v.emission, 1.0);
})";

GLuint compile(GLenum stage, const char* source) {
    const GLuint shader = glCreateShader(stage);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    GLint ok = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(shader, sizeof log, nullptr, log);
        throw Error(ErrorCode::ShaderCompile, std::string("host engine shader: ") + log);
    }
    return shader;
}

GLuint texture(GLenum format, int width, int height) {
    GLuint t = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &t);
    glTextureStorage2D(t, 1, format, width, height);
    return t;
}

// The normal of each triangle corner, as a triangle list: the mesh's own vertex normals, or
// else smooth ones, as a modelling tool makes them: the area-weighted normals of the faces
// that share the corner's position and turn less than 45 degrees from its own face (so that
// a box keeps its edges). `deviation` gets the largest angle between a corner's normal and
// its face's.
std::vector<glm::vec3> cornerNormals(const MeshData& mesh, float& deviation) {
    const std::size_t count = mesh.indices.empty() ? mesh.positions.size() : mesh.indices.size();
    const auto at = [&](std::size_t i) { return mesh.indices.empty() ? i : std::size_t(mesh.indices[i]); };
    std::vector<glm::vec3> faces(count / 3);
    const auto key = [](const glm::vec3& p) { return std::array<float, 3>{p.x, p.y, p.z}; };
    std::map<std::array<float, 3>, std::vector<std::size_t>> facesAt; // faces around each position
    for (std::size_t f = 0; f < faces.size(); ++f) {
        const glm::vec3 a = mesh.positions[at(3 * f)], b = mesh.positions[at(3 * f + 1)], c = mesh.positions[at(3 * f + 2)];
        faces[f] = glm::cross(b - a, c - a);
        for (const glm::vec3& p : {a, b, c}) facesAt[key(p)].push_back(f);
    }
    std::vector<glm::vec3> normals(faces.size() * 3);
    for (std::size_t i = 0; i < normals.size(); ++i) {
        const glm::vec3 own = glm::length(faces[i / 3]) > 0.0f ? glm::normalize(faces[i / 3]) : glm::vec3(0, 1, 0);
        glm::vec3 n(0.0f);
        if (!mesh.normals.empty()) n = mesh.normals[at(i)];
        else
            for (std::size_t g : facesAt[key(mesh.positions[at(i)])])
                if (glm::dot(glm::normalize(faces[g]), own) > 0.7071f) n += faces[g];
        normals[i] = glm::length(n) > 0.0f ? glm::normalize(n) : own;
        deviation = std::max(deviation, std::acos(std::clamp(glm::dot(own, normals[i]), -1.0f, 1.0f)));
    }
    return normals;
}

template <typename T>
std::string line(const char* name, const T* values, int count) {
    std::ostringstream out;
    out << name;
    for (int i = 0; i < count; ++i) out << ' ' << values[i];
    return out.str();
}

std::string integers(const char* name, GLenum pname, int count = 1) {
    GLint v[4] = {};
    glGetIntegerv(pname, v);
    return line(name, v, count);
}

std::string floats(const char* name, GLenum pname, int count = 1) {
    GLfloat v[4] = {};
    glGetFloatv(pname, v);
    return line(name, v, count);
}

std::string enabled(const char* name, GLenum cap) { return std::string(name) + (glIsEnabled(cap) ? " on" : " off"); }

} // namespace

HostEngine::HostEngine(const assets::LoadedScene& scene, int width, int height)
    : width_(width), height_(height), scene_(scene.scene) {
    std::vector<Vertex> vertices;
    float deviation = 0.0f;
    for (const Mesh& mesh : scene_.meshes) {
        const MeshData& data = *mesh.data;
        const std::vector<glm::vec3> normals = cornerNormals(data, deviation);
        const glm::mat3 normalMatrix = glm::transpose(glm::inverse(glm::mat3(mesh.model)));
        const Material& m = scene_.materials[mesh.material];
        for (std::size_t i = 0; i < normals.size(); ++i) {
            const std::size_t v = data.indices.empty() ? i : data.indices[i];
            vertices.push_back({glm::vec3(mesh.model * glm::vec4(data.positions[v], 1.0f)),
                                glm::normalize(normalMatrix * normals[i]), m.albedo, m.emission});
        }
    }
    normalDeviation_ = std::min(2.0f * deviation, 1.5707963f);
    vertexCount_ = static_cast<GLsizei>(vertices.size());
    glCreateBuffers(1, &vertices_);
    glNamedBufferStorage(vertices_, GLsizeiptr(std::max<std::size_t>(1, vertices.size()) * sizeof(Vertex)),
                         vertices.empty() ? nullptr : vertices.data(), 0);
    glCreateVertexArrays(1, &vao_);
    glVertexArrayVertexBuffer(vao_, 0, vertices_, 0, sizeof(Vertex));
    for (GLuint a = 0; a < 4; ++a) {
        glVertexArrayAttribFormat(vao_, a, 3, GL_FLOAT, GL_FALSE, a * GLuint(sizeof(glm::vec3)));
        glVertexArrayAttribBinding(vao_, a, 0);
        glEnableVertexArrayAttrib(vao_, a);
    }
    const GLuint vs = compile(GL_VERTEX_SHADER, kVertexShader), fs = compile(GL_FRAGMENT_SHADER, kFragmentShader);
    program_ = glCreateProgram();
    glAttachShader(program_, vs);
    glAttachShader(program_, fs);
    glLinkProgram(program_);
    glDeleteShader(vs);
    glDeleteShader(fs);

    depth_ = texture(GL_DEPTH_COMPONENT32F, width, height);
    normal_ = texture(GL_RGBA16F, width, height);
    albedo_ = texture(GL_SRGB8_ALPHA8, width, height);
    lit_ = texture(GL_RGBA16F, width, height);
    glCreateFramebuffers(1, &gbufferFbo_);
    glNamedFramebufferTexture(gbufferFbo_, GL_DEPTH_ATTACHMENT, depth_, 0);
    const GLuint targets[3] = {normal_, albedo_, lit_};
    for (GLenum i = 0; i < 3; ++i) glNamedFramebufferTexture(gbufferFbo_, GL_COLOR_ATTACHMENT0 + i, targets[i], 0);
    const GLenum drawBuffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    glNamedFramebufferDrawBuffers(gbufferFbo_, 3, drawBuffers);
    display_ = texture(GL_RGBA8, width, height); // display-encoded values, as Composer::compose gives them
    glCreateFramebuffers(1, &displayFbo_);
    glNamedFramebufferTexture(displayFbo_, GL_COLOR_ATTACHMENT0, display_, 0);
    stateTexture_ = texture(GL_RGBA8, 4, 4);

    // The scene's lights, as the fragment shader takes them.
    glm::vec4 position[kMaxLights] = {}, direction[kMaxLights] = {}, power[kMaxLights] = {};
    for (const Light& l : scene_.lights) {
        if (lightCount_ == kMaxLights) break;
        const int i = lightCount_++;
        float scale = l.intensity; // W/sr, or W/m^2 for directional lights
        if (l.type == LightType::Rect) scale *= l.size.x * l.size.y;          // radiance over the area
        if (l.type == LightType::Sphere) scale *= 3.14159265f * l.radius * l.radius;
        const float kind = l.type == LightType::Directional ? 2.0f : l.type == LightType::Spot ? 1.0f : 0.0f;
        position[i] = glm::vec4(l.position, kind);
        direction[i] = glm::vec4(glm::normalize(l.direction), std::cos(l.outerAngle));
        power[i] = glm::vec4(l.color * scale, std::cos(l.innerAngle));
    }
    glProgramUniform1i(program_, 2, lightCount_);
    glProgramUniform4fv(program_, 3, kMaxLights, &position[0][0]);
    glProgramUniform4fv(program_, 11, kMaxLights, &direction[0][0]);
    glProgramUniform4fv(program_, 19, kMaxLights, &power[0][0]);
}

HostEngine::~HostEngine() {
    const GLuint textures[] = {depth_, normal_, albedo_, lit_, display_, stateTexture_};
    glDeleteTextures(6, textures);
    const GLuint framebuffers[] = {gbufferFbo_, displayFbo_};
    glDeleteFramebuffers(2, framebuffers);
    glDeleteBuffers(1, &vertices_);
    glDeleteVertexArrays(1, &vao_);
    glDeleteProgram(program_);
}

void HostEngine::renderGBuffer(const Camera& camera) {
    glBindFramebuffer(GL_FRAMEBUFFER, gbufferFbo_);
    glViewport(0, 0, width_, height_);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE); // reversed-Z: near -> 1, far -> 0
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);
    glDepthMask(GL_TRUE);
    glEnable(GL_FRAMEBUFFER_SRGB); // the albedo target stores sRGB
    const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f}, opaqueBlack[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    glClearNamedFramebufferfv(gbufferFbo_, GL_DEPTH, 0, zero);
    glClearNamedFramebufferfv(displayFbo_, GL_COLOR, 0, opaqueBlack); // the post-process stage draws its RGB
    for (int i = 0; i < 3; ++i) glClearNamedFramebufferfv(gbufferFbo_, GL_COLOR, i, zero);
    const glm::mat4 viewProjection = camera.projection * camera.view;
    glProgramUniformMatrix4fv(program_, 0, 1, GL_FALSE, &viewProjection[0][0]);
    glProgramUniformMatrix4fv(program_, 1, 1, GL_FALSE, &camera.view[0][0]);
    glUseProgram(program_);
    glBindVertexArray(vao_);
    glDrawArrays(GL_TRIANGLES, 0, vertexCount_);
}

void HostEngine::setOwnState() {
    glUseProgram(program_);
    glBindVertexArray(vao_);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, gbufferFbo_);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, displayFbo_);
    glViewport(3, 5, width_ / 2, height_ / 3);
    glEnable(GL_SCISSOR_TEST);
    glScissor(1, 2, 7, 9);
    glDepthFunc(GL_GEQUAL);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE);
    glBlendEquation(GL_FUNC_REVERSE_SUBTRACT);
    glBlendColor(0.25f, 0.5f, 0.75f, 1.0f);
    glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
    glFrontFace(GL_CW);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.5f, 3.0f);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_EQUAL, 3, 0x0F);
    glActiveTexture(GL_TEXTURE3);
    glBindTexture(GL_TEXTURE_2D, stateTexture_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glLineWidth(1.0f);
}

void HostEngine::resetOwnState() {
    glUseProgram(0);
    glBindVertexArray(0);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, width_, height_);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glBlendFunc(GL_ONE, GL_ZERO);
    glBlendEquation(GL_FUNC_ADD);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_CULL_FACE);
    glFrontFace(GL_CCW);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDisable(GL_STENCIL_TEST);
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
}

std::vector<std::string> HostEngine::ownState() const {
    return {integers("program", GL_CURRENT_PROGRAM),
            integers("vertex array", GL_VERTEX_ARRAY_BINDING),
            integers("draw framebuffer", GL_DRAW_FRAMEBUFFER_BINDING),
            integers("read framebuffer", GL_READ_FRAMEBUFFER_BINDING),
            integers("viewport", GL_VIEWPORT, 4),
            integers("scissor box", GL_SCISSOR_BOX, 4),
            enabled("scissor test", GL_SCISSOR_TEST),
            enabled("depth test", GL_DEPTH_TEST),
            integers("depth func", GL_DEPTH_FUNC),
            integers("depth mask", GL_DEPTH_WRITEMASK),
            enabled("blend", GL_BLEND),
            integers("blend src, dst", GL_BLEND_SRC_RGB) + " " + integers("", GL_BLEND_DST_RGB),
            integers("blend equation", GL_BLEND_EQUATION_RGB),
            floats("blend colour", GL_BLEND_COLOR, 4),
            integers("colour mask", GL_COLOR_WRITEMASK, 4),
            enabled("cull face", GL_CULL_FACE),
            integers("cull face mode", GL_CULL_FACE_MODE),
            integers("front face", GL_FRONT_FACE),
            enabled("polygon offset fill", GL_POLYGON_OFFSET_FILL),
            floats("polygon offset factor", GL_POLYGON_OFFSET_FACTOR) + floats(" units", GL_POLYGON_OFFSET_UNITS),
            enabled("stencil test", GL_STENCIL_TEST),
            integers("stencil func, ref, mask", GL_STENCIL_FUNC) + integers("", GL_STENCIL_REF) +
                integers("", GL_STENCIL_VALUE_MASK),
            integers("clip origin, depth mode", GL_CLIP_ORIGIN) + integers("", GL_CLIP_DEPTH_MODE),
            enabled("framebuffer sRGB", GL_FRAMEBUFFER_SRGB),
            integers("active texture", GL_ACTIVE_TEXTURE),
            integers("texture 2D on unit 3", GL_TEXTURE_BINDING_2D),
            integers("unpack alignment", GL_UNPACK_ALIGNMENT),
            floats("line width", GL_LINE_WIDTH)};
}

std::vector<unsigned char> HostEngine::readDisplay() const {
    const std::size_t row = std::size_t(width_) * 4;
    std::vector<unsigned char> bottomUp(row * std::size_t(height_)), topDown(bottomUp.size());
    glGetTextureImage(display_, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(bottomUp.size()), bottomUp.data());
    for (int y = 0; y < height_; ++y)
        std::memcpy(&topDown[std::size_t(y) * row], &bottomUp[std::size_t(height_ - 1 - y) * row], row);
    return topDown;
}

} // namespace obscura::examples

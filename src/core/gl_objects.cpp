#include "core/gl_objects.hpp"

#include "core/context_impl.hpp"

#include <string>

namespace obscura::detail {
namespace {

GLenum labelNamespace(ObjectKind kind) {
    switch (kind) {
    case ObjectKind::Buffer: return GL_BUFFER;
    case ObjectKind::Texture: return GL_TEXTURE;
    case ObjectKind::Framebuffer: return GL_FRAMEBUFFER;
    case ObjectKind::VertexArray: return GL_VERTEX_ARRAY;
    case ObjectKind::Sampler: return GL_SAMPLER;
    case ObjectKind::Query: return GL_QUERY;
    case ObjectKind::Program: return GL_PROGRAM;
    }
    return GL_NONE;
}

void label(ContextImpl& ctx, ObjectKind kind, GLuint name, std::string_view text) {
    if (!text.empty())
        ctx.gl.ObjectLabel(labelNamespace(kind), name, static_cast<GLsizei>(text.size()), text.data());
}

template <ObjectKind Kind>
Handle<Kind> track(ContextImpl& ctx, GLuint name, std::string_view text) {
    ++ctx.liveObjects;
    label(ctx, Kind, name, text);
    return Handle<Kind>(ctx, name);
}

const char* glErrorName(GLenum e) {
    switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    default: return "unknown GL error";
    }
}

} // namespace

void destroyObject(ContextImpl& ctx, ObjectKind kind, GLuint name) noexcept {
    auto& gl = ctx.gl;
    switch (kind) {
    case ObjectKind::Buffer: gl.DeleteBuffers(1, &name); break;
    case ObjectKind::Texture: gl.DeleteTextures(1, &name); break;
    case ObjectKind::Framebuffer: gl.DeleteFramebuffers(1, &name); break;
    case ObjectKind::VertexArray: gl.DeleteVertexArrays(1, &name); break;
    case ObjectKind::Sampler: gl.DeleteSamplers(1, &name); break;
    case ObjectKind::Query: gl.DeleteQueries(1, &name); break;
    case ObjectKind::Program: gl.DeleteProgram(name); break;
    }
    --ctx.liveObjects;
}

void drainGlErrors(ContextImpl& ctx) {
    for (int i = 0; i < 32 && ctx.gl.GetError() != GL_NO_ERROR; ++i) {
    }
}

void checkAllocation(ContextImpl& ctx, std::string_view what) {
    GLenum first = ctx.gl.GetError();
    if (first == GL_NO_ERROR) return;
    drainGlErrors(ctx);
    if (first == GL_OUT_OF_MEMORY)
        throw Error(ErrorCode::OutOfMemory, "out of GPU memory allocating " + std::string(what));
    throw Error(ErrorCode::InvalidState,
                std::string(glErrorName(first)) + " while creating " + std::string(what) + " (a bug in Obscura)");
}

int fullMipLevels(int size) {
    int levels = 1;
    while ((size >> levels) > 0) ++levels;
    return levels;
}

namespace {

// A texture of `target` with 2D storage (a 2D texture, or a cube map's six faces).
Texture createTexture2DStorage(ContextImpl& ctx, GLenum target, GLenum internalFormat, int width, int height, int levels,
                               std::string_view name, const std::string& extent) {
    drainGlErrors(ctx);
    GLuint t = 0;
    ctx.gl.CreateTextures(target, 1, &t);
    Texture tex = track<ObjectKind::Texture>(ctx, t, name);
    ctx.gl.TextureStorage2D(t, levels, internalFormat, width, height);
    checkAllocation(ctx, std::string(name) + " (" + extent + ")");
    return tex;
}

} // namespace

Texture createTexture2D(ContextImpl& ctx, GLenum internalFormat, int width, int height, int levels,
                        std::string_view name) {
    return createTexture2DStorage(ctx, GL_TEXTURE_2D, internalFormat, width, height, levels, name,
                                  std::to_string(width) + "x" + std::to_string(height));
}

Texture createTextureCube(ContextImpl& ctx, GLenum internalFormat, int size, int levels, std::string_view name) {
    return createTexture2DStorage(ctx, GL_TEXTURE_CUBE_MAP, internalFormat, size, size, levels, name,
                                  "6x" + std::to_string(size) + "x" + std::to_string(size));
}

namespace {

// A texture of `target` with 3D storage and one level (a 2D array's layers, or depth slices).
Texture createTexture3DStorage(ContextImpl& ctx, GLenum target, GLenum internalFormat, int width, int height, int depth,
                               std::string_view name) {
    drainGlErrors(ctx);
    GLuint t = 0;
    ctx.gl.CreateTextures(target, 1, &t);
    Texture tex = track<ObjectKind::Texture>(ctx, t, name);
    ctx.gl.TextureStorage3D(t, 1, internalFormat, width, height, depth);
    checkAllocation(ctx, std::string(name) + " (" + std::to_string(width) + "x" + std::to_string(height) + "x" +
                             std::to_string(depth) + ")");
    return tex;
}

} // namespace

Texture createTexture2DArray(ContextImpl& ctx, GLenum internalFormat, int width, int height, int layers,
                             std::string_view name) {
    return createTexture3DStorage(ctx, GL_TEXTURE_2D_ARRAY, internalFormat, width, height, layers, name);
}

Texture createTexture3D(ContextImpl& ctx, GLenum internalFormat, int width, int height, int depth, std::string_view name) {
    return createTexture3DStorage(ctx, GL_TEXTURE_3D, internalFormat, width, height, depth, name);
}

Buffer createBuffer(ContextImpl& ctx, GLsizeiptr bytes, const void* data, GLbitfield flags, std::string_view name) {
    drainGlErrors(ctx);
    GLuint b = 0;
    ctx.gl.CreateBuffers(1, &b);
    Buffer buf = track<ObjectKind::Buffer>(ctx, b, name);
    ctx.gl.NamedBufferStorage(b, bytes > 0 ? bytes : 1, data, flags);
    checkAllocation(ctx, std::string(name) + " (" + std::to_string(bytes) + " bytes)");
    return buf;
}

void uploadUniformBlock(ContextImpl& ctx, Buffer& buffer, const void* data, std::size_t bytes, GLuint binding,
                        std::string_view label) {
    if (!buffer) buffer = createBuffer(ctx, GLsizeiptr(bytes), nullptr, GL_DYNAMIC_STORAGE_BIT, label);
    ctx.gl.NamedBufferSubData(buffer.get(), 0, GLsizeiptr(bytes), data);
    ctx.state.bindUniformBuffer(ctx, binding, buffer.get());
}

Framebuffer createFramebuffer(ContextImpl& ctx, std::string_view name) {
    GLuint f = 0;
    ctx.gl.CreateFramebuffers(1, &f);
    return track<ObjectKind::Framebuffer>(ctx, f, name);
}

VertexArray createVertexArray(ContextImpl& ctx, std::string_view name) {
    GLuint v = 0;
    ctx.gl.CreateVertexArrays(1, &v);
    return track<ObjectKind::VertexArray>(ctx, v, name);
}

Sampler createSampler(ContextImpl& ctx, GLenum filter, GLenum wrap, std::string_view name) {
    GLuint s = 0;
    ctx.gl.CreateSamplers(1, &s);
    Sampler sampler = track<ObjectKind::Sampler>(ctx, s, name);
    auto& gl = ctx.gl;
    // Magnification has no mipmap modes: it takes the base filter of the minification one.
    const bool nearest = filter == GL_NEAREST || filter == GL_NEAREST_MIPMAP_NEAREST || filter == GL_NEAREST_MIPMAP_LINEAR;
    gl.SamplerParameteri(s, GL_TEXTURE_MIN_FILTER, static_cast<GLint>(filter));
    gl.SamplerParameteri(s, GL_TEXTURE_MAG_FILTER, nearest ? GL_NEAREST : GL_LINEAR);
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_S, static_cast<GLint>(wrap));
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_T, static_cast<GLint>(wrap));
    gl.SamplerParameteri(s, GL_TEXTURE_WRAP_R, static_cast<GLint>(wrap));
    // Samplers override the texture's own compare mode, so a host depth texture set up
    // for shadow lookups still returns depth values through ours.
    gl.SamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_NONE);
    return sampler;
}

Query createQuery(ContextImpl& ctx, GLenum target) {
    GLuint q = 0;
    ctx.gl.CreateQueries(target, 1, &q);
    return track<ObjectKind::Query>(ctx, q, {});
}

std::size_t bytesPerTexel(GLenum f) {
    switch (f) {
    case GL_R8: return 1;
    case GL_R16F: case GL_RG8: return 2;
    case GL_R32F: case GL_R32UI: case GL_RG16F: case GL_RGBA8: case GL_SRGB8_ALPHA8: case GL_RGB10_A2:
    case GL_DEPTH_COMPONENT32F: case GL_DEPTH24_STENCIL8: return 4;
    case GL_RG32F: case GL_RG32UI: case GL_RGBA16F: case GL_DEPTH32F_STENCIL8: return 8;
    case GL_RGBA32F: case GL_RGBA32UI: return 16;
    default: return 0;
    }
}

GLuint SizedTexture::ensure(ContextImpl& ctx, GLenum internalFormat, int width, int height, std::string_view label) {
    if (!texture_ || format_ != internalFormat || width_ != width || height_ != height) {
        texture_ = createTexture2D(ctx, internalFormat, width, height, 1, label);
        format_ = internalFormat;
        width_ = width;
        height_ = height;
    }
    return texture_.get();
}

Program adoptProgram(ContextImpl& ctx, GLuint name) { return track<ObjectKind::Program>(ctx, name, {}); }

} // namespace obscura::detail

#pragma once
// RAII ownership of GL objects, created with DSA (glCreate*), labelled for KHR_debug, and
// counted per context so that tests can prove no call leaks an object.
#include "core/gl.hpp"

#include <string_view>
#include <utility>

namespace obscura::detail {

struct ContextImpl;

enum class ObjectKind { Buffer, Texture, Framebuffer, VertexArray, Sampler, Query, Program };

//! Deletes a GL object of the given kind and decrements the context's live count.
void destroyObject(ContextImpl& ctx, ObjectKind kind, GLuint name) noexcept;

template <ObjectKind Kind>
class Handle {
public:
    Handle() = default;
    Handle(ContextImpl& ctx, GLuint name) noexcept : ctx_(&ctx), name_(name) {}
    ~Handle() { reset(); }
    Handle(Handle&& o) noexcept : ctx_(o.ctx_), name_(std::exchange(o.name_, 0)) {}
    Handle& operator=(Handle&& o) noexcept {
        if (this != &o) {
            reset();
            ctx_ = o.ctx_;
            name_ = std::exchange(o.name_, 0);
        }
        return *this;
    }
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;

    GLuint get() const noexcept { return name_; }
    explicit operator bool() const noexcept { return name_ != 0; }
    void reset() noexcept {
        if (name_ != 0) destroyObject(*ctx_, Kind, std::exchange(name_, 0));
    }

private:
    ContextImpl* ctx_ = nullptr;
    GLuint name_ = 0;
};

using Buffer = Handle<ObjectKind::Buffer>;
using Texture = Handle<ObjectKind::Texture>;
using Framebuffer = Handle<ObjectKind::Framebuffer>;
using VertexArray = Handle<ObjectKind::VertexArray>;
using Sampler = Handle<ObjectKind::Sampler>;
using Query = Handle<ObjectKind::Query>;
using Program = Handle<ObjectKind::Program>;

// Creation. `label` names the object in debuggers (KHR_debug); use the pass name.
// Allocations check GL_OUT_OF_MEMORY and throw Error{OutOfMemory} without leaking.
Texture createTexture2D(ContextImpl& ctx, GLenum internalFormat, int width, int height, int levels,
                        std::string_view label);
//! A GL_TEXTURE_2D_ARRAY with one level.
Texture createTexture2DArray(ContextImpl& ctx, GLenum internalFormat, int width, int height, int layers,
                             std::string_view label);
//! A GL_TEXTURE_3D with one level.
Texture createTexture3D(ContextImpl& ctx, GLenum internalFormat, int width, int height, int depth, std::string_view label);
//! Levels of a full mip chain for a texture whose larger side is `size` texels (1 for size 1).
int fullMipLevels(int size);
//! A GL_TEXTURE_CUBE_MAP of `size` x `size` faces and `levels` levels.
Texture createTextureCube(ContextImpl& ctx, GLenum internalFormat, int size, int levels, std::string_view label);
Buffer createBuffer(ContextImpl& ctx, GLsizeiptr bytes, const void* data, GLbitfield flags, std::string_view label);

//! Writes a parameter block into `buffer` (created on first use, `label`d) and binds it at
//! uniform-buffer `binding`.
void uploadUniformBlock(ContextImpl& ctx, Buffer& buffer, const void* data, std::size_t bytes, GLuint binding,
                        std::string_view label);
template <typename Block>
void uploadUniformBlock(ContextImpl& ctx, Buffer& buffer, const Block& block, GLuint binding, std::string_view label) {
    uploadUniformBlock(ctx, buffer, &block, sizeof block, binding, label);
}
Framebuffer createFramebuffer(ContextImpl& ctx, std::string_view label);
VertexArray createVertexArray(ContextImpl& ctx, std::string_view label);
//! `filter` is the minification filter; magnification uses its non-mipmap part.
Sampler createSampler(ContextImpl& ctx, GLenum filter, GLenum wrap, std::string_view label);
Query createQuery(ContextImpl& ctx, GLenum target);
Program adoptProgram(ContextImpl& ctx, GLuint name);

//! Bytes per texel of the uncompressed formats Obscura allocates (0 for others).
std::size_t bytesPerTexel(GLenum internalFormat);

//! A 2D texture that is reallocated only when its size or format changes (outputs of
//! passes whose size follows their input).
class SizedTexture {
public:
    GLuint ensure(ContextImpl& ctx, GLenum internalFormat, int width, int height, std::string_view label);
    GLuint get() const noexcept { return texture_.get(); }
    std::size_t bytes() const { return texture_ ? bytesPerTexel(format_) * std::size_t(width_) * std::size_t(height_) : 0; }
    //! Frees the texture (a later ensure() allocates it again).
    void release() noexcept {
        texture_.reset();
        format_ = GL_NONE;
        width_ = height_ = 0;
    }

private:
    Texture texture_;
    GLenum format_ = GL_NONE;
    int width_ = 0, height_ = 0;
};

//! Discards pending GL errors. Allocations call it first, so that an error the host left
//! pending is not taken for an allocation failure (it is consumed, as context.hpp says).
void drainGlErrors(ContextImpl& ctx);

//! Throws Error{OutOfMemory} if the last allocation failed; any other pending error is a bug
//! in Obscura and throws Error{InvalidState} with the GL error name and `what`.
void checkAllocation(ContextImpl& ctx, std::string_view what);

} // namespace obscura::detail

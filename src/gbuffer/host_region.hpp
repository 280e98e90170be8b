#pragma once
// HostGBuffer::region: the rectangle of the host's textures a view covers, and the copies
// adopt() reads from when it is smaller than the textures.
#include "core/gl_objects.hpp"
#include "core/texture_info.hpp"
#include "obscura/gbuffer.hpp"

#include <cstddef>
#include <string>
#include <string_view>

namespace obscura::detail {

struct ContextImpl;

//! The region in texels: the whole depth texture for the default (0 x 0), else `region`
//! itself once it lies within the depth texture. Throws Error{InvalidArgument} naming
//! HostGBuffer::region otherwise.
HostRect resolveRegion(const HostRect& region, const TextureInfo& depth);

//! Refuses (Error{InvalidArgument} naming `who`) a host texture that glCopyImageSubData
//! would refuse: one in an unsized format (compressed ones adopt() refuses anyway), or
//! mutable (glTexImage2D) with a min filter that samples
//! mipmaps and without the levels it needs (GL counts it incomplete; a level-0-only texture
//! under the default filter is one). Read in place, such textures are fine: our samplers do
//! not use mipmaps.
void requireCopyable(ContextImpl& ctx, GLuint texture, GLenum internalFormat, const std::string& who);

//! True where `region` is the whole of a texture of `depth`'s size: read in place.
bool coversWhole(const HostRect& region, const TextureInfo& depth);

//! A texture of ours holding one host texture's region: its format, size and swizzle.
class RegionCopy {
public:
    //! Copies `region` of `source` (level 0, `format`), returns the copy's name.
    GLuint copy(ContextImpl& ctx, GLuint source, GLenum format, const HostRect& region, std::string_view label);
    //! Frees the copy (a view without a region, or without this texture, needs none).
    void release() noexcept;
    //! The copy's name; 0 when there is none.
    GLuint name() const noexcept { return texture_.get(); }
    //! The copy's size by GL's channel sizes (drivers may pad, e.g. 24-bit depth to 32).
    std::size_t bytes() const noexcept { return bytes_; }

private:
    Texture texture_;
    GLenum format_ = GL_NONE;
    int width_ = 0, height_ = 0;
    std::size_t bytes_ = 0;
};

} // namespace obscura::detail

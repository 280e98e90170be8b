#include "gbuffer/host_region.hpp"

#include "core/context_impl.hpp"
#include "obscura/error.hpp"

#include <algorithm>
#include <string>

namespace obscura::detail {
namespace {

std::string describe(const HostRect& r) {
    return "(x " + std::to_string(r.x) + ", y " + std::to_string(r.y) + ", " + std::to_string(r.width) + "x" +
           std::to_string(r.height) + ")";
}

// Bytes a texel of level 0 holds by GL's own channel sizes.
std::size_t texelBytes(ContextImpl& ctx, GLuint texture) {
    GLint bits = 0;
    for (const GLenum channel : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE, GL_TEXTURE_ALPHA_SIZE,
                                 GL_TEXTURE_DEPTH_SIZE, GL_TEXTURE_STENCIL_SIZE}) {
        GLint size = 0;
        ctx.gl.GetTextureLevelParameteriv(texture, 0, channel, &size);
        bits += size;
    }
    return static_cast<std::size_t>(bits + 7) / 8;
}

// Whether a mutable texture's own min filter, which samples mipmaps, finds every level it
// needs (GL 4.5, 8.17): levels 1 to min(log2 of the larger side, GL_TEXTURE_MAX_LEVEL) of
// the halved sizes and level 0's format. Base level 0 is adopt()'s rule already.
bool mipmapComplete(ContextImpl& ctx, GLuint texture) {
    const auto level = [&](int i, GLenum what) {
        GLint v = 0;
        ctx.gl.GetTextureLevelParameteriv(texture, i, what, &v);
        return v;
    };
    GLint maxLevel = 0;
    ctx.gl.GetTextureParameteriv(texture, GL_TEXTURE_MAX_LEVEL, &maxLevel);
    const int width = level(0, GL_TEXTURE_WIDTH), height = level(0, GL_TEXTURE_HEIGHT);
    const int format = level(0, GL_TEXTURE_INTERNAL_FORMAT);
    int last = 0;
    while ((std::max(width, height) >> (last + 1)) > 0) ++last; // floor(log2(larger side))
    last = std::min(last, maxLevel);
    for (int i = 1; i <= last; ++i)
        if (level(i, GL_TEXTURE_WIDTH) != std::max(1, width >> i) || level(i, GL_TEXTURE_HEIGHT) != std::max(1, height >> i) ||
            level(i, GL_TEXTURE_INTERNAL_FORMAT) != format)
            return false;
    return true;
}

} // namespace

HostRect resolveRegion(const HostRect& region, const TextureInfo& depth) {
    if (region.x == 0 && region.y == 0 && region.width == 0 && region.height == 0)
        return {0, 0, depth.width, depth.height};
    // In 64 bits: x + width must not wrap for a region far past the texture.
    const long long right = static_cast<long long>(region.x) + region.width;
    const long long top = static_cast<long long>(region.y) + region.height;
    if (region.x < 0 || region.y < 0 || region.width < 1 || region.height < 1 || right > depth.width || top > depth.height)
        throw Error(ErrorCode::InvalidArgument,
                    "HostGBuffer::region " + describe(region) + " must lie within the depth texture (" +
                        std::to_string(depth.width) + "x" + std::to_string(depth.height) +
                        "): x, y >= 0, width, height >= 1, x + width <= its width, y + height <= its height; "
                        "all four 0 for the whole texture");
    return region;
}

void requireCopyable(ContextImpl& ctx, GLuint texture, GLenum internalFormat, const std::string& who) {
    switch (internalFormat) {
    case GL_RED: case GL_RG: case GL_RGB: case GL_RGBA: case GL_SRGB: case GL_SRGB_ALPHA: case GL_DEPTH_COMPONENT:
    case GL_DEPTH_STENCIL: case GL_COMPRESSED_RED: case GL_COMPRESSED_RG: case GL_COMPRESSED_RGB:
    case GL_COMPRESSED_RGBA: case GL_COMPRESSED_SRGB: case GL_COMPRESSED_SRGB_ALPHA:
        throw Error(ErrorCode::InvalidArgument, who + " has an unsized format (" + formatName(internalFormat) +
                                                    "): HostGBuffer::region copies it, and GL copies only sized ones");
    default: break;
    }
    GLint immutable = GL_FALSE, minFilter = GL_NEAREST;
    ctx.gl.GetTextureParameteriv(texture, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    ctx.gl.GetTextureParameteriv(texture, GL_TEXTURE_MIN_FILTER, &minFilter);
    if (!immutable && minFilter != GL_NEAREST && minFilter != GL_LINEAR && !mipmapComplete(ctx, texture))
        throw Error(ErrorCode::InvalidArgument,
                    who + " is mutable with a mipmap min filter and lacks mipmap levels that filter needs: "
                          "HostGBuffer::region copies it, and GL refuses to copy an incomplete texture. Set "
                          "GL_TEXTURE_MIN_FILTER to GL_NEAREST or GL_LINEAR (or GL_TEXTURE_MAX_LEVEL to 0), "
                          "give it every level, or allocate it with glTexStorage2D");
}

bool coversWhole(const HostRect& region, const TextureInfo& depth) {
    return region.x == 0 && region.y == 0 && region.width == depth.width && region.height == depth.height;
}

GLuint RegionCopy::copy(ContextImpl& ctx, GLuint source, GLenum format, const HostRect& region, std::string_view label) {
    auto& gl = ctx.gl;
    if (!texture_ || format_ != format || width_ != region.width || height_ != region.height) {
        texture_ = createTexture2D(ctx, format, region.width, region.height, 1, label);
        format_ = format;
        width_ = region.width;
        height_ = region.height;
        bytes_ = texelBytes(ctx, texture_.get()) * static_cast<std::size_t>(width_) * static_cast<std::size_t>(height_);
    }
    // The swizzle is the texture's, not the sampler's: our samplers would not restore it.
    GLint swizzle[4] = {GL_RED, GL_GREEN, GL_BLUE, GL_ALPHA};
    gl.GetTextureParameteriv(source, GL_TEXTURE_SWIZZLE_RGBA, swizzle);
    gl.TextureParameteriv(texture_.get(), GL_TEXTURE_SWIZZLE_RGBA, swizzle);
    gl.CopyImageSubData(source, GL_TEXTURE_2D, 0, region.x, region.y, 0, texture_.get(), GL_TEXTURE_2D, 0, 0, 0, 0,
                        region.width, region.height, 1);
    return texture_.get();
}

void RegionCopy::release() noexcept {
    texture_.reset();
    format_ = GL_NONE;
    width_ = height_ = 0;
    bytes_ = 0;
}

} // namespace obscura::detail

#include "core/texture_info.hpp"

#include "core/context_impl.hpp"
#include "obscura/error.hpp"

#include <cstdio>

#include <cmath>

namespace obscura::detail {

namespace {

// The sRGB formats of GL 4.5 core a texture that passes queryTexture2D can have, sized and
// unsized (compressed ones are refused; a generic compressed one may be stored uncompressed).
// The sampler decodes them.
bool isSrgbFormat(GLenum format) {
    switch (format) {
    case GL_SRGB8: case GL_SRGB8_ALPHA8: case GL_SRGB: case GL_SRGB_ALPHA: case GL_COMPRESSED_SRGB:
    case GL_COMPRESSED_SRGB_ALPHA: return true;
    default: return false;
    }
}

} // namespace

std::string formatName(GLenum f) {
    switch (f) {
    case GL_DEPTH_COMPONENT16: return "GL_DEPTH_COMPONENT16";
    case GL_DEPTH_COMPONENT24: return "GL_DEPTH_COMPONENT24";
    case GL_DEPTH_COMPONENT32: return "GL_DEPTH_COMPONENT32";
    case GL_DEPTH_COMPONENT32F: return "GL_DEPTH_COMPONENT32F";
    case GL_DEPTH24_STENCIL8: return "GL_DEPTH24_STENCIL8";
    case GL_DEPTH32F_STENCIL8: return "GL_DEPTH32F_STENCIL8";
    case GL_RGBA8: return "GL_RGBA8";
    case GL_RGB8: return "GL_RGB8";
    case GL_SRGB8_ALPHA8: return "GL_SRGB8_ALPHA8";
    case GL_RGBA16F: return "GL_RGBA16F";
    case GL_RGB16F: return "GL_RGB16F";
    case GL_RGBA32F: return "GL_RGBA32F";
    case GL_RGB32F: return "GL_RGB32F";
    case GL_R32F: return "GL_R32F";
    case GL_R16F: return "GL_R16F";
    case GL_RG16F: return "GL_RG16F";
    case GL_RGB10_A2: return "GL_RGB10_A2";
    case GL_RGBA16: return "GL_RGBA16";
    case GL_RGB16: return "GL_RGB16";
    case GL_R8: return "GL_R8";
    case GL_SRGB8: return "GL_SRGB8";
    case GL_R11F_G11F_B10F: return "GL_R11F_G11F_B10F";
    case GL_RGB9_E5: return "GL_RGB9_E5";
    case GL_R3_G3_B2: return "GL_R3_G3_B2";
    case GL_RGBA32UI: return "GL_RGBA32UI";
    case GL_R32UI: return "GL_R32UI";
    case GL_RGBA16UI: return "GL_RGBA16UI";
    case GL_RGBA8UI: return "GL_RGBA8UI";
    case GL_RGBA8I: return "GL_RGBA8I";
    case GL_R32I: return "GL_R32I";
    case GL_R8UI: return "GL_R8UI";
    case GL_STENCIL_INDEX8: return "GL_STENCIL_INDEX8";
    case GL_RGBA8_SNORM: return "GL_RGBA8_SNORM";
    case GL_RGBA16_SNORM: return "GL_RGBA16_SNORM";
    case GL_SRGB: return "GL_SRGB";
    case GL_SRGB_ALPHA: return "GL_SRGB_ALPHA";
    case GL_RGBA: return "GL_RGBA";
    case GL_RGB: return "GL_RGB";
    default: {
        char buf[32];
        std::snprintf(buf, sizeof buf, "0x%04X", f);
        return buf;
    }
    }
}

void requireBaseLevelZero(ContextImpl& ctx, GLuint name, const std::string& who) {
    GLint base = 0;
    ctx.gl.GetTextureParameteriv(name, GL_TEXTURE_BASE_LEVEL, &base);
    if (base != 0)
        throw Error(ErrorCode::InvalidArgument, who + ": GL_TEXTURE_BASE_LEVEL is " + std::to_string(base) +
                                                    "; Obscura samples level 0, so the base level must be 0");
}

TextureInfo queryTexture2D(ContextImpl& ctx, GLuint name, const std::string& who) {
    auto& gl = ctx.gl;
    if (name == 0 || !gl.IsTexture(name))
        throw Error(ErrorCode::InvalidArgument, who + ": " + std::to_string(name) + " is not a GL texture name");
    GLint target = 0;
    gl.GetTextureParameteriv(name, GL_TEXTURE_TARGET, &target);
    if (target != GL_TEXTURE_2D)
        throw Error(ErrorCode::InvalidArgument,
                    who + ": texture " + std::to_string(name) + " is not a GL_TEXTURE_2D (multisampled, array "
                    "and cube textures are not accepted; resolve or copy to a 2D texture first)");
    TextureInfo t;
    GLint v = 0;
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_INTERNAL_FORMAT, &v);
    t.internalFormat = static_cast<GLenum>(v);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_WIDTH, &t.width);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_HEIGHT, &t.height);
    if (t.width < 1 || t.height < 1)
        throw Error(ErrorCode::InvalidArgument, who + ": texture " + std::to_string(name) + " has no level 0 image");
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_COMPRESSED, &v);
    if (v) throw Error(ErrorCode::InvalidArgument, who + ": compressed textures are not accepted");

    GLint depthSize = 0, stencilSize = 0, sizes[4] = {}, redType = 0;
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_DEPTH_SIZE, &depthSize);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_STENCIL_SIZE, &stencilSize);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_RED_SIZE, &sizes[0]);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_GREEN_SIZE, &sizes[1]);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_BLUE_SIZE, &sizes[2]);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_ALPHA_SIZE, &sizes[3]);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_RED_TYPE, &redType);
    if (depthSize > 0) {
        GLint depthType = 0;
        gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_DEPTH_TYPE, &depthType);
        if (depthType == GL_UNSIGNED_NORMALIZED) t.depthStep = 1.0 / (std::ldexp(1.0, depthSize) - 1.0);
        t.depth = true;
        t.stencil = stencilSize > 0;
        t.channels = 1;
        t.pixelFormat = GL_DEPTH_COMPONENT;
        return t;
    }
    if (stencilSize > 0) { // GL_STENCIL_INDEX8: integers, read only through usampler
        t.stencil = true;
        t.integer = true;
        t.channels = 1;
        t.pixelFormat = GL_STENCIL_INDEX;
        return t;
    }
    t.srgb = isSrgbFormat(t.internalFormat);
    t.integer = redType == GL_INT || redType == GL_UNSIGNED_INT;
    t.floating = redType == GL_FLOAT;
    t.signedFloat = t.floating && t.internalFormat != GL_R11F_G11F_B10F && t.internalFormat != GL_RGB9_E5;
    t.signedNormalized = redType == GL_SIGNED_NORMALIZED;
    t.isSigned = redType == GL_INT;
    t.channels = sizes[3] > 0 ? 4 : sizes[2] > 0 ? 3 : sizes[1] > 0 ? 2 : 1;
    static constexpr GLenum floatFormats[4] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
    static constexpr GLenum intFormats[4] = {GL_RED_INTEGER, GL_RG_INTEGER, GL_RGB_INTEGER, GL_RGBA_INTEGER};
    t.pixelFormat = (t.integer ? intFormats : floatFormats)[t.channels - 1];
    return t;
}

void requireSampledDepth(ContextImpl& ctx, GLuint name, const TextureInfo& t, const std::string& who) {
    if (!t.depth)
        throw Error(ErrorCode::InvalidArgument,
                    who + " must have a depth format (GL_DEPTH_COMPONENT16/24/32/32F, GL_DEPTH24_STENCIL8, "
                          "GL_DEPTH32F_STENCIL8), got " + formatName(t.internalFormat));
    if (!t.stencil) return;
    GLint mode = 0;
    ctx.gl.GetTextureParameteriv(name, GL_DEPTH_STENCIL_TEXTURE_MODE, &mode);
    if (mode != GL_DEPTH_COMPONENT)
        throw Error(ErrorCode::InvalidArgument,
                    who + " samples stencil: set its GL_DEPTH_STENCIL_TEXTURE_MODE to GL_DEPTH_COMPONENT");
}

namespace {

bool readableAs(const TextureInfo& info, SampledAs kind) {
    if (info.depth || info.stencil || info.integer) return false;
    switch (kind) {
    case SampledAs::Colour: return true;
    case SampledAs::Rgb: return info.channels >= 3;
    case SampledAs::FloatRgb: return info.channels >= 3 && info.floating;
    case SampledAs::Normal: return info.channels >= 3 && (info.signedFloat || info.signedNormalized);
    case SampledAs::Depth: break;
    }
    return false;
}

const char* acceptedFormats(SampledAs kind) {
    switch (kind) {
    case SampledAs::Rgb:
        return "a normalized or float RGB or RGBA colour format (GL_RGB8, GL_RGBA8, GL_SRGB8, GL_SRGB8_ALPHA8, GL_RGB16F, "
               "GL_RGBA16F, ...)";
    case SampledAs::FloatRgb: return "a float RGB or RGBA format (GL_R11F_G11F_B10F, GL_RGB16F, GL_RGBA16F, GL_RGB32F, GL_RGBA32F)";
    case SampledAs::Normal: return "a signed float or signed normalized RGB or RGBA format (GL_RGBA16F, GL_RGBA32F, GL_RGBA8_SNORM)";
    default: return "a normalized or float colour format";
    }
}

} // namespace

void requireReadableAs(ContextImpl& ctx, GLuint name, const TextureInfo& info, const std::string& who, SampledAs kind) {
    requireBaseLevelZero(ctx, name, who);
    if (kind == SampledAs::Depth) return requireSampledDepth(ctx, name, info, who);
    if (!readableAs(info, kind))
        throw Error(ErrorCode::InvalidArgument,
                    who + " has format " + formatName(info.internalFormat) + "; accepted: " + acceptedFormats(kind));
}

double depthStepOf(ContextImpl& ctx, GLuint depthTexture) {
    return queryTexture2D(ctx, depthTexture, "depth texture").depthStep;
}

void requireDescribedAs(const obscura::TextureView& given, const TextureInfo& actual, const std::string& who) {
    const auto refuse = [&](const std::string& field, const std::string& said, const std::string& is) {
        throw Error(ErrorCode::InvalidArgument, who + "." + field + " says " + said + " but texture " +
                                                    std::to_string(given.name) + " is " + is +
                                                    " (leave the field 0 to take GL's)");
    };
    if (given.internalFormat != 0 && given.internalFormat != actual.internalFormat)
        refuse("internalFormat", formatName(given.internalFormat), formatName(actual.internalFormat));
    if (given.width != 0 && given.width != actual.width)
        refuse("width", std::to_string(given.width), std::to_string(actual.width) + " texels wide");
    if (given.height != 0 && given.height != actual.height)
        refuse("height", std::to_string(given.height), std::to_string(actual.height) + " texels high");
}

} // namespace obscura::detail

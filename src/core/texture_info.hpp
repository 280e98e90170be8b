#pragma once
// Facts about a texture name, queried without changing any binding (DSA queries), after
// checking that the name is a texture (querying a non-texture would raise a GL error).
#include "core/gl.hpp"
#include "obscura/texture.hpp"

#include <string>

namespace obscura::detail {

struct ContextImpl;

struct TextureInfo {
    GLenum internalFormat = 0;
    int width = 0, height = 0;
    int channels = 0;          //!< 1..4 (depth = 1)
    bool depth = false;        //!< a depth or depth-stencil format
    bool stencil = false;      //!< depth-stencil, or stencil only (then also `integer`)
    bool integer = false;      //!< *I / *UI formats
    bool floating = false;     //!< float components (GL_TEXTURE_RED_TYPE is GL_FLOAT)
    //! float components with a sign bit: not the packed GL_R11F_G11F_B10F and GL_RGB9_E5,
    //! which cannot hold a normal's negative components
    bool signedFloat = false;
    bool signedNormalized = false; //!< *_SNORM formats (GL_TEXTURE_RED_TYPE is GL_SIGNED_NORMALIZED)
    bool isSigned = false;     //!< for integer formats
    bool srgb = false;         //!< sRGB-encoded storage (GL_SRGB8, GL_SRGB8_ALPHA8)
    GLenum pixelFormat = 0;    //!< glGetTextureImage format matching `channels`
    //! Depth formats: one step of the stored depth in [0, 1], 1 / (2^bits - 1) when fixed
    //! point, 0 when float (GL_TEXTURE_DEPTH_SIZE and _TYPE: unsized formats too).
    double depthStep = 0.0;
};

//! Throws Error{InvalidArgument} mentioning `who` unless `name` is a single-sampled,
//! uncompressed GL_TEXTURE_2D with a level 0.
TextureInfo queryTexture2D(ContextImpl& ctx, GLuint name, const std::string& who);

//! TextureInfo::depthStep of a depth texture (queried from GL, whatever format it claims).
double depthStepOf(ContextImpl& ctx, GLuint depthTexture);

//! For textures Obscura samples: level 0 must be the base level (texelFetch and
//! non-mipmapped sampling read the base level).
void requireBaseLevelZero(ContextImpl& ctx, GLuint name, const std::string& who);

//! For textures Obscura samples as depth: a depth format, and depth (not stencil) when it
//! has both (GL_DEPTH_STENCIL_TEXTURE_MODE). Throws Error{InvalidArgument} mentioning `who`.
void requireSampledDepth(ContextImpl& ctx, GLuint name, const TextureInfo& info, const std::string& who);

//! How a pass reads a texture: Depth through a depth sampler's first channel; Colour as
//! floats from one or more channels (a normalized or float format; sRGB ones decoded, which
//! only colours may be); Rgb the same from three or more; FloatRgb as Rgb from a float format
//! only (radiance, which normalized formats would bound by 1); Normal as signed unit vectors
//! from three or more channels (a float format with a sign bit, or signed normalized).
enum class SampledAs { Depth, Colour, Rgb, FloatRgb, Normal };
//! For textures Obscura samples at level 0 as `kind`: requireBaseLevelZero, then for Depth
//! requireSampledDepth, else a format as `kind` describes. Throws Error{InvalidArgument}
//! mentioning `who`.
void requireReadableAs(ContextImpl& ctx, GLuint name, const TextureInfo& info, const std::string& who, SampledAs kind);

//! A host's description of its texture: each field it states (internalFormat, width, height
//! not 0) must be what GL reports, so that a description that lies (a copied snippet's format,
//! last frame's size) is refused instead of silently ignored. Throws Error{InvalidArgument}
//! naming `who`, the field, and both values.
void requireDescribedAs(const obscura::TextureView& given, const TextureInfo& actual, const std::string& who);

std::string formatName(GLenum internalFormat);

} // namespace obscura::detail

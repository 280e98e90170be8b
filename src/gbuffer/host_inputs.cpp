#include "gbuffer/host_inputs.hpp"

#include "core/context_impl.hpp"
#include "core/diagnostics.hpp"
#include "core/validate.hpp"
#include "obscura/error.hpp"

#include <algorithm>
#include <cmath>

namespace obscura::detail {
namespace {

constexpr double kHalfPi = 1.5707963705062866; // pi / 2 as the float nearest it, which lies above

} // namespace

TextureInfo hostTextureBeside(ContextImpl& ctx, const TextureView& given, const std::string& who, const TextureInfo& depth) {
    const TextureInfo t = queryTexture2D(ctx, given.name, who);
    requireDescribedAs(given, t, who);
    requireBaseLevelZero(ctx, given.name, who);
    if (t.width != depth.width || t.height != depth.height)
        throw Error(ErrorCode::InvalidArgument, who + " is " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                                                    " but depth is " + std::to_string(depth.width) + "x" +
                                                    std::to_string(depth.height));
    return t;
}

TextureView hostBackDepth(ContextImpl& ctx, const TextureView& texture, GLuint depthName, const TextureInfo& depth) {
    if (!texture) return {};
    if (texture.name == depthName)
        throw Error(ErrorCode::InvalidArgument,
                    "HostGBuffer::backDepth is HostGBuffer::depth (texture " + std::to_string(depthName) +
                        "): it must be a second layer, the nearest surfaces behind the first");
    const TextureInfo t = hostTextureBeside(ctx, texture, "HostGBuffer::backDepth", depth);
    requireSampledDepth(ctx, texture.name, t, "HostGBuffer::backDepth");
    return {texture.name, t.internalFormat, t.width, t.height};
}

TextureView hostColour(ContextImpl& ctx, const TextureView& texture, const std::string& who, const TextureInfo& depth,
                       SampledAs kind) {
    if (!texture) return {};
    const TextureInfo t = hostTextureBeside(ctx, texture, who, depth);
    requireReadableAs(ctx, texture.name, t, who, kind);
    return {texture.name, t.internalFormat, t.width, t.height};
}

Defines normalDefines(const HostGBuffer& host) {
    if (host.normal.name == 0) return {"FROM_DEPTH"};
    Defines defines;
    if (host.normalEncoding == NormalEncoding::Unsigned) defines.push_back("UNSIGNED_ENCODING");
    if (host.normalSpace == NormalSpace::World) defines.push_back("WORLD_SPACE");
    return defines;
}

void requireNormalEnumerators(const HostGBuffer& host) {
    requireEnumerator(host.normalEncoding, {NormalEncoding::Signed, NormalEncoding::Unsigned, NormalEncoding::ViewContract},
                      "HostGBuffer::normalEncoding");
    requireEnumerator(host.normalSpace, {NormalSpace::View, NormalSpace::World}, "HostGBuffer::normalSpace");
}

HostNormals checkHostNormals(ContextImpl& ctx, const HostGBuffer& host, const TextureInfo& depth) {
    requireNormalEnumerators(host);
    requireInRange(host.normalDeviation, 0.0, kHalfPi, "HostGBuffer::normalDeviation", "radians");
    HostNormals out;
    out.defines = normalDefines(host);
    if (host.normal.name == 0) return out;
    const TextureInfo n = hostTextureBeside(ctx, host.normal, "HostGBuffer::normal", depth);
    out.texture = {host.normal.name, n.internalFormat, n.width, n.height};
    GLint componentType = 0;
    ctx.gl.GetTextureLevelParameteriv(host.normal.name, 0, GL_TEXTURE_RED_TYPE, &componentType);
    // The coarsest of the three channels bounds the error (GL_R3_G3_B2's blue has 2 bits).
    GLint bits = 0;
    for (const GLenum channel : {GL_TEXTURE_RED_SIZE, GL_TEXTURE_GREEN_SIZE, GL_TEXTURE_BLUE_SIZE}) {
        GLint size = 0;
        ctx.gl.GetTextureLevelParameteriv(host.normal.name, 0, channel, &size);
        bits = channel == GL_TEXTURE_RED_SIZE ? size : std::min(bits, size);
    }
    const NormalEncoding encoding = host.normalEncoding;
    const bool signedOk = encoding == NormalEncoding::Signed && n.signedFloat;
    // 3 bits a channel already bound the error by asin(sqrt(3) / 7) + 2^-10 = 0.2510, past
    // kMaxNormalError: the screen-space tests would refuse the view later, with less to say.
    // sRGB storage would be decoded by the sampler, bending every normal.
    const bool unsignedOk = encoding == NormalEncoding::Unsigned && componentType == GL_UNSIGNED_NORMALIZED && !n.srgb &&
                            bits >= 1 && adoptedNormalError(NormalEncoding::Unsigned, bits) <= kMaxNormalError;
    const bool contractOk = encoding == NormalEncoding::ViewContract && n.signedFloat && n.channels == 4;
    if (n.depth || n.channels < 3 || !(signedOk || unsignedOk || contractOk))
        throw Error(ErrorCode::InvalidArgument,
                    "HostGBuffer::normal has format " + formatName(n.internalFormat) + "; accepted: " +
                        (encoding == NormalEncoding::Signed
                             ? "a signed float RGB/RGBA format (GL_RGB16F, GL_RGBA16F, GL_RGB32F, GL_RGBA32F) "
                               "with NormalEncoding::Signed"
                         : encoding == NormalEncoding::Unsigned
                             ? "a normalized unsigned RGB/RGBA format of at least 4 bits a channel, not sRGB "
                               "(GL_RGB8, GL_RGBA8, GL_RGB10_A2, GL_RGBA16) with NormalEncoding::Unsigned"
                             : "GL_RGBA16F or GL_RGBA32F (alpha holds the bound) with NormalEncoding::ViewContract"));
    if (encoding == NormalEncoding::ViewContract && (host.normalSpace != NormalSpace::View || host.normalDeviation != 0.0f))
        throw Error(ErrorCode::InvalidArgument, "NormalEncoding::ViewContract normals are read in place: they must be in "
                                                "NormalSpace::View with HostGBuffer::normalDeviation 0 (the conversion "
                                                "pass applies the other settings)");
    out.inPlace = encoding == NormalEncoding::ViewContract;
    // Read in place, no store of ours rounds them again: the host format's own rounding, as
    // adoptedNormalError counts it (our half floats' for 16 bits).
    out.normalError = !out.inPlace ? adoptedNormalError(encoding, bits) : bits <= 16 ? kHalfNormalError : 0x1p-23f;
    return out;
}

void reportClipDepthMismatch(ContextImpl& ctx, const Camera& camera, bool& reported) {
    GLint mode = GL_NEGATIVE_ONE_TO_ONE;
    ctx.gl.GetIntegerv(GL_CLIP_DEPTH_MODE, &mode);
    const bool zeroToOne = camera.clipDepth == ClipDepth::ZeroToOne;
    const bool mismatch = zeroToOne != (mode == GL_ZERO_TO_ONE);
    const bool repeated = reported;
    reported = mismatch;
    if (!mismatch || (repeated && !ctx.desc.strictChecks)) return; // a host that means it hears it once
    reportDiagnostic(
        ctx, Diagnostic::ClipDepthMismatch,
        std::string("GBuffer::adopt: the camera's ClipDepth is ") + (zeroToOne ? "ZeroToOne" : "NegativeOneToOne") +
            " but the current GL_CLIP_DEPTH_MODE is " + (mode == GL_ZERO_TO_ONE ? "GL_ZERO_TO_ONE" : "GL_NEGATIVE_ONE_TO_ONE") +
            ": depth written under the current mode is read with the other mapping, and AO and GI are quietly wrong. "
            "ClipDepth::NegativeOneToOne is for hosts with GL's default clip control (glm::perspective), ZeroToOne for "
            "those that call glClipControl(..., GL_ZERO_TO_ONE) (reversed-Z, glm::perspectiveZO). If the depth pass ran "
            "under another clip control than the one current now, ignore this.");
}

void reportNearPlanePixels(ContextImpl& ctx, GLuint pixels, int w, int h, const Camera& camera) {
    const std::size_t total = std::size_t(w) * std::size_t(h);
    if (std::size_t(pixels) * 100 < total) return;
    const bool reversed = analyzeProjection(camera).reversedZ;
    reportDiagnostic(ctx, Diagnostic::DepthOnNearPlane,
                     "GBuffer::adopt: " + std::to_string(pixels) + " of " + std::to_string(total) +
                         " host depth pixels lie exactly on the camera's near plane (depth " + (reversed ? "1" : "0") +
                         (reversed ? " with its reversed-Z projection" : " with its standard projection") +
                         "), where no rendered surface lies. Is the depth cleared for the other convention (background "
                         "must hold " + (reversed ? "0" : "1") + ") or rendered with another projection than the camera's?");
}

} // namespace obscura::detail

#pragma once
// What adopt() checks and reads of the host's buffers (HostGBuffer): each texture against
// the depth and its own description, the normals' encoding, and the diagnostics of a camera
// that does not fit the depth.
#include "core/shader_library.hpp"
#include "core/texture_info.hpp"
#include "obscura/camera.hpp"
#include "obscura/gbuffer.hpp"

#include <string>

namespace obscura::detail {

struct ContextImpl;

//! A host texture read beside the depth: level 0, the depth's size, as the host described it
//! (requireDescribedAs). Throws Error{InvalidArgument} naming `who`.
TextureInfo hostTextureBeside(ContextImpl& ctx, const TextureView& given, const std::string& who, const TextureInfo& depth);

//! The host's second depth layer, read in place beside the first; empty stays empty. The first
//! layer itself (`depthName`) is refused: every peeled interval would be empty.
TextureView hostBackDepth(ContextImpl& ctx, const TextureView& texture, GLuint depthName, const TextureInfo& depth);

//! The host's albedo (SampledAs::Rgb) or radiance (SampledAs::FloatRgb: not bounded by 1), RGB
//! or RGBA, read in place, described as GL reports it. Empty stays empty.
TextureView hostColour(ContextImpl& ctx, const TextureView& texture, const std::string& who, const TextureInfo& depth,
                       SampledAs kind);

//! The host's normals as adopt() reads them: the texture (empty: reconstructed from depth),
//! the view's normalError, the conversion pass's defines, or none when read in place.
struct HostNormals {
    TextureView texture;
    float normalError = kHalfNormalError;
    Defines defines;
    bool inPlace = false; //!< NormalEncoding::ViewContract: no conversion pass
};

//! The conversion pass's defines for the host's normals (none given: FROM_DEPTH).
Defines normalDefines(const HostGBuffer& host);

//! HostGBuffer::normalEncoding and normalSpace among their enumerators, else
//! Error{InvalidArgument}.
void requireNormalEnumerators(const HostGBuffer& host);

//! Checks the normals' enumerators, deviation, format and encoding. Throws
//! Error{InvalidArgument} naming what is wrong and what is accepted.
HostNormals checkHostNormals(ContextImpl& ctx, const HostGBuffer& host, const TextureInfo& depth);

//! Diagnostic::ClipDepthMismatch: the camera's ClipDepth against the current clip control.
//! Reported once while a mismatch lasts (`reported` carries that between calls: a host whose
//! depth pass ran under another clip control hears it once, not every frame); with
//! ContextDesc::strictChecks thrown every time.
void reportClipDepthMismatch(ContextImpl& ctx, const Camera& camera, bool& reported);

//! Diagnostic::DepthOnNearPlane, from the count of the normals pass (from 1 % of w x h).
void reportNearPlanePixels(ContextImpl& ctx, GLuint pixels, int w, int h, const Camera& camera);

} // namespace obscura::detail

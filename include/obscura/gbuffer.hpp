#pragma once
// G-buffer: the per-pixel inputs every screen-space module reads.
//
// Either Obscura rasterizes the scene (render), or the host hands over its own depth buffer
// and optionally its normals, albedo, lit image and second depth layer (adopt, post-process
// mode). Both give a GBufferView with the same contract:
//   depth           hardware depth of `camera` (32F when ours); background = clear depth
//   normal          GL_RGBA16F (a host's GL_RGBA32F with NormalEncoding::ViewContract),
//                   view-space normal, unit length, turned toward the camera: the geometric
//                   (face) normal for ours, the host's (face or shading) normal otherwise;
//                   alpha = 0 on background, and on geometry the pixel's normal error in
//                   units of normalError, >= 1: 1 for ours and for a host's face normals,
//                   more for shading normals (HostGBuffer::normalDeviation), bent ones and
//                   normals reconstructed from depth
//   albedo          GL_SRGB8_ALPHA8, linear diffuse reflectance when sampled (ours; or the
//                   host's, HostGBuffer::albedo)
//   backDepth       second depth layer (depthLayers = 2, or HostGBuffer::backDepth): per
//                   pixel the nearest surface strictly behind `depth` (depth peeling), 32F
//                   when ours, clear depth where none; the back of closed objects, for
//                   screen-space thickness
//   directRadiance  GL_RGBA16F, W/(sr·m²): emission + Lambert from the scene's lights with
//                   the interpolated shading normal, each light shadowed when
//                   GBufferSettings::shadows has maps for it. Saturates at 65504, the
//                   largest finite half float, instead of overflowing to Inf. (Or the
//                   host's lit image, HostGBuffer::directRadiance.)
// View-space positions are never stored: they are reconstructed from depth
// (shaders/common/depth.glsl, DepthReconstruction in camera.hpp), along each pixel centre's
// ray. Their precision is the rasterizer's: one that interpolates depth from vertices
// snapped to its sub-pixel grid (NVIDIA, GL_SUBPIXEL_BITS = 8) puts the point off the
// surface by up to the depth's change over 1/256 of a pixel (docs/integration.md). Obscura's
// passes tolerate that, and the reference moves such samples onto the surface.
#include "obscura/camera.hpp"
#include "obscura/export.hpp"
#include "obscura/scene.hpp"
#include "obscura/shadow_maps.hpp"
#include "obscura/texture.hpp"

#include <cstddef>
#include <memory>

namespace obscura {

class Context;

//! The rounding of a unit normal stored as half floats that may round toward zero (llvmpipe's
//! stores do): each component within 2^-10 of its size, so the vector within 2^-10.
inline constexpr float kHalfNormalError = 1.0f / 1024.0f;
//! The largest GBufferView::normalError accepted: a tangent plane uncertain by more than
//! about 14 degrees says little about which side of it a point lies.
inline constexpr float kMaxNormalError = 0.25f;

//! Plain data: its textures stay their owner's. Every pass checks the ones it samples at
//! each call, since a host may change them after adopt() (or build a view by hand): depth and
//! backDepth a depth format sampled as depth (not stencil); normal a signed float or signed
//! normalized RGB(A) format (read as the vector itself); albedo and directRadiance a
//! normalized or float RGB(A) format; each with base level 0 and the depth's size.
//! Error{InvalidArgument} names the texture otherwise.
struct GBufferView {
    TextureView depth;
    TextureView normal;
    TextureView albedo;         //!< adopted host buffers: the host's, if it gave one
    TextureView directRadiance; //!< adopted host buffers: the host's, if it gave one
    TextureView backDepth;      //!< empty unless GBufferSettings::depthLayers == 2 or the host gave one
    //! Unitless, [0, kMaxNormalError]: a bound on the distance between a stored normal and the unit
    //! normal it stands for, times each pixel's normal alpha. Screen-space tests allow a point
    //! at distance d from a pixel, in that pixel's plane, up to d * normalError * alpha off
    //! the stored tangent plane (so a plane does not occlude itself). Ours and the default:
    //! 2^-10, the half-float store's rounding. adopt() adds what the host's format lost
    //! before that store (an 8-bit encoding: 7.8e-3 in all), see kHalfNormalError and
    //! adoptedNormalError, and puts in alpha what a pixel's normal may lie off its face
    //! beyond that (shading normals' HostGBuffer::normalDeviation, a bend at a silhouette,
    //! the bound of a normal reconstructed from depth).
    float normalError = kHalfNormalError;
    Camera camera;
    int width = 0;  //!< pixels
    int height = 0; //!< pixels
};

struct GBufferSettings {
    int width = 0;  //!< also at most GL_MAX_TEXTURE_SIZE
    int height = 0; //!< also at most GL_MAX_TEXTURE_SIZE
    bool directLighting = true;
    glm::vec3 background{0.0f};
    //! 2 adds `backDepth` (a second, depth-only pass over the scene that peels the first
    //! layer), for ScreenThickness::DepthPeeling and PeelingOrConstant (depthLayersFor).
    int depthLayers = 1;
    //! With directLighting: each light that has maps here is multiplied by its shadow, looked
    //! up per fragment as ShadowMaps::mask does (ShadowMaps::render with this camera, whose
    //! set must outlive the call). Null: unshadowed lights.
    const ShadowMapSet* shadows = nullptr;
    ShadowMaskSettings shadowFilter{}; //!< how `shadows` are filtered and biased: Hard or Pcf

    static const SettingsTable<GBufferSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<GBufferSettings>& GBufferSettings::table() {
    using S = GBufferSettings;
    using namespace settings;
    static const SettingsTable<S> rows = {
        number("width", &S::width, "pixels", "[1, 65536]", "image width"),
        number("height", &S::height, "pixels", "[1, 65536]", "image height"),
        flag("directLighting", &S::directLighting, "add the lights to directRadiance (off: emission only)"),
        color("background", &S::background, "W/(sr m^2)", "[0, 65504]", "radiance of background pixels, per channel"),
        number("depthLayers", &S::depthLayers, "layers", "[1, 2]", "2: also the second depth layer (backDepth)"),
    };
    return rows;
}

enum class NormalSpace { View, World };
enum class NormalEncoding {
    Signed,   //!< signed float formats holding n in [-1,1] (GL_RGB(A)16F/32F)
    //! n * 0.5 + 0.5 in a normalized format of at least 4 bits a channel (GL_RGB(A)8,
    //! GL_RGB10_A2, GL_RGB(A)16); not sRGB, which the sampler would decode
    Unsigned,
    //! Already as GBufferView::normal holds them: a float RGBA format (GL_RGBA16F as ours, or
    //! GL_RGBA32F), view space, unit, facing the camera, alpha 1 on geometry and 0 on
    //! background (another GBuffer's view normals, or a host pass written to that contract).
    //! Read in place: no conversion pass and no memory (a region is still copied). The host
    //! vouches for the contract, which nothing checks per pixel; alpha is each pixel's bound in
    //! units of the view's normalError (1 for exact normals). NormalSpace::View only, and
    //! HostGBuffer::normalDeviation must be 0 (it is applied by the conversion).
    ViewContract,
};

//! GBufferView::normalError of host normals with `bits` in their coarsest channel in
//! `encoding`, after adopt() normalizes them and stores them as half floats. The host's
//! encoding moves a unit normal by delta: Unsigned rounds each component to a step of [0, 1],
//! half a step off, 1 / (2^bits - 1) in [-1, 1], delta = sqrt(3) / (2^bits - 1); Signed floats
//! keep each component within 2^-10 (16-bit, rounded toward zero) or 2^-23 (32-bit) of its
//! size, delta = that. Normalizing turns the direction by at most asin(delta), which bounds
//! the chord; then kHalfNormalError for our store. Normals reconstructed from depth (no
//! HostGBuffer::normal) get kHalfNormalError here and a bound per pixel in their alpha (see
//! HostGBuffer::normal). Throws Error{InvalidArgument} for bits outside [1, 32].
OBSCURA_API float adoptedNormalError(NormalEncoding encoding, int bits);

//! A rectangle of texels, GL's origin: (x, y) is its lower-left texel, counted from the
//! texture's first column and row (the bottom one, as rendered with GL_LOWER_LEFT).
struct HostRect {
    int x = 0, y = 0;             //!< texels, >= 0
    int width = 0, height = 0;    //!< texels, >= 1 (HostGBuffer::region: both 0 for the whole texture)
};

//! The host's own buffers, for post-process use.
struct HostGBuffer {
    //! Required. GL_TEXTURE_2D, single-sampled, GL_DEPTH_COMPONENT16/24/32/32F or
    //! GL_DEPTH24_STENCIL8/GL_DEPTH32F_STENCIL8 (then GL_DEPTH_STENCIL_TEXTURE_MODE must be
    //! GL_DEPTH_COMPONENT). Here and in the other host textures, `name` is required and
    //! `internalFormat`, `width` and `height` are checked where not 0 (0: take GL's): a field
    //! that differs from what GL reports is refused with InvalidArgument naming both, since a
    //! description that lies (a copied snippet's format, last frame's size) is a host's bug. Pixels at the camera's
    //! clear depth are background, and so are those a float format lets hold what no
    //! rasterizer writes (NaN, +-Inf, below 0 or above 1), and depths farther than
    //! kMaxViewDistance (camera.hpp: with an infinite far plane, below near / 2^56);
    //! subnormal values count as 0 (the clear depth with reversed-Z, the near plane
    //! otherwise). Every pass leaves background pixels out.
    TextureView depth;
    //! Optional, same size: face normals, or smooth shading normals (interpolated from
    //! vertices; say how far they may lie from the faces' in normalDeviation). A normal
    //! facing away from the camera is turned around when the depth's own plane there lies on
    //! its other side (a back face drawn two-sided), and else (a shading normal past a
    //! silhouette, which turned around would point into the surface) bent just enough to face
    //! the camera: its component along the view ray removed down to dot(n, toward camera) =
    //! 1/64; that pixel's bound (alpha) grows by how far it was bent
    //! (tests/gl/test_silhouette_normals.cpp).
    //! Without it normals are reconstructed from depth: the cross product
    //! of one-sided differences to the neighbours whose depth steps least. Each pixel's alpha
    //! then bounds its error from the depth's precision (a step of the depth format through
    //! the projection; each pixel's depth must lie within one step of one plane through it and
    //! its neighbours: a smooth offset, like that of the host's own transform's rounding, does
    //! not count, the rasterizer's per-pixel rounding does; llvmpipe's rasterization into
    //! 16-, 24- and 32-bit depth keeps it in tests/gl/test_depth_normals.cpp's views) where the
    //! pixel and the two neighbours lie on one plane: 2 (any direction) where that precision
    //! cannot tell the plane or whether it faces the camera. The bound is about twice the
    //! depth error over the pixel spacing: it grows with the resolution and, for standard
    //! perspective depth, with the square of the distance. A floor 6 units away at 64 x 48
    //! pixels (50 degree field of view, near plane 0.05, seen from 15 degrees up or more)
    //! gets at most 0.014 with 24-bit depth, 0.3-0.56 with 16-bit depth. Alpha is in units of
    //! the adopted view's normalError (kHalfNormalError), and per-pixel bounds are not held
    //! to kMaxNormalError. Across creases and silhouettes the reconstruction is not the face
    //! normal, and no bound holds there.
    TextureView normal;
    //! Radians, [0, pi/2]: how far `normal` may lie from the face normals of the surface
    //! around its point (its own face and the faces that share a vertex with it). 0 (the
    //! default) for face normals. The screen-space tests trust each normal to within its
    //! bound and compare a pixel's rays with its neighbours' tangent planes, which may lie on
    //! the next face; a bound too small lets a curved surface's own neighbours hide its rays
    //! (ray-marched AO 0.2-0.5 along a coarse sphere's outline). For smooth shading normals
    //! give twice the largest angle between a vertex normal and the normals of the faces
    //! around that vertex (22 degrees on a 320-face sphere). Every pixel's bound (its alpha
    //! in the view) grows by 2 sin(deviation / 2), at the price of occluders that close to a
    //! tangent plane going unseen, as for 8-bit normals (docs/integration.md). Ignored
    //! without `normal`.
    float normalDeviation = 0.0f;
    NormalSpace normalSpace = NormalSpace::View;
    NormalEncoding normalEncoding = NormalEncoding::Signed;
    //! Optional, same size, used in place: diffuse reflectance, which IndirectLight and
    //! Composer need (AO does not read it). A normalized or float RGB/RGBA format; sRGB ones
    //! (GL_SRGB8, GL_SRGB8_ALPHA8) are decoded when read, others hold linear reflectance in
    //! [0, 1] (read clamped to it, NaN as 0); alpha is not read. In a metallic workflow that is
    //! base colour times (1 - metallic); baked AO or cavity do not belong in it (AO multiplies
    //! the ambient term itself).
    TextureView albedo;
    //! Optional, same size, used in place: the radiance each pixel sends to the camera from
    //! direct light, W/(sr·m²), linear (the host's lit image before AO, indirect light and
    //! tone mapping), in a float RGB/RGBA format (GL_R11F_G11F_B10F, GL_RGB16F, GL_RGBA16F,
    //! GL_RGB32F, GL_RGBA32F). IndirectLight gathers it; Composer needs it and albedo.
    TextureView directRadiance;
    //! Optional, same size, used in place: a second depth layer, for the screen-space thickness
    //! modes that read one (ScreenThickness::DepthPeeling, PeelingOrConstant). The same
    //! formats and rules as `depth`, written with the same camera and depth convention: per
    //! pixel the nearest surface strictly behind `depth` (a peeling pass that discards
    //! fragments at or in front of the first layer's depth), clear depth where there is none.
    //! Screen-space tests count a point as solid between the two layers, so another second
    //! layer (a pass of back faces, say) is used as given. Not `depth` itself (nothing would
    //! be solid; adopt() refuses it with InvalidArgument). The same format as `depth` is
    //! best: a coarser one may round the back in front of the first layer, and such a pixel
    //! has no depth behind it.
    TextureView backDepth;
    //! The part of the textures above that is the view, for a host that renders into part
    //! of larger targets (dynamic resolution, split screen). Every given texture is read at
    //! the same rectangle, which must lie within them; the camera is the one the host
    //! rendered that rectangle with, and the view is region.width x region.height pixels.
    //! The default (all 0): the whole textures, read in place. A rectangle smaller than the
    //! textures is copied out of each given texture into one of ours of the same format and
    //! swizzle (glCopyImageSubData, pass "gbuffer.region"), and the view's textures are
    //! those copies: they cost that memory (memoryBytes()) and the copy on every adopt(),
    //! and hold what the host's held at the call.
    HostRect region;
};

class OBSCURA_API GBuffer {
public:
    explicit GBuffer(Context& context);
    ~GBuffer();

    //! Rasterizes every mesh and mesh reference of the scene. Pass "gbuffer.render".
    //! Throws Error{InvalidArgument} for a bad size, a non-finite camera or light, a material
    //! index out of range, non-finite mesh positions, an unusable host buffer, or a material
    //! texture that is one of this GBuffer's own images (drawn into while sampled: render the
    //! frame that shows it with another GBuffer).
    GBufferView render(const Scene& scene, const Camera& camera, const GBufferSettings& settings);

    //! Wraps the host's depth (and normal, albedo, radiance, back depth) textures. Depth,
    //! albedo, radiance and back depth are used in place (or their region's copies); normals
    //! are converted to the view-space contract above, or reconstructed from depth when
    //! absent (pass "gbuffer.normals"), or used in place with NormalEncoding::ViewContract;
    //! HostGBuffer::region is copied out where it is not the whole textures. Throws
    //! Error{InvalidArgument} for a wrong target, format, sample count or size, a stated
    //! format or size other than GL's, a region outside the depth texture, a backDepth that
    //! names the depth texture, and for a texture of a view this GBuffer's adopt() returned
    //! (its normals or a region's copy, which this call would overwrite or free; another
    //! GBuffer may adopt it). Reports Diagnostic::ClipDepthMismatch and DepthOnNearPlane
    //! (context.hpp), once for each change of what they compare; with
    //! ContextDesc::strictChecks it throws them as Error{InvalidArgument} instead, the clip
    //! depth before any GL work, the near-plane count after the normals pass (which wrote
    //! only this GBuffer's own texture).
    GBufferView adopt(const HostGBuffer& host, const Camera& camera);

    //! Compiles the program adopt() runs for such host buffers ahead of time (from whether
    //! `host.normal` is given, its encoding and space; no texture is read, and nothing is
    //! allocated). Throws Error{InvalidArgument} for enumerators out of range.
    void prepareAdopt(const HostGBuffer& host);

    //! View-space positions reconstructed from depth into a GL_RGBA32F texture (xyz in world
    //! units, alpha = 1 on geometry, 0 on background with xyz = 0). Pass "gbuffer.positions".
    //! For debugging, tests and tools; modules reconstruct on the fly instead.
    TextureView positions(const GBufferView& view);

    //! GPU memory this module holds right now, bytes.
    std::size_t memoryBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura

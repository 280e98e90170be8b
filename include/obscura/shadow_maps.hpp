#pragma once
// Shadow maps of the scene's spot and directional lights, and the shadow mask they give at
// a G-buffer's samples (obscura::reference::Shadow is the ground truth).
//
// Maps are GL_DEPTH_COMPONENT32F layers of one 2D array texture, rendered with reversed-Z
// (near -> 1) through clip control and with depth clamp, so that casters in front of a
// map's near plane still occlude (clamped onto it):
//   Spot         one perspective map over the outer cone (field of view 2 outerAngle); far
//                plane at the scene's farthest point, near plane far / 10^4.
//   Directional  `cascades` orthographic maps over slices of the camera's view distance
//                range inside the scene's bounds, split by the PSSM rule
//                d_i = lambda d_log + (1 - lambda) d_uniform. Each covers its slice's bounding
//                sphere (whose size depends only on the slice's distances and the projection,
//                not on where the camera looks; the distances follow the scene's depth range),
//                with its centre snapped to whole texels in light space, so that the maps do
//                not shimmer with camera motion; along the light each spans the whole scene,
//                so every caster is in every cascade.
//   Point        a cube of six perspective maps along the world axes (+x, -x, +y, -y, +z,
//                -z), each a little wider than 90 degrees so that filter kernels near a
//                face's edge stay on it; a receiver is looked up in the face of the major
//                axis of its direction from the light.
//                With PointShadowMapping::DualParaboloid instead: two paraboloid maps, the
//                first looking down (-y), the second up (+y). A unit direction r from the
//                light (in the map's frame, r_z along its axis) lands at
//                (r_x, r_y) / (1 + r_z), which fills the map's inscribed disc with one
//                hemisphere; the other hemisphere is clipped off (at r_z = 0, in 3D, before
//                the projection). The projection is non-linear but the rasterizer draws
//                straight edges, so each fragment's depth is corrected: it is the distance
//                along the fragment's exact direction to its triangle's plane. What stays
//                wrong is coverage: a triangle covers the straight-edged shape of its
//                projected corners, not its curved image, so pixels near a silhouette edge
//                can see a caster that misses them or miss one that covers them. That
//                residual is measured against the reference by `obscura bench`
//                (shadow.paraboloid next to shadow.cube: false_shadow and false_light);
//                away from silhouette edges the mask equals the reference exactly
//                (tests/gl/test_shadow_maps.cpp, a 40 m floor of two triangles). A texel
//                spans (L + r_z L) 2 / resolution world units at distance L: twice as fine
//                at the rim as on the axis. PCF kernels that cross the disc's rim read the
//                empty margin around it (lit).
// Sphere lights are mapped like point lights, from their centre (for Pcss). Rect lights get
// one paraboloid map from their centre, its axis along Light::direction (x along the
// tangent), over the side they emit toward; receivers behind their plane are 0 (unlit), and
// receivers in front of it that face away from its centre are 1 (the map from the centre
// cannot tell what part of the light they see; the light's shading clips it to their
// horizon). Triangles whose plane passes through a light's centre (a rect light flush with
// its ceiling) are seen edge-on and left out of its paraboloid maps.
// Lights with castsShadows off get no map: mask() refuses them.
//
// Mask: per G-buffer pixel, the fraction of the filter's depth comparisons that find the
// receiver lit, in [0, 1] (1 = lit), GL_R16F (values rounded by at most 2^-12). The
// receiver is the pixel's reconstructed point moved, in world units, toward the light by
// constantBias + slopeBias * texel * tan(theta) and along its geometric normal by
// normalOffset * texel, where texel is the side of one map texel at the receiver and theta
// the angle between the normal and the light. Pixels the light does not reach (facing away,
// outside a spot's outer cone) are 0; background pixels are 1.
//   Hard  one comparison: the texel the receiver falls in;
//   Pcf   (2 pcfRadius + 1)^2 comparisons one texel apart, each bilinearly weighted over
//         its four texels (hardware comparison with linear filtering), each against the
//         receiver's plane extended to the tap (receiverPlane). With PcfKernel::OptimizedGrid
//         the same texel weights from (pcfRadius + 1)^2 comparisons (Castaño's optimized
//         PCF, as in The Witness): per axis the grid weighs the 2 pcfRadius + 2 texels it
//         touches (1 - f, 1, ..., 1, f) / (2 pcfRadius + 1), f the receiver's position past
//         the texel centre below it; one comparison serves each pair of neighbouring texels,
//         placed where its bilinear weights split the pair's total as the grid does. Without
//         receiverPlane it equals Grid up to the filtering's sub-texel precision (8 bits on
//         most GPUs); with it, each comparison uses the plane at its own position. With PcfKernel::PoissonDisc
//         instead: 16 bilinear comparisons at a Poisson disc's points (minimum distance
//         0.3 of the disc's radius) scaled to pcfRadius + 0.5 texels and rotated per pixel
//         (interleaved gradient noise on the map coordinate), which trades the grid's
//         banding for noise at a fixed cost.
//   Vsm, Esm, Evsm2, Evsm4, Msm   from prefiltered moments of the maps' distances (see the
//         settings); ShadowMaps::mask only (the G-buffer's lookups are Hard or Pcf).
//   Pcss  percentage-closer soft shadows (Fernando 2005) for a light of radius R
//         (Light::radius; for a rect light sqrt(w h / pi), the disc of its area, whatever
//         the receiver's angle to it; 0 for directional lights, which then get a half-texel
//         kernel):
//         the mean distance z_b of the blockers among 16 Poisson-disc depth reads (a
//         blocker: nearer the light than the receiver's plane; see pcssBlockerFraction for
//         the disc), then a 16-tap Poisson PCF of radius R (z_r - z_b) / z_b world units at
//         the receiver (distance z_r), the penumbra's half-width for a blocker parallel to
//         the receiver, converted to texels there and clamped to [0.5, 128]. No blocker
//         found: lit. The flat-blocker assumption and the 16 taps (noise in wide penumbrae)
//         are its error against an area light's shadow; ShadowMaps::mask only.
// Between cascades the mask blends linearly over the last `cascadeBlend` of each slice.
#include "obscura/camera.hpp"
#include "obscura/export.hpp"
#include "obscura/settings_table.hpp"
#include "obscura/scene.hpp"
#include "obscura/texture.hpp"

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace obscura {

class Context;
struct GBufferView; // obscura/gbuffer.hpp, which includes this header for its settings

constexpr int kMaxShadowCascades = 4;
constexpr int kMaxShadowMapsPerLight = 6; //!< a point light's cube

//! How a point light is mapped: "shadow.cube" and "shadow.paraboloid".
enum class PointShadowMapping {
    Cube,           //!< six perspective maps
    DualParaboloid, //!< two paraboloid maps (a third of the cube's memory), per-pixel depth correction
};

struct ShadowMapSettings {
    int resolution = 1024; //!< also at most GL_MAX_TEXTURE_SIZE
    int cascades = 3;      //!< at most kMaxShadowCascades
    float splitLambda = 0.75f;
    PointShadowMapping pointMapping = PointShadowMapping::Cube;
    //! Rendered in the same draws as the depth (ShadowMapSet::flux, normal, position).
    bool reflective = false;

    static const SettingsTable<ShadowMapSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<ShadowMapSettings>& ShadowMapSettings::table() {
    using S = ShadowMapSettings;
    using namespace settings;
    static const SettingsTable<S> rows = {
        number("resolution", &S::resolution, "texels", "[16, 8192]", "side of every map"),
        number("cascades", &S::cascades, "maps", "[1, 4]", "maps per directional light"),
        number("splitLambda", &S::splitLambda, "", "[0, 1]", "PSSM weight of the logarithmic split (0: uniform)"),
        choice("pointMapping", &S::pointMapping,
               {{"cube", PointShadowMapping::Cube}, {"paraboloid", PointShadowMapping::DualParaboloid}},
               "how point lights are mapped"),
        flag("reflective", &S::reflective, "also render reflective shadow maps of spot and directional lights"),
    };
    return rows;
}

//! The maps of one light.
struct ShadowMapInfo {
    std::size_t light = 0;          //!< index in Scene::lights
    Light source;                   //!< that light, as the maps were rendered for it
    LightType type = LightType::Spot;
    int firstLayer = 0;             //!< of ShadowMapSet::depth
    int layers = 0;                 //!< 1 (spot, rect), the cascades (directional), 6 (cube) or 2 (paraboloid)
    bool paraboloid = false;        //!< a point light's dual-paraboloid maps, or a rect light's one
    //! World -> clip space of each map (reversed-Z, clip control zero-to-one); paraboloid
    //! maps: world -> the map's frame (rigid; the light at the origin, the map's axis +z).
    std::array<glm::mat4, kMaxShadowMapsPerLight> worldToClip{};
    //! Directional: the far end of each cascade's slice, view distance along the camera's
    //! axis, world units (the first slice starts at the scene's nearest point, >= near).
    std::array<float, kMaxShadowMapsPerLight> sliceEnd{};
    float sliceStart = 0.0f; //!< directional: where the first slice begins (view distance, world units)
    //! Side of one texel: world units (directional), world units per unit distance along
    //! the map's axis (spot, cube), or 2 / resolution (paraboloid: see above).
    std::array<float, kMaxShadowMapsPerLight> texelSize{};
    //! Per map (a, b, near, far): a window depth d lies at distance b / (d + a) (perspective)
    //! or (b - d) / a (orthographic) along the map's axis (paraboloid: from the light),
    //! between its near and far planes
    //! (world units): the moment filters work on that distance scaled to [0, 1].
    std::array<glm::vec4, kMaxShadowMapsPerLight> depthMapping{};
};

//! Whether ShadowMaps::render gives `light` maps: any light with castsShadows.
OBSCURA_API bool hasShadowMaps(const Light& light);

//! What ShadowMaps::render produced; valid until its next render.
struct ShadowMapSet {
    unsigned depth = 0; //!< GL_TEXTURE_2D_ARRAY, GL_DEPTH_COMPONENT32F; 0 when no light casts shadows
    //! Reflective shadow maps (ShadowMapSettings::reflective; else 0), GL_TEXTURE_2D_ARRAY with
    //! the layers of `depth`, filled for spot and directional lights' layers (point lights'
    //! stay 0). Per texel, of the surface the light sees through it:
    //!   flux      GL_RGBA16F: the flux it reflects, W (RGB): albedo times the power through
    //!             the texel (directional: irradiance x texel area; spot: intensity x cone x
    //!             the texel's solid angle), the material's albedo factor (not its texture);
    //!   normal    GL_RGBA16F: its geometric (triangle) normal, world space, facing the light;
    //!   position  GL_RGBA32F: its world position, world units.
    //! Alpha is 1 where a surface was seen, 0 elsewhere.
    unsigned flux = 0, normal = 0, position = 0;
    int resolution = 0; //!< texels per side
    int layers = 0;
    std::vector<ShadowMapInfo> maps;
    Camera camera;      //!< the camera the cascades were fitted to
    //! The maps of Scene::lights[light], or null when it has none.
    const ShadowMapInfo* find(std::size_t light) const;
};

//! How the moment filters store their moments.
enum class ShadowMomentPrecision {
    Float32, //!< RGBA32F
    //! 8 bytes a texel: RGBA16F for Vsm, Esm, Evsm (Evsm's exponents clamped to
    //! ln(65504) / 2 = 5.54 so that e^(2c) stays finite), and for Msm 16-bit UNORM in Peters
    //! and Klein's optimized basis with their 64-bit bias (6e-5 toward uniform moments).
    //! Half floats round t and t^2 by 2^-11 relative, so Vsm's variance floor wants to be
    //! ~1e-4 rather than 1e-6 for the same light bleeding.
    Bits16,
};

enum class PcfKernel {
    Grid,          //!< (2 pcfRadius + 1)^2 taps one texel apart
    PoissonDisc,   //!< 16 taps, a rotated Poisson disc of radius pcfRadius + 0.5 texels
    OptimizedGrid, //!< the Grid's texel weights from (pcfRadius + 1)^2 taps
};

enum class ShadowFilter {
    Hard,  //!< "shadow.hard"
    Pcf,   //!< "shadow.pcf"
    Vsm,   //!< "shadow.vsm": variance shadow map, Chebyshev's bound
    Esm,   //!< "shadow.esm": exponential shadow map, prefiltered in log space
    Evsm2, //!< "shadow.evsm2": exponentially warped VSM, positive warp
    Evsm4, //!< "shadow.evsm4": positive and negative warps
    Msm,   //!< "shadow.msm": four moments, Hamburger reconstruction (32F)
    Pcss,  //!< "shadow.pcss": percentage-closer soft shadows for a light of Light::radius (rect: its area's disc)
};

struct ShadowMaskSettings {
    ShadowFilter filter = ShadowFilter::Pcf;
    int pcfRadius = 1;
    PcfKernel pcfKernel = PcfKernel::Grid;
    //! The search covers a disc of R (1 - f) / f world units at the receiver (at most 128
    //! texels); nearer blockers are found only in part.
    float pcssBlockerFraction = 0.25f;
    float constantBias = 0.0f;
    float slopeBias = 1.0f; //!< tan(theta) clamped at 16
    float normalOffset = 1.0f;
    float cascadeBlend = 0.1f;
    //! Not where the light sees the plane edge-on (within 1e-3 rad). Past tan theta = 16 (3.6
    //! degrees off edge-on) the slope bias is clamped, and PCF's own taps may meet acne there;
    //! PCSS, which finds no blocker, does not.
    bool receiverPlane = true;
    // Moment filters (Vsm .. Msm): the maps' distances t in [0, 1] (near to far plane) become
    // moments, blurred by a separable Gaussian, sampled bilinearly.
    int momentBlur = 2; //!< sigma = radius / 2
    ShadowMomentPrecision momentPrecision = ShadowMomentPrecision::Float32;
    float minVariance = 1e-6f;
    float lightBleedReduction = 0.2f;
    //! Log-space filtering keeps e^(c t) out of the float range; Evsm's c+ is clamped to 42
    //! so that e^(2 c+) stays finite in 32F (5.54 with Bits16).
    float exponent = 40.0f;
    float negativeExponent = 5.0f;
    //! ShadowMaps::mask only: ScreenVisibility's view-space march from the receiver lifted by a
    //! texel; restores the contact shadows that the biases remove.
    float contactLength = 0.0f;
    int contactSteps = 16;
    //! Thin, so that rays passing behind an occluder stay lit.
    float contactThickness = 0.05f;

    static const SettingsTable<ShadowMaskSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<ShadowMaskSettings>& ShadowMaskSettings::table() {
    using S = ShadowMaskSettings;
    using namespace settings;
    static const SettingsTable<S> rows = {
        choice("filter", &S::filter,
               {{"hard", ShadowFilter::Hard}, {"pcf", ShadowFilter::Pcf}, {"vsm", ShadowFilter::Vsm},
                {"esm", ShadowFilter::Esm}, {"evsm2", ShadowFilter::Evsm2}, {"evsm4", ShadowFilter::Evsm4},
                {"msm", ShadowFilter::Msm}, {"pcss", ShadowFilter::Pcss}},
               "the lookup (ShadowFilter)"),
        number("pcfRadius", &S::pcfRadius, "texels", "[0, 8]", "Pcf: comparisons each side of the centre"),
        choice("pcfKernel", &S::pcfKernel,
               {{"grid", PcfKernel::Grid}, {"optimized", PcfKernel::OptimizedGrid}, {"poisson", PcfKernel::PoissonDisc}},
               "Pcf: the taps (PcfKernel)"),
        number("pcssBlockerFraction", &S::pcssBlockerFraction, "", "(0, 1)",
               "Pcss: blockers searched down to this fraction of the receiver's distance"),
        number("constantBias", &S::constantBias, "world units", "[0, inf)", "receiver moved toward the light"),
        number("slopeBias", &S::slopeBias, "texels", "[0, 16]", "depth per unit tan(theta), toward the light"),
        number("normalOffset", &S::normalOffset, "texels", "[0, 16]", "receiver moved along its geometric normal"),
        number("cascadeBlend", &S::cascadeBlend, "", "[0, 0.5]", "fraction of each cascade's slice blended into the next"),
        flag("receiverPlane", &S::receiverPlane, "Pcf: compare each tap with the receiver's plane extended to it"),
        number("momentBlur", &S::momentBlur, "texels", "[0, 8]", "moment filters: Gaussian prefilter radius"),
        choice("momentPrecision", &S::momentPrecision,
               {{"32", ShadowMomentPrecision::Float32}, {"16", ShadowMomentPrecision::Bits16}},
               "moment filters: RGBA32F, or 8 bytes a texel (ShadowMomentPrecision)"),
        number("minVariance", &S::minVariance, "t^2", "[0, 1]", "Vsm, Evsm: variance floor (warped: scaled)"),
        number("lightBleedReduction", &S::lightBleedReduction, "", "[0, 1)", "Vsm, Evsm: Chebyshev bounds below it count as 0"),
        number("exponent", &S::exponent, "", "[0, 80]", "Esm: c; Evsm: the positive warp's c+"),
        number("negativeExponent", &S::negativeExponent, "", "[0, 42]", "Evsm4: the negative warp's c-"),
        number("contactLength", &S::contactLength, "world units", "[0, inf)",
               "screen-space contact-shadow ray toward the light (0: off)"),
        number("contactSteps", &S::contactSteps, "samples", "[1, 256]", "samples of the contact ray"),
        number("contactThickness", &S::contactThickness, "world units", "(0, inf)",
               "how far behind a depth sample the contact ray counts as inside"),
    };
    return rows;
}

class OBSCURA_API ShadowMaps {
public:
    explicit ShadowMaps(Context& context);
    ~ShadowMaps();

    //! Renders the maps of every shadow-casting light (pass
    //! "shadow.maps"); allocates nothing when there is none. Throws Error{InvalidArgument}
    //! for settings out of range, an invalid scene or camera.
    const ShadowMapSet& render(const Scene& scene, const Camera& camera, const ShadowMapSettings& settings);

    //! As above, but directional cascades split the view distances that `depth`'s pixels
    //! hold (its nearest and farthest geometry: pass "shadow.depth_range", a GPU min/max and
    //! an 8-byte read-back, which waits for the G-buffer) instead of the range over which the
    //! scene's bounds are visible; meshes the bounds miss (MeshRefs) count too. `depth` must
    //! be a view of `camera`: a depth pre-pass, or the last frame's G-buffer while the camera
    //! has not moved. Without geometry in it, the bounds' range is used. Throws as above, and
    //! Error{InvalidArgument} for a view of another camera or without depth.
    const ShadowMapSet& render(const Scene& scene, const Camera& camera, const ShadowMapSettings& settings,
                               const GBufferView& depth);

    //! The mask of Scene::lights[light] at the G-buffer's samples (pass "shadow.mask"),
    //! GL_R16F at the G-buffer's size. `maps` must come from render() with the G-buffer's
    //! camera. Throws Error{InvalidArgument} for settings out of range, a light without
    //! maps, maps of another camera, or a G-buffer without depth or normal.
    TextureView mask(const GBufferView& gbuffer, const ShadowMapSet& maps, std::size_t light,
                     const ShadowMaskSettings& settings);

    //! GPU memory held right now, bytes.
    std::size_t memoryBytes() const;
    //! The same, split by the pass that writes it: "shadow.maps" (depth maps, reflective maps,
    //! the meshes' buffers), "shadow.moments" (the moment maps and their blur temporary),
    //! "shadow.mask" (the mask, its parameters), "shadow.depth_range" (its result). Sums to
    //! memoryBytes().
    std::vector<std::pair<std::string, std::size_t>> memoryByPass() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura

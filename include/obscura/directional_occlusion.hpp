#pragma once
// Screen-space directional occlusion (SSDO; Ritschel, Grosch and Seidel 2009, "Approximating
// dynamic global illumination in image space") from a G-buffer, lit by an environment.
//
// Direct light: per pixel, `rays` cosine-weighted directions in the normal's hemisphere, each
// tested with `steps` depth-buffer samples out to r_max = `radius` (steps = 1 is the paper's
// one point at a random distance in [0, r_max]; more find thin occluders a point misses). A
// direction with no hidden sample is open and brings the environment's radiance:
//   L_dir(x) = (rho/pi) Integral L_env(w) V(x, w) (n.w) dw ~ rho * mean over the directions of
//   L_env(w) V(w),
// the environment read from its cube at the whole mip level nearest the one whose texels
// subtend 2 pi / rays (a sample stands for that much of the hemisphere; `prefilter` false:
// level 0). This estimates
// obscura::reference::ImageBasedLight with visibility limited to r_max; what the screen
// cannot see counts as open (AmbientOcclusion's border and thickness rules).
//
// Bounce (`bounce`): every hidden sample stands for a sender patch of area A_s = pi r_max^2 /
// rays of the surface its pixel shows, with that pixel's outgoing radiance (the direct pass's
// result, plus the G-buffer's directRadiance where it has one: its lights):
//   L_ind(x) = strength (rho/pi) Sum L_q min(A_s cos_s / d^2, omega_max) cos_r,
// senders seen from behind (cos_s <= 0) or below x's tangent plane rejected. The paper
// clamps d >= 1 scene unit instead, which changes the result when the scene's unit changes;
// omega_max = 2 pi (1 - 1/sqrt(2)) ~ 1.84 sr is the solid angle a disc of area A_s subtends
// on its axis at its own radius r_max / sqrt(rays), the same d/r_max threshold at every scale:
// the result does not change when the scene and r_max are scaled together.
//
// Lights (DirectionalOcclusionInputs::lights): their irradiance at each pixel as the
// G-buffer computes it, times their shadow maps' lit fraction, times a screen-space
// correction: the shadow biases move a map's receiver toward the light, so an occluder on
// that segment (a contact shadow) is missed; a screen-space march from the pixel toward the
// light over `shadowCorrection` times that segment finds it (ShadowMaskSettings::contactSteps
// samples, as thin as its contactThickness; its contactLength is ShadowMaps::mask's only).
//
// Instant radiosity (`vplGrid` > 0, pass "ssdo.vpls", full resolution): virtual point lights
// from the reflective shadow maps of the spot and directional lights (ShadowMapSettings::
// reflective; a directional light's widest cascade), one per cell of a vplGrid x vplGrid grid
// over each map with the cell's flux, each tested with the shadow correction's screen-space
// march along the whole segment to it; the irradiance of a VPL is bounded by its cell's
// exitance (d^2 >= area / pi). Added to `indirect`; the bounce's senders then carry the
// environment's light only (the VPLs are the lights' bounce).
//
// Extra views (`extraViews`, 1 to 4): cameras with the main one's projection, their eyes
// moved right, left, up and down by `extraViewOffset` times the scene's bounding radius,
// looking at the point of the main view axis nearest the scene's centre, rendered at
// `extraViewScale` of the G-buffer's size (pass "ssdo.views"). A sample is occluded when some
// view sees it hidden and none sees it in front of its surface (a view it lies outside of, or
// sees it behind a surface deeper than `thickness`, has no vote): occluders off screen or
// behind others in the main view are found, and gaps behind a front surface that another view
// sees into stay open. A thin occluder that any view sees past (one seen edge-on) is missed. With extra views the march
// takes view-space samples (`march` is ignored).
//
// Depth peeling: `thicknessMode` DepthPeeling (GBufferSettings::depthLayers = 2) classifies
// samples against the second depth layer, so gaps behind thin objects stay open.
//
// Outputs, GL_RGBA16F radiance in W/(sr m^2) at the G-buffer's size (alpha 1 on geometry; 0
// on background pixels): `direct` and, with `bounce`, `indirect`. Each is filtered and
// upsampled as AO is (integratorRows), the albedo multiplied in after the filters.
#include "obscura/ambient_occlusion.hpp"
#include "obscura/environment.hpp"
#include "obscura/export.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/screen_visibility.hpp"
#include "obscura/scene.hpp"
#include "obscura/settings_table.hpp"
#include "obscura/shadow_maps.hpp"
#include "obscura/texture.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

namespace obscura {

class Context;

struct DirectionalOcclusionSettings {
    float radius = 1.0f;
    int rays = 16;
    int steps = 4;
    float thickness = 0.0f;
    ScreenThickness thicknessMode = ScreenThickness::Constant;
    ScreenMarch march = ScreenMarch::View;
    //! Each lookup stands for 2 pi / rays of the hemisphere: false reads level 0 (sharp, noisier).
    bool prefilter = true;
    bool bounce = false;
    float bounceStrength = 1.0f;
    float shadowCorrection = 2.0f;
    //! Needs reflective shadow maps in DirectionalOcclusionInputs::shadows.
    int vplGrid = 0;
    //! Needs DirectionalOcclusionInputs::scene: a host's G-buffer has none to render them from.
    int extraViews = 0;
    float extraViewScale = 0.5f;
    float extraViewOffset = 0.25f;
    AoResolution resolution = AoResolution::Full;
    int blurRadius = 0;
    float blurDepthSigma = 0.05f;
    float blurNormalPower = 16.0f;
    float refineThreshold = 0.25f;
    int rayLanes = 1;
    bool geometryTiles = true;
    std::uint32_t frameIndex = 0;
    TemporalSettings temporal{}; //!< of each output

    static const SettingsTable<DirectionalOcclusionSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<DirectionalOcclusionSettings>& DirectionalOcclusionSettings::table() {
    using S = DirectionalOcclusionSettings;
    using namespace settings;
    static const SettingsTable<S> rows = join<S>(
        {
            number("radius", &S::radius, "world units", "(0, inf)", "r_max: how far occluders are looked for"),
            number("rays", &S::rays, "", "[1, 1024]", "cosine-weighted directions per pixel (N)"),
            number("steps", &S::steps, "", "[1, 256]", "depth samples per direction (1: one point at a random distance)"),
            number("thickness", &S::thickness, "world units", "[0, inf)",
                   "how far behind a depth sample's tangent plane a point is inside (0: the radius)"),
            screenThicknessRow(&S::thicknessMode, "constant thickness, the second depth layer (peeling), or the deeper of both"),
            screenMarchRow(&S::march, "3D samples, 2D samples, or 2D samples skipping runs through a Hi-Z pyramid"),
            flag("prefilter", &S::prefilter, "read the environment at the level whose texels subtend 2 pi / rays (false: level 0)"),
            flag("bounce", &S::bounce, "also compute `indirect`, the occluders' light (pass ssdo.bounce)"),
            number("bounceStrength", &S::bounceStrength, "", "[0, inf)", "scales the bounce (1: the estimate)"),
            number("vplGrid", &S::vplGrid, "cells per side", "[0, 64]",
                   "instant radiosity: a VPL per cell of this grid over each reflective shadow map (0: off)"),
            number("extraViews", &S::extraViews, "views", "[0, 4]",
                   "more cameras whose depth classifies the samples too (scene mode; 0: off)"),
            number("extraViewScale", &S::extraViewScale, "", "(0, 1]", "extra views' resolution, relative to the G-buffer's"),
            number("extraViewOffset", &S::extraViewOffset, "scene radii", "(0, 16]",
                   "how far each extra eye moves from the camera's, right, left, up, down"),
            number("shadowCorrection", &S::shadowCorrection, "biased segments", "[0, inf)",
                   "lights: the screen march toward each shadowed light covers this multiple of the segment the "
                   "shadow biases skip (0: off)"),
        },
        integratorRows<S>());
    return rows;
}

//! What lights the pixels.
struct DirectionalOcclusionInputs {
    //! The environment (required): its cube, at its lookup's intensity and rotation. Its sun,
    //! when split out, is not included: pass it among `lights`.
    const EnvironmentMap* environment = nullptr;
    //! Point, spot, directional, sphere and rect lights (Scene::lights' units), added to
    //! `direct` at full resolution by pass "ssdo.lights" with their shadow maps' visibility:
    //! give the G-buffer no direct lighting of its own (GBufferSettings::directLighting), or
    //! the bounce counts these lights twice. The span must outlive the call.
    std::span<const Light> lights{};
    //! Maps of some of `lights` (ShadowMaps::render with the same lights, in order): their
    //! visibility, Hard or Pcf as `shadowFilter` says, corrected in screen space along the
    //! segment the biases skip (DirectionalOcclusionSettings::shadowCorrection). Null: unshadowed.
    const ShadowMapSet* shadows = nullptr;
    ShadowMaskSettings shadowFilter{};
    //! The scene the G-buffer shows (its CPU meshes), for `extraViews`: each extra view is a
    //! G-buffer of it rendered by the module. A host G-buffer (GBuffer::adopt) has no scene:
    //! leave it null and extraViews 0. Must outlive the call.
    const Scene* scene = nullptr;
};

struct DirectionalOcclusionView {
    TextureView direct;   //!< GL_RGBA16F, W/(sr m^2)
    TextureView indirect; //!< GL_RGBA16F, W/(sr m^2); empty unless settings.bounce or vplGrid
    int width = 0, height = 0;
};

class OBSCURA_API DirectionalOcclusion {
public:
    explicit DirectionalOcclusion(Context& context);
    ~DirectionalOcclusion();

    //! Passes "ssdo.hiz" (HiZ march), "ssdo.direct", then "ssdo.blur", "ssdo.upsample",
    //! "ssdo.refine", "ssdo.temporal" when used, "ssdo.lights" with lights; with `bounce`
    //! "ssdo.bounce" and its own "ssdo_bounce.*" filters. Throws Error{InvalidArgument} for
    //! settings out of range, no environment (or one of another Context), lights out of range,
    //! shadow maps that do not fit them or the camera, a G-buffer without depth, normal or albedo
    //! (or backDepth for DepthPeeling and PeelingOrConstant), or a G-buffer texture that is
    //! one of this object's outputs. The view stays valid until the next run.
    DirectionalOcclusionView run(const GBufferView& gbuffer, const DirectionalOcclusionInputs& inputs,
                                 const DirectionalOcclusionSettings& settings);

    //! Compiles the programs run() takes for these settings (as AmbientOcclusion::prepare): the
    //! direct pass and, with `bounce`, the bounce, with their filters. The lights pass's
    //! program depends on the inputs (rect lights, shadow maps and their filter), and the extra
    //! views' G-buffer programs on the scene: they compile on the first run that takes them.
    void prepare(const DirectionalOcclusionSettings& settings);

    //! The last run's refinement (RefinementCount, ambient_occlusion.hpp), the direct pass's
    //! and the bounce's added; zeros at full resolution. Waits for the run: not for every frame.
    RefinementCount lastRefinement() const;

    //! Forgets the temporal history of both outputs.
    void resetHistory();

    std::size_t memoryBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura

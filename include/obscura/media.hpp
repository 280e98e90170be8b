#pragma once
// Participating media: single scattering of the scene's point, spot and directional lights in
// media boxes (Scene::media: homogeneous, exponential height fog, or a density grid sampled
// trilinearly), seen along each pixel's view ray up to its surface
// (or through the whole box on background pixels):
//   L_s = Integral_0^t_s T(0,t) Sum_lights sigma_s p(theta) L_i(t) T(t, light) V(t) dt
// with L_i = I / max(d^2, r^2) (times a spot's cone) for point and spot lights, E for
// directional ones, theta between the light's travel direction and the way to the camera.
// This is what obscura::reference::SingleScattering computes. Area lights are left out (as
// there).
//
// Methods (MediaSettings::method):
//   RayMarch  `steps` samples over the view ray's part inside the media, jittered per pixel,
//             each integrated with the energy-conserving step (Hillaire 2015), the shadow maps
//             tested at every sample (MediaInputs::shadows). Error: with jitter, noise of
//             O(1/steps) per pixel; without, O(1/steps^2) for smooth
//             integrands; a dense medium tends to sigma_s/sigma_t of the source (never above it).
//             `resolution` half or quarter marches one pixel in 2x2 or 4x4 and upsamples by
//             depth (joint bilateral, background pixels at a depth past the media, so fog in
//             front of the sky blends as any other); `blurRadius` blurs the march's jitter
//             at its resolution, weighted by depth (no blur across depth edges). The optical
//             depth stays per pixel.
//   Analytic  Sun et al. 2005's airlight closed form per box and light, no shadows, the
//             light's whole path taken as inside the box (exact for a light inside it).
//             integral Quadrature: `steps` intervals in the equiangular variable, the phase and
//             a spot's cone at their middles, the exponential's exact mean over each; Table: a tabulated integral (tableSize^2 texels,
//             bilinear in float), the phase and cone at the segment's point nearest the
//             light (exact for isotropic media and point lights). Relative error of the
//             tabulated integral: below 6e-3 at tableSize 64 and 3e-3 at 128
//             (tests/unit/test_media_table); the result is a difference of two such terms, so
//             on a segment much shorter than its distance to the light its relative error is
//             that bound times their ratio to the difference. Near the light's line (its
//             distance from the ray under 0.1 of the distances along it) both integrals take
//             `steps` nodes in 1/distance, where the closed form would divide 0 by 0.
//             Directional lights: exact while the segment's light paths leave the box through
//             one face.
//   Bounded   RayMarch within the lit part of each view ray: every spot light's lit volume is
//             rebuilt from its shadow map as a closed mesh (McCool 2000; a height field over
//             cells of volumeCell^2 texels, conservative: each cell at its farthest depth plus
//             the map's bias), drawn from the camera to find each pixel's first and last
//             crossing, and the `steps` samples go between them (or from the camera where it
//             lies in a spot's frustum). Rays that cross no volume cost nothing. The same
//             integrand as RayMarch, so the same error for the same sample spacing; the
//             spacing is finer by the ratio of the media's span to the lit one. Only when
//             every light is a spot with a map (MediaInputs::shadows); otherwise, as there is
//             no bound to take from a point or directional light, it is RayMarch.
//   Froxel    Volumetric fog in a grid of screen tiles (froxelTile pixels) times `steps` depth
//             slices out to froxelRange: lights (and shadow maps) evaluated once per froxel,
//             integrated front to back with the energy-conserving step, read per pixel at its
//             depth. Error: the grid's resolution (light shafts narrower than a froxel blur).
//
// Outputs, the G-buffer's size, GL_RGBA16F:
//   scattering    L_s, RGB W/(sr m^2) (alpha 1);
//   opticalDepth  tau = -ln T of the view ray up to its surface, per channel, exact for
//                 constant and height-fog boxes whatever the method (a grid's: densitySteps
//                 midpoint samples) (a half float keeps 3 significant digits of tau,
//                 where T itself would round to 1 for tau < 5e-4); 65504 stands for opaque.
// apply() composes them onto a lit frame (ours or the host's): L = L_lit exp(-tau) + L_s.
//
// Numbers: no NaN or Inf leaves a pass (tested with sigma_t = 0 and 1e-8 to 1e4 per unit, 1
// to 1024 steps, g = +-0.999, the light on the view ray's line); (1 - e^-x)/x is a series near
// 0; the analytic form has finite limits where the light lies on the view ray's line (gamma ->
// 0 or pi, d_lv -> 0), and saturates at 65504 only where the integral is infinite (a light of
// radius 0 on the ray inside the segment). Lights of radius r give 1/max(d^2, r^2), as the
// reference. Shadow maps are fitted to the meshes: media points off a map's extent or past its
// far plane count as lit.
#include "obscura/ambient_occlusion.hpp"
#include "obscura/export.hpp"
#include "obscura/gbuffer.hpp"
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

enum class MediaMethod { RayMarch, Analytic, Froxel, Bounded };
enum class AnalyticIntegral { Quadrature, Table };

struct MediaSettings {
    MediaMethod method = MediaMethod::RayMarch;
    int steps = 64;
    bool jitter = true;
    AnalyticIntegral integral = AnalyticIntegral::Quadrature;
    int tableSize = 128;
    int froxelTile = 8;
    float froxelRange = 0.0f;
    int densitySteps = 16;
    int volumeCell = 8;
    AoResolution resolution = AoResolution::Full;
    int blurRadius = 0;
    float blurDepthSigma = 0.05f;
    std::uint32_t frameIndex = 0;

    static const SettingsTable<MediaSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<MediaSettings>& MediaSettings::table() {
    using S = MediaSettings;
    using namespace settings;
    static const SettingsTable<S> rows = {
        choice("method", &S::method,
               {{"raymarch", MediaMethod::RayMarch},
                {"analytic", MediaMethod::Analytic},
                {"froxel", MediaMethod::Froxel},
                {"bounded", MediaMethod::Bounded}},
               "ray marching, Sun et al.'s closed form (no shadows), a froxel grid, or marching within shadow volumes"),
        number("steps", &S::steps, "", "[1, 1024]",
               "raymarch, bounded: samples per view ray; analytic quadrature: nodes; froxel: depth slices"),
        flag("jitter", &S::jitter, "raymarch, bounded: offset each pixel's samples within their steps (else at the steps' centres)"),
        choice("integral", &S::integral, {{"quadrature", AnalyticIntegral::Quadrature}, {"table", AnalyticIntegral::Table}},
               "analytic: nodes in the shader, or the tabulated integral"),
        number("tableSize", &S::tableSize, "texels per side", "[16, 256]",
               "analytic table: its resolution (computed on the CPU once per size: 0.5 s at 128, 1.8 s at 256 on one core)"),
        number("froxelTile", &S::froxelTile, "pixels", "[1, 64]", "froxel: the grid's tile side"),
        number("froxelRange", &S::froxelRange, "world units", "[0, inf)",
               "froxel: view depth the last slice ends at (0: the media boxes' farthest corner)"),
        number("densitySteps", &S::densitySteps, "", "[1, 256]",
               "raymarch, bounded, froxel: midpoint steps of a density grid's optical depth along each segment"),
        number("volumeCell", &S::volumeCell, "shadow-map texels per side", "[1, 64]",
               "bounded: the shadow volumes' cells (coarser: fewer triangles, a looser bound)"),
        choice("resolution", &S::resolution,
               {{"full", AoResolution::Full}, {"half", AoResolution::Half}, {"quarter", AoResolution::Quarter}},
               "raymarch, bounded: the march's resolution; reduced, it is upsampled by depth"),
        number("blurRadius", &S::blurRadius, "pixels at the march's resolution", "[0, 16]",
               "raymarch, bounded: depth-aware blur taps each side (smooths the jitter); 0: none"),
        number("blurDepthSigma", &S::blurDepthSigma, "", "(0, 1]",
               "raymarch, bounded: relative view-depth difference the blur and the upsampling weight e^-1/2"),
        number("frameIndex", &S::frameIndex, "", "[0, 4294967295]", "raymarch, bounded: shifts the jitter per frame"),
    };
    return rows;
}

//! What the media are and what lights them.
struct MediaInputs {
    //! Media boxes (Scene::media's units), at most 8, of which at most one a density grid.
    //! Analytic takes Constant densities only. Empty: nothing to do (run() returns an empty
    //! view and no memory is kept). The span must outlive the call.
    std::span<const Medium> media{};
    //! Point, spot and directional lights (others are left out), in Scene::lights' units.
    std::span<const Light> lights{};
    //! Maps of some of `lights` (ShadowMaps::render with the same lights, in order), tested
    //! with one hard comparison per sample by RayMarch, Bounded and Froxel (Analytic has no
    //! shadows); Bounded's volumes come from the spot lights' maps.
    //! Null: unshadowed.
    const ShadowMapSet* shadows = nullptr;
};

struct MediaView {
    TextureView scattering;   //!< GL_RGBA16F, W/(sr m^2)
    TextureView opticalDepth; //!< GL_RGBA16F, tau per channel (rgb)
    int width = 0, height = 0;
};

class OBSCURA_API Media {
public:
    explicit Media(Context& context);
    ~Media();

    //! Passes "media.raymarch", "media.analytic", "media.bounded.volume",
    //! "media.bounded.interval" and "media.bounded", or "media.froxel.inject",
    //! (marches at reduced resolution: "media.optical_depth"; blurred: "media.blur"; reduced:
    //! "media.upsample"),
    //! "media.froxel.integrate" and "media.froxel.resolve". Reads the G-buffer's depth only.
    //! Throws Error{InvalidArgument} for settings out of range, more than 8 media, media or
    //! lights that validateScene refuses, shadow maps that do not fit the lights or the camera,
    //! or a G-buffer without depth. The view stays valid until the next run.
    MediaView run(const GBufferView& gbuffer, const MediaInputs& inputs, const MediaSettings& settings);

    //! L_lit exp(-tau) + L_s into a GL_RGBA16F texture the module owns (pass "media.apply"),
    //! `lit`'s alpha kept: `lit` is our G-buffer's direct radiance, Composer::radiance(), or
    //! a host's linear HDR frame (float or normalized RGB/RGBA, the view's size). Throws
    //! Error{InvalidArgument} for a lit frame of another size or kind, or one that is this
    //! module's own output.
    TextureView apply(const MediaView& view, const TextureView& lit);

    //! Compiles the programs run() takes for these settings (and apply()'s).
    void prepare(const MediaSettings& settings);

    std::size_t memoryBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura

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

enum class MediaMethod { RayMarch, Analytic, Froxel };
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
    std::uint32_t frameIndex = 0;

    static const SettingsTable<MediaSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<MediaSettings>& MediaSettings::table() {
    using S = MediaSettings;
    using namespace settings;
    static const SettingsTable<S> rows = {
        choice("method", &S::method,
               {{"raymarch", MediaMethod::RayMarch}, {"analytic", MediaMethod::Analytic}, {"froxel", MediaMethod::Froxel}},
               "ray marching, Sun et al.'s closed form (no shadows), or a froxel grid"),
        number("steps", &S::steps, "", "[1, 1024]",
               "raymarch: samples per view ray; analytic quadrature: nodes; froxel: depth slices"),
        flag("jitter", &S::jitter, "raymarch: offset each pixel's samples within their steps (else at the steps' centres)"),
        choice("integral", &S::integral, {{"quadrature", AnalyticIntegral::Quadrature}, {"table", AnalyticIntegral::Table}},
               "analytic: nodes in the shader, or the tabulated integral"),
        number("tableSize", &S::tableSize, "texels per side", "[16, 256]",
               "analytic table: its resolution (computed on the CPU once per size: 0.5 s at 128, 1.8 s at 256 on one core)"),
        number("froxelTile", &S::froxelTile, "pixels", "[1, 64]", "froxel: the grid's tile side"),
        number("froxelRange", &S::froxelRange, "world units", "[0, inf)",
               "froxel: view depth the last slice ends at (0: the media boxes' farthest corner)"),
        number("densitySteps", &S::densitySteps, "", "[1, 256]",
               "raymarch, froxel: midpoint steps of a density grid's optical depth along each segment"),
        number("frameIndex", &S::frameIndex, "", "[0, 4294967295]", "raymarch: shifts the jitter per frame"),
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
    //! with one hard comparison per sample by RayMarch and Froxel (Analytic has no shadows).
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

    //! Passes "media.raymarch", "media.analytic", or "media.froxel.inject",
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

#pragma once
// One-bounce diffuse indirect light from a G-buffer: screen-space gathering and the hybrid
// of voxel visibility with screen radiance.
//
// Both estimate obscura::reference::IndirectLight at the G-buffer's samples:
//   L1(x) = (rho(x) / pi) Integral L(y(x, w)) (n.w) dw ~ rho(x) * mean over cosine-weighted
//   directions of L at the first hit y within the radius,
// where L is the G-buffer's direct radiance: emission and the lights, shadowed where
// GBufferSettings::shadows has maps for them (the bench's "indirect" compares with the
// reference's shadowed hits; "indirect_unshadowed", measured only with `--set shadows=0`,
// with the gathering of unshadowed light: the method's own error). The radiance
// at a hit is read from the screen, so only hits the camera sees, on their visible side,
// contribute; others (hidden, behind the image border, seen from behind) count as dark. The
// ray must go into the surface it reads from the front, and cross its tangent plane no
// earlier than the last step and a half before the hit (Screen) or a voxel diagonal before
// the voxel it enters (Hybrid; plus a step with March traversal): a ray that went behind the
// visible surface through a side the camera does not see counts as dark, not as the light
// of the face in front of it.
//   Screen: hits found by marching the depth buffer (as AoMethod::RayMarch).
//   Hybrid: hits found in the voxel grid (as AoMethod::Voxel, a ray that may sink back toward
//           its own plane reading nothing beyond where it might), then looked up on screen; a
//           hit farther than `thickness` from the tangent plane of the surface its pixel
//           shows is not on that surface, and contributes nothing.
//
// Output `radiance`: GL_RGBA16F, W/(sr m^2), the G-buffer's size; alpha 1 on geometry, and
// (0, 0, 0, 0) on background pixels.
#include "obscura/ambient_occlusion.hpp"
#include "obscura/export.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/screen_visibility.hpp"
#include "obscura/texture.hpp"
#include "obscura/voxelizer.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>

namespace obscura {

class Context;

enum class GiMethod {
    Screen, //!< "gi.screen": rays x steps through the depth buffer, radiance from the screen
    Hybrid, //!< "gi.hybrid": rays through `voxels`, radiance from the screen
};

struct IndirectLightSettings {
    GiMethod method = GiMethod::Screen;
    float radius = 1.0f;
    int rays = 16;
    int steps = 8;
    //! Hybrid: a plane, not the pixel centre's depth, so that surfaces seen edge-on, whose
    //! pixels span more depth than a fine grid's voxels, are still found.
    float thickness = 0.0f;
    ScreenThickness thicknessMode = ScreenThickness::Constant;
    ScreenMarch march = ScreenMarch::View;
    AoResolution resolution = AoResolution::Full;
    //! The blur and the upsampling filter the incident light alone; each G-buffer pixel's own
    //! albedo multiplies it after them, so albedo (texture) edges stay sharp.
    int blurRadius = 0;
    float blurDepthSigma = 0.05f;
    float blurNormalPower = 16.0f;
    float refineThreshold = 0.25f;
    int rayLanes = 1;
    bool geometryTiles = true;
    std::uint32_t frameIndex = 0;
    TemporalSettings temporal{}; //!< of the radiance
    const VoxelGrid* voxels = nullptr; //!< Hybrid: the voxelized scene (as AmbientOcclusionSettings::voxels)
    VoxelTraversal voxelTraversal = VoxelTraversal::Hierarchical;

    static const SettingsTable<IndirectLightSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<IndirectLightSettings>& IndirectLightSettings::table() {
    using S = IndirectLightSettings;
    using namespace settings;
    static const SettingsTable<S> rows = join<S>(
        {
            choice("method", &S::method, {{"screen", GiMethod::Screen}, {"hybrid", GiMethod::Hybrid}},
                   "where rays find hits (GiMethod)"),
            number("radius", &S::radius, "world units", "(0, inf)", "hits farther away are not gathered"),
            number("rays", &S::rays, "", "[1, 1024]", "cosine-weighted directions per pixel"),
            number("steps", &S::steps, "", "[1, 256]", "depth samples per ray (Hybrid: march samples)"),
            number("thickness", &S::thickness, "world units", "[0, inf)",
                   "Screen: as AO's; Hybrid: how far a voxel hit may lie off the pixel's tangent plane "
                   "(0: the radius, or two voxel diagonals)"),
            screenThicknessRow(&S::thicknessMode, "Screen: constant thickness, the second depth layer, or the deeper of both"),
            screenMarchRow(&S::march, "Screen: 3D samples, 2D samples, or 2D samples skipping runs through a Hi-Z pyramid"),
            voxelTraversalRow("voxelTraversal", &S::voxelTraversal, "Hybrid: the visibility query"),
        },
        integratorRows<S>());
    return rows;
}

struct IndirectLightView {
    TextureView radiance; //!< GL_RGBA16F, W/(sr m^2)
    int width = 0, height = 0;
};

class OBSCURA_API IndirectLight {
public:
    explicit IndirectLight(Context& context);
    ~IndirectLight();

    //! Passes "gi.hiz" (Screen with HiZ), "gi.screen" or "gi.hybrid", then "gi.blur",
    //! "gi.upsample", "gi.refine" and "gi.temporal" when used. Throws Error{InvalidArgument} for settings
    //! out of range (enumerators included), a G-buffer without depth, normal, albedo or direct
    //! radiance (adopted host buffers have them only where the host gave them), without
    //! backDepth for DepthPeeling and PeelingOrConstant, the hybrid method without a grid, or
    //! a G-buffer texture it reads that is one of this object's own outputs (the last
    //! radiance fed back as direct radiance, for more bounces: alternate two objects).
    IndirectLightView run(const GBufferView& gbuffer, const IndirectLightSettings& settings);

    //! Compiles every shader program run() takes for these settings, ahead of time (as
    //! AmbientOcclusion::prepare). Throws as run() does for the settings.
    void prepare(const IndirectLightSettings& settings);

    //! The last run's refinement (RefinementCount, ambient_occlusion.hpp); zeros when it ran
    //! at full resolution or without one; a refused run leaves it unchanged. Waits for the run
    //! to finish: not for every frame.
    RefinementCount lastRefinement() const;

    //! Forgets the temporal history (as AmbientOcclusion::resetHistory).
    void resetHistory();

    std::size_t memoryBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura

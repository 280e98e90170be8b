#pragma once
// Ambient occlusion and obscurance from a G-buffer, in screen space or in voxel space.
//
// The methods estimate the quantities of obscura::reference (AmbientOcclusion, Obscurance,
// BentNormal) with the geometric normal of the G-buffer (Points and Horizon under their own
// models, see AoMethod; docs/results.md gives each method's error against the reference):
//   AO_r(x) = (1/pi) Integral V_r(x, w) (n.w) dw    (cosine-weighted; or (1/2pi) Integral V_r dw)
//   W(x)    = (1/pi) Integral rho(d(x, w) / r) (n.w) dw   (obscurance, `falloff` != None)
// V_r(x, w) = 1 when nothing is hit within the radius r. Directions are Hammersley points
// mapped to the hemisphere (cosine or uniform, so the estimate is the plain mean of V or rho),
// rotated per pixel by a tiled random texture (shaders/common/sampling.glsl).
//
// What the screen-space methods cannot see, they count as unoccluded: geometry outside the
// image (the border policy), behind the depth buffer's front layer beyond `thickness`, and
// depth samples more than a radius in front of the ray (objects "extending to infinity"
// behind their front face are cut off at `thickness`).
//
// Output: `ao` holds AO_r or W in [0, 1] (1 = open) at the G-buffer's resolution, GL_R16F
// (11-bit mantissa: values are rounded by at most 2^-12); background pixels are 1.
// `bentNormal` (when asked for) holds the view-space bent normal, GL_RGBA16F, alpha 1 on
// geometry. The blur and the upsampling average bent normals as offsets from their pixels'
// normals and add the mean to the normal of the pixel they write, so that where nothing
// occludes, a curved surface keeps its own normals.
#include "obscura/export.hpp"
#include "obscura/gbuffer.hpp"
#include "obscura/settings_table.hpp"
#include "obscura/screen_visibility.hpp"
#include "obscura/texture.hpp"
#include "obscura/voxelizer.hpp"

#include <cstddef>
#include <cstdint>
#include <memory>

namespace obscura {

class Context;

//! Distance weighting rho of obscurance, of t = d / radius in [0, 1): None: 0 (plain AO);
//! Linear: t; Quadratic: t^2; Smooth: 3t^2 - 2t^3. No hit within the radius: 1.
enum class ObscuranceFalloff { None, Linear, Quadratic, Smooth };

enum class AoMethod {
    RayMarch, //!< "ao.raymarch": `rays` directions, `steps` depth-buffer tests along each
    Points,   //!< "ao.points": Crytek-style: `rays` points in the hemisphere ball of radius r
              //!< (3D Hammersley: direction, distance); the share not behind the depth
              //!< buffer, a volume estimate, not AO_r: a direction first hitting at t < r is
              //!< (t/r)^3 open (obscurance-like); with a falloff, hidden points count rho
    Horizon,  //!< "ao.horizon": per screen slice, the horizon angles found with `steps` samples
              //!< on each side and the cosine-weighted integral above them (GTAO-style; exact
              //!< for height fields, darker than AO_r under overhangs: below a disc as high
              //!< as it is wide, 0.09-0.19 on 0.5); `rays` / 2 slices; cosine weighting only;
              //!< the bent normal integrates each slice's visible arc in closed form; a slice's
              //!< screen direction is mirrored where the projection mirrors x or y (camera.hpp)
    //! "ao.voxel": `rays` segments of length r through `voxels` (first-hit distance), from a
    //! start lifted off the surface's own voxels by a voxel diagonal and the depth's error,
    //! more for a pixel whose normal is only known within a bound (HostGBuffer::normal); a
    //! segment that may sink back toward its own plane ends where it might (open beyond).
    //! Where other geometry lies within about a voxel diagonal of the lifted start (an inner
    //! corner, a gap narrower than a voxel), every ray hits at once: AO 0, whatever the radius
    //! (docs/ambient-occlusion.md counts such pixels per grid resolution).
    Voxel,
};

enum class AoResolution { Full = 1, Half = 2, Quarter = 4 }; //!< of the G-buffer, per axis

//! Temporal accumulation of a result (AO, indirect light) over frames, at the G-buffer's
//! resolution, pass "<module>.temporal": each pixel's value is averaged with its history, the
//! last run's result at the same surface point, found by reprojecting the point through the
//! last run's camera (bilinearly, from the four texels around it). A texel whose stored point
//! lies off the point's tangent plane, or whose normal differs, is left out, so that what
//! comes into view starts afresh instead of ghosting. The result is history + (current -
//! history) / min(n + 1, maxFrames): the mean of up to maxFrames frames, then an exponential
//! average. Give each frame its own `frameIndex`. Points are reprojected with the camera's
//! motion only (no motion vectors): a moving object's contact shadows trail by up to maxFrames
//! frames or are dropped by the tests. Other settings' changes keep the history: call
//! resetHistory() for a clean start. Bent normals are not accumulated. The history costs 32
//! bytes a G-buffer pixel, held while enabled.
struct TemporalSettings {
    bool enabled = false;
    int maxFrames = 16;
    float depthTolerance = 0.02f;
    float normalThreshold = 0.9f;

    static const SettingsTable<TemporalSettings>& table();
};

inline const SettingsTable<TemporalSettings>& TemporalSettings::table() {
    using S = TemporalSettings;
    static const SettingsTable<S> rows = {
        settings::flag("enabled", &S::enabled, "accumulate over frames, reprojected"),
        settings::number("maxFrames", &S::maxFrames, "frames", "[1, 256]", "frames averaged at most"),
        settings::number("depthTolerance", &S::depthTolerance, "of view depth", "(0, 1]",
                         "a history point further off the tangent plane is another surface"),
        settings::number("normalThreshold", &S::normalThreshold, "cosine", "[-1, 1]",
                         "the least cosine between a history texel's normal and the pixel's"),
    };
    return rows;
}

namespace settings {

//! The rows AO and indirect light share (the same fields, by name): resolution, filters,
//! lanes, tiles, frame index, temporal accumulation.
template <class S>
SettingsTable<S> integratorRows() {
    return join<S>(
        {
            choice("resolution", &S::resolution,
                   {{"full", AoResolution::Full}, {"half", AoResolution::Half}, {"quarter", AoResolution::Quarter}},
                   "resolution of the integrator, relative to the G-buffer"),
            number("blurRadius", &S::blurRadius, "taps", "[0, 16]",
                   "geometry-aware separable blur at the integrator's resolution, taps each side (0: off)"),
            number("blurDepthSigma", &S::blurDepthSigma, "", "(0, 1]",
                   "blur and upsampling: relative view-depth difference weighted e^-1/2"),
            number("blurNormalPower", &S::blurNormalPower, "", "[0, 256]",
                   "blur and upsampling: normal weight max(0, n.n')^power"),
            // The share of a pixel's bilinear weight that similar reduced-resolution
            // neighbours must carry (see RefinementCount for the list's bound).
            number("refineThreshold", &S::refineThreshold, "", "[0, 1]",
                   "half, quarter: pixels with less similar-neighbour weight are computed at full resolution (0: none)"),
            // More lanes pay where a pass covers few pixels (refinement, small objects).
            number("rayLanes", &S::rayLanes, "", "1|2|4|8|16",
                   "invocations sharing each pixel's rays (the same rays; sums in another order)"),
            flag("geometryTiles", &S::geometryTiles,
                 "half, quarter: run only over the 8x8 tiles holding geometry (the same result; false: every tile)"),
            number("frameIndex", &S::frameIndex, "", "[0, 4294967295]",
                   "shifts every pixel's samples by this point of a low-discrepancy sequence (0: none)"),
        },
        nested("temporal", &S::temporal, TemporalSettings::table()));
}

} // namespace settings

struct AmbientOcclusionSettings {
    AoMethod method = AoMethod::RayMarch;
    float radius = 1.0f;
    int rays = 16;
    int steps = 8;
    bool cosineWeighted = true;
    ObscuranceFalloff falloff = ObscuranceFalloff::None;
    //! Larger closes gaps behind thin objects, smaller lets rays pass behind them. With
    //! DepthPeeling it applies only where the second layer is empty; with PeelingOrConstant
    //! everywhere, and matters where the second layer is nearer than it.
    float thickness = 0.0f;
    //! DepthPeeling needs GBufferView::backDepth (GBufferSettings::depthLayers = 2, or
    //! HostGBuffer::backDepth). PeelingOrConstant keeps a slab behind thin parts; the slab runs
    //! along the normal, so with the default thickness it is nearly Constant at grazing angles:
    //! a thickness well below the radius keeps peeling's depth.
    ScreenThickness thicknessMode = ScreenThickness::Constant;
    ScreenMarch march = ScreenMarch::View;
    AoResolution resolution = AoResolution::Full;
    int blurRadius = 0;
    float blurDepthSigma = 0.05f;
    float blurNormalPower = 16.0f;
    float refineThreshold = 0.25f;
    int rayLanes = 1;
    bool geometryTiles = true;
    bool bentNormals = false;
    std::uint32_t frameIndex = 0;
    TemporalSettings temporal{};
    //! Voxel: the voxelized scene (Voxelizer::voxelize with the same scene; octree needed for
    //! Hierarchical). Ignored by the other methods.
    const VoxelGrid* voxels = nullptr;
    VoxelTraversal voxelTraversal = VoxelTraversal::Hierarchical;

    //! Units, ranges and meanings of the fields above (settings_table.hpp).
    static const SettingsTable<AmbientOcclusionSettings>& table();
};

inline const SettingsTable<AmbientOcclusionSettings>& AmbientOcclusionSettings::table() {
    using S = AmbientOcclusionSettings;
    using namespace settings;
    static const SettingsTable<S> rows = join<S>(
        {
            choice("method", &S::method,
                   {{"raymarch", AoMethod::RayMarch}, {"points", AoMethod::Points}, {"horizon", AoMethod::Horizon},
                    {"voxel", AoMethod::Voxel}},
                   "the estimator (AoMethod)"),
            number("radius", &S::radius, "world units", "(0, inf)", "the reach r of V_r and obscurance's distance scale"),
            number("rays", &S::rays, "", "[1, 1024]", "directions (Points: points) per pixel; Horizon: 2 per slice, even"),
            number("steps", &S::steps, "", "[1, 256]",
                   "depth samples per ray (RayMarch), per side (Horizon), or voxel march samples"),
            flag("cosineWeighted", &S::cosineWeighted, "cosine (AO_r) or uniform hemisphere weighting; Horizon: cosine only"),
            choice("falloff", &S::falloff,
                   {{"none", ObscuranceFalloff::None}, {"linear", ObscuranceFalloff::Linear},
                    {"quadratic", ObscuranceFalloff::Quadratic}, {"smooth", ObscuranceFalloff::Smooth}},
                   "obscurance's rho (none: AO); not for Horizon"),
            number("thickness", &S::thickness, "world units", "[0, inf)",
                   "RayMarch, Points: how far behind a depth sample's tangent plane a point is inside (0: the radius)"),
            screenThicknessRow(&S::thicknessMode,
                               "RayMarch, Points: constant thickness, the second depth layer, or the deeper of both"),
            screenMarchRow(&S::march, "RayMarch: 3D samples, 2D samples, or 2D samples skipping runs through a Hi-Z pyramid"),
            flag("bentNormals", &S::bentNormals, "also write `bentNormal`, the cosine-weighted mean open direction"),
            voxelTraversalRow("voxelTraversal", &S::voxelTraversal, "Voxel: the visibility query (March takes `steps` samples)"),
        },
        integratorRows<S>());
    return rows;
}

struct AmbientOcclusionView {
    TextureView ao;         //!< GL_R16F, the G-buffer's size
    TextureView bentNormal; //!< GL_RGBA16F, view space; empty unless settings.bentNormals
    int width = 0, height = 0;
};

//! What the refinement of a run at a reduced resolution did (`refineThreshold`, pass
//! "<module>.refine"). The share of edge pixels is what decides whether a reduced resolution
//! pays: a small or thin object at a low resolution is mostly edges.
struct RefinementCount {
    //! G-buffer pixels with geometry the upsampling found too little similar reduced-resolution
    //! weight for
    std::size_t asked = 0;
    //! Of them, computed at full resolution: all, or none when more asked than the list holds
    //! (a quarter of the G-buffer's pixels, at most 65535 x 64 = 4194240: the groups of 64 one
    //! indirect dispatch is sure to take; they keep the upsampled value)
    std::size_t refined = 0;
};

class OBSCURA_API AmbientOcclusion {
public:
    explicit AmbientOcclusion(Context& context);
    ~AmbientOcclusion();

    //! Passes "ao.hiz" (RayMarch with HiZ), "ao.<method>", then "ao.blur", "ao.upsample",
    //! "ao.refine" and "ao.temporal" when used. Throws Error{InvalidArgument} for settings out of range
    //! (enumerators included), a G-buffer without depth or normal (or without backDepth for
    //! DepthPeeling and PeelingOrConstant), the Voxel method without a grid, or a G-buffer
    //! texture it reads that is one of this object's own outputs (a bent normal fed back as
    //! the normal: alternate two objects). The view stays valid until the next run.
    AmbientOcclusionView run(const GBufferView& gbuffer, const AmbientOcclusionSettings& settings);

    //! Compiles every shader program run() takes for these settings, ahead of time, so that
    //! the first frame does not stall on compiling (docs/integration.md). Allocates
    //! nothing. Throws as run() does for the settings (the Voxel method needs its grid). For
    //! images of more than 65535 geometry tiles (`geometryTiles`), run() compiles the untiled
    //! integrator on its first call.
    void prepare(const AmbientOcclusionSettings& settings);

    //! The last run's refinement; zeros when it ran at full resolution or without one. A run
    //! refused for its settings or inputs (it throws before any GL work) leaves it unchanged.
    //! Reads a count back from the GPU, so it waits for the run to finish: for diagnostics
    //! and benchmarks, not for every frame.
    RefinementCount lastRefinement() const;

    //! Forgets the temporal history (settings.temporal): the next run starts afresh, as after
    //! a camera cut. Frees its memory.
    void resetHistory();

    std::size_t memoryBytes() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura

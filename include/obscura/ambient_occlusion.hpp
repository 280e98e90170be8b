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
    //! corner, a gap narrower than a voxel), the start is inside its voxels and every ray hits
    //! at once: AO 0, whatever the radius (the grid cannot tell nearer geometry apart). Measured
    //! at 128 x 128: 230 of the Cornell box's 15252 geometry pixels (its corners' edges) and
    //! 552 of 2CylinderEngine's 2720 at voxel_resolution 128, 74 and 423 at 256, 51 and 43 at
    //! 512; the ray march gives 0 at none.
    Voxel,
};

enum class AoResolution { Full = 1, Half = 2, Quarter = 4 }; //!< of the G-buffer, per axis

//! Temporal accumulation of a result (AO, indirect light) over frames, at the G-buffer's
//! resolution, pass "<module>.temporal": each pixel's value is averaged with its history, the
//! last run's result at the same surface point, found by reprojecting the point through the
//! last run's camera and read bilinearly from the four texels around it; a texel whose stored
//! point lies off the point's tangent plane, or whose normal differs (a surface the camera did
//! not see last frame), is left out, so that what comes into view starts afresh instead of
//! ghosting. The history
//! counts its frames n; the result is history + (current - history) / min(n + 1, maxFrames):
//! the plain mean of up to maxFrames frames, then an exponential average of weight
//! 1 / maxFrames. Give each frame its own `frameIndex` (the settings' field), so that the
//! frames' samples differ. Points are reprojected with the camera's motion only: a moving
//! object's history is found where the object was (there is no motion-vector input), so its
//! contact shadows trail by up to maxFrames frames or are dropped by the plane and normal
//! tests. Changing other settings (radius, method) keeps the history, which fades over
//! maxFrames frames: call resetHistory() for a clean start. Bent normals are not accumulated. The history costs two RGBA16F
//! and two RG32UI textures of the G-buffer's size (32 bytes a pixel), held while enabled.
struct TemporalSettings {
    bool enabled = false;
    int maxFrames = 16;           //!< frames averaged at most, [1, 256]
    //! (0, 1]: a history texel whose point lies further from the point's tangent plane than
    //! this share of its view depth is another surface.
    float depthTolerance = 0.02f;
    float normalThreshold = 0.9f; //!< [-1, 1]: the least cosine between the texel's normal and the point's
};

// Setting keys for tools (`--set`) are the field names in snake case (blurRadius: blur_radius).
struct AmbientOcclusionSettings {
    AoMethod method = AoMethod::RayMarch;
    float radius = 1.0f;        //!< world units, (0, inf): the reach r of V_r and obscurance's distance scale
    int rays = 16;              //!< directions (points for Points) per pixel, [1, 1024]; Horizon: [2, 1024], even
    int steps = 8;              //!< depth samples per ray (RayMarch) or per side (Horizon), [1, 256]
    bool cosineWeighted = true; //!< cosine (AO_r) or uniform hemisphere weighting; Horizon: cosine only
    //! rho of obscurance (None: AO); not for Horizon, whose slices find horizons, not hits
    ObscuranceFalloff falloff = ObscuranceFalloff::None;
    //! RayMarch, Points: how far behind a depth sample's tangent plane (along its normal), in
    //! world units, a point still counts as inside the object, [0, inf); 0 = the radius.
    //! Larger closes gaps behind thin objects, smaller lets rays pass behind them. With
    //! DepthPeeling it applies only where the second layer is empty; with PeelingOrConstant
    //! it applies everywhere and matters where the second layer is nearer than it.
    float thickness = 0.0f;
    //! RayMarch, Points: Constant (`thickness`) or DepthPeeling: down to the second depth
    //! layer, GBufferView::backDepth (GBufferSettings::depthLayers = 2, or
    //! HostGBuffer::backDepth): objects are as thick as they are, so rays pass behind them
    //! and are not cut off inside them; or
    //! PeelingOrConstant: the deeper of the two, which keeps a constant slab behind thin
    //! parts (where other parts lie behind them, stacked). With the default thickness (the
    //! radius) that is nearly Constant: the slab runs along the normal, so on faces seen at
    //! grazing angles it reaches far along the view ray; a thickness well below the radius
    //! (a tenth in docs/results.md, "Screen-space thickness") keeps peeling's depth.
    ScreenThickness thicknessMode = ScreenThickness::Constant;
    //! RayMarch: View (3D samples), Texture (2D samples, classified like View) or HiZ (the
    //! Texture samples, with runs skipped through a min/max depth pyramid: the same result
    //! with fewer fetches; pass "ao.hiz" builds it). See ScreenVisibility.
    ScreenMarch march = ScreenMarch::View;
    AoResolution resolution = AoResolution::Full;
    //! Geometry-aware separable blur at the AO resolution: taps each side, [0, 16] (0 = off).
    int blurRadius = 0;
    //! Blur and upsampling: relative view-depth difference weighted e^-1/2, (0, 1].
    float blurDepthSigma = 0.05f;
    //! Blur and upsampling: normal weight max(0, n.n')^power, [0, 256].
    float blurNormalPower = 16.0f;
    //! Upsampling (Half, Quarter): G-buffer pixels whose similar low-resolution neighbours
    //! carry less than this share of their bilinear weight (the guide weights times the
    //! bilinear ones, summed) are computed at full resolution instead, pass "ao.refine":
    //! mostly the edges of parts thinner than the low resolution's pixels. [0, 1]; 0: none
    //! (where no neighbour is similar, the one nearest in depth fills in). At most a quarter
    //! of the G-buffer's pixels, and at most 65535 x 64 = 4194240, are refined: when more ask
    //! for it, none is (all are blended as with 0), so that a frame does not depend on the
    //! order the GPU lists them.
    float refineThreshold = 0.25f;
    //! Invocations that share each pixel's rays (Horizon: slices): 1, 2, 4, 8 or 16. With 1 a
    //! pixel's rays run one after another in one invocation, so a pass over few pixels (the
    //! refinement, a reduced resolution, a small object) lasts as long as its slowest pixel
    //! however idle the GPU; more lanes split them, at the cost of a sum in shared memory.
    //! The same rays either way: results differ only in the order the sums are added.
    int rayLanes = 1;
    //! Half, Quarter: the integrator, the blur and the upsampling run only over the tiles of
    //! 8 x 8 AO pixels that hold geometry, listed by a pass over the depth ("ao.tiles"); the
    //! other tiles get the background values by a clear. The same results either way. Pays
    //! where background covers much of the image: on llvmpipe at 512 x 512, ao.points at half
    //! resolution took 12.0 ms instead of 25.2 on 2CylinderEngine (17 % geometry), and 4 %
    //! longer on the Cornell box (no background). false: every tile, without the pass. Images
    //! of more than 65535 tiles (above about 4096 x 4096 at half resolution: GL guarantees no
    //! larger indirect dispatch) run every tile.
    bool geometryTiles = true;
    //! Also write `bentNormal`, the cosine-weighted mean of the open directions (Horizon: of the
    //! directions above its slices' horizons, integrated over each slice's visible arc).
    bool bentNormals = false;
    //! [0, 2^32 - 1]: shifts every pixel's sampling pattern (rotation and offsets along the
    //! rays) by point frameIndex of a low-discrepancy sequence. 0 (the default) is no shift;
    //! counting it up every frame gives each frame other samples, whose noise a host's TAA, or
    //! `temporal`, averages away.
    std::uint32_t frameIndex = 0;
    TemporalSettings temporal; //!< off by default
    //! Voxel: the voxelized scene (Voxelizer::voxelize with the same scene; world units via
    //! grid.worldToVoxel; octree needed for Hierarchical). Ignored by the other methods.
    const VoxelGrid* voxels = nullptr;
    VoxelTraversal voxelTraversal = VoxelTraversal::Hierarchical; //!< Voxel; March takes `steps` samples
};

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
    AmbientOcclusion(const AmbientOcclusion&) = delete;
    AmbientOcclusion& operator=(const AmbientOcclusion&) = delete;

    //! Passes "ao.hiz" (RayMarch with HiZ), "ao.<method>", then "ao.blur", "ao.upsample",
    //! "ao.refine" and "ao.temporal" when used. Throws Error{InvalidArgument} for settings out of range
    //! (enumerators included), a G-buffer without depth or normal (or without backDepth for
    //! DepthPeeling and PeelingOrConstant), the Voxel method without a grid, or a G-buffer
    //! texture it reads that is one of this object's own outputs (a bent normal fed back as
    //! the normal: alternate two objects). The view stays valid until the next run.
    AmbientOcclusionView run(const GBufferView& gbuffer, const AmbientOcclusionSettings& settings);

    //! Compiles every shader program run() takes for these settings, ahead of time, so that
    //! the first frame does not stall on compiling (0.2-1 s for a method's programs). Allocates
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

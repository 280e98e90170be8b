#pragma once
// obscura::reference: CPU ray-traced ground truth (Embree 3) for the quantities Obscura's
// techniques approximate, evaluated on the same pixels.
//
// Where: ShadingPoints are either the G-buffer's own samples (positions and normals read
// back, so that only a technique's own error is measured) or the hits of primary rays
// through pixel centres.
//
// Noise: every reference is rendered as two independent halves A and B (half the samples
// each, independent random streams); the result is (A+B)/2 and its own mean squared error is
// estimated as MSE(A,B)/4 (the variance of a difference of two i.i.d. estimates is twice
// their variance; averaging two halves it). Seeds are fixed: results are deterministic and
// do not depend on the number of threads.
#include "obscura/camera.hpp"
#include "obscura/ambient_occlusion.hpp"
#include "obscura/export.hpp"
#include "obscura/scene.hpp"
#include "obscura/texture.hpp"
#include "obscura/voxelizer.hpp"

#include <cstdint>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace obscura::reference {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

//! The scene's CPU meshes in world space, in an Embree BVH (RTC_SCENE_FLAG_ROBUST).
class OBSCURA_API RayScene {
public:
    //! Throws Error{InvalidArgument} for an invalid scene (validateScene) or one with host
    //! MeshRefs (their triangles live in GPU buffers), Error{Io} for an unreadable environment.
    explicit RayScene(const Scene& scene);
    ~RayScene();

    const Scene& scene() const noexcept;
    Bounds bounds() const noexcept;
    std::size_t triangleCount() const noexcept;
    //! A hash of everything the references depend on (geometry, materials, lights, media,
    //! environment file and parameters), for cache keys.
    std::uint64_t contentHash() const noexcept;

    struct Impl;
    const Impl& impl() const noexcept { return *impl_; }

private:
    std::unique_ptr<Impl> impl_;
};

//! One pixel's view ray and, if it hits, the surface point.
struct ShadingPoint {
    glm::dvec3 origin{0.0};    //!< start of the view ray (camera position), world units
    glm::dvec3 direction{0.0}; //!< unit view-ray direction, world
    double distance = kInfinity; //!< along the view ray to the surface; infinite: background
    glm::dvec3 position{0.0};  //!< surface point, world units
    glm::dvec3 normal{0.0};    //!< unit geometric normal turned toward the viewer, world
    //! Unit interpolated vertex normal on the normal's side (= normal for meshes without
    //! normals): the receiver's cosine in DirectLight uses it, as the G-buffer does.
    glm::dvec3 shadingNormal{0.0};
    glm::dvec3 albedo{0.0};    //!< diffuse reflectance at the point (material x texture)
    glm::dvec3 emission{0.0};  //!< emitted radiance at the point, W/(sr m^2)
    //! How far, in world units, `position` may be from the true surface: the float error of a
    //! ray hit, or for G-buffer samples the view ray did not find a surface near (silhouette
    //! pixels) the 32F depth quantization (4 float steps of the stored depth, mapped to
    //! distance). Secondary rays start at least this far off the surface.
    double uncertainty = 0.0;
    bool surface() const noexcept { return distance < kInfinity; }
};

//! Row 0 is the top row of the picture.
struct ShadingPoints {
    int width = 0;
    int height = 0;
    std::vector<ShadingPoint> points;
};

//! Primary rays through pixel centres (mode b).
OBSCURA_API ShadingPoints fromCamera(const RayScene& scene, const Camera& camera, int width, int height);
//! The G-buffer's samples (mode a): view-space positions (GBuffer::positions, alpha = 1 on
//! geometry) and normals (GBufferView::normal) read back with readTexture. A sample moves
//! along its view ray onto the surface found within 2^-10 of its distance (plus its depth
//! uncertainty) of it, whose material it takes; a sample with none there (a silhouette
//! pixel) stays, with the material of the nearest surface along the ray.
OBSCURA_API ShadingPoints fromGBuffer(const RayScene& scene, const Camera& camera, const Image& viewPositions,
                                      const Image& viewNormals);

// ---- Quantities ------------------------------------------------------------------------

//! Ambient occlusion, 1 channel in [0, 1], 1 = unoccluded. With the geometric normal n and
//! V_r(x, w) = 1 when a ray from x toward w hits nothing within `radius`:
//!   cosine-weighted  AO_r(x) = (1/pi)   Integral_hemisphere V_r(x, w) (n.w) dw
//!   uniform-weighted AO_r(x) = (1/2 pi) Integral_hemisphere V_r(x, w) dw
struct AmbientOcclusion {
    double radius = kInfinity;   //!< world units, (0, inf]
    bool cosineWeighted = true;
};

//! Distance functions rho of obscurance (obscura::ObscuranceFalloff, shared with the AO
//! module), of t = d / maxDistance in [0, 1): None: 0 (obscurance = AO with radius
//! maxDistance); Linear: t; Quadratic: t^2; Smooth: 3t^2 - 2t^3. Beyond maxDistance, or
//! without a hit, rho = 1.
using obscura::ObscuranceFalloff;
OBSCURA_API double obscuranceWeight(ObscuranceFalloff falloff, double distance, double maxDistance);

//! Obscurance, 1 channel in [0, 1]: W(x) = (1/pi) Integral rho(d(x, w)) (n.w) dw, d the
//! distance to the first hit along w; uniformly weighted, (1/(2 pi)) Integral rho(d(x, w)) dw.
struct Obscurance {
    double maxDistance = 1.0; //!< world units, (0, inf)
    ObscuranceFalloff falloff = ObscuranceFalloff::Linear;
    bool cosineWeighted = true; //!< cosine (n.w / pi) or uniform (1 / (2 pi)) weighting of directions
};

//! Bent normal, 3 channels, world space: the normalized cosine-weighted mean unoccluded
//! direction, (1/pi) Integral V_r(x, w) w (n.w) dw normalized; n where all rays are occluded.
struct BentNormal {
    double radius = kInfinity; //!< world units, (0, inf]
};

//! Direct radiance, RGB, W/(sr m^2): L(x) = Le(x) + (rho(x)/pi) Sum_lights E_i(x), with each
//! light's irradiance E_i including visibility (shadows) unless `visibility` is off.
//! Rect and sphere lights are integrated over their area / subtended cone.
struct DirectLight {
    bool visibility = true;
};

//! One-bounce diffuse indirect radiance, RGB, W/(sr m^2):
//! L1(x) = (rho(x)/pi) Integral L(y(x, w)) (n.w) dw, L the direct radiance (with visibility,
//! including emission) at the first hit y, counting only hits within `radius` (the near
//! field that screen-space methods see) when finite.
struct IndirectLight {
    double radius = kInfinity; //!< world units, (0, inf]
    //! Whether L at the hits includes the lights' visibility (shadows). Off: the unshadowed
    //! direct radiance that a G-buffer without shadow maps provides, so that a gatherer's
    //! own error can be told from the error of its input.
    bool directVisibility = true;
    //! Whether L at the hits includes the environment's light, (albedo / pi) Integral L_env V
    //! cos (Scene::environment, with visibility): the bounce of image-based light.
    bool environment = false;
};

//! Shadow of Scene::lights[light], 2 channels. Channel 0 in [0, 1], 1 = lit: for point,
//! spot and directional lights the visibility of the light (a hard mask); for rect and
//! sphere lights the fraction of their irradiance that arrives, E_visible / E_unoccluded.
//! Channel 1 is 1 where the light reaches the surface's front side at all (unoccluded
//! irradiance > 0, geometric normal), else 0 (and channel 0 is 0): only those pixels are
//! lit or shadowed, the others face away or lie outside a spot's cone. The area-light
//! fraction is a ratio of two estimates from the same samples: consistent, with a bias of
//! order 1/samples that the two-halves noise estimate does not include.
struct Shadow {
    std::size_t light = 0;
};

//! Single scattering along the view ray up to the surface, in Scene::media[medium], from
//! the point, spot and directional lights: RGB W/(sr m^2)
//!   Ls = Integral T(0,t) sigma_s Sum_lights p(theta) Li(t) T(t, light) V(t) dt
//! and, in the 4th channel, the transmittance T(0, t_end) of the view ray (mean over RGB).
struct SingleScattering {
    std::size_t medium = 0;
    bool shadows = true; //!< V(t): geometry between the scattering point and the light
};

//! Diffuse image-based lighting from Scene::environment, with visibility: irradiance
//! E(x) = Integral L_env(w) V(x, w) (n.w) dw, output as radiance (rho/pi) E, RGB, or as E
//! itself with `irradianceOnly`. Sampled by multiple importance sampling of the
//! environment's luminance and the cosine.
struct ImageBasedLight {
    bool irradianceOnly = false;
    bool visibility = true;
    //! Occluders farther than this do not block the environment (world units, (0, inf]): the
    //! quantity a method that looks for occluders within a radius estimates.
    double radius = kInfinity;
    //! Also the scene's lights' direct light (DirectLight without emission, shadowed by every
    //! occluder, with the geometric normal), as SSDO's `direct` holds it.
    bool lights = false;
};

using Quantity = std::variant<AmbientOcclusion, Obscurance, BentNormal, DirectLight, IndirectLight, Shadow,
                              SingleScattering, ImageBasedLight>;

//! Channels of the quantity's image (1, 3 or 4).
OBSCURA_API int channels(const Quantity& quantity);
//! Canonical text, e.g. "ao radius=1 cosine=1": names the quantity in reports and keys caches.
OBSCURA_API std::string describe(const Quantity& quantity);

struct RenderSettings {
    int samplesPerPixel = 256; //!< [2, 1048576]; each half gets half of them (odd: one fewer)
    std::uint64_t seed = 1;
    int threads = 0;           //!< worker threads, [0, 4096]; 0 = all cores
    bool progress = false;     //!< a progress bar on stderr
};

struct Reference {
    Image value;           //!< (A + B) / 2; pixels without a surface are 0 (except SingleScattering)
    Image halfA, halfB;
    double noiseMse = 0.0; //!< MSE(A, B) / 4 over the evaluated pixels and channels
    double seconds = 0.0;  //!< wall time of the render
    std::uint64_t rays = 0; //!< rays traced (intersection and occlusion queries)
    int samplesPerPixel = 0;
};

//! Renders the quantity at every point. Background points (no surface) are 0 in every
//! channel except for SingleScattering, which the medium in front of the background has; the
//! GPU modules write their own background values there (AmbientOcclusion 1), so compare the
//! two on surfaceMask. Throws Error{InvalidArgument} for a quantity that refers to a missing
//! light, medium or environment, or settings outside their ranges.
OBSCURA_API Reference render(const RayScene& scene, const ShadingPoints& points, const Quantity& quantity,
                             const RenderSettings& settings);

//! As render(), but cached on disk under `directory` as EXR (value and halves) plus JSON,
//! keyed by a hash of scene content, points, quantity, samples and seed.
OBSCURA_API Reference renderCached(const std::filesystem::path& directory, const RayScene& scene,
                                   const ShadingPoints& points, const Quantity& quantity,
                                   const RenderSettings& settings);

//! The key renderCached files a reference under: a hash of everything render() depends on.
//! Equal keys give the same reference (e.g. for a cache in memory).
OBSCURA_API std::uint64_t referenceKey(const RayScene& scene, const ShadingPoints& points, const Quantity& quantity,
                                       const RenderSettings& settings);

//! Which pixels have a surface (1) or not (0), as a 1-channel image for metrics masks.
OBSCURA_API Image surfaceMask(const ShadingPoints& points);

// ---- Voxels ----------------------------------------------------------------------------

//! CPU surface voxelization on the layout of `grid` (its dims and worldToVoxel): a voxel is
//! set when a triangle of the scene's CPU meshes overlaps its closed box (separating axis
//! test in double precision), grown by `grow` voxel on every side, [0, 0.5) (0: exact; tests
//! use a small value to bound the GPU's conservative rounding). A zero-area triangle sets the
//! voxels its segment or point touches, as on the GPU.
OBSCURA_API DenseVoxels voxelizeSurface(const Scene& scene, const VoxelGrid& grid, double grow = 0.0);
//! CPU solid voxelization by parity: a voxel is set when the number of surfaces crossing
//! its column (through the column's centre, along z) below the voxel's centre is odd.
OBSCURA_API DenseVoxels voxelizeSolid(const Scene& scene, const VoxelGrid& grid);

} // namespace obscura::reference

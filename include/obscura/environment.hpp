#pragma once
// An HDR environment on the GPU: the distant light of Scene::environment, precomputed once
// for the modules that light with it (DirectionalOcclusion; image-based lighting next).
//
// Input: an equirectangular image (longitude along x, row 0 at the zenith, +y up; the
// convention of src/reference/environment.cpp), RGB radiance in W/(sr m^2). Texels that are
// NaN, infinite or negative are replaced by 0, and warnings() says how many (lossy EXR
// compression leaves small negative values; a NaN would poison every sum).
//
// Precomputed, in the environment's own frame:
//   - `cube`: a cube map of the radiance (GL_RGBA16F, `cubeSize` texels a face, a full mip
//     chain by 2x2 averages). Filtering does not cross face edges (GL's seamless cube
//     filtering is global state a library may not change), so coarse levels show seams.
//   - irradiance E(n) = Integral L(w) max(0, n.w) dw (W/m^2), two ways:
//     * shIrradiance(): the order-2 spherical-harmonic projection (9 coefficients, Ramamoorthi
//       and Hanrahan 2001). The projection integrates each basis function exactly over each
//       texel (the texel's radiance is taken as constant), so a constant environment L has
//       no band 1 or 2 and gives E = pi L for every n, to float rounding.
//     * `irradiance`: a cube map (GL_RGBA32F, `irradianceSize` a face) by direct summation over
//       the environment reduced to `convolutionWidth` x convolutionWidth/2 texels (area
//       averages), with the discrete cosine weights normalized to integrate to pi: a constant
//       environment again gives pi L exactly, and no ringing.
//   - an importance table: the probability of each texel of that reduced image in proportion
//     to its luminance times its solid angle, the luminance floored at 1e-6 of the largest so
//     that every direction keeps a non-zero density (as the reference's sampler).
//   - a sun: with `sunThreshold` > 0, the texels brighter than sunThreshold times the mean
//     luminance are taken out of all the above and returned by sun() as one directional light
//     (its travel direction the luminance-weighted mean; its intensity the irradiance the
//     texels give a surface facing them). The SH projection of a sharp light rings: its
//     irradiance kernel 1/4 + x/2 + (15 x^2 - 5)/32 peaks at 1.0625 and falls to -0.0396 at
//     x = cos = -8/15 (order 2, no window), i.e. a sun of irradiance E_s raises the lit side by
//     up to 0.0625 E_s and lowers the far side by up to 0.0396 E_s. With the sun split out, the ringing is that of the remainder, whose brightest
//     texel is sunThreshold times the mean. `shWindow` lambda further damps bands 1 and 2 by
//     1 / (1 + lambda l^2 (l + 1)^2) (Sloan 2008, "Stupid spherical harmonics tricks":
//     the least-squares fit with a curvature penalty); band 0 is never changed, so a constant
//     environment keeps E = pi L. Lookups clamp SH irradiance at 0.
// Intensity and rotation (as in Scene::environment) apply at lookup: setLookup() changes no
// precomputed data.
#include "obscura/export.hpp"
#include "obscura/scene.hpp"
#include "obscura/settings_table.hpp"
#include "obscura/texture.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace obscura {

class Context;

struct EnvironmentSettings {
    int cubeSize = 128;
    int irradianceSize = 16;
    int convolutionWidth = 128;
    float sunThreshold = 0.0f;
    float shWindow = 0.0f;

    static const SettingsTable<EnvironmentSettings>& table(); //!< units and ranges (settings_table.hpp)
};

inline const SettingsTable<EnvironmentSettings>& EnvironmentSettings::table() {
    using S = EnvironmentSettings;
    using namespace settings;
    static const SettingsTable<S> rows = {
        number("cubeSize", &S::cubeSize, "texels", "[4, 4096]", "the radiance cube's face edge at level 0"),
        number("irradianceSize", &S::irradianceSize, "texels", "[1, 256]", "the convolved irradiance cube's face edge"),
        number("convolutionWidth", &S::convolutionWidth, "texels", "[8, 1024]",
               "width of the reduced image the convolution and the importance table use (height: half)"),
        number("sunThreshold", &S::sunThreshold, "x mean luminance", "[0, inf)",
               "texels brighter than this become sun() (0: no sun split)"),
        number("shWindow", &S::shWindow, "", "[0, inf)", "SH damping lambda: band l times 1/(1 + lambda l^2 (l+1)^2)"),
    };
    return rows;
}

struct EnvironmentView {
    unsigned cube = 0;       //!< GL_TEXTURE_CUBE_MAP, GL_RGBA16F, with mips; environment frame
    unsigned irradiance = 0; //!< GL_TEXTURE_CUBE_MAP, GL_RGBA32F, W/m^2; environment frame
    int cubeSize = 0, cubeLevels = 0, irradianceSize = 0;
};

//! The luminance importance table over the reduced image (width x height texels, row 0 at the
//! zenith): probability of each texel, summing to 1. A direction in texel (x, y) has the
//! density probability / solidAngle(y) per steradian.
struct EnvironmentImportance {
    int width = 0, height = 0;
    std::vector<double> probability; //!< row-major
    //! The solid angle of a texel of row y: 2 pi / width (cos(pi y / height) - cos(pi (y + 1) / height)).
    double solidAngle(int y) const;
};

class OBSCURA_API EnvironmentMap {
public:
    //! Precomputes everything from `image` (equirectangular, 1 to 4 channels: one is grey,
    //! the first three are RGB). Throws Error{InvalidArgument} for an empty image or settings
    //! out of range, Error{OutOfMemory} when the textures do not fit.
    EnvironmentMap(Context& context, const Image& image, const EnvironmentSettings& settings = {});
    ~EnvironmentMap();

    //! Radiance scale, [0, inf), and rotation about +y, radians, finite (Scene::environment's).
    //! Throws Error{InvalidArgument} outside.
    void setLookup(float intensity, float rotation);
    float intensity() const;
    float rotation() const;

    EnvironmentView view() const;
    //! Irradiance from the SH projection for a world-space unit normal, at the current lookup,
    //! clamped at 0 (W/m^2; what shaders/environment/environment.glsl computes).
    glm::vec3 shIrradiance(const glm::vec3& normal) const;
    //! The 9 SH coefficients of the radiance (environment frame, no window, intensity 1), in
    //! the order of shaders/environment/environment_bindings.h.
    std::array<glm::dvec3, 9> shCoefficients() const;
    //! The split-out sun as a directional light at the current lookup (intensity and rotation
    //! applied), or nothing.
    std::optional<Light> sun() const;
    const EnvironmentImportance& importance() const;
    //! Texels replaced by 0 (NaN, infinite or negative in any channel).
    std::size_t replacedTexels() const;
    //! What the precomputation had to warn about (the replaced texels), one line each.
    const std::vector<std::string>& warnings() const;
    std::size_t memoryBytes() const;

private:
    friend struct EnvironmentBinding;
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

} // namespace obscura

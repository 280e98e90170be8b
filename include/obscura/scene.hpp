#pragma once
// Scene description: meshes (CPU arrays we upload, or the host's own GL buffers), materials,
// lights, and placeholders for the environment and participating media.
//
// Units: lengths in the scene's world units. Light is radiometric: radiance in
// W/(sr·m²), radiant intensity in W/sr, irradiance in W/m² (with metres replaced by the
// world unit). For photometric work pass cd and lux instead; every formula is linear in
// the light, so outputs are then luminance (cd/m²). Colours are linear RGB.
#include "obscura/export.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace obscura {

//! Triangle mesh in CPU memory. Obscura uploads it on first use and keeps the GPU copy for as
//! long as this object lives, so treat it as immutable once shared: to change a mesh, make
//! a new MeshData. Non-finite positions are rejected with Error{InvalidArgument}.
struct MeshData {
    std::vector<glm::vec3> positions;     //!< object space, world units
    std::vector<glm::vec3> normals;       //!< empty, or one per position (need not be unit)
    std::vector<glm::vec2> texcoords;     //!< empty, or one per position
    std::vector<std::uint32_t> indices;   //!< triangle list; empty means positions are a triangle list
};

struct Mesh {
    std::shared_ptr<const MeshData> data;
    glm::mat4 model{1.0f};      //!< object → world
    std::uint32_t material = 0; //!< index into Scene::materials
    std::string name;
};

//! One vertex attribute in a host GL buffer.
struct VertexStream {
    unsigned buffer = 0;       //!< GL buffer name; 0 = absent
    std::size_t offset = 0;    //!< bytes to the first element
    unsigned stride = 0;       //!< bytes between elements, [1, GL_MAX_VERTEX_ATTRIB_STRIDE]
    int components = 3;        //!< 2 for texcoords, 3 (or 4, w ignored) for positions and normals; 4 for 2_10_10_10 types
    unsigned type = 0x1406;    //!< GL_FLOAT, GL_HALF_FLOAT, GL_SHORT, ... (GL_FLOAT default)
    bool normalized = false;   //!< for integer types
};

//! A mesh that lives in the host's GL buffers, drawn as a triangle list. Either give the
//! host's vertex array object and the attribute locations it uses, or the streams directly.
//! Obscura never modifies the host VAO: it reads its layout (binding it for the query; the
//! binding is restored with the rest of the host state) and draws through a VAO of its own
//! that points at the host's buffers. Offsets, strides and counts are checked against the
//! buffers' sizes; index values are not (they live on the GPU), so indices past the end of
//! the vertex data are undefined behaviour as in GL itself.
struct MeshRef {
    unsigned vao = 0;             //!< host VAO; when non-zero, the *Location fields are used
    int positionLocation = 0;     //!< attribute location of positions in `vao`
    int normalLocation = -1;      //!< -1 = none
    int texcoordLocation = -1;    //!< -1 = none
    VertexStream position;        //!< used when vao == 0; required
    VertexStream normal;          //!< used when vao == 0; optional
    VertexStream texcoord;        //!< used when vao == 0; optional
    unsigned indexBuffer = 0;     //!< vao == 0: element buffer, 0 = non-indexed; with a VAO its own element buffer is used
    unsigned indexType = 0x1405;  //!< GL_UNSIGNED_INT, GL_UNSIGNED_SHORT or GL_UNSIGNED_BYTE
    std::size_t indexOffset = 0;  //!< bytes into the element buffer
    unsigned count = 0;           //!< indices (or vertices when non-indexed), a multiple of 3 in [3, INT_MAX]
    glm::mat4 model{1.0f};        //!< object → world
    std::uint32_t material = 0;   //!< index into Scene::materials
};

//! An sRGB-encoded RGBA8 image, row 0 at the top.
struct TextureImage {
    int width = 0;                  //!< pixels, [1, GL_MAX_TEXTURE_SIZE]
    int height = 0;                 //!< pixels, [1, GL_MAX_TEXTURE_SIZE]
    std::vector<std::uint8_t> rgba; //!< width * height * 4 bytes
};

struct Material {
    glm::vec3 albedo{0.8f};     //!< linear diffuse reflectance, [0,1] per channel
    //! emitted radiance, W/(sr·m²), [0, inf), from the front side of each triangle only: the
    //! side from which its vertices, as placed in the world, wind counter-clockwise (as a
    //! rect light emits from one side)
    glm::vec3 emission{0.0f};
    unsigned albedoTexture = 0; //!< optional host GL_TEXTURE_2D multiplying albedo (needs texcoords)
    std::shared_ptr<const TextureImage> albedoImage; //!< optional CPU image, used when albedoTexture == 0
    std::string name;
};

enum class LightType {
    Point,       //!< isotropic point (or small sphere, see radius)
    Spot,        //!< point with a smooth cone
    Directional, //!< distant light
    Rect,        //!< one-sided Lambertian rectangle (area light)
    Sphere,      //!< Lambertian sphere (area light)
};

struct Light {
    LightType type = LightType::Point;
    glm::vec3 color{1.0f};   //!< linear RGB factor, [0, inf)
    //! Point and spot: radiant intensity, W/sr. Directional: irradiance on a surface facing
    //! the light, W/m². Rect and sphere: emitted radiance, W/(sr·m²). [0, inf).
    float intensity = 1.0f;
    glm::vec3 position{0.0f};           //!< point, spot, sphere: position/centre; rect: centre; world units
    //! Spot: cone axis; directional: direction the light travels; rect: the side it emits
    //! toward (its normal). Any length > 0.
    glm::vec3 direction{0.0f, -1.0f, 0.0f};
    glm::vec3 tangent{1.0f, 0.0f, 0.0f}; //!< rect: direction of its width; made orthogonal to direction; not parallel to it
    glm::vec2 size{1.0f};                //!< rect: width and height, world units, (0, inf)
    float innerAngle = 0.3f;  //!< spot: half-angle of full intensity, radians, [0, outerAngle]
    float outerAngle = 0.5f;  //!< spot: half-angle where intensity reaches 0, radians, [1e-6, pi/2)
    //! Point and spot: radius of the emitting sphere, world units, [0, inf). Irradiance uses
    //! 1/max(d², radius²), so a surface touching a light of radius > 0 stays finite. With
    //! radius 0 a point exactly at the light receives nothing (the direction is undefined).
    //! Sphere: its radius, (0, inf).
    float radius = 0.0f;
    bool castsShadows = true; //!< for the shadow-map module
};

//! Placeholder for the image-based lighting module: an equirectangular HDR environment.
struct Environment {
    std::string path;        //!< EXR/HDR file, equirectangular (longitude along x)
    float intensity = 1.0f;  //!< radiance scale, [0, inf)
    float rotation = 0.0f;   //!< about +y, radians, any finite value (taken modulo 2 pi)
};

enum class PhaseFunction {
    Isotropic,         //!< 1/(4 pi)
    HenyeyGreenstein,  //!< (1 - g²) / (4 pi (1 + g² - 2 g cos)^(3/2)), g = Medium::anisotropy
    Rayleigh,          //!< 3 (1 + cos²) / (16 pi)
    //! Schlick's fit of Henyey-Greenstein: (1 - k²) / (4 pi (1 - k cos)²), k = 1.55 g - 0.55 g³
    //! with |k| at most 1 - (1 - |g|)²: the cubic exceeds 1 from |g| ~ 0.94 on (the phase
    //! would turn negative); the bound takes over from |g| ~ 0.83, changing k by < 0.5 %.
    Schlick,
};

//! How a medium's density varies inside its box: it multiplies scattering and absorption.
enum class MediumDensity {
    Constant, //!< 1: a homogeneous medium
    Height,   //!< exponential height fog: exp(-heightFalloff (y - boxMin.y))
    Grid,     //!< Medium::grid, trilinear over the box
};

//! A density grid: size.x * size.y * size.z values, x fastest, at the centres of equal cells
//! that tile the medium's box; finite and >= 0 (any scale: sigma multiplies them). Immutable
//! once shared with a Medium (as MeshData is): modules upload a grid object once and do not
//! see its values change; to animate, share a new grid.
struct DensityGrid {
    glm::ivec3 size{0}; //!< cells per axis, each [1, 1024]
    std::vector<float> values;
};

//! A medium in an axis-aligned box (for the participating-media module and its reference):
//! sigma_s(x) = density(x) scattering, sigma_a(x) = density(x) absorption inside the box, 0
//! outside. Phase angles are between the light's travel direction and the view ray's.
struct Medium {
    glm::vec3 boxMin{0.0f}, boxMax{0.0f}; //!< world units, finite, boxMin <= boxMax per axis
    glm::vec3 scattering{0.0f};           //!< sigma_s at density 1, 1/world unit, [0, inf)
    glm::vec3 absorption{0.0f};           //!< sigma_a at density 1, 1/world unit, [0, inf)
    PhaseFunction phase = PhaseFunction::HenyeyGreenstein;
    float anisotropy = 0.0f;              //!< Henyey-Greenstein's and Schlick's g, (-1, 1)
    MediumDensity density = MediumDensity::Constant;
    float heightFalloff = 0.0f;           //!< Height: 1/world unit, [0, inf) (0: constant)
    std::shared_ptr<const DensityGrid> grid; //!< Grid: the values (shared between copies)
};

//! The density of `medium` at world point p: 0 outside its box (boundary included inside).
OBSCURA_API double mediumDensity(const Medium& medium, const glm::dvec3& p);
//! Its largest density anywhere in the box (the majorant's factor).
OBSCURA_API double mediumMaxDensity(const Medium& medium);
//! A procedural density grid: the sum of `octaves` octaves of smooth value noise (a lattice of
//! random values from `seed`, trilinear with smoothstep weights, each octave twice the
//! frequency and half the amplitude of the last, the first with 4 lattice cells per axis), each
//! value of the sum mapped by max(0, 2 v - 0.5) to make clumps and clear gaps; in [0, 1.5].
OBSCURA_API DensityGrid noiseDensityGrid(glm::ivec3 size, std::uint32_t seed, int octaves = 3);

//! Schlick's k for anisotropy g (PhaseFunction::Schlick), in (-1, 1) for g in (-1, 1).
OBSCURA_API double schlickK(double g);
//! The phase function value for the cosine of the scattering angle (1/sr).
OBSCURA_API double phaseFunction(PhaseFunction phase, double anisotropy, double cosTheta);

struct Scene {
    std::vector<Mesh> meshes;
    std::vector<MeshRef> meshRefs;
    std::vector<Material> materials; //!< a mesh whose material index is out of range is an error
    std::vector<Light> lights;
    std::optional<Environment> environment;
    std::vector<Medium> media;
};

struct Bounds {
    glm::vec3 min{0.0f}, max{0.0f};
    bool empty = true;
};

//! Checks everything that can be checked on the CPU: lights (finite, in range, consistent
//! types), materials, the environment and media (finite, in range, enumerators), CPU meshes
//! (sizes, finite positions, index range) and material indices.
//! Throws Error{InvalidArgument} naming the offending element, e.g. "Scene::lights[2].radius".
OBSCURA_API void validateScene(const Scene& scene);

//! World-space bounds of the CPU meshes (host MeshRefs are not read back).
OBSCURA_API Bounds sceneBounds(const Scene& scene);

} // namespace obscura

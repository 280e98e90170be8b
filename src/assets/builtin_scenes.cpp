// Built-in scenes: the Cornell box from its published measurements, and analytic scenes
// whose ambient occlusion and lighting have closed forms (tests, benchmarks).
#include "obscura/assets.hpp"
#include "obscura/error.hpp"

#include <array>
#include <cmath>
#include <functional>
#include <map>

namespace obscura::assets {
namespace {

using Quad = std::array<glm::vec3, 4>;

// Appends quads as two triangles each, with their face normal, to one mesh.
class MeshBuilder {
public:
    MeshBuilder& quad(const Quad& q) {
        const glm::vec3 n = glm::normalize(glm::cross(q[1] - q[0], q[2] - q[0]));
        const auto base = static_cast<std::uint32_t>(data_.positions.size());
        for (const auto& v : q) {
            data_.positions.push_back(v);
            data_.normals.push_back(n);
        }
        for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) data_.indices.push_back(base + i);
        return *this;
    }
    // An axis-aligned box from lo to hi; `inward` turns the faces to the inside (a room).
    MeshBuilder& box(glm::vec3 lo, glm::vec3 hi, bool inward) {
        const glm::vec3 c[8] = {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {lo.x, hi.y, lo.z},
                                {lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}};
        const int faces[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 4, 7, 3}, {1, 2, 6, 5}, {0, 1, 5, 4}, {3, 7, 6, 2}};
        for (const auto& f : faces) {
            Quad q{c[f[0]], c[f[1]], c[f[2]], c[f[3]]};
            if (inward) std::swap(q[1], q[3]);
            quad(q);
        }
        return *this;
    }
    Mesh build(std::uint32_t material, const std::string& name) {
        Mesh m;
        m.data = std::make_shared<MeshData>(std::move(data_));
        m.material = material;
        m.name = name;
        data_ = {};
        return m;
    }

private:
    MeshData data_;
};

Material material(const std::string& name, glm::vec3 albedo, glm::vec3 emission = glm::vec3(0.0f)) {
    Material m;
    m.name = name;
    m.albedo = albedo;
    m.emission = emission;
    return m;
}

// Cornell Program of Computer Graphics, "Cornell Box Data" (../shared/data/cornell_box.md):
// millimetres, y up. Reflectances use the common linear-RGB approximation of the measured
// spectra: white (0.725, 0.71, 0.68), red (0.63, 0.065, 0.05), green (0.14, 0.45, 0.091);
// emitter radiance (17, 12, 4) in relative units. The emitter is lowered from y = 548.8 to
// 548.7 so that the ceiling does not cover it.
LoadedScene cornell() {
    LoadedScene s;
    s.name = "cornell";
    s.unitsPerMetre = 1000.0f;
    auto& sc = s.scene;
    sc.materials = {material("white", {0.725f, 0.71f, 0.68f}), material("red", {0.63f, 0.065f, 0.05f}),
                    material("green", {0.14f, 0.45f, 0.091f}),
                    material("light", {0.78f, 0.78f, 0.78f}, {17.0f, 12.0f, 4.0f})};
    MeshBuilder white;
    white.quad({{{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}}})                    // floor
        .quad({{{556.0f, 548.8f, 0}, {556.0f, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}}}) // ceiling
        .quad({{{549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556.0f, 548.8f, 559.2f}}}); // back
    // Short block.
    white.quad({{{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}}})
        .quad({{{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}}})
        .quad({{{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}}})
        .quad({{{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}}})
        .quad({{{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}}});
    // Tall block.
    white.quad({{{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}}})
        .quad({{{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}}})
        .quad({{{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}}})
        .quad({{{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}}})
        .quad({{{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}}});
    sc.meshes.push_back(white.build(0, "white"));
    sc.meshes.push_back(
        MeshBuilder().quad({{{552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556.0f, 548.8f, 559.2f}, {556.0f, 548.8f, 0}}}).build(1, "red"));
    sc.meshes.push_back(
        MeshBuilder().quad({{{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}}}).build(2, "green"));
    sc.meshes.push_back(
        MeshBuilder().quad({{{343, 548.7f, 227}, {343, 548.7f, 332}, {213, 548.7f, 332}, {213, 548.7f, 227}}}).build(3, "light"));
    // Until area lights exist, the emitter is approximated for direct lighting by a point
    // light just below its centre with the emitter's on-axis intensity I = L * A
    // (A = 130 mm x 105 mm); the cosine falloff of the real emitter is ignored. Its radius is
    // that of a disc of the same area, so irradiance stays bounded next to the emitter.
    Light l;
    l.type = LightType::Point;
    l.position = {278.0f, 548.0f, 279.5f};
    l.color = glm::vec3(17.0f, 12.0f, 4.0f);
    l.intensity = 130.0f * 105.0f;
    l.radius = std::sqrt(130.0f * 105.0f / 3.14159265f);
    sc.lights.push_back(l);
    s.camera.lookAt = {{278.0f, 273.0f, -800.0f}, {278.0f, 273.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    s.camera.fovyDegrees = 39.3077f; // 2 atan(0.025 / (2 * 0.035))
    s.camera.nearPlane = 10.0f;
    s.camera.farPlane = 3000.0f;
    return s;
}

// The Cornell box lit by a sphere light of the point light's radius and the emitter's
// radiance, hanging below the emitter: an area light, whose soft shadows the reference computes (shadow.pcss).
LoadedScene cornellSphere() {
    LoadedScene s = cornell();
    s.name = "cornell_sphere";
    Light& l = s.scene.lights.at(0);
    l.type = LightType::Sphere;
    l.intensity = 1.0f; // sphere lights: emitted radiance = color, the emitter's (17, 12, 4)
    l.position.y = 548.7f - l.radius - 1.0f; // hanging 1 mm below the ceiling, not through it
    return s;
}

// The Cornell box lit by its published emitter as a rect light (130 mm x 105 mm, facing
// down, the emitter's radiance), just below the emitter's quad: an area light whose soft
// shadows the reference computes (shadow.pcss).
LoadedScene cornellRect() {
    LoadedScene s = cornell();
    s.name = "cornell_rect";
    Light& l = s.scene.lights.at(0);
    l.type = LightType::Rect;
    l.intensity = 1.0f; // rect lights: emitted radiance = color, the emitter's (17, 12, 4)
    l.position = {278.0f, 548.6f, 279.5f};
    l.direction = {0.0f, -1.0f, 0.0f};
    l.tangent = {1.0f, 0.0f, 0.0f};
    l.size = {130.0f, 105.0f};
    l.radius = 0.0f;
    return s;
}

// The Cornell box filled with fog (0.8 per metre scattering, 0.2 absorption, isotropic), seen
// from outside it: the media techniques' closed room.
LoadedScene cornellFog() {
    LoadedScene s = cornell();
    s.name = "cornell_fog";
    Medium fog;
    fog.boxMin = {0.0f, 0.0f, 0.0f};
    fog.boxMax = {556.0f, 548.8f, 559.2f};
    fog.scattering = glm::vec3(0.0008f); // per mm
    fog.absorption = glm::vec3(0.0002f);
    fog.phase = PhaseFunction::Isotropic;
    s.scene.media.push_back(fog);
    return s;
}

// The Cornell box filled with smoke: a noise density grid (noiseDensityGrid, 32^3, seed 3:
// clumps up to 1.5 and clear gaps) at twice the fog's coefficients, isotropic. The
// heterogeneous case of the media techniques.
LoadedScene cornellSmoke() {
    LoadedScene s = cornellFog();
    s.name = "cornell_smoke";
    Medium& smoke = s.scene.media.at(0);
    smoke.scattering *= 2.0f;
    smoke.absorption *= 2.0f;
    smoke.density = MediumDensity::Grid;
    smoke.grid = std::make_shared<DensityGrid>(noiseDensityGrid({32, 32, 32}, 3));
    return s;
}

// God rays (the volumetric-lighting thesis's test): a spot light above a lattice of bars
// shining through its holes into forward-scattering fog over a floor, seen from outside the
// fog. Metres.
LoadedScene godRays() {
    LoadedScene s;
    s.name = "god_rays";
    s.unitsPerMetre = 1.0f;
    s.scene.materials = {material("grey", glm::vec3(0.5f))};
    MeshBuilder b;
    b.quad({{{-10, 0, -10}, {-10, 0, 10}, {10, 0, 10}, {10, 0, -10}}});
    for (int i = -2; i <= 2; ++i) {
        const float at = float(i);
        b.box({-2.5f, 3.0f, at - 0.15f}, {2.5f, 3.1f, at + 0.15f}, false);
        b.box({at - 0.15f, 3.0f, -2.5f}, {at + 0.15f, 3.1f, 2.5f}, false);
    }
    s.scene.meshes.push_back(b.build(0, "god_rays"));
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 5.5f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.innerAngle = 0.45f;
    spot.outerAngle = 0.6f;
    spot.intensity = 60.0f;
    s.scene.lights.push_back(spot);
    Medium fog;
    fog.boxMin = {-5.0f, 0.0f, -5.0f};
    fog.boxMax = {5.0f, 6.0f, 5.0f};
    fog.scattering = glm::vec3(0.12f);
    fog.absorption = glm::vec3(0.02f);
    fog.phase = PhaseFunction::HenyeyGreenstein;
    fog.anisotropy = 0.5f;
    s.scene.media.push_back(fog);
    s.camera.lookAt = {{0.0f, 1.2f, 8.5f}, {0.0f, 2.6f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    s.camera.fovyDegrees = 50.0f;
    s.camera.nearPlane = 0.05f;
    s.camera.farPlane = 100.0f;
    return s;
}

// Analytic scenes, in metres: a 20 m floor at y = 0 centred on the origin, plus walls.
constexpr float kHalf = 10.0f;
constexpr float kWallHeight = 5.0f;

Quad floorQuad() { return {{{-kHalf, 0, -kHalf}, {-kHalf, 0, kHalf}, {kHalf, 0, kHalf}, {kHalf, 0, -kHalf}}}; }
Quad backWall() { return {{{-kHalf, 0, 0}, {kHalf, 0, 0}, {kHalf, kWallHeight, 0}, {-kHalf, kWallHeight, 0}}}; }
Quad sideWall() { return {{{0, 0, kHalf}, {0, 0, 0}, {0, kWallHeight, 0}, {0, kWallHeight, kHalf}}}; }

LoadedScene analytic(const std::string& name, const std::function<void(MeshBuilder&)>& build, const CameraSpec& camera) {
    LoadedScene s;
    s.name = name;
    s.scene.materials = {material("grey", glm::vec3(0.5f))};
    MeshBuilder b;
    build(b);
    s.scene.meshes.push_back(b.build(0, name));
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.6f));
    sun.intensity = 3.14159265f; // irradiance pi: a white surface facing the sun has radiance 1
    s.scene.lights.push_back(sun);
    s.camera = camera;
    return s;
}

CameraSpec view(glm::vec3 eye, glm::vec3 target) {
    CameraSpec c;
    c.lookAt = {eye, target, {0.0f, 1.0f, 0.0f}};
    c.fovyDegrees = 50.0f;
    c.nearPlane = 0.05f;
    c.farPlane = 100.0f;
    return c;
}

const std::map<std::string, std::function<LoadedScene()>>& registry() {
    static const std::map<std::string, std::function<LoadedScene()>> scenes = {
        {"cornell", cornell},
        {"cornell_sphere", cornellSphere},
        {"cornell_rect", cornellRect},
        {"cornell_fog", cornellFog},
        {"cornell_smoke", cornellSmoke},
        {"god_rays", godRays},
        {"plane", [] { return analytic("plane", [](MeshBuilder& b) { b.quad(floorQuad()); }, view({0, 3, 6}, {0, 0, 0})); }},
        {"wall", [] {
             return analytic("wall", [](MeshBuilder& b) { b.quad(floorQuad()).quad(backWall()); },
                             view({0, 2.5f, 6}, {0, 0.8f, 0}));
         }},
        {"corner", [] {
             // Three mutually perpendicular planes meeting at the origin (floor x,z >= 0).
             return analytic(
                 "corner",
                 [](MeshBuilder& b) {
                     b.quad({{{0, 0, 0}, {0, 0, kHalf}, {kHalf, 0, kHalf}, {kHalf, 0, 0}}})
                         .quad({{{0, 0, 0}, {kHalf, 0, 0}, {kHalf, kWallHeight, 0}, {0, kWallHeight, 0}}})
                         .quad(sideWall());
                 },
                 view({4, 3, 5}, {0, 0.5f, 0}));
         }},
        {"box_room", [] {
             return analytic(
                 "box_room",
                 [](MeshBuilder& b) {
                     b.box({-3, 0, -3}, {3, 3, 3}, true);
                     b.box({-0.5f, 0, -0.5f}, {0.5f, 1, 0.5f}, false);
                 },
                 view({2.2f, 1.6f, 2.6f}, {0, 0.5f, 0}));
         }},
    };
    return scenes;
}

} // namespace

std::vector<std::string> builtinSceneNames() {
    std::vector<std::string> names;
    for (const auto& e : registry()) names.push_back(e.first);
    return names;
}

LoadedScene builtinScene(const std::string& name) {
    const auto it = registry().find(name);
    if (it == registry().end()) {
        std::string known;
        for (const auto& n : builtinSceneNames()) known += (known.empty() ? "" : ", ") + n;
        throw Error(ErrorCode::InvalidArgument, "unknown built-in scene \"" + name + "\" (known: " + known + ")");
    }
    return it->second();
}

} // namespace obscura::assets

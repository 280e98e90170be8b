// Shadow maps: the hard and PCF masks of a square plate's shadow under a spot light, a point
// light (cube, paraboloids) and a cascaded directional light against the Embree reference,
// misclassified pixels allowed only within a band of texels around the shadow's edge; contact
// shadows, depth-fitted cascades, reflective maps, shimmer, the shadowed G-buffer, stability
// and bad input. Soft shadows are in test_soft_shadows.cpp.
#include "shadow_plates.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

using namespace obscura;
using namespace obscura::test;

TEST_CASE("Spot and point light hard and PCF shadows of a plate match the reference away from the edge", "[shadows][reference]") {
    // Spot, point (cube), point (dual paraboloid). The floor is two triangles 40 m wide seen
    // from 3 m: nearly the whole lower paraboloid, so interpolated depth would be far off.
    for (const auto& [type, mapping] : {std::pair{LightType::Spot, PointShadowMapping::Cube},
                                        std::pair{LightType::Point, PointShadowMapping::Cube},
                                        std::pair{LightType::Point, PointShadowMapping::DualParaboloid}}) {
        const bool paraboloid = mapping == PointShadowMapping::DualParaboloid;
        Light light;
        light.type = type;
        light.position = {0.0f, 3.0f, 0.0f};
        light.direction = {0.0f, -1.0f, 0.0f};
        light.intensity = 10.0f;
        light.outerAngle = 1.2f; // the cone's edge (7.7 m out on the floor) is out of view
        light.innerAngle = 1.0f;
        const Scene scene = plateScene(light);
        constexpr int W = 96, H = 72;
        ShadowFixture f(plateCamera(W, H), W, H);
        f.render(scene);
        const reference::Reference truth = f.truth(scene);
        ShadowMapSettings maps;
        maps.resolution = 512;
        maps.pointMapping = mapping;
        const ShadowMapSet& set = f.shadows.render(scene, f.camera, maps);
        REQUIRE(set.find(0) != nullptr);
        REQUIRE(set.find(0)->layers == (type == LightType::Point ? (paraboloid ? 2 : 6) : 1));
        REQUIRE(set.find(0)->paraboloid == paraboloid);
        const double texelPerUnit = set.find(0)->texelSize[0];
        // The shadow: the plate scaled from the light onto the floor.
        const double scale = light.position.y / (light.position.y - kHeight);
        const auto edge = [&](const glm::dvec3& p) { return squareEdgeDistance(p.x, p.z, {0, 0}, kPlate * scale); };
        for (const auto& [filter, kernel] : {std::pair{ShadowFilter::Hard, PcfKernel::Grid}, std::pair{ShadowFilter::Pcf, PcfKernel::Grid},
                                             std::pair{ShadowFilter::Pcf, PcfKernel::OptimizedGrid},
                                             std::pair{ShadowFilter::Pcf, PcfKernel::PoissonDisc}}) {
            ShadowMaskSettings s;
            s.filter = filter;
            s.pcfRadius = 1;
            s.pcfKernel = kernel;
            const Image mask = readTexture(f.ctx, f.shadows.mask(f.view, set, 0, s));
            // Where the edge can be: the plate's outline lands in a texel of the map (one
            // texel at the floor), the receiver in another (half a diagonal), the biases move
            // it by under a texel here (normal offset 1 texel up, slope tan <= 0.6); PCF adds
            // its kernel's reach, pcfRadius + 1 texels (the Poisson disc's radius is
            // pcfRadius + 0.5, plus the bilinear texel: pcfRadius + 2 rounded up). A texel at a point is the texel per
            // unit distance times its distance along the map's axis (at most the largest
            // component of its offset from the light); a paraboloid's is 2 / resolution times
            // |v| + v.z (v: the offset in the lower map's frame, whose axis is -y). The
            // paraboloid draws the plate's edges straight between projected corners while the
            // true images curve: an edge's midpoint (0.5, 0, 2) projects to x = 0.12311, its
            // corners (0.5, +-0.5, 2) to 0.12132, 0.46 of a 2/512 texel apart: half a texel more.
            const int reach = filter == ShadowFilter::Pcf ? s.pcfRadius + (kernel == PcfKernel::PoissonDisc ? 2 : 1) : 0;
            const auto band = [&](const glm::dvec3& p) {
                const glm::dvec3 v = p - glm::dvec3(light.position), d = glm::abs(v);
                const double texel = paraboloid ? texelPerUnit * (glm::length(v) - v.y) : texelPerUnit * std::max({d.x, d.y, d.z});
                return (3.0 + reach + (paraboloid ? 0.5 : 0.0)) * texel;
            };
            CAPTURE(static_cast<int>(type), paraboloid, static_cast<int>(filter), static_cast<int>(kernel));
            CHECK(checkMask(f, mask, truth, band, edge) > W * H / 3);
        }
    }
}

TEST_CASE("A rect light flush with its ceiling shadows like a point light at its centre", "[shadows][reference]") {
    // The light lies in the ceiling's plane (y = 3), emitting down: the ceiling is edge-on to
    // its paraboloid map and must not cover it. Its hard mask is the visibility of its centre,
    // so the reference is a point light there (whose rays end on the ceiling's plane).
    Light rect;
    rect.type = LightType::Rect;
    rect.position = {0.0f, 3.0f, 0.0f};
    rect.direction = {0.0f, -1.0f, 0.0f};
    rect.size = {0.4f, 0.4f};
    Scene scene = plateScene(rect);
    // (It ends at z = 1, short of where the camera's highest rays cross y = 3, z = 1.48: the
    // view shows neither side of it, whose pixels would lie in the light's plane.)
    const auto ceiling = test::quadMesh({glm::dvec3(-4, 3, -4), {4, 3, -4}, {4, 3, 1}, {-4, 3, 1}});
    scene.meshes.push_back({ceiling, glm::mat4(1.0f), 0, "ceiling"});
    constexpr int W = 96, H = 72;
    ShadowFixture f(plateCamera(W, H), W, H);
    f.render(scene);
    Scene point = scene;
    point.lights[0].type = LightType::Point;
    const reference::Reference truth = f.truth(point);
    const ShadowMapSet& set = f.shadows.render(scene, f.camera, {512, 1, 0.5f});
    REQUIRE(set.find(0) != nullptr);
    const double texelPerUnit = set.find(0)->texelSize[0];
    ShadowMaskSettings s;
    s.filter = ShadowFilter::Hard;
    const Image mask = readTexture(f.ctx, f.shadows.mask(f.view, set, 0, s));
    // As the plate test's paraboloid: the shadow is the plate scaled by 3 / 2, the band 3.5
    // texels of 2 / 512 times |v| + v.z (v: the offset in the map's frame, axis -y).
    const auto edge = [&](const glm::dvec3& p) { return squareEdgeDistance(p.x, p.z, {0, 0}, kPlate * 1.5); };
    const auto band = [&](const glm::dvec3& p) {
        const glm::dvec3 v = p - glm::dvec3(rect.position);
        return 3.5 * texelPerUnit * (glm::length(v) - v.y);
    };
    CHECK(checkMask(f, mask, truth, band, edge) > W * H / 3);
}

TEST_CASE("Contact shadows recover the shadow next to an occluder's base that a large bias removes", "[shadows][reference]") {
    // contactWallScene: a constant bias longer than the wall is thick (peter-panning).
    const Scene lit = contactWallScene();
    constexpr int W = 96, H = 72;
    ShadowFixture f(contactWallCamera(W, H), W, H);
    f.render(lit);
    const reference::Reference truth = f.truth(lit);
    const ShadowMapSet& set = f.shadows.render(lit, f.camera, {1024, 1, 0.5f});
    ShadowMaskSettings s;
    s.filter = ShadowFilter::Hard;
    s.constantBias = 0.2f;
    const auto misclassified = [&](const Image& mask) {
        glm::ivec2 wrong(0); // false shadow, false light
        for (std::size_t i = 0; i < std::size_t(W) * H; ++i) {
            if (truth.value.pixels[2 * i + 1] == 0.0f || f.positions.pixels[4 * i + 3] == 0.0f) continue;
            const bool isLit = mask.pixels[i] >= 0.5f, truthLit = truth.value.pixels[2 * i] >= 0.5f;
            wrong += glm::ivec2(truthLit && !isLit ? 1 : 0, !truthLit && isLit ? 1 : 0);
        }
        return wrong;
    };
    const glm::ivec2 without = misclassified(readTexture(f.ctx, f.shadows.mask(f.view, set, 0, s)));
    s.contactLength = 0.5f;
    s.contactSteps = 32;
    const glm::ivec2 with = misclassified(readTexture(f.ctx, f.shadows.mask(f.view, set, 0, s)));
    INFO("false shadow / false light: " << without.x << " / " << without.y << " without contact shadows, " << with.x
                                        << " / " << with.y << " with");
    // The bias's peter-panning is there to recover, and the ray recovers most of it without
    // trading it for as many false shadows.
    CHECK(without.y > 20);
    CHECK(with.y * 2 < without.y);
    CHECK(with.x + with.y < without.x + without.y);
}

namespace {
// The directional light the cascade tests cast the plate's shadow with.
Light slantedSun() {
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = glm::normalize(glm::vec3(-0.3f, -1.0f, -0.2f));
    return sun;
}
} // namespace

TEST_CASE("A directional light's cascaded shadows of a plate match the reference away from the edge", "[shadows][reference]") {
    Light sun = slantedSun();
    sun.intensity = 3.0f;
    const Scene scene = plateScene(sun);
    constexpr int W = 96, H = 72;
    ShadowFixture f(Camera::perspective({{0.5f, 2.5f, 5.0f}, {0, 0, -1}, {0, 1, 0}}, 0.9f, float(W) / H, 0.05f, 100.0f), W, H);
    f.render(scene);
    const reference::Reference truth = f.truth(scene);
    ShadowMapSettings maps;
    maps.resolution = 1024;
    maps.cascades = 3;
    const ShadowMapSet& set = f.shadows.render(scene, f.camera, maps);
    const ShadowMapInfo& info = *set.find(0);
    REQUIRE(info.layers == 3);
    CHECK(info.texelSize[0] < info.texelSize[2]);
    INFO("cascades end at " << info.sliceEnd[0] << ", " << info.sliceEnd[1] << ", " << info.sliceEnd[2] << " with texels "
                            << info.texelSize[0] << ", " << info.texelSize[1] << ", " << info.texelSize[2]);
    // The shadow: the plate moved along the light onto the floor.
    const glm::dvec2 offset = glm::dvec2(sun.direction.x, sun.direction.z) * (kHeight / -sun.direction.y);
    const auto edge = [&](const glm::dvec3& p) { return squareEdgeDistance(p.x, p.z, offset, kPlate); };
    for (const ShadowFilter filter : {ShadowFilter::Hard, ShadowFilter::Pcf}) {
        ShadowMaskSettings s;
        s.filter = filter;
        const Image mask = readTexture(f.ctx, f.shadows.mask(f.view, set, 0, s));
        const int reach = filter == ShadowFilter::Pcf ? s.pcfRadius + 1 : 0;
        // As for the spot, in the texels of the pixel's cascade or, in its blend band, the
        // coarser next one's (a texel of a tilted receiver along the light is 1 / cos
        // longer: cos >= 0.9 here).
        const auto band = [&](const glm::dvec3& p) {
            const double distance = -(glm::dmat4(f.camera.view) * glm::dvec4(p, 1.0)).z;
            std::size_t c = 0;
            while (c + 1 < std::size_t(info.layers) && distance > info.sliceEnd[c]) ++c;
            const double start = c > 0 ? info.sliceEnd[c - 1] : 0.0, end = info.sliceEnd[c];
            const bool blending = c + 1 < std::size_t(info.layers) && distance > end - s.cascadeBlend * (end - start);
            return (3.0 + reach) * info.texelSize[blending ? c + 1 : c] / 0.9;
        };
        CAPTURE(static_cast<int>(filter));
        CHECK(checkMask(f, mask, truth, band, edge) > W * H / 3);
    }
}

TEST_CASE("Cascades fitted to the depth buffer span the visible distances and match the reference", "[shadows][reference]") {
    const Light sun = slantedSun();
    const Scene scene = plateScene(sun);
    constexpr int W = 96, H = 72;
    // Looking down at the plate: the visible floor ends a few metres away, while the scene's
    // 40 m floor is visible (by its bounds) out to ~25 m.
    ShadowFixture f(Camera::perspective({{0.0f, 4.0f, 2.0f}, {0, 0, -0.5f}, {0, 1, 0}}, 0.9f, float(W) / H, 0.05f, 100.0f), W, H);
    f.render(scene);
    double nearest = INFINITY, farthest = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (f.positions.at(x, y, 3) != 0.0f) {
                nearest = std::min(nearest, -double(f.positions.at(x, y, 2)));
                farthest = std::max(farthest, -double(f.positions.at(x, y, 2)));
            }
    ShadowMapSettings maps;
    maps.resolution = 1024;
    maps.cascades = 3;
    // The texel of the cascade a view distance falls in.
    const auto texelAt = [](const ShadowMapInfo& m, double distance) {
        std::size_t c = 0;
        while (c + 1 < std::size_t(m.layers) && distance > m.sliceEnd[c]) ++c;
        return m.texelSize[c];
    };
    const ShadowMapInfo byBounds = *f.shadows.render(scene, f.camera, maps).find(0);
    const float boundsEnd = byBounds.sliceEnd[2];
    const ShadowMapSet& set = f.shadows.render(scene, f.camera, maps, f.view);
    const ShadowMapInfo& info = *set.find(0);
    // The reduction reads the same depth the positions were reconstructed from: the range
    // agrees to float rounding of the reconstruction (relative 1e-5).
    CAPTURE(nearest, farthest, info.sliceStart, info.sliceEnd[2], boundsEnd);
    CHECK(std::abs(info.sliceStart - nearest) <= 1e-5 * nearest);
    CHECK(std::abs(info.sliceEnd[2] - farthest) <= 1e-5 * farthest);
    CHECK(farthest < 0.5 * boundsEnd);
    // The bounds' split spends cascades on distances with no geometry: where there is some,
    // the depth's cascades are finer (at the middle of the range) or no coarser.
    CHECK(texelAt(info, 0.5 * (nearest + farthest)) < texelAt(byBounds, 0.5 * (nearest + farthest)));
    CHECK(texelAt(info, nearest) <= texelAt(byBounds, nearest) * 1.001f);
    CHECK(texelAt(info, farthest) <= texelAt(byBounds, farthest) * 1.001f);
    const reference::Reference truth = f.truth(scene);
    const glm::dvec2 offset = glm::dvec2(sun.direction.x, sun.direction.z) * (kHeight / -sun.direction.y);
    const auto edge = [&](const glm::dvec3& p) { return squareEdgeDistance(p.x, p.z, offset, kPlate); };
    ShadowMaskSettings s;
    s.filter = ShadowFilter::Hard;
    const Image mask = readTexture(f.ctx, f.shadows.mask(f.view, set, 0, s));
    // The band of the cascaded test: 3 texels of the pixel's cascade or the next one.
    const auto band = [&](const glm::dvec3& p) {
        const double distance = -(glm::dmat4(f.camera.view) * glm::dvec4(p, 1.0)).z;
        std::size_t c = 0;
        while (c + 1 < std::size_t(info.layers) && distance > info.sliceEnd[c]) ++c;
        return 3.0 * info.texelSize[std::min(c + 1, std::size_t(info.layers) - 1)] / 0.9;
    };
    CHECK(checkMask(f, mask, truth, band, edge) > W * H / 3);
    // A scene without a shadowed directional light measures nothing.
    Light spot = sun;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 3.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    CHECK(f.shadows.render(plateScene(spot), f.camera, maps, f.view).find(0)->layers == 1);
    Camera moved = f.camera;
    moved.view[3][0] += 0.1f;
    CHECK_THROWS_WITH(f.shadows.render(scene, moved, maps, f.view), Catch::Contains("another camera"));
}

namespace {

// One layer of a GL_TEXTURE_2D_ARRAY of RGBA, read back as floats.
std::vector<float> readLayer(unsigned texture, int resolution, int layer) {
    std::vector<float> texels(std::size_t(resolution) * std::size_t(resolution) * 4u);
    glGetTextureSubImage(texture, 0, 0, 0, layer, resolution, resolution, 1, GL_RGBA, GL_FLOAT,
                         static_cast<GLsizei>(texels.size() * sizeof(float)), texels.data());
    return texels;
}

// Sum of the RGB channel c over the texels whose alpha is 1, and how many have alpha 1.
std::pair<double, std::size_t> sumSeen(const std::vector<float>& texels, int c) {
    double sum = 0.0;
    std::size_t seen = 0;
    for (std::size_t i = 0; i < texels.size(); i += 4)
        if (texels[i + 3] == 1.0f) {
            sum += texels[i + std::size_t(c)];
            ++seen;
        }
    return {sum, seen};
}

} // namespace

TEST_CASE("Reflective shadow maps hold the reflected flux, normal and position of what the light sees", "[shadows][rsm]") {
    constexpr int W = 48, H = 36, R = 256;
    Light sun;
    sun.type = LightType::Directional;
    sun.direction = {0.0f, -1.0f, 0.0f};
    sun.intensity = 2.0f;
    Light spot;
    spot.type = LightType::Spot;
    spot.position = {0.0f, 3.0f, 0.0f};
    spot.direction = {0.0f, -1.0f, 0.0f};
    spot.intensity = 5.0f;
    spot.innerAngle = spot.outerAngle = 0.6f; // a hard cone: its solid angle is 2 pi (1 - cos 0.6)
    Scene scene = plateScene(sun);
    scene.lights.push_back(spot);
    const double albedo = scene.materials[0].albedo.x;
    ShadowFixture f(Camera::perspective({{0.0f, 4.0f, 2.0f}, {0, 0, -0.5f}, {0, 1, 0}}, 0.9f, float(W) / H, 0.05f, 100.0f), W, H);
    f.render(scene);
    ShadowMapSettings s;
    s.resolution = R;
    s.cascades = 1;
    CHECK(f.shadows.render(scene, f.camera, s, f.view).flux == 0); // only when asked for
    s.reflective = true;
    const ShadowMapSet& set = f.shadows.render(scene, f.camera, s, f.view);
    REQUIRE(set.flux != 0);
    const ShadowMapInfo& sunMaps = *set.find(0);
    const ShadowMapInfo& spotMaps = *set.find(1);
    // The sun's cascade lies within the 40 m floor, so every texel sees the floor or the plate
    // and the power through it, E s^2, comes back times the albedo: the sum is rho E (R s)^2.
    // The 16F flux rounds each texel by at most 2^-11 relative, so the sum too.
    const auto [sunFlux, sunSeen] = sumSeen(readLayer(set.flux, R, sunMaps.firstLayer), 0);
    REQUIRE(sunSeen == std::size_t(R) * R);
    const double side = double(sunMaps.texelSize[0]) * R;
    CHECK(std::abs(sunFlux - albedo * sun.intensity * side * side) <= 4.9e-4 * sunFlux);
    // The spot: the cone's solid angle times I times rho. The sum counts whole texels whose
    // centre lies in the cone: along its edge (2 pi r texels, r = R / 2 on the map) each is
    // off by at most half its solid angle, a relative 1 / r of the pi r^2 inside (plus 16F).
    const auto [spotFlux, spotSeen] = sumSeen(readLayer(set.flux, R, spotMaps.firstLayer), 0);
    const double cone = 2.0 * 3.14159265358979 * (1.0 - std::cos(0.6));
    CAPTURE(spotFlux, albedo * spot.intensity * cone, spotSeen);
    CHECK(std::abs(spotFlux - albedo * spot.intensity * cone) <= (2.0 / R + 4.9e-4) * spotFlux);
    // Positions on the floor (y = 0) or the plate (y = 1), normals straight up (toward both lights).
    for (const int layer : {sunMaps.firstLayer, spotMaps.firstLayer}) {
        const std::vector<float> position = readLayer(set.position, R, layer), normal = readLayer(set.normal, R, layer);
        int bad = 0, seen = 0;
        for (std::size_t i = 0; i < position.size(); i += 4) {
            if (position[i + 3] != 1.0f) continue;
            ++seen;
            const float y = position[i + 1];
            bad += (std::abs(y) <= 1e-5f || std::abs(y - 1.0f) <= 1e-5f) && std::abs(normal[i + 1] - 1.0f) <= 1e-3f &&
                           normal[i + 3] == 1.0f
                       ? 0
                       : 1;
        }
        CAPTURE(layer);
        CHECK(seen > R * R / 2);
        CHECK(bad == 0);
    }
    // By pass: the maps pass holds the two layers' depth (4 bytes) and reflective maps (8 + 8 +
    // 16); no moment filter ran, so the moments pass holds nothing; the parts sum to the whole.
    std::size_t total = 0;
    for (const auto& [pass, bytes] : f.shadows.memoryByPass()) {
        CAPTURE(pass, bytes);
        if (pass == "shadow.maps") CHECK(bytes >= std::size_t(R) * R * 2 * (4 + 8 + 8 + 16));
        if (pass == "shadow.moments") CHECK(bytes == 0);
        total += bytes;
    }
    CHECK(total == f.shadows.memoryBytes());
}

TEST_CASE("Snapped cascades keep fixed receivers' shadows under sub-texel camera motion", "[shadows][stability]") {
    const Light sun = slantedSun();
    const Scene scene = plateScene(sun);
    constexpr int W = 96, H = 72;
    ShadowFixture f(Camera::perspective({{0.5f, 2.5f, 5.0f}, {0, 0, -1}, {0, 1, 0}}, 0.9f, float(W) / H, 0.05f, 100.0f), W, H);
    f.render(scene);
    const ShadowMapSettings maps{1024, 3, 0.75f};
    for (const auto& [filter, kernel] : {std::pair{ShadowFilter::Hard, PcfKernel::Grid}, std::pair{ShadowFilter::Pcf, PcfKernel::Grid},
                                         std::pair{ShadowFilter::Pcf, PcfKernel::OptimizedGrid},
                                         std::pair{ShadowFilter::Pcf, PcfKernel::PoissonDisc}}) {
        ShadowMaskSettings s;
        s.filter = filter;
        s.pcfKernel = kernel;
        const ShadowMapSet& base = f.shadows.render(scene, f.camera, maps);
        const float texel = base.find(0)->texelSize[0];
        const Image still = readTexture(f.ctx, f.shadows.mask(f.view, base, 0, s));
        const glm::mat4 toWorld = glm::inverse(f.camera.view);
        const glm::vec3 diagonal = glm::normalize(glm::vec3(toWorld[0]) + glm::vec3(toWorld[1]));
        double worst = 0.0;
        for (int k = 1; k <= 8; ++k) {
            // The cascades follow the camera moved by k/8 texel; the receivers (the G-buffer) stay.
            Camera moved = f.camera;
            moved.view = f.camera.view * glm::translate(glm::mat4(1.0f), -diagonal * (texel * float(k) / 8.0f));
            ShadowMapSet set = f.shadows.render(scene, moved, maps);
            set.camera = f.camera;
            const Image mask = readTexture(f.ctx, f.shadows.mask(f.view, set, 0, s));
            for (std::size_t i = 0; i < mask.pixels.size(); ++i)
                worst = std::max(worst, double(std::abs(mask.pixels[i] - still.pixels[i])));
        }
        // Snapped to whole texels, the maps hold the same texels in the same places: a hard
        // lookup is unchanged. PCF's bilinear weights come from the receiver's position in a
        // texel, which the float-rounded snapped eye can move slightly: one step of the R16F
        // mask at 1 (2^-11) is allowed (0 is measured here). The Poisson disc's rotation is
        // counted from the world origin's place in the cascade, so it does not change either.
        CAPTURE(static_cast<int>(filter), static_cast<int>(kernel), worst);
        CHECK(worst <= (filter == ShadowFilter::Hard ? 0.0 : std::ldexp(1.0, -11)));
    }
}

TEST_CASE("The G-buffer's direct light is shadowed by the maps of its lights", "[shadows][gbuffer][reference]") {
    Light light;
    light.type = LightType::Point;
    light.position = {0.0f, 3.0f, 0.0f};
    light.intensity = 10.0f;
    Scene scene = plateScene(light);
    Light sun; // a second light, without maps: stays unshadowed
    sun.type = LightType::Directional;
    sun.castsShadows = false;
    sun.direction = {0.0f, -1.0f, 0.0f};
    scene.lights.push_back(sun);
    constexpr int W = 96, H = 72;
    ShadowFixture f(plateCamera(W, H), W, H);
    f.render(scene);
    const reference::Reference truth = f.truth(scene);
    const ShadowMapSet& set = f.shadows.render(scene, f.camera, {512, 1, 0.5f});
    REQUIRE(set.find(1) == nullptr);
    const double texelPerUnit = set.find(0)->texelSize[0];
    const double scale = light.position.y / (light.position.y - kHeight);
    GBufferSettings lit{W, H, true, {}};
    const Image unshadowed = readTexture(f.ctx, f.gbuffer.render(scene, f.camera, lit).directRadiance);
    // The sun alone: what a shadowed pixel keeps.
    Scene sunOnly = scene;
    sunOnly.lights = {sun};
    const Image sunLight = readTexture(f.ctx, f.gbuffer.render(sunOnly, f.camera, lit).directRadiance);
    for (const ShadowFilter filter : {ShadowFilter::Hard, ShadowFilter::Pcf}) {
        lit.shadows = &set;
        lit.shadowFilter.filter = filter;
        const Image shadowed = readTexture(f.ctx, f.gbuffer.render(scene, f.camera, lit).directRadiance);
        // Away from the edge (as in the mask test) the per-fragment lookup gives the
        // reference's 0 or 1 exactly: a lit pixel keeps both lights' radiance, a shadowed one
        // only the sun's. Both come from the same shader arithmetic: compared bit for bit.
        int compared = 0, shadowedPixels = 0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const std::size_t i = std::size_t(y) * W + std::size_t(x);
                if (f.positions.at(x, y, 3) == 0.0f || truth.value.pixels[2 * i + 1] == 0.0f) continue;
                const glm::dvec3 p = f.world(x, y);
                const glm::dvec3 d = glm::abs(p - glm::dvec3(light.position));
                const double band = (filter == ShadowFilter::Pcf ? 5.0 : 3.0) * texelPerUnit * std::max({d.x, d.y, d.z});
                if (std::abs(p.y) < 1e-3 && std::abs(squareEdgeDistance(p.x, p.z, {0, 0}, kPlate * scale)) <= band) continue;
                const bool inShadow = truth.value.pixels[2 * i] == 0.0f;
                const Image& expected = inShadow ? sunLight : unshadowed;
                CAPTURE(x, y, inShadow, static_cast<int>(filter));
                for (int c = 0; c < 3; ++c) CHECK(shadowed.at(x, y, c) == expected.at(x, y, c));
                ++compared;
                shadowedPixels += inShadow ? 1 : 0;
            }
        CHECK(compared > W * H / 3);
        CHECK(shadowedPixels > 20);
    }
    GBufferSettings other = lit;
    other.shadows = &set;
    const Camera moved = Camera::perspective({{0, 3.5f, 4.6f}, {0, 0.3f, 0}, {0, 1, 0}}, 0.9f, float(W) / H, 0.05f, 100.0f);
    CHECK_THROWS_WITH(f.gbuffer.render(scene, moved, other), Catch::Contains("another camera"));
}

namespace {

const ShadowFilter kAllFilters[] = {ShadowFilter::Hard,  ShadowFilter::Pcf,   ShadowFilter::Vsm, ShadowFilter::Esm,
                                    ShadowFilter::Evsm2, ShadowFilter::Evsm4, ShadowFilter::Msm};

// Pixels of the mask that are not finite or not in [0, 1].
int badValues(const Image& mask) {
    int bad = 0;
    for (const float v : mask.pixels) bad += std::isfinite(v) && v >= 0.0f && v <= 1.0f ? 0 : 1;
    return bad;
}

} // namespace

TEST_CASE("Shadow masks stay finite for vertical and grazing light and extreme depth ranges", "[shadows][stability]") {
    constexpr int W = 48, H = 36;
    for (const glm::vec3 direction : {glm::vec3(0, -1, 0), glm::vec3(0, 1, 0), glm::vec3(1, -1e-4f, 0)})
        for (const auto& [nearPlane, farPlane] : {std::pair{1e-4f, 100.0f}, std::pair{0.05f, 1e6f}, std::pair{1e-4f, 1e6f}}) {
            Light sun;
            sun.type = LightType::Directional;
            sun.direction = direction;
            const Scene scene = plateScene(sun);
            ShadowFixture f(Camera::perspective({{0, 2.5f, 5.0f}, {0, 0, 0}, {0, 1, 0}}, 0.9f, float(W) / H, nearPlane, farPlane), W, H);
            f.render(scene);
            const ShadowMapSet& set = f.shadows.render(scene, f.camera, {256, 4, 0.9f});
            for (const ShadowFilter filter : kAllFilters) {
                ShadowMaskSettings s;
                s.filter = filter;
                CAPTURE(direction.x, direction.y, nearPlane, farPlane, static_cast<int>(filter));
                CHECK(badValues(readTexture(f.ctx, f.shadows.mask(f.view, set, 0, s))) == 0);
            }
            for (const PcfKernel kernel : {PcfKernel::OptimizedGrid, PcfKernel::PoissonDisc}) {
                ShadowMaskSettings wide;
                wide.pcfKernel = kernel;
                wide.pcfRadius = 8;
                CHECK(badValues(readTexture(f.ctx, f.shadows.mask(f.view, set, 0, wide))) == 0);
            }
        }
}

TEST_CASE("Point, spot and rect lights inside geometry or on a vertex and extreme exponents stay finite", "[shadows][stability]") {
    constexpr int W = 48, H = 36;
    // Inside the unit cube lifted onto the floor, on the plate's corner, and just above it.
    for (const glm::vec3 position : {glm::vec3(0.3f, 0.5f, 0.2f), glm::vec3(0.5f, 1.0f, 0.5f), glm::vec3(0.0f, 1.0f + 1e-6f, 0.0f)})
        for (const auto& [type, mapping] : {std::pair{LightType::Point, PointShadowMapping::Cube},
                                            std::pair{LightType::Point, PointShadowMapping::DualParaboloid},
                                            std::pair{LightType::Spot, PointShadowMapping::Cube},
                                            std::pair{LightType::Rect, PointShadowMapping::Cube}}) {
            Light light;
            light.type = type;
            light.position = position;
            light.direction = {0.0f, -1.0f, 0.0f};
            light.size = {0.4f, 0.2f}; // rect
            Scene scene = plateScene(light);
            scene.meshes.push_back({test::cubeMesh(), glm::translate(glm::mat4(1.0f), glm::vec3(-0.2f, 0.0f, -0.3f)), 0, "cube"});
            ShadowFixture f(Camera::perspective({{0, 2.5f, 5.0f}, {0, 0, 0}, {0, 1, 0}}, 0.9f, float(W) / H, 0.05f, 100.0f), W, H);
            f.render(scene);
            const ShadowMapSet& set = f.shadows.render(scene, f.camera, {128, 1, 0.5f, mapping});
            for (const ShadowFilter filter : kAllFilters)
                for (const float exponent : {0.0f, 42.0f, 80.0f})
                for (const ShadowMomentPrecision precision : {ShadowMomentPrecision::Float32, ShadowMomentPrecision::Bits16}) {
                    ShadowMaskSettings s;
                    s.filter = filter;
                    s.momentPrecision = precision; // 16F EVSM at c = 42: clamped to 5.54
                    s.exponent = exponent; // ESM up to 80; EVSM at and beyond its 32F clamp (42)
                    s.negativeExponent = std::min(exponent, 42.0f);
                    CAPTURE(position.x, position.y, position.z, static_cast<int>(type), static_cast<int>(mapping),
                            static_cast<int>(filter), exponent, static_cast<int>(precision));
                    CHECK(badValues(readTexture(f.ctx, f.shadows.mask(f.view, set, 0, s))) == 0);
                }
            GBufferSettings lit{W, H, true, {}};
            lit.shadows = &set;
            const Image direct = readTexture(f.ctx, f.gbuffer.render(scene, f.camera, lit).directRadiance);
            CHECK(std::all_of(direct.pixels.begin(), direct.pixels.end(), [](float v) { return std::isfinite(v) && v >= 0.0f; }));
        }
}

TEST_CASE("Shadow maps are left out without shadowed lights and refuse bad settings", "[shadows][bad-input]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    ShadowMaps shadows(ctx);
    GBuffer gbuffer(ctx);
    const Camera camera = Camera::perspective({{0, 2.5f, 5.0f}, {0, 0, 0}, {0, 1, 0}}, 0.9f, 1.0f, 0.05f, 100.0f);
    Light rect; // a light that casts no shadows has no maps
    rect.type = LightType::Rect;
    rect.position = {0, 2, 0};
    rect.castsShadows = false;
    Scene scene = plateScene(rect);
    const GBufferView view = gbuffer.render(scene, camera, {32, 32, false, {}});
    const ShadowMapSet& none = shadows.render(scene, camera, {});
    CHECK(none.depth == 0);
    CHECK(none.maps.empty());
    CHECK(shadows.memoryBytes() == 0);
    CHECK_THROWS_WITH(shadows.mask(view, none, 0, {}), Catch::Contains("has no shadow map"));
    Light sun;
    sun.type = LightType::Directional;
    sun.castsShadows = false;
    scene.lights = {sun};
    CHECK(shadows.render(scene, camera, {}).maps.empty());
    scene.lights[0].castsShadows = true;
    CHECK_THROWS_WITH(shadows.render(scene, camera, {8, 1, 0.5f}), Catch::Contains("resolution"));
    CHECK_THROWS_WITH(shadows.render(scene, camera, {256, 5, 0.5f}), Catch::Contains("cascades"));
    CHECK_THROWS_WITH(shadows.render(scene, camera, {256, 2, 1.5f}), Catch::Contains("splitLambda"));
    const ShadowMapSet& set = shadows.render(scene, camera, {256, 2, 0.5f});
    CHECK(shadows.memoryBytes() >= 256u * 256u * 4u * 2u);
    ShadowMaskSettings bad;
    bad.pcfRadius = 9;
    CHECK_THROWS_WITH(shadows.mask(view, set, 0, bad), Catch::Contains("pcfRadius"));
    bad = {};
    bad.constantBias = NAN;
    CHECK_THROWS_WITH(shadows.mask(view, set, 0, bad), Catch::Contains("constantBias"));
    // Enumerators outside their lists: a filter ran as Hard, a kernel as Grid, and a moment
    // precision stored 16 bits for a shader reading 32.
    bad = {};
    bad.filter = static_cast<ShadowFilter>(8);
    CHECK_THROWS_WITH(shadows.mask(view, set, 0, bad), Catch::Contains("::filter"));
    bad = {};
    bad.pcfKernel = static_cast<PcfKernel>(3);
    CHECK_THROWS_WITH(shadows.mask(view, set, 0, bad), Catch::Contains("::pcfKernel"));
    bad = {};
    bad.momentPrecision = static_cast<ShadowMomentPrecision>(2);
    CHECK_THROWS_WITH(shadows.mask(view, set, 0, bad), Catch::Contains("::momentPrecision"));
    ShadowMapSettings mapping{256, 2, 0.5f};
    mapping.pointMapping = static_cast<PointShadowMapping>(2); // mapped as Cube before
    CHECK_THROWS_WITH(shadows.render(scene, camera, mapping), Catch::Contains("ShadowMapSettings::pointMapping"));
    const Camera other = Camera::perspective({{0, 2.5f, 5.1f}, {0, 0, 0}, {0, 1, 0}}, 0.9f, 1.0f, 0.05f, 100.0f);
    const GBufferView otherView = gbuffer.render(scene, other, {32, 32, false, {}});
    CHECK_THROWS_WITH(shadows.mask(otherView, set, 0, {}), Catch::Contains("another camera"));
}

// Scene sources without GL: built-in scenes, the JSON format, assimp files, camera specs.
#include "obscura/assets.hpp"
#include "obscura/error.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <array>
#include <filesystem>
#include <fstream>

using namespace obscura;

namespace {

std::filesystem::path writeTemp(const std::string& name, const std::string& text) {
    const auto path = std::filesystem::temp_directory_path() / ("obscura_test_" + name);
    std::ofstream(path) << text;
    return path;
}

std::size_t triangles(const Scene& s) {
    std::size_t n = 0;
    for (const Mesh& m : s.meshes) n += m.data->indices.size() / 3;
    return n;
}

} // namespace

namespace {
using Quad = std::array<glm::vec3, 4>;
// Transcribed again, independently of src/assets/builtin_scenes.cpp, from the Cornell
// Program of Computer Graphics' "Cornell Box Data" (mm). The emitter is the published one
// lowered from y = 548.8 to 548.7, as documented in the scene.
const std::vector<std::pair<std::string, Quad>> kPublishedQuads = {
    {"white", {{{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}}}},
    {"white", {{{556.0f, 548.8f, 0}, {556.0f, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}}}},
    {"white", {{{549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556.0f, 548.8f, 559.2f}}}},
    {"green", {{{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}}}},
    {"red", {{{552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556.0f, 548.8f, 559.2f}, {556.0f, 548.8f, 0}}}},
    {"light", {{{343.0f, 548.7f, 227.0f}, {343.0f, 548.7f, 332.0f}, {213.0f, 548.7f, 332.0f}, {213.0f, 548.7f, 227.0f}}}},
    {"white", {{{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}}}},
    {"white", {{{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}}}},
    {"white", {{{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}}}},
    {"white", {{{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}}}},
    {"white", {{{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}}}},
    {"white", {{{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}}}},
    {"white", {{{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}}}},
    {"white", {{{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}}}},
    {"white", {{{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}}}},
    {"white", {{{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}}}},
};
} // namespace

TEST_CASE("The Cornell box matches the published measurements", "[unit][scenes]") {
    const assets::LoadedScene s = assets::builtinScene("cornell");
    // Every published quad is in the scene, as the two triangles (0,1,2), (0,2,3), with its
    // material, and nothing else is.
    std::vector<std::pair<std::string, Quad>> built;
    for (const Mesh& m : s.scene.meshes) {
        const auto& d = *m.data;
        REQUIRE(d.indices.size() % 6 == 0);
        for (std::size_t i = 0; i < d.indices.size(); i += 6) {
            CHECK(d.indices[i + 3] == d.indices[i]);
            CHECK(d.indices[i + 4] == d.indices[i + 2]);
            const glm::vec3 c = glm::vec3(m.model * glm::vec4(d.positions[d.indices[i + 5]], 1.0f));
            built.push_back({s.scene.materials[m.material].name,
                             {glm::vec3(m.model * glm::vec4(d.positions[d.indices[i]], 1.0f)),
                              glm::vec3(m.model * glm::vec4(d.positions[d.indices[i + 1]], 1.0f)),
                              glm::vec3(m.model * glm::vec4(d.positions[d.indices[i + 2]], 1.0f)), c}});
        }
    }
    CHECK(built.size() == kPublishedQuads.size());
    for (const auto& q : kPublishedQuads) {
        INFO(q.first << " quad starting at " << q.second[0].x << "," << q.second[0].y << "," << q.second[0].z);
        CHECK(std::find(built.begin(), built.end(), q) != built.end());
    }
    const Bounds b = sceneBounds(s.scene);
    CHECK(b.min.x == 0.0f);
    CHECK(b.min.y == 0.0f);
    CHECK(b.min.z == 0.0f);
    CHECK(b.max.x == 556.0f);
    CHECK(b.max.y == 548.8f);
    CHECK(b.max.z == 559.2f);
    // 5 walls + light + 2 blocks of 5 quads: 16 quads.
    CHECK(triangles(s.scene) == 32);
    CHECK(s.scene.materials.size() == 4);
    CHECK(s.scene.materials[1].albedo == glm::vec3(0.63f, 0.065f, 0.05f));
    CHECK(s.scene.materials[3].emission == glm::vec3(17.0f, 12.0f, 4.0f));
    CHECK(s.camera.lookAt.eye == glm::vec3(278, 273, -800));
    CHECK(s.camera.fovyDegrees == Approx(39.31).margin(0.01));
    CHECK(s.unitsPerMetre == 1000.0f);
}

TEST_CASE("Every built-in scene loads and is well formed", "[unit][scenes]") {
    for (const std::string& name : assets::builtinSceneNames()) {
        CAPTURE(name);
        const assets::LoadedScene s = assets::loadScene(name);
        CHECK(s.name == name);
        CHECK(triangles(s.scene) > 0);
        for (const Mesh& m : s.scene.meshes) {
            CHECK(m.material < s.scene.materials.size());
            CHECK(m.data->normals.size() == m.data->positions.size());
        }
    }
    CHECK_THROWS_WITH(assets::builtinScene("nope"), Catch::Contains("cornell"));
    CHECK_THROWS_WITH(assets::loadScene("nope"), Catch::Contains("neither a built-in scene"));
}

TEST_CASE("A JSON scene gives meshes materials lights camera and media", "[unit][scenes]") {
    const assets::LoadedScene s = assets::loadJsonScene(OBSCURA_TEST_DATA "/two_quads.json");
    CHECK(s.name == "two quads");
    REQUIRE(s.scene.materials.size() == 2);
    CHECK(s.scene.materials[1].emission == glm::vec3(4.0f));
    CHECK(s.scene.materials[1].albedo == glm::vec3(0.5f));
    REQUIRE(s.scene.meshes.size() >= 3);
    CHECK(s.scene.meshes[1].material == 1);
    // translate(0,2,0) * rotate_x(180) * scale(0.25) applied to (1, 0, 1): (0.25, 2, -0.25)
    const glm::vec4 p = s.scene.meshes[1].model * glm::vec4(1, 0, 1, 1);
    CHECK(p.x == Approx(0.25));
    CHECK(p.y == Approx(2.0));
    CHECK(p.z == Approx(-0.25));
    for (std::size_t i = 2; i < s.scene.meshes.size(); ++i) CHECK(s.scene.meshes[i].material == 0);
    REQUIRE(s.scene.lights.size() == 2);
    CHECK(s.scene.lights[0].type == LightType::Spot);
    CHECK(s.scene.lights[0].outerAngle == Approx(30.0 * 3.14159265 / 180));
    CHECK(s.camera.fovyDegrees == 50.0f);
    CHECK(s.camera.nearPlane == 0.05f);
    REQUIRE(s.scene.media.size() == 1);
    CHECK(s.scene.media[0].scattering == glm::vec3(0.1f));
}

TEST_CASE("JSON errors name the file and the path of the bad value", "[unit][scenes]") {
    CHECK_THROWS_WITH(assets::loadJsonScene(writeTemp("bad1.json", "{\"meshes\": [{\"positions\": [0,0]}]}")),
                      Catch::Contains("meshes[0].positions") && Catch::Contains("multiple of 3"));
    CHECK_THROWS_WITH(assets::loadJsonScene(writeTemp("bad2.json", "{\"materials\": {\"a\": {\"albedo\": [1, 2]}}}")),
                      Catch::Contains("materials.a.albedo"));
    CHECK_THROWS_WITH(assets::loadJsonScene(writeTemp("bad3.json", "{\"meshes\": [{\"material\": \"x\", \"positions\": []}]}")),
                      Catch::Contains("no material named \"x\""));
    CHECK_THROWS_WITH(assets::loadJsonScene(writeTemp("bad4.json", "{\"lights\": [{\"type\": \"area\"}]}")),
                      Catch::Contains("lights[0].type"));
    CHECK_THROWS_WITH(assets::loadJsonScene(writeTemp("bad5.json", "{ not json")), Catch::Contains("bad5.json"));
    CHECK_THROWS_WITH(assets::loadJsonScene(writeTemp("bad6.json", "{\"lights\": [{\"type\": \"point\", \"casts_shadows\": 1}]}")),
                      Catch::Contains("lights[0].casts_shadows") && Catch::Contains("true or false"));
    const std::string unshadowed = "{\"lights\": [{\"type\": \"point\", \"casts_shadows\": false}]}";
    CHECK_FALSE(assets::loadJsonScene(writeTemp("unshadowed.json", unshadowed)).scene.lights.at(0).castsShadows);
    CHECK_THROWS_AS(assets::loadJsonScene("/nonexistent/scene.json"), Error);
}

TEST_CASE("Real models load through assimp", "[unit][scenes]") {
    for (const char* file : {"/PLY/Wuson.ply", "/OBJ/spider.obj", "/Collada/duck.dae",
                             "/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"}) {
        CAPTURE(file);
        const assets::LoadedScene s = assets::loadScene(std::string(OBSCURA_ASSIMP_MODELS) + file);
        CHECK(triangles(s.scene) > 100);
        const Bounds b = sceneBounds(s.scene);
        CHECK_FALSE(b.empty);
        CHECK(glm::length(s.camera.lookAt.eye - 0.5f * (b.min + b.max)) > 0.0f);
        CHECK(s.camera.nearPlane > 0.0f);
        CHECK(s.camera.farPlane > s.camera.nearPlane);
    }
    CHECK_THROWS_AS(assets::loadMeshFile("/nonexistent/model.obj"), Error);
}

TEST_CASE("Camera specs parse the lookAt/fovy convention", "[unit][scenes]") {
    const assets::CameraSpec base;
    const assets::CameraSpec c = assets::parseCameraSpec("1,2,3,0,0,0,0,1,0,45", base);
    CHECK(c.lookAt.eye == glm::vec3(1, 2, 3));
    CHECK(c.fovyDegrees == 45.0f);
    CHECK_THROWS_WITH(assets::parseCameraSpec("1,2,3", base), Catch::Contains("10 or 12 numbers"));
    const assets::CameraSpec planes = assets::parseCameraSpec("1,2,3,0,0,0,0,1,0,45,0.5,20", base);
    CHECK((planes.nearPlane == 0.5f && planes.farPlane == 20.0f));
    CHECK_THROWS_WITH(assets::parseCameraSpec("1,2,3,0,0,0,0,1,0,45,2,1", base), Catch::Contains("0 < near < far"));
    CHECK_THROWS_WITH(assets::parseCameraSpec("1,2,x,0,0,0,0,1,0,45", base), Catch::Contains("\"x\""));
    const Camera cam = assets::makeCamera(c, 64, 32);
    CHECK(analyzeProjection(cam).kind == ProjectionKind::Perspective);
    // Vertical fov 45 deg: projection[1][1] = 1 / tan(22.5 deg); aspect 2.
    CHECK(cam.projection[1][1] == Approx(1.0 / std::tan(3.14159265 / 8)));
    CHECK(cam.projection[0][0] == Approx(cam.projection[1][1] / 2));
}

// The issue's case: a floor-and-wall model 4 units wide, framed as mesh files are (from 8.6
// units, near plane 4.1), seen from 3 units before its wall. Every corner of the model lies
// nearer than the framing camera's near plane from there (nothing would be drawn); the planes
// fitted to the bounds hold every corner, and a base camera's own eye keeps its own planes.
TEST_CASE("A camera given without planes fits them to the scene seen from its eye", "[unit][scenes]") {
    Bounds floorAndWall;
    floorAndWall.min = {-2.0f, 0.0f, -2.0f};
    floorAndWall.max = {2.0f, 2.0f, 2.0f};
    floorAndWall.empty = false;
    const assets::CameraSpec framed = assets::framingCamera(floorAndWall);
    const std::string closeUp = "0,1,1,0,0.5,-2,0,1,0,60";
    const auto cornerDepths = [&](const assets::CameraSpec& c) {
        const glm::vec3 forward = glm::normalize(c.lookAt.target - c.lookAt.eye);
        std::vector<float> depths;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 corner{(i & 1) ? 2.0f : -2.0f, (i & 2) ? 2.0f : 0.0f, (i & 4) ? 2.0f : -2.0f};
            depths.push_back(glm::dot(corner - c.lookAt.eye, forward));
        }
        return depths;
    };
    const assets::CameraSpec kept = assets::parseCameraSpec(closeUp, framed);
    for (float depth : cornerDepths(kept)) CHECK(depth < kept.nearPlane);
    const assets::CameraSpec fitted = assets::parseCameraSpec(closeUp, framed, floorAndWall);
    for (float depth : cornerDepths(fitted))
        if (depth > 0.0f) CHECK((depth > fitted.nearPlane && depth < fitted.farPlane));
    CHECK(fitted.farPlane / fitted.nearPlane <= 1000.0f * 1.0001f);
    // Seen through that camera the bounds are in view; turned around, they are not.
    CHECK(assets::boundsMayBeVisible(assets::makeCamera(fitted, 64, 48), floorAndWall));
    CHECK_FALSE(assets::boundsMayBeVisible(assets::makeCamera(kept, 64, 48), floorAndWall));
    const assets::CameraSpec away = assets::parseCameraSpec("0,1.5,2.5,0,1.5,10,0,1,0,45", framed, floorAndWall);
    CHECK_FALSE(assets::boundsMayBeVisible(assets::makeCamera(away, 64, 48), floorAndWall));
    // A base camera's own eye keeps its planes, whatever they are.
    assets::CameraSpec base = framed;
    base.lookAt = {{0.0f, 3.0f, 8.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}};
    base.nearPlane = 7.0f;
    const assets::CameraSpec same = assets::parseCameraSpec("0,3,8,0,0,0,0,1,0,45", base, floorAndWall);
    CHECK((same.nearPlane == 7.0f && same.farPlane == base.farPlane));
}

TEST_CASE("validateScene refuses a light type, environment or medium outside its range", "[unit][scenes]") {
    // Before, a light type outside the enumerators shaded as nothing, an environment's NaN
    // rotation or negative intensity and a medium's NaN coefficients or unknown phase passed
    // (media were checked only by the reference, and only the one it rendered).
    const auto refused = [](const Scene& s, const std::string& needle) {
        CHECK_THROWS_WITH(validateScene(s), Catch::Contains(needle));
    };
    Scene s;
    s.lights.push_back({});
    s.lights[0].type = static_cast<LightType>(7);
    refused(s, "Scene::lights[0].type");
    s = {};
    s.environment = Environment{"sky.exr", -1.0f, 0.0f};
    refused(s, "Scene::environment.intensity");
    s.environment = Environment{"sky.exr", 1.0f, NAN};
    refused(s, "Scene::environment.rotation");
    s.environment = Environment{"sky.exr", 2.0f, 7.0f}; // any finite rotation
    CHECK_NOTHROW(validateScene(s));
    Medium good;
    good.boxMin = {-1, -1, -1};
    good.boxMax = {1, 1, 1};
    good.scattering = glm::vec3(0.5f);
    s = {};
    s.media = {good, good};
    CHECK_NOTHROW(validateScene(s));
    const auto bad = [&](auto change, const std::string& needle) {
        Scene t = s;
        change(t.media[1]);
        refused(t, "Scene::media[1]" + needle);
    };
    bad([](Medium& m) { m.scattering.y = NAN; }, ".scattering");
    bad([](Medium& m) { m.absorption = glm::vec3(INFINITY); }, ".absorption");
    bad([](Medium& m) { m.boxMax.x = NAN; }, ".boxMax");
    bad([](Medium& m) { m.boxMax.z = -2.0f; }, ".boxMax must be >= boxMin");
    bad([](Medium& m) { m.absorption.x = -0.1f; }, ": scattering and absorption");
    bad([](Medium& m) { m.phase = static_cast<PhaseFunction>(5); }, ".phase");
    bad([](Medium& m) { m.anisotropy = 1.0f; }, ".anisotropy");
}

TEST_CASE("An EXR of more than ten channels reads back in the order it was written", "[unit][scenes]") {
    // OpenEXR sorts channels by name: OpenImageIO's default names put channel10 before
    // channel4, which garbled the reference cache's halves of RGBA quantities (12 channels).
    Image img{2, 1, 12, {}};
    for (int i = 0; i < 24; ++i) img.pixels.push_back(float(i));
    const auto path = std::filesystem::temp_directory_path() / "obscura_twelve_channels.exr";
    assets::writeImage(path, img);
    const Image back = assets::readImage(path);
    std::filesystem::remove(path);
    REQUIRE(back.channels == 12);
    CHECK(back.pixels == img.pixels);
}

TEST_CASE("JSON media densities: height fog, a raw grid, EXR slices and noise", "[unit][scenes]") {
    // A 3 x 2 x 2 grid whose value is its index, as raw float32 and as EXR slices (width 3,
    // height 2 * 2): both give the same values in x-fastest order.
    std::vector<float> values(12);
    for (int i = 0; i < 12; ++i) values[std::size_t(i)] = float(i);
    const auto raw = std::filesystem::temp_directory_path() / "obscura_test_grid.raw";
    std::ofstream(raw, std::ios::binary).write(reinterpret_cast<const char*>(values.data()), std::streamsize(12 * sizeof(float)));
    Image slices{3, 4, 1, values}; // slice z = rows 2z, 2z + 1; row j of a slice: y = j
    const auto exr = std::filesystem::temp_directory_path() / "obscura_test_grid.exr";
    assets::writeImage(exr, slices);
    const auto scene = [](const std::string& density) {
        return "{\"media\": [{\"min\": [0, 0, 0], \"max\": [1, 1, 1], \"scattering\": 1, \"density\": " + density + "}]}";
    };
    const Scene fromRaw = assets::loadJsonScene(writeTemp("grid_raw.json", scene(R"({"type": "grid", "size": [3, 2, 2], "file": ")" +
                                                                                  raw.string() + "\"}"))).scene;
    const Scene fromExr = assets::loadJsonScene(writeTemp("grid_exr.json", scene(R"({"type": "grid", "size": [3, 2, 2], "file": ")" +
                                                                                  exr.string() + "\"}"))).scene;
    REQUIRE(fromRaw.media.at(0).grid);
    REQUIRE(fromExr.media.at(0).grid);
    CHECK(fromRaw.media[0].grid->values == values);
    CHECK(fromExr.media[0].grid->values == values);
    const Scene fog = assets::loadJsonScene(writeTemp("fog.json", scene(R"({"type": "height", "falloff": 0.5})"))).scene;
    CHECK(fog.media.at(0).density == MediumDensity::Height);
    CHECK(mediumDensity(fog.media[0], {0.5, 1.0, 0.5}) == Approx(std::exp(-0.5)));
    const Scene noise = assets::loadJsonScene(writeTemp("noise.json", scene(R"({"type": "noise", "size": [8, 8, 8], "seed": 2})"))).scene;
    CHECK(noise.media.at(0).grid->values.size() == 512);
    CHECK_THROWS_WITH(assets::loadJsonScene(writeTemp("bad_grid.json", scene(R"({"type": "grid", "size": [4, 2, 2], "file": ")" +
                                                                              exr.string() + "\"}"))),
                      Catch::Contains("need x by y * z"));
    std::filesystem::remove(raw);
    std::filesystem::remove(exr);
}

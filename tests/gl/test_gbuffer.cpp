// G-buffer: position reconstruction precision, normals, direct lighting, sizes, degenerate and
// NaN input, scenes and area lights (the host's depth, normals and meshes: test_gbuffer_host.cpp).
#include "gl_fixture.hpp"
#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>

#include <cfloat>
#include <cmath>

using namespace obscura;
using test::AnalyticQuad;
using test::kHalfRelative;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The "depth range" scene: a floor from 1.7 to ~110 units away, and in the upper half eight
// camera-facing stripes at depths from 0.15 to 990 (near/far = 0.1/1000).
struct DepthRangeScene {
    std::vector<AnalyticQuad> quads;
    static constexpr double depths[8] = {0.15, 0.5, 2.0, 10.0, 50.0, 200.0, 600.0, 990.0};

    explicit DepthRangeScene(double tanHalfFovy, double aspect) {
        quads.push_back({{{{-5000, -1, -0.05}, {5000, -1, -0.05}, {5000, -1, -999}, {-5000, -1, -999}}}});
        for (int k = 0; k < 8; ++k) {
            const double z = depths[k];
            const double x0 = (-1.0 + k / 4.0) * tanHalfFovy * aspect * z, x1 = (-1.0 + (k + 1) / 4.0) * tanHalfFovy * aspect * z;
            const double y0 = 0.02 * tanHalfFovy * z, y1 = 1.1 * tanHalfFovy * z;
            quads.push_back({{{{x0, y0, -z}, {x1, y0, -z}, {x1, y1, -z}, {x0, y1, -z}}}});
        }
    }

    // Nearest hit of a view-space ray, in double.
    std::optional<glm::dvec3> trace(const test::ViewRay& ray) const {
        std::optional<double> best;
        for (const auto& q : quads)
            if (auto t = q.intersect(ray.origin, ray.direction); t && (!best || *t < *best)) best = t;
        if (!best) return std::nullopt;
        return ray.origin + *best * ray.direction;
    }
};

double relativeError(const glm::dvec3& a, const glm::dvec3& b) { return glm::length(a - b) / glm::length(b); }

// ulp of a float value in [0, 1]
double floatUlp(double v) { return std::nextafter(static_cast<float>(v), 2.0f) - static_cast<float>(v); }

} // namespace

TEST_CASE("View-space positions are reconstructed from depth to 1e-5 relative (near/far 0.1/1000)", "[gbuffer]") {
    const auto mode = GENERATE(DepthMode::Standard, DepthMode::StandardZeroToOne, DepthMode::Reversed);
    CAPTURE(static_cast<int>(mode));
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    constexpr int W = 64, H = 64;
    const double fovy = kPi / 3.0;
    const Camera camera = Camera::perspective({{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}, static_cast<float>(fovy), 1.0f, 0.1f,
                                              1000.0f, mode);
    const DepthRangeScene scene(std::tan(fovy / 2), 1.0);
    const GBufferView view = gbuffer.render(test::quadScene(scene.quads), camera, {W, H, false, {}});
    const Image depth = readTexture(ctx, view.depth);
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const ProjectionInfo info = analyzeProjection(camera);

    double worstReconstruction = 0, worstEndToEnd = 0, worstNaive = 0, farthest = 0;
    glm::dvec4 worstPixel(0.0); // x, y, stored depth, true distance
    int geometry = 0;
    const glm::mat4 inverseProjection = glm::inverse(camera.projection);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const auto truth = scene.trace(test::pixelRay(camera, x, y, W, H));
            const double d = depth.at(x, y, 0);
            const glm::dvec3 gpu = test::texel3(positions, x, y);
            if (!truth) {
                CHECK(d == info.clearDepth);
                CHECK(positions.at(x, y, 3) == 0.0f);
                continue;
            }
            ++geometry;
            CHECK(positions.at(x, y, 3) == 1.0f);
            // (1) The reconstruction itself: GPU float result against the double-precision
            //     inverse of the same stored depth value.
            const glm::dvec2 ndc = test::pixelNdc(x, y, W, H);
            const glm::dvec3 reference = viewPositionFromDepth(camera, ndc, d);
            const double e = relativeError(gpu, reference);
            worstReconstruction = std::max(worstReconstruction, e);
            CHECK(e < 1e-5);
            // (2) End to end, against the exact ray/plane intersection. The stored depth can
            //     differ from the exact one by the rasterizer's rounding; allow 4 float ulps of
            //     d (measured: at most 2 on llvmpipe) propagated through dz/dd.
            const double zTrue = truth->z;
            const double dzdd = std::abs(viewPositionFromDepth(camera, ndc, d + 1e-7).z - reference.z) / 1e-7;
            const double quantization = 4.0 * floatUlp(d) * dzdd / std::abs(zTrue);
            const double endToEnd = relativeError(gpu, *truth);
            if (endToEnd > worstEndToEnd) worstPixel = {x, y, d, -zTrue};
            worstEndToEnd = std::max(worstEndToEnd, endToEnd);
            farthest = std::max(farthest, -zTrue);
            CHECK(endToEnd < 1e-5 + quantization);
            // Reversed-Z stores depth precisely enough for 1e-5 everywhere.
            if (mode == DepthMode::Reversed) CHECK(endToEnd < 1e-5);
            // The textbook inverse-projection multiply, in float, for comparison.
            const float zn = camera.clipDepth == ClipDepth::ZeroToOne ? static_cast<float>(d) : 2.0f * static_cast<float>(d) - 1.0f;
            const glm::vec4 v = inverseProjection * glm::vec4(glm::vec2(ndc), zn, 1.0f);
            worstNaive = std::max(worstNaive, relativeError(glm::dvec3(glm::vec3(v) / v.w), reference));
        }
    INFO("worst reconstruction " << worstReconstruction << ", end to end " << worstEndToEnd << ", naive float "
                                 << worstNaive << ", farthest " << farthest << "; worst pixel " << worstPixel.x << ","
                                 << worstPixel.y << " stored depth " << worstPixel.z << " at distance " << worstPixel.w);
    CHECK(geometry > W * H / 2);
    CHECK(farthest > 900.0);
    // The test can tell a careful reconstruction from a naive one: with standard depth the
    // plain inverse-projection multiply misses 1e-5 at the far end.
    if (mode != DepthMode::Reversed) CHECK(worstNaive > 1e-5);
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Orthographic reconstruction is exact to the depth buffer's resolution", "[gbuffer]") {
    const auto mode = GENERATE(DepthMode::Standard, DepthMode::Reversed);
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    constexpr int W = 48, H = 32;
    const float n = 0.1f, f = 1000.0f;
    const Camera camera = Camera::orthographic({{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}, 2.0f, 1.5f, n, f, mode);
    // A slanted plane from z = -0.5 to z = -950 across the image.
    const AnalyticQuad slope{{{{-4, -3, -0.5}, {4, -3, -950}, {4, 3, -950}, {-4, 3, -0.5}}}};
    const GBufferView view = gbuffer.render(test::quadScene({slope}), camera, {W, H, false, {}});
    const Image depth = readTexture(ctx, view.depth);
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    // Orthographic depth is linear in z: one float ulp of d near 1 is (f - n) * 2^-24; the
    // float reconstruction may add a few such steps.
    const double bound = 4.0 * (f - n) * std::ldexp(1.0, -24);
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            REQUIRE(positions.at(x, y, 3) == 1.0f);
            const glm::dvec3 ref = viewPositionFromDepth(camera, test::pixelNdc(x, y, W, H), depth.at(x, y, 0));
            CHECK(glm::length(test::texel3(positions, x, y) - ref) < bound);
            const auto t = slope.intersect(test::pixelRay(camera, x, y, W, H).origin, {0, 0, -1});
            REQUIRE(t);
            CHECK(std::abs(ref.z + *t) < bound);
        }
}

TEST_CASE("Normals are unit face normals turned toward the camera - background is marked", "[gbuffer]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    constexpr int W = 40, H = 30;
    const Camera camera = Camera::perspective({{0, 2, 4}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 4.0f / 3.0f, 0.1f, 50.0f);
    // The floor is wound so that its normal points down, away from the camera, the wall
    // toward it: both must come out facing the camera.
    const AnalyticQuad floor{{{{-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3}}}};
    const AnalyticQuad wall{{{{-1, 0, -1}, {1, 0, -1}, {1, 1.5, -1}, {-1, 1.5, -1}}}};
    const GBufferView view = gbuffer.render(test::quadScene({floor, wall}), camera, {W, H, true, {}});
    const Image normals = readTexture(ctx, view.normal);
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const glm::dmat3 viewRotation(camera.view);
    int floorPixels = 0, wallPixels = 0, sky = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const glm::dvec3 n = test::texel3(normals, x, y);
            if (normals.at(x, y, 3) == 0.0f) {
                ++sky;
                CHECK(n == glm::dvec3(0.0));
                continue;
            }
            CHECK(std::abs(glm::length(n) - 1.0) < 2 * kHalfRelative);
            const glm::dvec3 p = test::texel3(positions, x, y);
            CHECK(glm::dot(n, -p) > 0.0);
            const glm::dvec3 up = viewRotation * glm::dvec3(0, 1, 0), towardCamera = viewRotation * glm::dvec3(0, 0, 1);
            if (glm::length(n - up) < 2e-3) ++floorPixels;
            else if (glm::length(n - towardCamera) < 2e-3) ++wallPixels;
            else FAIL("normal " << n.x << "," << n.y << "," << n.z << " is neither the floor's nor the wall's");
        }
    CHECK(floorPixels > 100);
    CHECK(wallPixels > 50);
    CHECK(sky > 0);
}

TEST_CASE("Direct radiance follows Lambert's law for directional point and spot lights", "[gbuffer]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    constexpr int W = 32, H = 32;
    const Camera camera = Camera::perspective({{0, 6, 0.01f}, {0, 0, 0}, {0, 1, 0}}, 1.2f, 1.0f, 0.1f, 100.0f);
    const AnalyticQuad floor{{{{-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}}}};
    Scene scene = test::quadScene({floor}, glm::vec3(0.6f, 0.4f, 0.2f));
    const glm::dvec3 albedo(0.6, 0.4, 0.2);

    Light light;
    // 0 directional, 1 point, 2 spot, 3 spot with a hard edge (inner == outer), 4 a point
    // light below the floor (lights nothing on the visible side).
    const auto lightKind = GENERATE(0, 1, 2, 3, 4);
    if (lightKind == 0) {
        light.type = LightType::Directional;
        light.direction = glm::normalize(glm::vec3(1, -2, 0.5f));
        light.intensity = 2.0f;
    } else {
        light.type = lightKind == 1 || lightKind == 4 ? LightType::Point : LightType::Spot;
        light.position = lightKind == 4 ? glm::vec3(1, -2, -1) : glm::vec3(1, 2, -1);
        light.direction = {0, -1, 0};
        light.intensity = 3.0f;
        light.innerAngle = lightKind == 3 ? 0.9f : 0.4f;
        light.outerAngle = 0.9f;
    }
    light.color = {1.0f, 0.5f, 2.0f};
    scene.lights.push_back(light);
    const GBufferView view = gbuffer.render(scene, camera, {W, H, true, {}});
    const Image direct = readTexture(ctx, view.directRadiance);
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const glm::dmat4 inverseView = glm::inverse(glm::dmat4(camera.view));
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            REQUIRE(positions.at(x, y, 3) == 1.0f);
            const glm::dvec3 p = test::worldPoint(positions, inverseView, x, y);
            double e;
            if (light.type == LightType::Directional) {
                e = light.intensity * std::max(0.0, -glm::normalize(glm::dvec3(light.direction)).y);
            } else {
                const glm::dvec3 toLight = glm::dvec3(light.position) - p;
                const double d2 = glm::dot(toLight, toLight);
                const glm::dvec3 l = toLight / std::sqrt(d2);
                e = light.intensity * std::max(0.0, l.y) / d2;
                if (light.type == LightType::Spot) {
                    const double c = l.y /* dot(-l, axis = -y) */;
                    const double c0 = std::cos(double(light.outerAngle)), c1 = std::cos(double(light.innerAngle));
                    if (c1 > c0) {
                        const double s = std::clamp((c - c0) / (c1 - c0), 0.0, 1.0);
                        e *= s * s * (3 - 2 * s);
                    } else {
                        // Hard edge: pixels within a float rounding of cos(outer) may fall either way.
                        if (std::abs(c - c0) < 1e-6) continue;
                        e *= c >= c0 ? 1.0 : 0.0;
                    }
                }
            }
            for (int c = 0; c < 3; ++c) {
                const double expected = albedo[c] / kPi * e * light.color[c];
                INFO("light " << lightKind << " pixel " << x << "," << y << " channel " << c << ": got "
                              << direct.at(x, y, c) << ", expected " << expected);
                // Half-float storage: an ulp relative (2^-10) for normal values, and 2^-24
                // absolute in the subnormal range below 2^-14; twice that for float arithmetic.
                CHECK(std::abs(direct.at(x, y, c) - expected) <= 2 * (kHalfRelative * expected + std::ldexp(1.0, -24)));
            }
        }
}

TEST_CASE("Albedo and emission come from the material - emission from the front side - radiance saturates instead of overflowing", "[gbuffer]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    const Camera camera = Camera::perspective({{0, 0, 3}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f);
    const AnalyticQuad quad{{{{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}}}};
    Scene scene = test::quadScene({quad}, glm::vec3(0.25f, 0.5f, 0.75f));
    scene.materials[0].emission = {1.0f, 2.0f, 1e30f};
    const GBufferView view = gbuffer.render(scene, camera, {8, 8, true, {}});
    const Image albedo = readTexture(ctx, view.albedo);
    const Image direct = readTexture(ctx, view.directRadiance);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            // sRGB8 storage: half a code step at the value, through the sRGB decode slope (< 1/255 linear).
            CHECK(albedo.at(x, y, 0) == Approx(0.25).margin(1.0 / 255));
            CHECK(albedo.at(x, y, 1) == Approx(0.5).margin(1.0 / 255));
            CHECK(albedo.at(x, y, 2) == Approx(0.75).margin(1.0 / 255));
            CHECK(direct.at(x, y, 0) == Approx(1.0).epsilon(kHalfRelative));
            CHECK(direct.at(x, y, 1) == Approx(2.0).epsilon(kHalfRelative));
            CHECK(direct.at(x, y, 2) == 65504.0f);
        }
    // Materials emit from their front side (counter-clockwise, here +z) only: from behind the
    // quad shows its albedo and, without lights, no radiance.
    const Camera behind = Camera::perspective({{0, 0, -3}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f);
    const GBufferView back = gbuffer.render(scene, behind, {8, 8, true, {}});
    const Image backAlbedo = readTexture(ctx, back.albedo), backDirect = readTexture(ctx, back.directRadiance);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
            CHECK(backAlbedo.at(x, y, 1) == Approx(0.5).margin(1.0 / 255));
            for (int c = 0; c < 3; ++c) CHECK(backDirect.at(x, y, c) == 0.0f);
        }
}

TEST_CASE("Tiny odd and non-square targets work and reversed-Z with an infinite far plane", "[gbuffer]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    const AnalyticQuad quad{{{{-50, -1, 0}, {50, -1, 0}, {50, -1, -100}, {-50, -1, -100}}}};
    const Scene scene = test::quadScene({quad});
    const auto size = GENERATE(std::pair{1, 1}, std::pair{7, 3}, std::pair{3, 17}, std::pair{129, 65});
    const auto mode = GENERATE(DepthMode::Standard, DepthMode::Reversed);
    const float far = mode == DepthMode::Reversed ? INFINITY : 500.0f;
    const Camera camera = Camera::perspective({{0, 0, 1}, {0, -0.2f, -1}, {0, 1, 0}}, 1.0f,
                                              float(size.first) / float(size.second), 0.05f, far, mode);
    const GBufferView view = gbuffer.render(scene, camera, {size.first, size.second, true, {}});
    REQUIRE(view.width == size.first);
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const Image normals = readTexture(ctx, view.normal);
    REQUIRE(positions.width == size.first);
    REQUIRE(positions.height == size.second);
    for (float v : positions.pixels) CHECK(std::isfinite(v));
    for (float v : normals.pixels) CHECK(std::isfinite(v));
    CHECK(test::drainGlErrors().empty());
}

TEST_CASE("Degenerate triangles are skipped and NaN host vertices never reach the output", "[gbuffer][stability]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    const Camera camera = Camera::perspective({{0, 0, 3}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f);
    auto data = std::make_shared<MeshData>();
    // A collapsed triangle, a line-like sliver, and one good triangle.
    data->positions = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}, {-1, -1, 0}, {1, 1, 0}, {0, 0, 0}, {-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    data->normals = std::vector<glm::vec3>(9, glm::vec3(0.0f)); // zero normals fall back to the face normal
    Scene scene = test::quadScene({});
    scene.meshes.push_back({data, glm::mat4(1), 0, "degenerate"});
    // A host buffer with a NaN vertex (validation cannot see GPU data).
    const float nan = std::nanf("");
    const float hostVertices[9] = {nan, 0, 0, 1, 0, 0, 0, 1, 0};
    GLuint buffer = 0;
    glCreateBuffers(1, &buffer);
    glNamedBufferData(buffer, sizeof hostVertices, hostVertices, GL_STATIC_DRAW);
    MeshRef ref;
    ref.position = {buffer, 0, 12, 3, GL_FLOAT, false};
    ref.count = 3;
    scene.meshRefs.push_back(ref);
    const GBufferView view = gbuffer.render(scene, camera, {16, 16, true, {}});
    int covered = 0;
    for (const TextureView& t : {view.normal, view.directRadiance, gbuffer.positions(view)}) {
        const Image img = readTexture(ctx, t);
        for (float v : img.pixels) CHECK(std::isfinite(v));
    }
    const Image normals = readTexture(ctx, view.normal);
    for (int i = 0; i < 16 * 16; ++i) covered += normals.pixels[static_cast<std::size_t>(i) * 4 + 3] > 0.0f;
    CHECK(covered > 0);
    glDeleteBuffers(1, &buffer);
}

TEST_CASE("The built-in Cornell box renders its walls with their published colours", "[gbuffer][scenes]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    const assets::LoadedScene cornell = assets::builtinScene("cornell");
    constexpr int W = 64, H = 64;
    const Camera camera = assets::makeCamera(cornell.camera, W, H);
    const GBufferView view = gbuffer.render(cornell.scene, camera, {W, H, true, {}});
    const Image albedo = readTexture(ctx, view.albedo);
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(camera.view));
    int red = 0, green = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (positions.at(x, y, 3) == 0.0f) continue;
            const glm::dvec3 p = test::worldPoint(positions, toWorld, x, y);
            const glm::dvec3 a = test::texel3(albedo, x, y);
            // The red wall is x ~ 550 (image left), the green wall x = 0 (image right); the
            // back wall (z = 559.2), floor and ceiling share their edges.
            const bool inside = p.y > 1 && p.y < 547 && p.z < 558;
            INFO("pixel " << x << "," << y << " world " << p.x << "," << p.y << "," << p.z << " albedo " << a.x << "," << a.y << "," << a.z);
            if (p.x > 549.0 && inside) {
                ++red;
                CHECK(x < W / 2);
                CHECK(glm::length(a - glm::dvec3(0.63, 0.065, 0.05)) < 2.0 / 255);
            }
            if (p.x < 0.5 && inside) {
                ++green;
                CHECK(x >= W / 2);
                CHECK(glm::length(a - glm::dvec3(0.14, 0.45, 0.091)) < 2.0 / 255);
            }
        }
    CHECK(red > 50);
    CHECK(green > 50);
}

namespace {
// View factor from a differential area to a parallel rectangle with one corner straight
// above it (a, b: side lengths over the height), e.g. Howell's catalogue, configuration B-3.
double cornerViewFactor(double a, double b) {
    const double sa = std::sqrt(1 + a * a), sb = std::sqrt(1 + b * b);
    return (a / sa * std::atan(b / sa) + b / sb * std::atan(a / sb)) / (2 * kPi);
}
// Any parallel rectangle [x0,x1] x [y0,y1] at height h over the point (px, py): sum of four
// corner rectangles with signs (the corner factor is odd in each side).
double rectViewFactor(double x0, double x1, double y0, double y1, double h, double px, double py) {
    const auto g = [&](double a, double b) {
        const double s = (a < 0 ? -1.0 : 1.0) * (b < 0 ? -1.0 : 1.0);
        return s * cornerViewFactor(std::abs(a) / h, std::abs(b) / h);
    };
    return g(x1 - px, y1 - py) - g(x0 - px, y1 - py) - g(x1 - px, y0 - py) + g(x0 - px, y0 - py);
}
} // namespace

TEST_CASE("Area lights - a rectangle matches the view-factor closed form and a sphere its point equivalent",
          "[gbuffer]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    constexpr int W = 40, H = 40;
    const Camera camera = Camera::perspective({{0, 8, 0.01f}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 100.0f);
    const AnalyticQuad floor{{{{-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}}}};
    Scene scene = test::quadScene({floor}, glm::vec3(0.5f));
    const bool rect = GENERATE(true, false);
    Light light;
    light.color = glm::vec3(1.0f);
    light.intensity = 3.0f; // radiance, W/(sr m^2)
    if (rect) {
        light.type = LightType::Rect;
        light.position = {0.5f, 1.5f, -0.25f};
        light.direction = {0, -1, 0};
        light.tangent = {1, 0, 0};
        light.size = {2.0f, 1.0f}; // x in [-0.5, 1.5], z in [-0.75, 0.25]
    } else {
        light.type = LightType::Sphere;
        light.position = {0.3f, 1.2f, 0.2f};
        light.radius = 0.4f;
    }
    scene.lights.push_back(light);
    const GBufferView view = gbuffer.render(scene, camera, {W, H, true, {}});
    const Image direct = readTexture(ctx, view.directRadiance);
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(camera.view));
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const glm::dvec3 p = test::worldPoint(positions, toWorld, x, y);
            double e;
            if (rect) {
                e = kPi * light.intensity * rectViewFactor(-0.5, 1.5, -0.75, 0.25, 1.5, p.x, p.z);
            } else {
                const glm::dvec3 d = glm::dvec3(light.position) - p;
                const double r = light.radius;
                e = light.intensity * kPi * r * r * (d.y / glm::length(d)) / glm::dot(d, d);
            }
            const double expected = 0.5 / kPi * e;
            INFO("pixel " << x << "," << y << ": got " << direct.at(x, y, 0) << ", expected " << expected);
            // Half-float storage (2 half ulps), plus the float error of the polygon formula: up
            // to 5 edge terms of a few ulps (2^-22) each, of a projected solid angle <= pi.
            const double formula = 0.5 / kPi * light.intensity * 5 * std::ldexp(1.0, -22) * kPi;
            CHECK(std::abs(direct.at(x, y, 0) - expected) <= 2 * kHalfRelative * expected + formula);
        }
}

TEST_CASE("A rectangle light cut by the receiver's horizon lights like its part above it", "[gbuffer]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    constexpr int W = 40, H = 40;
    const Camera camera = Camera::perspective({{0, 8, 0.01f}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 100.0f);
    Scene scene = test::quadScene({{{{{-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}}}}}, glm::vec3(0.5f));
    // Upright at z = 2, emitting toward -z: the floor's points in front of it see only its
    // upper half (y in [0, 1]); the lower half is below their horizon and must be clipped
    // away, leaving the polygon of the half rectangle, which needs no clipping.
    Light light;
    light.type = LightType::Rect;
    light.intensity = 3.0f;
    light.direction = {0, 0, -1};
    light.tangent = {1, 0, 0};
    light.position = {0.2f, 0.0f, 2.0f};
    light.size = {2.0f, 2.0f};
    scene.lights = {light};
    const Image cut = readTexture(ctx, gbuffer.render(scene, camera, {W, H, true, {}}).directRadiance);
    // Shadowed by its map, with nothing in the way, it lights the same: the floor lies in a
    // plane through the light's centre (edge-on to its map, so left out of it) and faces
    // away from the centre, which the lookup must not count as shadow.
    ShadowMaps shadows(ctx);
    GBufferSettings shadowed{W, H, true, {}};
    shadowed.shadows = &shadows.render(scene, camera, {});
    REQUIRE(shadowed.shadows->find(0) != nullptr);
    const Image unblocked = readTexture(ctx, gbuffer.render(scene, camera, shadowed).directRadiance);
    for (std::size_t i = 0; i < cut.pixels.size(); ++i) CHECK(unblocked.pixels[i] == cut.pixels[i]);
    light.position.y = 0.5f;
    light.size.y = 1.0f;
    scene.lights = {light};
    const Image half = readTexture(ctx, gbuffer.render(scene, camera, {W, H, true, {}}).directRadiance);
    int lit = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const double a = cut.at(x, y, 0), b = half.at(x, y, 0);
            lit += b > 0.0 ? 1 : 0;
            INFO("pixel " << x << "," << y << ": cut " << a << ", upper half " << b);
            // Two half-float roundings and the float error of up to 5 edge terms (as above).
            const double formula = 0.5 / kPi * light.intensity * 5 * std::ldexp(1.0, -22) * kPi;
            CHECK(std::abs(a - b) <= 2 * kHalfRelative * b + 2 * formula);
        }
    CHECK(lit > W * H / 4);
}

TEST_CASE("Positions from a sloped floor's depth lie within the rasterizer's sub-pixel snap of it", "[gbuffer]") {
    // A rasterizer may evaluate depth from vertices snapped to its sub-pixel grid
    // (GL_SUBPIXEL_BITS): the stored depth is then the surface's at a point up to that step
    // off the pixel centre, and the position rebuilt along the centre's ray leaves the surface
    // by the depth's change over that step. The bound: the largest change of the floor's view
    // depth over one step in x and y, along the ray, projected on the floor's normal; plus
    // float rounding of the reconstruction (1e-5 relative, test (1) above).
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    constexpr int W = 128, H = 128;
    const Camera camera = Camera::perspective({{0, 1, 3}, {0, 0, 0}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 100.0f);
    const GBufferView view = gbuffer.render(
        test::quadScene({{{{{-20, 0, -20}, {-20, 0, 20}, {20, 0, 20}, {20, 0, -20}}}}}), camera, {W, H, false, {}});
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    GLint subpixelBits = 0;
    glGetIntegerv(GL_SUBPIXEL_BITS, &subpixelBits);
    const double step = std::ldexp(1.0, -std::max(subpixelBits, 0));
    const glm::dmat4 viewMatrix(camera.view), inverseProjection = glm::inverse(glm::dmat4(camera.projection));
    const glm::dvec3 normal = glm::dmat3(viewMatrix) * glm::dvec3(0, 1, 0);
    const double offset = glm::dot(normal, glm::dvec3(viewMatrix * glm::dvec4(0, 0, 0, 1)));
    const auto direction = [&](glm::dvec2 ndc) {
        const glm::dvec4 p = inverseProjection * glm::dvec4(ndc, 0.5, 1.0);
        return glm::normalize(glm::dvec3(p) / p.w);
    };
    const auto hitDepth = [&](glm::dvec2 ndc) {
        const glm::dvec3 d = direction(ndc);
        return offset / glm::dot(normal, d) * d.z;
    };
    double worstOff = 0, worstRatio = 0;
    int geometry = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (positions.at(x, y, 3) == 0.0f) continue;
            ++geometry;
            const glm::dvec2 ndc = test::pixelNdc(x, y, W, H);
            const glm::dvec3 d = direction(ndc);
            const double z = hitDepth(ndc);
            double change = 0;
            for (const glm::dvec2 shift : {glm::dvec2(step, 0), glm::dvec2(-step, 0), glm::dvec2(0, step), glm::dvec2(0, -step)})
                change = std::max(change, std::abs(hitDepth(ndc + shift * glm::dvec2(2.0 / W, 2.0 / H)) - z));
            const glm::dvec3 p = test::texel3(positions, x, y);
            const double off = std::abs(glm::dot(normal, p) - offset);
            const double bound = change / std::abs(d.z) * std::abs(glm::dot(normal, d)) + 1e-5 * glm::length(p);
            worstOff = std::max(worstOff, off);
            worstRatio = std::max(worstRatio, off / bound);
            CHECK(off <= bound);
        }
    INFO("GL_SUBPIXEL_BITS " << subpixelBits << ", worst distance off the floor " << worstOff << ", worst share of the bound "
                             << worstRatio);
    // Measured: llvmpipe 6.8e-6 (its depth follows the exact vertices), NVIDIA H100 1.4e-4.
    CHECK(geometry > W * H / 3);
}

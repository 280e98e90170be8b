// What one-bounce indirect light gathers, against integrals of the scene: a face seen from
// above lights a wall only through the rays that enter it (screen space and voxel hybrid),
// and filtered light takes each pixel's own albedo.
#include "ao_fixture.hpp"
#include "gl_fixture.hpp"
#include "scene_builders.hpp"

#include "obscura/obscura.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

using namespace obscura;
using test::wallCamera;

namespace {
constexpr double kPi = 3.14159265358979323846;
} // namespace

namespace {

// A floor y = 0, x in [-3, 3], z in [-1, 2.9], of square cells of side 0.15 in a checkerboard:
// the cells of one colour in the first mesh, the others in the second, so that two scenes
// can differ in the cells' albedo alone.
std::array<std::shared_ptr<MeshData>, 2> checkerFloor() {
    constexpr double side = 0.15;
    std::array<std::shared_ptr<MeshData>, 2> meshes = {std::make_shared<MeshData>(), std::make_shared<MeshData>()};
    for (int i = 0; i < 40; ++i)
        for (int k = 0; k < 26; ++k) {
            MeshData& m = *meshes[(i + k) % 2];
            const double x = -3.0 + i * side, z = -1.0 + k * side;
            const auto first = static_cast<std::uint32_t>(m.positions.size());
            for (const glm::dvec2 c : {glm::dvec2(x, z), {x, z + side}, {x + side, z + side}, {x + side, z}}) {
                m.positions.emplace_back(c.x, 0.0, c.y);
                m.normals.emplace_back(0.0f, 1.0f, 0.0f);
            }
            m.indices.insert(m.indices.end(), {first, first + 1, first + 2, first, first + 2, first + 3});
        }
    return meshes;
}

} // namespace

TEST_CASE("Filtered indirect light takes each pixel's own albedo", "[gi][filters]") {
    // The filters weigh by depth and normal, which do not see an albedo texture's edges, so
    // indirect light is filtered without its albedo and multiplied by each G-buffer pixel's
    // own after the last step. Scenes of the same geometry, a floor of small cells lit only
    // by an emissive wall: all cells white, or every other one black or grey. The floor's
    // albedo changes nothing it receives (its rays leave it upward; unlit, it reflects
    // nothing), so wherever the cells are white the results must be the same bits, wherever
    // they are black exactly 0, and wherever they are grey the white result times the grey,
    // at every resolution, blur and refinement. Multiplied before the filters, a black cell
    // took light from its white neighbours and a white one lost it to black ones; the grey
    // cells catch an albedo multiplied twice, which 0 and 1 cannot show.
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    IndirectLight gi(ctx);
    const auto cells = checkerFloor();
    Scene scene = test::quadScene({{{glm::dvec3(-20, 0, -1), {20, 0, -1}, {20, 20, -1}, {-20, 20, -1}}}});
    scene.materials[0].albedo = glm::vec3(0.0f);
    scene.materials[0].emission = glm::vec3(2.0f, 1.0f, 0.5f); // the wall
    Material white, other;
    white.albedo = glm::vec3(1.0f);
    scene.materials.push_back(white);
    scene.materials.push_back(other);
    for (const auto& mesh : cells) scene.meshes.push_back(Mesh{mesh, glm::mat4(1.0f), 1, "cells"});
    Scene checkered = scene;
    checkered.meshes.back().material = 2;
    constexpr int W = 64, H = 48;
    const Camera camera = wallCamera(W, H);
    // Grey: the G-buffer's albedo as read back (0.5 in 8-bit sRGB; llvmpipe stores code 187,
    // 0.4969). The shader's sRGB decoding may differ from the read-back's, as the GL allows
    // (here by 0.15 %), and the grey and white results are each rounded to a half float
    // (2^-11 relative; at least 2^-25 absolute, half the spacing of the subnormals, where
    // the faintest light lies): 1 % of the value plus 2^-24 covers both with room, and is
    // far from the 50 % an albedo multiplied twice would be off.
    constexpr double greyTolerance = 0.01, halfSubnormalSpacing = 0x1p-24;
    struct Setup {
        AoResolution resolution;
        int taps;
        float refine;
    };
    for (const float otherAlbedo : {0.0f, 0.5f})
        for (const Setup setup : {Setup{AoResolution::Full, 2, 0.0f}, Setup{AoResolution::Half, 0, 0.0f},
                                  Setup{AoResolution::Half, 2, 0.25f}, Setup{AoResolution::Quarter, 1, 0.0f},
                                  Setup{AoResolution::Quarter, 2, 0.25f}}) {
            CAPTURE(otherAlbedo, static_cast<int>(setup.resolution), setup.taps, setup.refine);
            checkered.materials[2].albedo = glm::vec3(otherAlbedo);
            IndirectLightSettings s;
            s.radius = 1.0f;
            s.rays = 64;
            s.steps = 16;
            s.resolution = setup.resolution;
            s.blurRadius = setup.taps;
            s.refineThreshold = setup.refine;
            const GBufferView whiteView = gbuffer.render(scene, camera, {W, H, false, {}});
            const Image allWhite = readTexture(ctx, gi.run(whiteView, s).radiance);
            const GBufferView checkeredView = gbuffer.render(checkered, camera, {W, H, false, {}});
            const Image albedo = readTexture(ctx, checkeredView.albedo);
            const Image positions = readTexture(ctx, gbuffer.positions(checkeredView));
            const Image result = readTexture(ctx, gi.run(checkeredView, s).radiance);
            int whiteLit = 0, otherUnderLight = 0, wrong = 0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    if (positions.at(x, y, 3) == 0.0f) continue; // the sky (the wall is black: it receives nothing)
                    const bool isWhite = albedo.at(x, y, 0) == 1.0f;
                    bool right = result.at(x, y, 3) == allWhite.at(x, y, 3);
                    for (int c = 0; c < 3; ++c) {
                        const double lit = allWhite.at(x, y, c), value = result.at(x, y, c);
                        if (isWhite) right = right && value == lit;
                        else if (otherAlbedo == 0.0f) right = right && value == 0.0;
                        else {
                            const double grey = albedo.at(x, y, c);
                            right = right && std::abs(value - grey * lit) <= greyTolerance * grey * lit + halfSubnormalSpacing;
                        }
                    }
                    wrong += right ? 0 : 1;
                    whiteLit += isWhite && allWhite.at(x, y, 0) > 0.0f;
                    otherUnderLight += !isWhite && allWhite.at(x, y, 0) > 0.0f;
                }
            CHECK(wrong == 0);
            // Enough of both colours under the wall's light for a mix-up to show.
            CHECK(whiteLit > 100);
            CHECK(otherUnderLight > 100);
        }
}

namespace {

// The view factor from a point P on the wall z = -1 (normal +z) to the part within `reach`
// of the rectangle y = top, x in [x0, x1], z in [z0, z1] (normal +y), P above it:
// (1/pi) Integral cos1 cos2 / d^2 dA = (1/pi) Integral (z + 1) (P.y - top) / d^4 dA, by the
// midpoint rule on 400 x 400 cells (the integrand is smooth: d >= 0.07 here).
double topFaceViewFactor(glm::dvec3 P, double top, double x0, double x1, double z0, double z1, double reach) {
    constexpr int n = 400;
    const double hx = (x1 - x0) / n, hz = (z1 - z0) / n, h = P.y - top;
    double sum = 0.0;
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const glm::dvec3 v(x0 + (i + 0.5) * hx - P.x, -h, z0 + (j + 0.5) * hz - P.z);
            const double d2 = glm::dot(v, v);
            if (d2 <= reach * reach) sum += v.z * h / (d2 * d2);
        }
    return sum * hx * hz / kPi;
}

// A black box x in [-1, 1], y in [-1, 0.5], z in [-0.9, -0.3] whose top emits Le = 1
// upward, 0.15 in front of a grey (0.8) wall z = -1, seen from above and in front.
constexpr double kBoxTop = 0.5;
constexpr int kBoxW = 160, kBoxH = 120;

Scene emittingTopScene() {
    constexpr double top = kBoxTop;
    const auto box = [](glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d) { return test::AnalyticQuad{{a, b, c, d}}; };
    Scene scene = test::quadScene({box({-20, -1, -1}, {20, -1, -1}, {20, 20, -1}, {-20, 20, -1}),         // wall
                                   box({-1, top, -0.9}, {-1, top, -0.3}, {1, top, -0.3}, {1, top, -0.9}), // top
                                   box({-1, -1, -0.3}, {1, -1, -0.3}, {1, top, -0.3}, {-1, top, -0.3}),   // front
                                   box({-1, top, -0.9}, {1, top, -0.9}, {1, -1, -0.9}, {-1, -1, -0.9}),   // back
                                   box({1, -1, -0.3}, {1, -1, -0.9}, {1, top, -0.9}, {1, top, -0.3}),     // +x
                                   box({-1, -1, -0.9}, {-1, -1, -0.3}, {-1, top, -0.3}, {-1, top, -0.9})}, // -x
                                  glm::vec3(0.8f));
    Material black, emitter;
    black.albedo = emitter.albedo = glm::vec3(0.0f);
    emitter.emission = glm::vec3(1.0f);
    scene.materials.push_back(black);
    scene.materials.push_back(emitter);
    for (std::size_t i = 2; i < scene.meshes.size(); ++i) scene.meshes[i].material = 1;
    scene.meshes[1].material = 2;
    return scene;
}

Camera emittingTopCamera(glm::vec3 eye) {
    return Camera::perspective({eye, {0, 0.4f, -0.9f}, {0, 1, 0}}, glm::radians(40.0f), float(kBoxW) / float(kBoxH), 0.05f, 200.0f);
}

} // namespace

TEST_CASE("Screen-space indirect light reads a visible face only for rays that enter through it", "[gi]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    IndirectLight gi(ctx);
    // Wall points just above the top's plane see the top nearly edge-on: little light. Rays
    // from them that dip below that plane in the gap and enter the box through its back,
    // which the camera does not see, hit black; the screen shows the emitting top where they
    // end, and reading it there made glowing spots.
    constexpr double top = kBoxTop, reach = 1.0;
    const Scene scene = emittingTopScene();
    constexpr int W = kBoxW, H = kBoxH;
    const Camera camera = emittingTopCamera({0.0f, 2.2f, 2.5f});
    const GBufferView view = gbuffer.render(scene, camera, {W, H, false, {}});
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(view.camera.view));
    constexpr int rays = 1024, steps = 64;
    IndirectLightSettings s;
    s.method = GiMethod::Screen;
    s.radius = static_cast<float>(reach);
    s.rays = rays;
    s.steps = steps;
    const Image radiance = readTexture(ctx, gi.run(view, s).radiance);
    const double step = reach / steps;
    int checked = 0;
    double meanError = 0.0, meanWindow = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (positions.at(x, y, 3) == 0.0f) continue;
            const glm::dvec3 p = test::worldPoint(positions, toWorld, x, y);
            if (std::abs(p.z + 1.0) > 1e-3 || p.y <= top + 1e-3 || p.y > top + 0.15 || std::abs(p.x) > 0.6) continue;
            // The march finds a hit at its first sample behind the top, inside the box: rays
            // that cross the top within about a step of its front edge (where later samples
            // show the box's black front) or its sides, or beyond r (1 - 1 / steps), may be
            // missed. A sample s up to delta = 1.5 steps below the top's plane (how far the
            // accepted crossing may lie before it) counts as behind the top wherever the
            // camera sees the top in front of it: up to 2 delta beyond the back edge (the
            // camera's rays there fall 1 in 2). So rays crossing the plane up to 4.5 steps
            // beyond the back edge (and, conservatively, the sides) may be read.
            const double lo = topFaceViewFactor(p, top, -1.0 + step, 1.0 - step, -0.9, -0.3 - 2.0 * step, reach - step);
            const double hi = topFaceViewFactor(p, top, -1.0 - 4.5 * step, 1.0 + 4.5 * step, -0.9 - 4.5 * step, -0.3, reach);
            // 5 sigma of the share of `rays` cosine-weighted directions, and the half float.
            const double sigma = std::sqrt(std::max({lo * (1.0 - lo), hi * (1.0 - hi), 1.0 / rays}) / rays);
            const double value = radiance.at(x, y, 0) / 0.8; // rho Le F, rho = 0.8, Le = 1
            const double tolerance = 5.0 * sigma + std::ldexp(1.0, -11);
            CAPTURE(x, y, p.x, p.y - top, value, lo, hi);
            CHECK(value >= lo - tolerance);
            CHECK(value <= hi + tolerance);
            meanError += value - 0.5 * (lo + hi);
            meanWindow += 0.5 * (hi - lo);
            ++checked;
        }
    CHECK(checked > 40);
    INFO("mean error " << meanError / checked << " over " << checked << " pixels, window +-" << meanWindow / checked);
    CHECK(std::abs(meanError / checked) <= meanWindow / checked + 5.0 * 0.5 / std::sqrt(double(rays) * checked) + std::ldexp(1.0, -11));
}

namespace {

// The share of cosine-weighted directions about +z for which `hits` holds. Such directions
// project uniformly onto the unit disc, so the share is the area of the disc's points (u, v)
// whose direction (u, v, sqrt(1 - u^2 - v^2)) hits, over pi: the midpoint rule on n x n
// cells of [-1, 1]^2. `unresolved` gets the share of the cells whose centre and corners do
// not all agree (outside the disc counts as a miss): the rule can be off by at most that
// where the set's edges cross a cell at most once between samples (here they are lines and
// conics, smooth on the scale of a cell).
double directionShare(const std::function<bool(glm::dvec3)>& hits, int n, double& unresolved) {
    const auto at = [&](double u, double v) {
        const double r2 = u * u + v * v;
        return r2 < 1.0 && hits(glm::dvec3(u, v, std::sqrt(1.0 - r2)));
    };
    const double h = 2.0 / n;
    std::vector<char> corner(std::size_t(n + 1) * std::size_t(n + 1));
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) corner[std::size_t(j) * (n + 1) + std::size_t(i)] = at(-1.0 + i * h, -1.0 + j * h);
    long inside = 0, mixed = 0;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const bool c = at(-1.0 + (i + 0.5) * h, -1.0 + (j + 0.5) * h);
            inside += c ? 1 : 0;
            const std::size_t k = std::size_t(j) * (n + 1) + std::size_t(i);
            const bool uniform = corner[k] == c && corner[k + 1] == c && corner[k + n + 1] == c && corner[k + n + 2] == c;
            mixed += uniform ? 0 : 1;
        }
    unresolved = double(mixed) * h * h / kPi;
    return double(inside) * h * h / kPi;
}

// Where a ray from `from` along w meets the plane y = level going down; -1 if it does not.
double downCrossing(glm::dvec3 from, glm::dvec3 w, double level) {
    return w.y < 0.0 && from.y > level ? (from.y - level) / -w.y : -1.0;
}

// Where a ray from `from` along w enters the box [lo, hi] (0 if it starts inside); -1 if it
// misses it.
double boxEntry(glm::dvec3 from, glm::dvec3 w, glm::dvec3 lo, glm::dvec3 hi) {
    double t0 = 0.0, t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
        if (w[a] == 0.0) {
            if (from[a] < lo[a] || from[a] > hi[a]) return -1.0;
            continue;
        }
        const double ta = (lo[a] - from[a]) / w[a], tb = (hi[a] - from[a]) / w[a];
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    return t0 <= t1 ? t0 : -1.0;
}

} // namespace

TEST_CASE("Hybrid indirect light reads a visible face only for rays that enter through it", "[gi]") {
    test::GlFixture gl;
    Context ctx(gl.desc());
    GBuffer gbuffer(ctx);
    Voxelizer voxelizer(ctx);
    IndirectLight gi(ctx);
    // The scene of the screen-space case. A voxel hit is the entry into the first occupied
    // voxel, which from the gap behind the box is the back's: the screen there shows the
    // emitting top in front of it.
    constexpr double top = kBoxTop, reach = 2.0; // reaches the whole top from every wall point
    const Scene scene = emittingTopScene();
    constexpr int W = kBoxW, H = kBoxH;
    // Seen from higher up than there, so that a pixel's footprint on the top is shorter.
    const glm::dvec3 eye(0.0, 3.5, 1.5);
    const GBufferView view = gbuffer.render(scene, emittingTopCamera(eye), {W, H, false, {}});
    const Image positions = readTexture(ctx, gbuffer.positions(view));
    const glm::dmat4 toWorld = glm::inverse(glm::dmat4(view.camera.view));
    // Cubic voxels of side 1/128: the gap (0.1) is many voxels wide. The box's faces do not
    // lie on voxel boundaries; every voxel a face touches lies within one side of it.
    VoxelizerSettings voxels;
    voxels.resolution = 512;
    voxels.targets = 4;
    voxels.fitBox = false;
    voxels.boxMin = glm::vec3(-2.0f, -1.5f, -1.5f);
    voxels.boxMax = glm::vec3(2.0f, 2.5f, 2.5f);
    const VoxelGrid& grid = voxelizer.voxelize(scene, voxels);
    const double side = 4.0 / 512.0, diagonal = std::sqrt(3.0) * side;
    constexpr int rays = 1024;
    IndirectLightSettings s;
    s.method = GiMethod::Hybrid;
    s.radius = static_cast<float>(reach);
    s.rays = rays;
    s.voxels = &grid;
    // A depth tolerance that alone would let the top be read for rays entering the back up
    // to 0.3 below it (the default, two voxel diagonals, leaves a few voxels' worth).
    s.thickness = 0.3f;
    const Image radiance = readTexture(ctx, gi.run(view, s).radiance);
    // Every occupied voxel a ray from the wall can meet lies in the box grown by a side.
    const glm::dvec3 grownLo(-1.0 - side, -1.0 - side, -0.9 - side), grownHi(1.0 + side, top + side, -0.3 + side);
    // An entry point at most a side above the top projects onto it up to shiftZ further back
    // and shiftX further out (the eye looks down `rise` over at most eye.z + 0.9 back and 1
    // across), and the pixel holding that projection reaches up to a pixel footprint on the
    // top (pixels of 2 tan(20 deg) / H radians at the back corners' distance, stretched along
    // z by the viewing angle's sine rise / distance).
    const double rise = eye.y - top;
    const double shiftZ = side * (eye.z + 0.9) / (rise - side), shiftX = side * 1.0 / (rise - side);
    const double far = glm::length(glm::dvec3(1.0, rise, eye.z + 0.9));
    const double pixel = 2.0 * std::tan(glm::radians(20.0)) / H, footX = pixel * far, footZ = pixel * far * far / rise;
    int checked = 0;
    double meanError = 0.0, meanWindow = 0.0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            if (positions.at(x, y, 3) == 0.0f) continue;
            const glm::dvec3 p = test::worldPoint(positions, toWorld, x, y);
            // Wall points a few voxels above the top's plane: closer, the rays to the top
            // pass its voxels at the back edge.
            if (std::abs(p.z + 1.0) > 1e-3 || p.y < top + 0.04 || p.y > top + 0.15 || std::abs(p.x) > 0.6) continue;
            const glm::dvec3 start = p + glm::dvec3(0.0, 0.0, diagonal); // lifted off the wall's voxels
            // Read for sure: rays that first meet the grown box through its top face (y = top +
            // side) and cross the top's plane, both inside the top shrunk by those margins.
            // Their first occupied voxel is entered between the two crossings (the top's voxels
            // hold its plane), so its entry projects onto the top, goes into it from the front,
            // and the plane's crossing does not come before it.
            const auto read = [&](glm::dvec3 w) {
                const double a = downCrossing(start, w, top + side), b = downCrossing(start, w, top);
                if (a < 0.0 || b > reach) return false;
                const auto onShrunkTop = [&](glm::dvec3 q) {
                    return std::abs(q.x) <= 1.0 - shiftX - footX && q.z >= -0.9 + shiftZ + footZ && q.z <= -0.3 - footZ;
                };
                return onShrunkTop(start + w * a) && onShrunkTop(start + w * b);
            };
            // May be read: rays that meet the grown box (their first occupied voxel is there, or
            // further) and cross the top's plane no more than a voxel diagonal before that.
            const auto mayRead = [&](glm::dvec3 w) {
                const double entry = boxEntry(start, w, grownLo, grownHi), c = downCrossing(start, w, top);
                return entry >= 0.0 && entry <= reach && c >= 0.0 && c >= entry - diagonal;
            };
            double unresolvedLo = 0.0, unresolvedHi = 0.0;
            const double lo = directionShare(read, 400, unresolvedLo), hi = directionShare(mayRead, 400, unresolvedHi);
            // 5 sigma of the share of `rays` cosine-weighted directions, the quadrature's
            // unresolved cells, and the half float.
            const double sigma = std::sqrt(std::max({lo * (1.0 - lo), hi * (1.0 - hi), 1.0 / rays}) / rays);
            const double value = radiance.at(x, y, 0) / 0.8; // rho Le share, rho = 0.8, Le = 1
            const double tolerance = 5.0 * sigma + std::ldexp(1.0, -11);
            CAPTURE(x, y, p.x, p.y - top, value, lo, hi, unresolvedLo, unresolvedHi);
            CHECK(value >= lo - unresolvedLo - tolerance);
            CHECK(value <= hi + unresolvedHi + tolerance);
            meanError += value - 0.5 * (lo + hi);
            meanWindow += 0.5 * (hi - lo) + 0.5 * (unresolvedLo + unresolvedHi);
            ++checked;
        }
    CHECK(checked > 40);
    INFO("mean error " << meanError / checked << " over " << checked << " pixels, window +-" << meanWindow / checked);
    CHECK(std::abs(meanError / checked) <= meanWindow / checked + 5.0 * 0.5 / std::sqrt(double(rays) * checked) + std::ldexp(1.0, -11));
}

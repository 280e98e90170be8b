// Ambient occlusion in a closed box room against the Embree reference at the G-buffer's own
// samples: the screen-space march with depth peeling, and voxel AO between two references.
#include "ao_fixture.hpp"
#include "gl_fixture.hpp"

#include "obscura/assets.hpp"
#include "obscura/obscura.hpp"
#include "obscura/reference.hpp"
#include "scene_builders.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace obscura;

namespace {

struct RoomFixture {
    test::GlFixture gl;
    Context ctx{gl.desc()};
    GBuffer gbuffer{ctx};
    AmbientOcclusion ao{ctx};
    assets::LoadedScene room = assets::builtinScene("box_room");
    Camera camera;
    GBufferView view;
    Image positions, normals;

    RoomFixture(int width, int height) : camera(assets::makeCamera(room.camera, width, height)) {
        GBufferSettings settings{width, height, false, {}};
        settings.depthLayers = 2;
        view = gbuffer.render(room.scene, camera, settings);
        positions = readTexture(ctx, gbuffer.positions(view));
        normals = readTexture(ctx, view.normal);
    }

    Image run(const AmbientOcclusionSettings& s) { return readTexture(ctx, ao.run(view, s).ao); }

    // Whether the cube of half side r around the view point of pixel (x, y), and so the ball
    // of its rays, projects inside the image in front of the camera: the projection of a
    // convex set in front of the camera is the hull of its corners' projections.
    bool ballOnScreen(int x, int y, float r) const {
        const glm::vec3 p(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2));
        for (int corner = 0; corner < 8; ++corner) {
            const glm::vec3 c = p + r * glm::vec3(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
            const glm::vec4 clip = camera.projection * glm::vec4(c, 1.0f);
            if (!(clip.w > 0.0f) || std::abs(clip.x) >= clip.w || std::abs(clip.y) >= clip.w) return false;
        }
        return true;
    }

    // Per pixel: whether no silhouette of the small box (a pixel whose 4-neighbours are
    // partly on the box and partly not) lies in the pixel rectangle that holds the
    // projection of the ray ball. There the depth buffer and its back layer hold every
    // surface within reach.
    std::vector<bool> ballsWithoutSilhouette(const reference::ShadingPoints& points, float r) const {
        const int w = positions.width, h = positions.height;
        auto onBox = [&](int x, int y) {
            const glm::dvec3 p = points.points[std::size_t(y) * w + std::size_t(x)].position;
            return points.points[std::size_t(y) * w + std::size_t(x)].surface() && std::abs(p.x) < 0.501 &&
                   std::abs(p.z) < 0.501 && p.y < 1.001;
        };
        std::vector<bool> silhouette(std::size_t(w) * h, false);
        for (int y = 1; y + 1 < h; ++y)
            for (int x = 1; x + 1 < w; ++x) {
                const bool c = onBox(x, y);
                silhouette[std::size_t(y) * w + std::size_t(x)] =
                    onBox(x - 1, y) != c || onBox(x + 1, y) != c || onBox(x, y - 1) != c || onBox(x, y + 1) != c;
            }
        std::vector<bool> clear(std::size_t(w) * h, false);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                if (!ballOnScreen(x, y, r)) continue;
                const glm::vec3 p(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2));
                glm::vec2 lo(1e30f), hi(-1e30f);
                for (int corner = 0; corner < 8; ++corner) {
                    const glm::vec3 c = p + r * glm::vec3(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
                    const glm::vec4 clip = camera.projection * glm::vec4(c, 1.0f);
                    // Pixel coordinates, row 0 at the top as in the images.
                    const glm::vec2 q((clip.x / clip.w * 0.5f + 0.5f) * float(w), (0.5f - clip.y / clip.w * 0.5f) * float(h));
                    lo = glm::min(lo, q);
                    hi = glm::max(hi, q);
                }
                bool any = false;
                for (int v = std::max(0, int(lo.y) - 1); v <= std::min(h - 1, int(hi.y) + 1); ++v)
                    for (int u = std::max(0, int(lo.x) - 1); u <= std::min(w - 1, int(hi.x) + 1); ++u)
                        any = any || silhouette[std::size_t(v) * w + std::size_t(u)];
                clear[std::size_t(y) * w + std::size_t(x)] = !any;
            }
        return clear;
    }
};

} // namespace

TEST_CASE("AO in a box room with depth peeling matches the reference within the march and sampling bounds", "[ao][reference]") {
    constexpr int W = 96, H = 72;
    RoomFixture f(W, H);
    constexpr float radius = 0.6f;
    constexpr int rays = 256, steps = 32;
    const reference::RayScene scene(f.room.scene);
    const reference::ShadingPoints points = reference::fromGBuffer(scene, f.camera, f.positions, f.normals);
    reference::RenderSettings rs;
    rs.samplesPerPixel = 1024;
    // The march samples up to r (1 - 1/steps) at least, so it may miss exactly the hits
    // beyond that: its expectation lies between AO_r and AO_r(1-1/steps).
    const reference::Reference lo = reference::render(scene, points, reference::AmbientOcclusion{radius, true}, rs);
    const reference::Reference hi =
        reference::render(scene, points, reference::AmbientOcclusion{radius * (1.0 - 1.0 / steps), true}, rs);
    const auto clear = f.ballsWithoutSilhouette(points, radius);
    AmbientOcclusionSettings s;
    s.radius = radius;
    s.rays = rays;
    s.steps = steps;
    double meanBound = 0.0;
    for (const ScreenThickness mode : {ScreenThickness::DepthPeeling, ScreenThickness::Constant}) {
        s.thicknessMode = mode; // Constant: the thickness is the radius
        const Image ao = f.run(s);
        int checked = 0, outside = 0, clearChecked = 0, clearOutside = 0;
        double meanError = 0.0, meanWindow = 0.0, sumSigma2 = 0.0;
        for (int y = 0; y < H; ++y)
            for (int x = 0; x < W; ++x) {
                const std::size_t i = std::size_t(y) * W + std::size_t(x);
                if (!points.points[i].surface() || !f.ballOnScreen(x, y, radius)) continue;
                const double a = lo.value.pixels[i], b = hi.value.pixels[i], value = ao.at(x, y, 0);
                // Five standard deviations of the GPU's mean of `rays` binary samples (the
                // rotated Hammersley set taken as random: conservative) and of the reference's,
                // and the 16-bit float rounding of the stored value (to nearest, roundedToHalf:
                // at most 2^-12 below 1).
                const double p = std::clamp(0.5 * (a + b), 1.0 / rays, 1.0 - 1.0 / rays);
                const double sigma = std::sqrt(p * (1.0 - p) / rays + p * (1.0 - p) / rs.samplesPerPixel);
                const double tolerance = 5.0 * sigma + std::ldexp(1.0, -12);
                const bool in = value >= a - tolerance && value <= b + tolerance;
                outside += in ? 0 : 1;
                if (clear[i]) {
                    ++clearChecked;
                    clearOutside += in ? 0 : 1;
                }
                meanError += value - 0.5 * (a + b);
                meanWindow += 0.5 * (b - a);
                sumSigma2 += sigma * sigma;
                ++checked;
            }
        meanError /= checked;
        // Independent pixels: their mean stays within the mean window plus five standard
        // deviations of a mean, plus the half-float rounding, which need not average out.
        meanBound = meanWindow / checked + 5.0 * std::sqrt(sumSigma2) / checked + std::ldexp(1.0, -12);
        INFO((mode == ScreenThickness::DepthPeeling ? "peeled" : "constant")
             << ": " << checked << " pixels, " << outside << " outside their window (" << clearOutside << " of "
             << clearChecked << " without a silhouette in reach); mean error " << meanError << ", bound " << meanBound);
        CHECK(checked > W * H / 4);
        CHECK(clearChecked > W * H / 20);
        if (mode == ScreenThickness::DepthPeeling) {
            // Where no silhouette is in reach the depth buffer and its back layer hold
            // all the geometry within the radius: every pixel is within its window. Near
            // silhouettes two things the pixel grid cannot resolve remain (a sample within
            // a pixel footprint of an edge is judged by the plane at the pixel's centre;
            // floor hidden behind the box is unknown): they are in the mean.
            CHECK(clearOutside == 0);
            CHECK(std::abs(meanError) <= meanBound);
        } else {
            // A constant thickness fills the space behind the box: rays passing behind it
            // count as occluded, which the mean shows beyond its bound.
            CHECK(meanError < -meanBound);
        }
    }
}

namespace {

// The box room's occluders (builtin_scenes.cpp) grown by `grow` on every side: the room's
// open space shrinks and the small box grows.
constexpr double kRoomHalf = 3.0, kRoomHeight = 3.0, kBoxHalf = 0.5, kBoxHeight = 1.0;

Scene grownRoom(double grow) {
    Scene scene = test::singleMeshScene(test::cubeMesh());
    const auto box = [](glm::dvec3 lo, glm::dvec3 hi) {
        return glm::mat4(glm::translate(glm::dmat4(1.0), lo) * glm::scale(glm::dmat4(1.0), hi - lo));
    };
    scene.meshes[0].model = box({-kRoomHalf + grow, grow, -kRoomHalf + grow}, {kRoomHalf - grow, kRoomHeight - grow, kRoomHalf - grow});
    Mesh small = scene.meshes[0];
    small.model = box({-kBoxHalf - grow, -grow, -kBoxHalf - grow}, {kBoxHalf + grow, kBoxHeight + grow, kBoxHalf + grow});
    scene.meshes.push_back(small);
    return scene;
}

// Whether p lies inside the grown occluders: in a wall's grown slab or in the grown box.
bool insideGrown(const glm::dvec3& p, double grow) {
    const bool inRoom = std::abs(p.x) < kRoomHalf - grow && std::abs(p.z) < kRoomHalf - grow && p.y > grow &&
                        p.y < kRoomHeight - grow;
    const bool inBox = std::abs(p.x) <= kBoxHalf + grow && std::abs(p.z) <= kBoxHalf + grow && p.y >= -grow &&
                       p.y <= kBoxHeight + grow;
    return !inRoom || inBox;
}

} // namespace

TEST_CASE("Voxel AO in a box room lies between the reference's AO of the room and of the room grown by a voxel",
          "[ao][reference][voxel]") {
    // A voxel is set when a triangle overlaps its closed box (voxelize_surface.geom.glsl), so
    // the set voxels hold every surface and lie within one voxel side of one (per axis).
    // Voxel AO's rays start a voxel diagonal off the surface (p + n lift; the shader adds the
    // depth's error and a 2^-8 margin, about 1 % of it here) and count a hit in
    // any set voxel they cross within r (exact and hierarchical traversals): a ray that meets
    // the room from there meets a set voxel no later, and a ray that meets a set voxel meets
    // the room grown by a side. So its expectation lies between the reference's AO_r from the
    // lifted start in the grown room (0 where the start is inside it) and in the room itself.
    // (The voxelizer grows the boxes it tests against float rounding by 1e-5 voxels plus a
    // few ulps of the triangle's extent, at most 2.5e-4 voxels here: no further voxel is set.) Here the walls lie on voxel faces, so both neighbours
    // are set and the voxels are nearly the grown room: the means sit at the windows' lower
    // edges. Measured when written: rays cut to 0.85 r fail the mean at 512; half the lift
    // fails every pixel.
    constexpr int W = 96, H = 72;
    RoomFixture f(W, H);
    constexpr float radius = 0.6f;
    constexpr int rays = 256;
    const reference::RayScene room(f.room.scene);
    const reference::ShadingPoints points = reference::fromGBuffer(room, f.camera, f.positions, f.normals);
    reference::RenderSettings rs;
    rs.samplesPerPixel = 1024;
    Voxelizer voxelizer(f.ctx);
    for (const int resolution : {128, 512}) {
        // Cubic voxels of side 6.4 / resolution; the walls' planes fall on voxel faces.
        const VoxelizerSettings grid = test::boxVoxels({-3.2f, -0.2f, -3.2f}, {3.2f, 6.2f, 3.2f}, resolution);
        const double side = 6.4 / resolution, lift = std::sqrt(3.0) * side;
        reference::ShadingPoints lifted = points;
        for (reference::ShadingPoint& p : lifted.points)
            if (p.surface()) p.position += p.normal * lift;
        const reference::Reference hi = reference::render(room, lifted, reference::AmbientOcclusion{radius, true}, rs);
        const reference::Reference lo =
            reference::render(reference::RayScene(grownRoom(side)), lifted, reference::AmbientOcclusion{radius, true}, rs);
        AmbientOcclusionSettings s;
        s.method = AoMethod::Voxel;
        s.voxels = &voxelizer.voxelize(f.room.scene, grid);
        s.radius = radius;
        s.rays = rays;
        for (const VoxelTraversal traversal : {VoxelTraversal::Exact, VoxelTraversal::Hierarchical}) {
            CAPTURE(resolution, static_cast<int>(traversal));
            s.voxelTraversal = traversal;
            const Image ao = f.run(s);
            int checked = 0, outside = 0, inside = 0;
            double meanError = 0.0, meanWindow = 0.0, sumSigma2 = 0.0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    const std::size_t i = std::size_t(y) * W + std::size_t(x);
                    if (!points.points[i].surface()) continue;
                    const bool buried = insideGrown(lifted.points[i].position, side);
                    inside += buried ? 1 : 0;
                    const double a = buried ? 0.0 : lo.value.pixels[i], b = hi.value.pixels[i], value = ao.at(x, y, 0);
                    // As in the test above: five standard deviations of the GPU's and the
                    // reference's means, and the half float's rounding.
                    const double p = std::clamp(0.5 * (a + b), 1.0 / rays, 1.0 - 1.0 / rays);
                    const double sigma = std::sqrt(p * (1.0 - p) / rays + p * (1.0 - p) / rs.samplesPerPixel);
                    const double tolerance = 5.0 * sigma + std::ldexp(1.0, -12);
                    if (value < a - tolerance || value > b + tolerance) {
                        ++outside;
                        UNSCOPED_INFO("pixel " << x << ", " << y << ": " << value << " outside [" << a << ", " << b << "] +- " << tolerance);
                    }
                    meanError += value - 0.5 * (a + b);
                    meanWindow += 0.5 * (b - a);
                    sumSigma2 += sigma * sigma;
                    ++checked;
                }
            meanError /= checked;
            const double meanBound = meanWindow / checked + 5.0 * std::sqrt(sumSigma2) / checked + std::ldexp(1.0, -12);
            INFO(checked << " pixels (" << inside << " start inside the grown room), mean error " << meanError
                         << " from the windows' centres, bound " << meanBound << " (mean window +-" << meanWindow / checked << ")");
            CHECK(checked > W * H / 2);
            CHECK(outside == 0);
            CHECK(std::abs(meanError) <= meanBound);
        }
    }
}

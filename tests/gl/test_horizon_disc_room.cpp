// Horizon-based AO (AoMethod::Horizon) under a disc and in a box room, against its own
// slice integral (horizon_window.hpp), and under the disc against the closed form too.
//
// The method takes the depth buffer for a height field: on each side of a slice everything
// between the highest point within r and the normal's plane counts as occluded, so under a
// disc it also hides the sky beyond the disc's far rim. Its estimate is the slice integral,
// and that integral can only be below the true AO_r there (a direction nearer v than the
// horizon that met the disc within r would meet a point the camera sees, on that side of the
// slice, with a larger cosine than the horizon's: nothing under the disc is hidden from the
// camera). Where r covers the disc AO_r is the closed form.
#include "ao_fixture.hpp"
#include "horizon_window.hpp"

#include "obscura/assets.hpp"

#include <catch2/catch.hpp>
#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

using namespace obscura;
namespace horizon = obscura::test::horizon;

TEST_CASE("Horizon AO under a disc matches its slice integral and lies below the closed form within the sampling bounds",
          "[ao]") {
    constexpr double a = 1.0, h = 1.0;
    const Scene scene = test::withDisc(test::floorScene(20.0), a, h);
    constexpr int size = 128;
    // r covers the disc from rho < 0.4: sqrt(h^2 + (a + 0.4)^2) = 1.72.
    const horizon::Sampling sampling{1.8, 128, 128};
    // The disc's underside (normal down); the 256-gon of withDisc lies between these radii.
    horizon::Face disc;
    disc.discInner = a * (1.0 - 2.5e-5) * (1.0 - 1e-6); // and float vertices
    disc.discOuter = a * (1.0 + 5e-5) * (1.0 + 1e-6);
    // Both views see the floor under the disc through the gap under the rim nearer the camera,
    // and the whole disc (checked below): nothing the closed form counts is lost at the
    // border. Perspective: from below the disc at a distance, where its underside is seen less
    // obliquely than from farther off (the windows' width comes mostly from how far a pixel's
    // rounding moves a sample on the disc). Orthographic: from above, looking down 25 degrees,
    // so from rho < 0.4 the way to the camera passes under the near rim (tan 25 * 1.4 =
    // 0.65 < h).
    const float elevation = glm::radians(25.0f);
    const glm::vec3 back(0.0f, std::sin(elevation), std::cos(elevation));
    const Camera cameras[] = {
        Camera::perspective({{0.0f, 0.3f, 2.0f}, {0.0f, 0.55f, 0.0f}, {0.0f, 1.0f, 0.0f}}, glm::radians(70.0f), 1.0f, 0.05f, 200.0f),
        Camera::orthographic({glm::vec3(0.0f, 0.5f, 0.0f) + 6.0f * back, {0.0f, 0.5f, 0.0f}, {0.0f, 1.0f, 0.0f}}, 1.3f, 1.0f, 0.5f, 30.0f)};
    for (const Camera& camera : cameras) {
        const bool perspective = camera.projection[2][3] == -1.0f;
        CAPTURE(perspective);
        test::AoFixture f;
        f.render(scene, camera, size, size);
        const Image ao = f.run(scene, sampling.settings());
        for (int i = 0; i < 256; ++i) { // the 256-gon's corners, all in the image
            const double angle = 2.0 * glm::pi<double>() * i / 256;
            const glm::vec4 clip = camera.projection * camera.view *
                                   glm::vec4(float(disc.discOuter * std::cos(angle)), float(h), float(disc.discOuter * std::sin(angle)), 1.0f);
            CHECK(std::max(std::abs(clip.x), std::abs(clip.y)) < 0.98f * clip.w);
        }
        const Image normals = readTexture(f.ctx, f.view.normal);
        const glm::dmat4 view(f.view.camera.view);
        disc.point = disc.discCentre = glm::dvec3(view * glm::dvec4(0.0, h, 0.0, 1.0));
        // The side the camera sees: the underside in perspective, the top in the orthographic view.
        disc.normal = glm::normalize(glm::dmat3(view) * glm::dvec3(0.0, perspective ? -1.0 : 1.0, 0.0));
        const horizon::ScreenRays rays(f.view.camera, size, size);
        // How far from a pixel's centre the disc's image reaches, in pixels (the hull of its
        // corners' images).
        std::vector<glm::dvec2> rim;
        for (int i = 0; i < 256; ++i) {
            const double angle = 2.0 * glm::pi<double>() * i / 256;
            const glm::dvec4 clip = glm::dmat4(camera.projection) * view *
                                    glm::dvec4(disc.discOuter * std::cos(angle), h, disc.discOuter * std::sin(angle), 1.0);
            rim.push_back((glm::dvec2(clip) / clip.w * 0.5 + 0.5) * double(size));
        }
        const auto rimReach = [&](const horizon::FloorPixel& px) {
            double most = 0.0;
            for (const glm::dvec2& corner : rim) most = std::max(most, glm::length(corner - px.centre));
            return most;
        };
        horizon::WindowTally tally;
        int underDisc = 0;
        double meanBelowClosedForm = 0.0, provenBelow = 0.0;
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                const std::optional<horizon::FloorPixel> px = horizon::floorPixel(f, normals, x, y, sampling.radius);
                if (!px) continue;
                if (tally.checked == 0) horizon::checkAffine(rays, disc, *px, sampling.radius);
                const horizon::AoWindow w = horizon::obliqueWindow(*px, {disc}, rays, sampling);
                const glm::dvec3 world = f.world(x, y);
                const double value = ao.at(x, y, 0), rho = std::hypot(world.x, world.z);
                CAPTURE(x, y, world.x, world.z, value, w.lo, w.hi);
                tally.check(value, w);
                // The closed form needs every point of the disc within r sampled: in perspective
                // the radius in pixels at p may fall short of a nearer rim that is within r.
                if (rho > 0.4 || rimReach(*px) > px->reach - 1.0) continue;
                // The integral lies in the window and below AO_r, so the estimate exceeds the
                // closed form by at most the window's width (and the half float's rounding).
                const double rounding = std::ldexp(1.0, -12);
                CAPTURE(test::discAo(rho, a, h));
                CHECK(value <= test::discAo(rho, a, h) + (w.hi - w.lo) + rounding);
                meanBelowClosedForm += test::discAo(rho, a, h) - value;
                provenBelow += test::discAo(rho, a, h) - w.hi;
                ++underDisc;
            }
        INFO(tally.summary());
        INFO("under the disc (rho <= 0.4, " << underDisc << " pixels) the estimate lies " << meanBelowClosedForm / underDisc
                                            << " below the closed form on average, its window's top "
                                            << provenBelow / underDisc << " (the height field's bias)");
        CHECK(tally.checked > 3000);
        CHECK(tally.occluded > 1500);
        CHECK(underDisc > 80);
        // Measured when written: +-0.031 in perspective, +-0.026 orthographic; under the disc
        // the estimate lay 0.091 and 0.187 below the closed form, the window's top 0.045 and
        // 0.152. Each a shader change then undone, checks of both views that fail: the weight
        // of every slice taken as 1, 9364; slice angles over [0, pi / 2) only, 13722; v =
        // (0, 0, 1) in perspective, 4297. Not caught here (the wall's test in
        // test_horizon_ao.cpp catches all three, the box's there the second): the radius in
        // pixels 10 % short (1 check, too few to count on); hits beyond 0.97 r dropped (the
        // horizon here is mostly the near rim, well within r); the slices' offset taken as 0.5.
        CHECK(tally.halfWidth() < 0.04);
    }
}

// The box room (assets' "box_room": walls and ceiling of [-3, 3] x [0, 3] x [-3, 3], a box
// [-0.5, 0.5] x [0, 1] x [-0.5, 0.5] on the floor) from its own camera: every floor pixel
// against the slice integral of the faces the camera sees within r of it (the room's walls
// and ceiling, the box's top and its two sides that face the camera). Only the box can hide
// anything, and only parts of the walls: the box's projection is a hole in the walls.
namespace {

// A face of an axis-aligned box on its plane `axis` = value, facing the camera along `facing`
// (+1 or -1), cut to the box's extent in the other two axes; 1 mm above the floor where it
// stands on it.
horizon::Face boxFace(const glm::dmat4& view, int axis, double value, double facing, glm::dvec3 lo, glm::dvec3 hi) {
    glm::dvec3 normal(0.0), point(0.0);
    normal[axis] = facing;
    point[axis] = value;
    std::vector<horizon::Face::Bound> bounds;
    for (int other = 0; other < 3; ++other) {
        if (other == axis) continue;
        glm::dvec3 up(0.0);
        up[other] = 1.0;
        bounds.push_back({up, -lo[other], other == 1 && lo[other] == 0.0 ? 1e-3 : 0.0}); // x >= lo
        bounds.push_back({-up, hi[other], 0.0});                                      // x <= hi
    }
    return horizon::viewFace(view, normal, point, bounds);
}

// The distance from p to the box [lo, hi].
double boxDistance(glm::dvec3 p, glm::dvec3 lo, glm::dvec3 hi) {
    return glm::length(glm::max(glm::max(lo - p, p - hi), glm::dvec3(0.0)));
}

} // namespace

TEST_CASE("Horizon AO in a box room matches its slice integral within the sampling bounds", "[ao]") {
    const assets::LoadedScene room = assets::builtinScene("box_room");
    constexpr int W = 128, H = 96;
    const Camera camera = assets::makeCamera(room.camera, W, H);
    test::AoFixture f;
    f.render(room.scene, camera, W, H);
    const horizon::Sampling sampling{1.2, 128, 128};
    AmbientOcclusionSettings s;
    s.method = AoMethod::Horizon;
    s.radius = float(sampling.radius);
    s.rays = 2 * sampling.slices;
    s.steps = sampling.steps;
    const Image ao = f.run(room.scene, s);
    const Image normals = readTexture(f.ctx, f.view.normal);
    const glm::dmat4 view(camera.view);
    const glm::dvec3 eye = glm::dvec3(glm::inverse(view)[3]);
    const glm::dvec3 roomLo(-3.0, 0.0, -3.0), roomHi(3.0, 3.0, 3.0), boxLo(-0.5, 0.0, -0.5), boxHi(0.5, 1.0, 0.5);
    // The box's projection (its corners', all in front of the camera), in GL pixels.
    glm::dvec2 holeLo(1e30), holeHi(-1e30);
    for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec3 c(corner & 1 ? boxHi.x : boxLo.x, corner & 2 ? boxHi.y : boxLo.y, corner & 4 ? boxHi.z : boxLo.z);
        const glm::dvec4 clip = glm::dmat4(camera.projection) * view * glm::dvec4(c, 1.0);
        REQUIRE(clip.w > 0.0);
        const glm::dvec2 pixel = (glm::dvec2(clip) / clip.w * 0.5 + 0.5) * glm::dvec2(W, H);
        holeLo = glm::min(holeLo, pixel);
        holeHi = glm::max(holeHi, pixel);
    }
    struct Placed {
        horizon::Face face;
        glm::dvec3 lo, hi; // its extent, to leave it out where it is beyond r
    };
    std::vector<Placed> faces;
    for (int axis : {0, 2}) // the walls, facing in
        for (const double side : {-1.0, 1.0}) {
            glm::dvec3 lo = roomLo, hi = roomHi;
            lo[axis] = hi[axis] = side * 3.0;
            faces.push_back({boxFace(view, axis, side * 3.0, -side, roomLo, roomHi), lo, hi});
            faces.back().face.holes.push_back({holeLo, holeHi});
        }
    faces.push_back({boxFace(view, 1, 3.0, -1.0, roomLo, roomHi), {-3.0, 3.0, -3.0}, {3.0, 3.0, 3.0}}); // the ceiling
    for (int axis = 0; axis < 3; ++axis) { // the box's faces toward the camera
        glm::dvec3 lo = boxLo, hi = boxHi;
        lo[axis] = boxHi[axis];
        REQUIRE(eye[axis] > boxHi[axis]);
        faces.push_back({boxFace(view, axis, boxHi[axis], 1.0, boxLo, boxHi), lo, hi});
    }
    const horizon::ScreenRays rays(camera, W, H);
    horizon::WindowTally tally;
    int nearWall = 0, nearBox = 0; // pixels (no pixel the camera sees is within r of both)
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const std::optional<horizon::FloorPixel> px = horizon::floorPixel(f, normals, x, y, sampling.radius);
            if (!px) continue;
            const glm::dvec3 world = f.world(x, y);
            std::vector<horizon::Face> near;
            for (const Placed& placed : faces)
                if (boxDistance(world, placed.lo, placed.hi) <= sampling.radius * (1.0 + 1e-4)) near.push_back(placed.face);
            if (tally.checked == 0) horizon::checkAffine(rays, faces.front().face, *px, sampling.radius);
            const horizon::AoWindow w = horizon::obliqueWindow(*px, near, rays, sampling);
            CAPTURE(x, y, world.x, world.z, near.size(), ao.at(x, y, 0), w.lo, w.hi);
            tally.check(ao.at(x, y, 0), w);
            // Within r of the box: of its top and a side at least (several faces' horizons).
            (boxDistance(world, boxLo, boxHi) <= sampling.radius ? nearBox : nearWall) += near.empty() ? 0 : 1;
        }
    INFO(tally.summary() << "; " << nearBox << " of them within r of the box, " << nearWall << " of a wall");
    CHECK(tally.checked > 3000);
    CHECK(nearBox > 1000);
    CHECK(nearWall > 1000);
    CHECK(tally.occluded > 3000);
    // Measured when written: +-0.022. Each a change then undone, checks that fail: the
    // weight of every slice taken as 1, 964; v = (0, 0, 1), 348; the radius in pixels 10 %
    // short, 41; slice angles over [0, pi / 2) only, 3633; the box's sides left out of the
    // model, 3528. Not caught: hits beyond 0.97 r dropped; the slices' offset taken as 0.5;
    // and the walls' hole left out (so this view never needs it).
    CHECK(tally.halfWidth() < 0.03);
}

// Horizon-based AO (AoMethod::Horizon, GTAO-style) against its own slice integral, on a
// floor beside a box seen from straight above.
//
// Why this view: in an orthographic view from above every slice plane is vertical and the
// view direction is the floor's normal, so the slice weights are all 1 and the normal's angle
// in each slice is 0. The depth buffer holds the box's top (its sides are edge-on), so in a
// direction phi the highest point within the radius r is the nearest point of the top's edge,
// at horizontal distance t(phi), if it lies within r: its elevation e has
// sin^2 e = h^2 / (t^2 + h^2), h the box's height. GTAO's arc for a horizon at elevation e,
// cosine-weighted with the normal at angle 0, is (1 - sin^2 e) / 2 per side, against 1/2
// open, so
//   AO = 1 - (1 / 2pi) Integral_0^2pi sin^2 e(phi) dphi.
// This is what the method estimates, not AO_r: a direction whose ray would meet the box's
// side within r while its top edge is beyond r counts as open here. (AO_r itself is tested on
// the other methods in test_ambient_occlusion.cpp.) This view makes the projected normal's
// weight and angle g of every slice 1 and 0: the second test, a floor before a wall seen
// obliquely, covers them.
#include "ao_fixture.hpp"
#include "horizon_window.hpp"

#include "core/sampling.hpp"
#include "gl_fixture.hpp"
#include "shaders/common/common_bindings.h"

#include <catch2/catch.hpp>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>
#include <vector>

using namespace obscura;
namespace horizon = obscura::test::horizon;

namespace {

constexpr double kPi = glm::pi<double>();

// The box [-b, b] x [0, h] x [-b, b] on the floor, the view and the settings.
struct BoxView {
    double b = 0.5, h = 0.5;
    double halfHeight = 1.6; // orthographic: 3.2 world units over the image's height
    int size = 128;          // pixels; 40 a world unit, so the box's edges lie on pixel edges
    double radius = 1.0;
    int slices = 256, steps = 64;

    double pixel() const { return 2.0 * halfHeight / size; }
    double spacing() const { return radius / steps; } // between depth samples, world units
    double lambda() const { return 0.72 * pixel(); }  // sqrt(1/2) pixels and float rounding
};

// Where the horizontal ray from (x, z) in `direction` enters and leaves the box's
// footprint (slab method); none when it misses.
struct Crossing {
    bool hit = false;
    double in = 0.0, out = 0.0;
};

Crossing crossFootprint(double x, double z, glm::dvec2 direction, double b) {
    const double o[2] = {x, z}, d[2] = {direction.x, direction.y};
    double lo = 0.0, hi = 1e30;
    for (int axis = 0; axis < 2; ++axis) {
        if (std::abs(d[axis]) < 1e-15) {
            if (std::abs(o[axis]) > b) return {};
            continue;
        }
        double t0 = (-b - o[axis]) / d[axis], t1 = (b - o[axis]) / d[axis];
        if (t0 > t1) std::swap(t0, t1);
        lo = std::max(lo, t0);
        hi = std::min(hi, t1);
    }
    return hi > lo ? Crossing{true, lo, hi} : Crossing{};
}

// sin^2 of the horizon's elevation for the box's top edge at horizontal distance t (0 when
// that point is beyond the radius).
double sin2Elevation(double t, const BoxView& v) {
    const double d2 = t * t + v.h * v.h;
    return d2 <= v.radius * v.radius ? v.h * v.h / d2 : 0.0;
}

// The least and the most sin^2 e the shader can find in the directions of an arc [lo, hi]
// (narrower than pi). In one direction its j-th depth sample is the pixel holding the point at
// (j + jitter) * spacing along it (the offset rounded per axis from the pixel's centre); the
// box's edges lie on pixel edges, so a sample is on the top exactly when that point is inside
// the footprint. The nearest such sample lies within a spacing past the entry, when the chord
// is at least a spacing long, and every one lies at least the entry away; a pixel's centre is
// at most half a pixel's diagonal (lambda) from the point it holds. Both bounds are monotone in
// the entry distance: over the arc the most is at the least entry distance of the directions
// that meet the footprint, and the least is 0 if a direction misses it or crosses it along
// less than a spacing, else at the largest entry distance. Between consecutive candidate
// angles (the arc's ends, the directions of the footprint's corners and the four axes, the
// perpendiculars to its sides) a ray enters and leaves through fixed sides, where the entry
// distance d / cos(phi - alpha) is convex in phi (least at the perpendicular alpha, largest
// at an end) and the chord is convex (opposite sides: least at the perpendicular) or monotone
// (adjacent sides). So the extremes over the arc are at candidates; where the directions that
// meet the footprint end inside the arc they end at a corner, which every such ray meets, at
// most its distance away.
struct Sin2Range {
    double least = 0.0, most = 0.0;
};

Sin2Range sin2Range(double x, double z, double lo, double hi, const BoxView& v) {
    struct Candidate {
        double angle;
        const glm::dvec2* corner;
    };
    const glm::dvec2 corners[4] = {{-v.b, -v.b}, {v.b, -v.b}, {v.b, v.b}, {-v.b, v.b}};
    std::vector<Candidate> candidates = {{lo, nullptr}, {hi, nullptr}};
    const auto add = [&](double angle, const glm::dvec2* corner) {
        const double a = lo + std::fmod(std::fmod(angle - lo, 2.0 * kPi) + 2.0 * kPi, 2.0 * kPi); // in [lo, lo + 2 pi)
        if (a <= hi) candidates.push_back({a, corner});
    };
    for (const glm::dvec2& c : corners) add(std::atan2(c.y - z, c.x - x), &c);
    for (int axis = 0; axis < 4; ++axis) add(0.5 * kPi * axis, nullptr);
    double leastIn = 1e30, mostIn = 0.0, leastChord = 1e30;
    bool all = true, any = false;
    for (const Candidate& c : candidates) {
        Crossing crossing = crossFootprint(x, z, {std::cos(c.angle), std::sin(c.angle)}, v.b);
        if (c.corner) { // it meets the footprint at the corner, if only grazing it
            const double toCorner = glm::length(*c.corner - glm::dvec2(x, z));
            crossing = crossing.hit ? Crossing{true, std::min(crossing.in, toCorner), crossing.out}
                                    : Crossing{true, toCorner, toCorner};
        }
        if (!crossing.hit) {
            all = false;
            continue;
        }
        any = true;
        leastIn = std::min(leastIn, crossing.in);
        mostIn = std::max(mostIn, crossing.in);
        leastChord = std::min(leastChord, crossing.out - crossing.in);
    }
    const double lambda = v.lambda();
    Sin2Range r;
    if (any) r.most = sin2Elevation(std::max(leastIn - lambda, 0.0), v);
    if (all && leastChord >= v.spacing()) r.least = sin2Elevation(mostIn + v.spacing() + lambda, v);
    return r;
}

// The horizontal distance from (x, z) to the box's footprint.
double footprintDistance(double x, double z, const BoxView& v) {
    return std::hypot(std::max(std::abs(x) - v.b, 0.0), std::max(std::abs(z) - v.b, 0.0));
}

// The range of the shader's AO at floor point (x, z). Its slices are phi_k = pi (k + u) / slices
// for one offset u per pixel, each with the directions phi_k and phi_k + pi: in each stratum
// [pi k, pi (k + 1)] / slices (widened by 1e-6 for the shader's float angles) a slice's
// occlusion, the mean of its sides' sin^2 e, lies within the range of that mean over the
// stratum, so the estimate lies within the mean over the strata of those ranges.
horizon::AoWindow aoWindow(double x, double z, const BoxView& v) {
    // No point of the top within the radius, however the pixels round: exactly open.
    const double reachable = std::max(footprintDistance(x, z, v) - v.lambda(), 0.0);
    if (reachable * reachable + v.h * v.h > v.radius * v.radius) return {};
    double least = 0.0, most = 0.0;
    for (int k = 0; k < v.slices; ++k) {
        const double lo = kPi * k / v.slices - 1e-6, hi = kPi * (k + 1) / v.slices + 1e-6;
        const Sin2Range ahead = sin2Range(x, z, lo, hi, v), behind = sin2Range(x, z, lo + kPi, hi + kPi, v);
        least += 0.5 * (ahead.least + behind.least) / v.slices;
        most += 0.5 * (ahead.most + behind.most) / v.slices;
    }
    return {1.0 - most, 1.0 - least};
}

// The window of the shader's bent normal at floor point (x, z), as ranges of its world x and z
// over its y. With g = 0 and weight 1 a slice's visible arc gives (aoBentArc) (2 - S_a - S_b) / 3
// up and C_a / 3 along each side's direction, S = sin^3 e and C = cos^3 e = (1 - sin^2 e)^(3/2)
// of that side's horizon elevation: the integrals of cos(t) and sin(t) times cos(t) |sin t| from
// the horizon's angle t = pi/2 - e to 0 (Integral_0^(pi/2 - e) cos^2 t sin t dt = (1 - S) / 3,
// Integral_0^(pi/2 - e) sin^2 t cos t dt = C / 3). Both are monotone in sin^2 e, whose range
// per side and stratum sin2Range gives, and each side's direction lies in its stratum: interval
// sums over the strata bound the three components' sums. (Screen slice angles map to world
// directions by a reflection, which takes the strata to themselves.)
struct BentWindow {
    double xLo = 0.0, xHi = 0.0, zLo = 0.0, zHi = 0.0; // x / y and z / y of the bent normal
};

BentWindow bentWindow(double x, double z, const BoxView& v) {
    double sum[3][2] = {{0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}}; // x, y, z: least and most
    const auto cube = [](double sin2) { return std::pow(sin2, 1.5); };
    const auto cosCube = [](double sin2) { return std::pow(1.0 - sin2, 1.5); };
    for (int k = 0; k < v.slices; ++k)
        for (int side = 0; side < 2; ++side) {
            const double lo = kPi * k / v.slices - 1e-6 + side * kPi, hi = kPi * (k + 1) / v.slices + 1e-6 + side * kPi;
            const Sin2Range r = sin2Range(x, z, lo, hi, v);
            const double cLo = cosCube(r.most) / 3.0, cHi = cosCube(r.least) / 3.0;
            // cos and sin over [lo, hi] (narrower than pi / 2: extremes at the ends or an axis).
            double range[2][2] = {{1e30, -1e30}, {1e30, -1e30}};
            for (double angle : {lo, hi, 0.0, 0.5 * kPi, kPi, 1.5 * kPi, 2.0 * kPi}) {
                if (angle < lo || angle > hi) continue;
                const double cs[2] = {std::cos(angle), std::sin(angle)};
                for (int c = 0; c < 2; ++c) range[c][0] = std::min(range[c][0], cs[c]), range[c][1] = std::max(range[c][1], cs[c]);
            }
            for (int c = 0; c < 2; ++c) {
                const double products[4] = {cLo * range[c][0], cLo * range[c][1], cHi * range[c][0], cHi * range[c][1]};
                sum[2 * c][0] += *std::min_element(products, products + 4);
                sum[2 * c][1] += *std::max_element(products, products + 4);
            }
            sum[1][0] += 1.0 / 3.0 - cube(r.most) / 3.0;
            sum[1][1] += 1.0 / 3.0 - cube(r.least) / 3.0;
        }
    const auto ratio = [&](int c) {
        const double q[4] = {sum[c][0] / sum[1][0], sum[c][0] / sum[1][1], sum[c][1] / sum[1][0], sum[c][1] / sum[1][1]};
        return std::pair{*std::min_element(q, q + 4), *std::max_element(q, q + 4)};
    };
    const auto [xLo, xHi] = ratio(0);
    const auto [zLo, zHi] = ratio(2);
    return {xLo, xHi, zLo, zHi};
}

} // namespace

TEST_CASE("Horizon AO beside a box seen from above matches its slice integral within the sampling bounds", "[ao]") {
    test::AoFixture f;
    const BoxView v;
    Scene scene = test::floorScene(20.0);
    const glm::mat4 box = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(float(-v.b), 0.0f, float(-v.b))),
                                     glm::vec3(float(2.0 * v.b), float(v.h), float(2.0 * v.b)));
    scene.meshes.push_back({test::cubeMesh(), box, 0, "box"});
    const LookAt look{{0.0f, 10.0f, 0.0f}, {0.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -1.0f}};
    f.render(scene, Camera::orthographic(look, float(v.halfHeight), 1.0f, 1.0f, 20.0f), v.size, v.size);
    AmbientOcclusionSettings s;
    s.method = AoMethod::Horizon;
    s.radius = float(v.radius);
    s.rays = 2 * v.slices; // two directions a slice
    s.steps = v.steps;
    s.bentNormals = true;
    const AmbientOcclusionView out = f.ao.run(f.view, s);
    const Image ao = readTexture(f.ctx, out.ao), bent = readTexture(f.ctx, out.bentNormal);
    const glm::dmat3 toWorld(glm::inverse(glm::dmat4(f.view.camera.view)));
    horizon::WindowTally tally;
    int tilted = 0;
    double widest = 0.0;
    for (int y = 0; y < v.size; ++y)
        for (int x = 0; x < v.size; ++x) {
            const glm::dvec3 p = f.world(x, y);
            if (!f.geometry(x, y) || std::abs(p.y) > 1e-3) continue; // the floor only
            // Within two pixels of the box the first samples (at least one pixel out) may
            // already be on it.
            if (footprintDistance(p.x, p.z, v) < 2.0 * v.pixel()) continue;
            const horizon::AoWindow w = aoWindow(p.x, p.z, v);
            CAPTURE(x, y, p.x, p.z, ao.at(x, y, 0), w.lo, w.hi);
            tally.check(ao.at(x, y, 0), w);
            // The bent normal, stored as half floats (2^-11 relative per component, so its
            // ratios within 2^-10 of their own size), and the shader's float sums (1e-5).
            const glm::dvec3 b = toWorld * glm::dvec3(bent.at(x, y, 0), bent.at(x, y, 1), bent.at(x, y, 2));
            const BentWindow bw = bentWindow(p.x, p.z, v);
            CAPTURE(b.x, b.y, b.z, bw.xLo, bw.xHi, bw.zLo, bw.zHi);
            REQUIRE(b.y > 0.0);
            const double rx = b.x / b.y, rz = b.z / b.y;
            const double slack = std::ldexp(std::max(std::abs(rx), std::abs(rz)), -10) + 1e-5;
            CHECK(rx >= bw.xLo - slack);
            CHECK(rx <= bw.xHi + slack);
            CHECK(rz >= bw.zLo - slack);
            CHECK(rz <= bw.zHi + slack);
            tilted += std::hypot(rx, rz) > 0.05;
            widest = std::max({widest, bw.xHi - bw.xLo, bw.zHi - bw.zLo});
        }
    INFO(tally.summary() << "; bent normals tilted by more than 0.05: " << tilted << ", widest window " << widest);
    CHECK(tilted > 500);
    // Measured when written, each a shader change then undone: hits beyond 0.97 r dropped
    // put 837 pixels outside their windows, slice angles over [0, pi / 2) only 7115.
    CHECK(tally.checked > 5000);
    CHECK(tally.occluded > 1000);
    CHECK(tally.halfWidth() < 0.015); // 1 - AO reaches about 0.3 beside the box
}

// A floor before a wall, seen obliquely from the front, orthographic and in perspective: the
// view direction leans 40 degrees below the horizontal, so the floor's normal leans out of most
// slice planes (weight < 1, g != 0, both varying with the slice's angle); in perspective v and
// the radius in pixels also vary from pixel to pixel. The window is horizon_window.hpp's, for
// the wall's face cut to where it is above the floor.
namespace {

struct WallView {
    double elevation = glm::radians(40.0); // of the view direction below the horizontal
    double halfHeight = 0.6;               // of the view at the target, world units
    double distance = 3.0;                 // from the target to the eye, world units
    int size = 256;
    horizon::Sampling sampling{0.4, 128, 128};
};

} // namespace

TEST_CASE("Horizon AO before a wall seen obliquely matches its slice integral within the sampling bounds", "[ao]") {
    const WallView view;
    Scene scene = test::floorScene(20.0);
    // The wall: x in [-5, 5], y in [0, 3], z in [-1, 0]; its face z = 0 looks at the camera.
    const glm::mat4 wallBox = glm::scale(glm::translate(glm::mat4(1.0f), glm::vec3(-5.0f, 0.0f, -1.0f)), glm::vec3(10.0f, 3.0f, 1.0f));
    scene.meshes.push_back({test::cubeMesh(), wallBox, 0, "wall"});
    const glm::vec3 target(0.0f, 0.0f, 0.24f);
    const glm::vec3 back(0.0f, float(std::sin(view.elevation)), float(std::cos(view.elevation)));
    const LookAt look{target + float(view.distance) * back, target, {0.0f, 1.0f, 0.0f}};
    // Orthographic and perspective with the full slice count; and orthographic with 2 slices,
    // where each pixel's slice offset decides which directions are sampled at all, so the
    // window must use the shader's own.
    // Then both with reversed depth (perspective with an infinite far plane), whose depth
    // buffer the shader must read as such: a standard linearization would put the floor
    // elsewhere and its windows would not hold.
    struct Case {
        bool perspective;
        int slices;
        DepthMode depth = DepthMode::Standard;
    };
    for (const Case c : {Case{false, 128}, Case{true, 128}, Case{false, 2}, Case{false, 128, DepthMode::Reversed},
                         Case{true, 128, DepthMode::Reversed}}) {
        CAPTURE(c.perspective, c.slices, static_cast<int>(c.depth));
        horizon::Sampling sampling = view.sampling;
        sampling.slices = c.slices;
        test::AoFixture f;
        const float fovy = 2.0f * std::atan(float(view.halfHeight / view.distance));
        f.render(scene,
                 c.perspective ? Camera::perspective(look, fovy, 1.0f, 0.5f, c.depth == DepthMode::Reversed ? INFINITY : 30.0f, c.depth)
                               : Camera::orthographic(look, float(view.halfHeight), 1.0f, 0.5f, 30.0f, c.depth),
                 view.size, view.size);
        const Image ao = f.run(scene, sampling.settings());
        const Image normals = readTexture(f.ctx, f.view.normal);
        const horizon::ScreenRays rays(f.view.camera, view.size, view.size);
        // The face z = 0 where it is above the floor, 1 mm well above the plane test's tolerance.
        const horizon::Face wall = horizon::viewFace(glm::dmat4(f.view.camera.view), {0.0, 0.0, 1.0}, {0.0, 0.0, 0.0},
                                                     {{{0.0, 1.0, 0.0}, 0.0, 1e-3}});
        horizon::WindowTally tally;
        for (int y = 0; y < view.size; ++y)
            for (int x = 0; x < view.size; ++x) {
                const std::optional<horizon::FloorPixel> px = horizon::floorPixel(f, normals, x, y, sampling.radius);
                if (!px) continue;
                // Every sample inside the image (the shader stops a side at the border).
                const double margin = px->reach + 2.0;
                if (px->centre.x < margin || px->centre.y < margin || px->centre.x > view.size - margin || px->centre.y > view.size - margin)
                    continue;
                if (tally.checked == 0) horizon::checkAffine(rays, wall, *px, sampling.radius);
                const horizon::AoWindow w = horizon::obliqueWindow(*px, {wall}, rays, sampling);
                CAPTURE(x, y, f.world(x, y).z, ao.at(x, y, 0), w.lo, w.hi);
                tally.check(ao.at(x, y, 0), w);
            }
        INFO(tally.summary());
        CHECK(tally.checked > 4000);
        CHECK(tally.occluded > 3000);
        // 1 - AO is up to about 0.5 here; the windows measured +-0.0072 (orthographic),
        // +-0.0065 (perspective) and +-0.0076 (2 slices), before the reversed-depth views were
        // added (their widths are in the summary above; the 0.02 bound covers them). Each a shader change then undone,
        // checks of the two 128-slice views that fail: the weight of every slice taken as 1
        // (0.64 to 1 here), 6093; the radius in pixels 10 % short, 5285; slice angles over
        // [0, pi / 2) only, 935; hits beyond 0.97 r dropped, 746. Of the 2-slice view only: the
        // slices' offset taken as 0.5, 2910; from the noise's other value, 3179; from the
        // pixel's row counted down, 3240 (with 128 slices a shift within a stratum moves the
        // sum by little). Not caught: v = (0, 0, 1) in perspective, at most 5 degrees off over
        // these pixels, moves the mean by only 0.0005 (about any axis, slices cover the same
        // hemisphere; the samples, off the assumed slices then, change little).
        CHECK(tally.halfWidth() < 0.02);
    }
}

// The horizon windows (horizon_window.cpp, kAngleError) take a slice's angle as the shader
// computes it to within 8 2^-24 of pi, and the driver's sin and cos to within 1e-5, which
// GLSL 4.50 does not promise: this checks both on the driver at hand, over the slice angles
// pi (k + u) / N of 128 slices and every offset u of the noise texture. Measured on llvmpipe
// (Mesa 22.3): the angle within 2.9e-7 rad of pi (k + u) / N, cos within 7.6e-8, sin 6.8e-8.
TEST_CASE("sin and cos of the horizon's slice angles are within 1e-5 on this driver", "[ao]") {
    test::GlFixture gl;
    constexpr int slices = 128, offsets = OBSCURA_NOISE_SIZE * OBSCURA_NOISE_SIZE;
    const char* source = R"(#version 450 core
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Offsets { float offsets[]; };
layout(std430, binding = 1) writeonly buffer Results { vec4 results[]; };
layout(location = 0) uniform int slices;
void main() {
    const uint i = gl_GlobalInvocationID.x, k = i % uint(slices);
    const float phi = 3.14159265358979323846 * (float(k) + offsets[i / uint(slices)]) / float(slices);
    results[i] = vec4(phi, cos(phi), sin(phi), 0.0);
}
)";
    const GLuint shader = glCreateShader(GL_COMPUTE_SHADER);
    glShaderSource(shader, 1, &source, nullptr);
    glCompileShader(shader);
    const GLuint program = glCreateProgram();
    glAttachShader(program, shader);
    glLinkProgram(program);
    glDeleteShader(shader);
    GLint linked = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &linked);
    REQUIRE(linked == GL_TRUE);
    std::vector<float> u;
    for (int y = 0; y < OBSCURA_NOISE_SIZE; ++y)
        for (int x = 0; x < OBSCURA_NOISE_SIZE; ++x) u.push_back(detail::noiseTexel(x, y).x);
    GLuint buffers[2];
    glCreateBuffers(2, buffers);
    glNamedBufferStorage(buffers[0], GLsizeiptr(u.size() * sizeof(float)), u.data(), 0);
    glNamedBufferStorage(buffers[1], GLsizeiptr(slices) * offsets * sizeof(glm::vec4), nullptr, GL_MAP_READ_BIT);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
    glUseProgram(program);
    glUniform1i(0, slices);
    glDispatchCompute(slices * offsets / 64, 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<glm::vec4> results(std::size_t(slices) * offsets);
    glGetNamedBufferSubData(buffers[1], 0, GLsizeiptr(results.size() * sizeof(glm::vec4)), results.data());
    glUseProgram(0);
    glDeleteProgram(program);
    glDeleteBuffers(2, buffers);
    double angle = 0.0, cosine = 0.0, sine = 0.0;
    for (std::size_t i = 0; i < results.size(); ++i) {
        const double phi = results[i].x, exact = kPi * (double(i % slices) + u[i / slices]) / slices;
        angle = std::max(angle, std::abs(phi - exact));
        cosine = std::max(cosine, std::abs(results[i].y - std::cos(phi)));
        sine = std::max(sine, std::abs(results[i].z - std::sin(phi)));
    }
    INFO("largest errors: angle " << angle << " rad, cos " << cosine << ", sin " << sine);
    CHECK(angle <= 8.0 * std::ldexp(1.0, -24) * kPi);
    CHECK(cosine <= 1e-5);
    CHECK(sine <= 1e-5);
}

TEST_CASE("Horizon bent normals of an open floor seen obliquely are its normal", "[ao]") {
    // Nothing above the floor: every slice's visible arc is its whole half circle, where the
    // normal leans out of the slice plane (weight < 1) and away from v in it (g != 0) by
    // amounts that vary with the slice's angle. Each slice's share (aoBentArc) is not along
    // the normal, but their sum over the slices, weighted by how far each turns the slice
    // plane about v, is the cosine-weighted mean of the hemisphere, the normal. Orthographic
    // (v constant, no turn): an open slice's share is (2/3)(n.v) v + (4/3)(n.s) s, s its side
    // direction, whose sum over N >= 2 equally spaced slices is (2/3) N n exactly, so 4 slices
    // suffice. Perspective: the turn-weighted shares sample a smooth periodic function of the
    // slice angle at equal spacing, whose sum converges geometrically (periodic trapezoid
    // rule): measured 3.6e-3 rad at 4 slices and 1.3e-4 at 32, so only 32 run here.
    // The bound: the stored half floats, each component within 2^-10 of its size (stores may
    // round toward zero), turn the vector by at most 2^-10 rad; 5e-4 more for the shader's
    // float sums and perspective's remaining 1.3e-4. Measured when written: without the turn
    // weights 0.067 rad in perspective; a wrong term in g or in the weight does not cancel.
    test::AoFixture f;
    const Scene scene = test::floorScene(50.0);
    constexpr int W = 48, H = 40;
    const LookAt look{{1.0f, 1.5f, 5.0f}, {0.0f, 0.0f, 0.0f}, {0, 1, 0}};
    struct View {
        const char* name;
        Camera camera;
    };
    const View views[] = {{"perspective", test::lookAt(look.eye, look.target, W, H)},
                          {"orthographic", Camera::orthographic(look, 2.0f, float(W) / H, 0.05f, 100.0f)}};
    const glm::dvec3 up(0.0, 1.0, 0.0);
    for (const View& view : views) {
        f.render(scene, view.camera, W, H);
        const glm::dmat3 toWorld(glm::inverse(glm::dmat4(f.view.camera.view)));
        for (int slices : {4, 32}) {
            if (std::string_view(view.name) == "perspective" && slices < 32) continue;
            CAPTURE(view.name, slices);
            AmbientOcclusionSettings s;
            s.method = AoMethod::Horizon;
            s.radius = 1.0f;
            s.rays = 2 * slices;
            s.bentNormals = true;
            const AmbientOcclusionView out = f.ao.run(f.view, s);
            const Image bent = readTexture(f.ctx, out.bentNormal);
            int checked = 0;
            double worst = 0.0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    if (!f.geometry(x, y)) continue;
                    const glm::dvec3 b = toWorld * glm::dvec3(bent.at(x, y, 0), bent.at(x, y, 1), bent.at(x, y, 2));
                    worst = std::max(worst, std::acos(std::clamp(glm::dot(glm::normalize(b), up), -1.0, 1.0)));
                    ++checked;
                }
            INFO("largest angle from the normal " << worst << " rad over " << checked << " pixels");
            CHECK(checked > W * H / 3);
            CHECK(worst < std::ldexp(1.0, -10) + 5e-4);
        }
    }
}

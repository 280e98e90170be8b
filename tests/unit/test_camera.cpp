// Camera math without GL: projections, their analysis and the depth reconstruction constants.
#include "obscura/camera.hpp"
#include "obscura/error.hpp"

#include <catch2/catch.hpp>

#include <cmath>

using namespace obscura;

namespace {
// Window depth of view-space point p, computed in double from the float matrix.
double depthOf(const Camera& c, const glm::dvec3& p) {
    const glm::dvec4 clip = glm::dmat4(c.projection) * glm::dvec4(p, 1.0);
    const double zn = clip.z / clip.w;
    return c.clipDepth == ClipDepth::ZeroToOne ? zn : 0.5 * zn + 0.5;
}
} // namespace

TEST_CASE("Projections map near and far to the documented depths", "[unit][camera]") {
    const LookAt look{{0, 0, 0}, {0, 0, -1}, {0, 1, 0}};
    for (DepthMode mode : {DepthMode::Standard, DepthMode::StandardZeroToOne, DepthMode::Reversed}) {
        const Camera c = Camera::perspective(look, 1.0f, 1.5f, 0.1f, 1000.0f, mode);
        const ProjectionInfo info = analyzeProjection(c);
        CHECK(info.kind == ProjectionKind::Perspective);
        CHECK(info.nearPlane == Approx(0.1).epsilon(1e-6));
        // The float matrix pins the far plane only to about (far/near) * 2^-23 relative: its
        // depth row is 1 + O(near/far), rounded to float.
        CHECK(info.farPlane == Approx(1000.0).epsilon(1e4 * std::ldexp(1.0, -23)));
        CHECK(info.reversedZ == (mode == DepthMode::Reversed));
        CHECK(depthOf(c, {0, 0, -0.1}) == Approx(info.reversedZ ? 1.0 : 0.0).margin(1e-6));
        CHECK(depthOf(c, {0, 0, -1000}) == Approx(info.reversedZ ? 0.0 : 1.0).margin(1e-6));
        const Camera o = Camera::orthographic(look, 2.0f, 1.5f, 0.1f, 1000.0f, mode);
        CHECK(analyzeProjection(o).kind == ProjectionKind::Orthographic);
        CHECK(analyzeProjection(o).farPlane == Approx(1000.0).epsilon(1e-5));
    }
    const Camera infinite = Camera::perspective(look, 1.0f, 1.0f, 0.1f, INFINITY, DepthMode::Reversed);
    CHECK(std::isinf(analyzeProjection(infinite).farPlane));
    CHECK(analyzeProjection(infinite).clearDepth == 0.0f);
}

TEST_CASE("Depth reconstruction constants invert the float projection", "[unit][camera]") {
    // Float emulation of the shader (depth.glsl), against the exact double inverse.
    const LookAt look{{1, 2, 3}, {0, 0, 0}, {0, 1, 0}};
    for (DepthMode mode : {DepthMode::Standard, DepthMode::StandardZeroToOne, DepthMode::Reversed}) {
        const Camera c = Camera::perspective(look, 0.9f, 1.3f, 0.1f, 1000.0f, mode);
        const DepthReconstruction r = depthReconstruction(c);
        for (double z : {0.1, 0.5, 3.0, 40.0, 333.0, 999.0}) {
            const float d = static_cast<float>(depthOf(c, {0, 0, -z}));
            const float zr = r.zScale / ((d + r.zBiasHi) + r.zBiasLo);
            const double exact = viewPositionFromDepth(c, {0, 0}, d).z;
            CAPTURE(static_cast<int>(mode), z);
            CHECK(std::abs(zr - exact) / std::abs(exact) < 1e-6);
        }
        const glm::dvec3 p = viewPositionFromDepth(c, {0.5, -0.25}, depthOf(c, {0.3, -0.2, -7.0}));
        CHECK(p.z == Approx(-7.0).epsilon(1e-6));
    }
}

TEST_CASE("The farthest depth lies at kMaxViewDistance where the far plane is beyond it, else at the clear depth",
          "[unit][camera]") {
    // Depths beyond farthestDepth are background (isBackgroundDepth): with a far plane past
    // kMaxViewDistance it must map back to that distance (float rounding of the depth, 2^-24
    // relative to it, and of the reconstruction: 1e-6 relative), and on the near side of it
    // every depth stays within it; with a nearer far plane it is the clear depth, which
    // leaves out nothing else.
    const LookAt look{{1, 2, 3}, {0, 0, 0}, {0, 1, 0}};
    for (DepthMode mode : {DepthMode::Standard, DepthMode::StandardZeroToOne, DepthMode::Reversed}) {
        CAPTURE(static_cast<int>(mode));
        for (const Camera& c : {Camera::perspective(look, 0.9f, 1.3f, 0.1f, 1000.0f, mode),
                                Camera::orthographic(look, 2.0f, 1.5f, 0.1f, 1000.0f, mode)}) {
            const DepthReconstruction r = depthReconstruction(c);
            CHECK(r.farthestDepth == r.clearDepth);
        }
    }
    const Camera infinite = Camera::perspective(look, 0.9f, 1.3f, 10.0f, INFINITY, DepthMode::Reversed);
    const Camera hugeOrtho = Camera::orthographic(look, 2.0f, 1.5f, 1e16f, 1e18f, DepthMode::Reversed);
    const Camera hugeOrthoStandard = Camera::orthographic(look, 2.0f, 1.5f, 1e16f, 1e18f, DepthMode::StandardZeroToOne);
    for (const Camera& c : {infinite, hugeOrtho, hugeOrthoStandard}) {
        const DepthReconstruction r = depthReconstruction(c);
        CAPTURE(r.farthestDepth);
        CHECK(r.farthestDepth > 0.0f);
        CHECK(r.farthestDepth < 1.0f);
        CHECK(-viewPositionFromDepth(c, {0, 0}, r.farthestDepth).z == Approx(kMaxViewDistance).epsilon(1e-6));
        const float nearer = std::nextafter(r.farthestDepth, r.clearDepth == 0.0f ? 2.0f : -1.0f);
        CHECK(-viewPositionFromDepth(c, {0, 0}, nearer).z <= kMaxViewDistance * (1.0 + 1e-6));
    }
    CHECK(depthReconstruction(infinite).farthestDepth == Approx(10.0 / kMaxViewDistance).epsilon(1e-6));
}

TEST_CASE("Unsupported projections are refused with a reason", "[unit][camera]") {
    Camera c = Camera::perspective({{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f);
    c.projection[2][3] = 1.0f; // left-handed
    CHECK_THROWS_WITH(analyzeProjection(c), Catch::Contains("right-handed"));
    c = Camera::perspective({{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f);
    c.view = glm::mat4(0.0f);
    CHECK_THROWS_WITH(analyzeProjection(c), Catch::Contains("singular"));
    CHECK_THROWS_AS(Camera::perspective({{0, 0, 0}, {0, 0, -1}, {0, 0, -1}}, 1.0f, 1.0f, 0.1f, 10.0f), Error);
    CHECK_THROWS_AS(Camera::perspective({{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}, 3.2f, 1.0f, 0.1f, 10.0f), Error);
    CHECK_THROWS_AS(Camera::orthographic({{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}, 0.0f, 1.0f, 0.1f, 10.0f), Error);
    // A DepthMode outside its enumerators left the depth row unset (perspective: zero rows).
    const DepthMode unknown = static_cast<DepthMode>(3);
    CHECK_THROWS_WITH(Camera::perspective({{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f, unknown),
                      Catch::Contains("DepthMode"));
    CHECK_THROWS_WITH(Camera::orthographic({{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}, 1.0f, 1.0f, 0.1f, 10.0f, unknown),
                      Catch::Contains("DepthMode"));
}

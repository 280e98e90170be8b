// View-space positions from hardware depth (see DepthReconstruction in camera.hpp).
// Works for standard and reversed-Z, [-1,1] and [0,1] clip depth, perspective (including an
// infinite far plane) and orthographic projections.
#include "frame.glsl"
#include "math.glsl"

// See isBackgroundDepth: the clear depth, a value no surface has (a host's float depth may
// hold NaN, Inf or values outside [0, 1]), or one beyond kMaxViewDistance.
bool isBackground(float depth) { return isBackgroundDepth(depth, frame.clearDepth, frame.farthestDepth); }

// View-space z (negative in front of the camera) of a non-background depth value.
float viewZFromDepth(float depth) {
    if (isPerspective()) {
        // The bias is a float pair: d + hi is exact where standard depth cancels near d = 1,
        // and `precise` forbids the compiler from reassociating the sum.
        precise float denominator = (depth + frame.depthBiasHi) + frame.depthBiasLo;
        return frame.depthScale / denominator;
    }
    return frame.depthScale * depth + frame.depthBiasHi;
}

// uv: [0,1]^2 texture coordinates of the pixel (centre = (pixel + 0.5) / size).
vec3 viewPositionFromDepth(vec2 uv, float depth) {
    float z = viewZFromDepth(depth);
    vec2 xy = (uv * 2.0 - 1.0) * frame.rayScale + frame.rayOffset;
    return isPerspective() ? vec3(-z * xy, z) : vec3(xy, z);
}

// How far the view point o reconstructed from `depth` may lie from the surface it samples,
// along its view ray: one step of the depth buffer (frame.depthStep; a float buffer's
// step is a float ulp of the depth) through the slope of viewZFromDepth. Standard
// perspective depth spends its precision near the camera: with the near plane at 0.05 a
// 24-bit buffer leaves a point 6 units away up to 4e-5 off, a 16-bit one 0.01.
float depthReconstructionError(vec3 o, float depth) {
    const float step = max(frame.depthStep, abs(depth) * 1.1920929e-7); // 2^-23
    if (!isPerspective()) return abs(frame.depthScale) * step;
    // |dz/dd| = z^2 / |zScale|, times |o| / |z| along the ray: |z| |o| / |zScale| (no z^2 to
    // overflow).
    return abs(o.z) / abs(frame.depthScale) * length(o) * step;
}

// Float rounding of reconstructed positions and of differences between them, relative to
// their magnitude: a few ulp (2^-23 each).
const float kPositionRounding = 4e-6;

// The magnitude a reconstructed point's rounding scales with: |o|, and in an orthographic
// view also the view's half-extent and offset, from which x and y are interpolated (a point
// near the camera plane at the image's centre is small, its x and y's rounding is not).
float positionRoundingScale(vec3 o) {
    return isPerspective() ? length(o) : length(o) + length(abs(frame.rayScale) + abs(frame.rayOffset));
}

vec2 pixelCenterUv(ivec2 pixel) { return (vec2(pixel) + 0.5) / vec2(frameSize()); }

// Unit vector from the surface point toward the camera.
vec3 viewDirectionTo(vec3 viewPosition) {
    if (!isPerspective()) return vec3(0.0, 0.0, 1.0);
    float len = length(viewPosition);
    return len > 0.0 ? -viewPosition / len : vec3(0.0, 0.0, 1.0);
}

#include "screen_mirror.hpp"

#include "gl_fixture.hpp"
#include "scene_builders.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace obscura::test {
namespace {

// Each GLSL add or multiply is taken as off by up to one ulp of its result (2^-23 relative:
// llvmpipe may round toward zero, and may or may not fuse a multiply with an add), a division
// by three (GLSL allows 2.5 ulp). Products of two such errors are left out: first order.
constexpr double u = 0x1p-23;
// depth.glsl's kPositionRounding, which the shader's tolerance adds.
constexpr double kPositionRounding = 4e-6;

// Row r of P times v, in absolute values: the magnitude its four products and three sums
// round at (4 ulp of it at most).
double rowMagnitude(const glm::dmat4& P, int r, const glm::dvec4& v) {
    double m = 0.0;
    for (int c = 0; c < 4; ++c) m += std::abs(P[c][r] * v[c]);
    return m;
}

double rowOfErrors(const glm::dmat4& P, int r, const glm::dvec3& e) {
    return std::abs(P[0][r]) * e.x + std::abs(P[1][r]) * e.y + std::abs(P[2][r]) * e.z;
}

// One march's rounding of one sample: its clip coordinates, then its pixel coordinates.
struct PathRounding {
    glm::dvec4 clip;
    glm::dvec2 pixel, uv;
};

PathRounding pixelRounding(const glm::dvec4& clip, const glm::dvec4& clipError, int width, int height) {
    PathRounding r{clipError, {}, {}};
    for (int a = 0; a < 2; ++a) {
        const double ndc = clip[a] / clip.w, size = a == 0 ? width : height;
        // c / w, then ndc * 0.5 + 0.5, then uv * size.
        const double ndcError = (clipError[a] + std::abs(ndc) * clipError.w) / std::abs(clip.w) + 3.0 * u * std::abs(ndc);
        const double uv = ndc * 0.5 + 0.5;
        r.uv[a] = 0.5 * ndcError + u * std::abs(uv);
        r.pixel[a] = size * r.uv[a] + u * std::abs(uv * size);
    }
    return r;
}

// Bounds on how far each march's float values of sample s = p + d t lie from the exact ones,
// the larger of the two marches': pixel coordinates (pixels), clip w, and the view point it
// classifies (world units). Where the exact value lies farther than this from a decision,
// both marches decide as the exact value does.
struct MarchRounding {
    glm::dvec2 pixel;
    double w = 0.0, point = 0.0;
};

MarchRounding marchRounding(const Camera& camera, int width, int height, glm::dvec3 p, glm::dvec3 d, double t) {
    const glm::dmat4 P(camera.projection);
    const DepthReconstruction rec = depthReconstruction(camera);
    const bool perspective = rec.kind == ProjectionKind::Perspective;
    const glm::dvec3 s = p + d * t;
    const glm::dvec4 clip = P * glm::dvec4(s, 1.0);
    // t = (float(j) + jitter) / float(steps): a sum and a division. d: a float difference
    // (to - from) or product (w * radius), within an ulp of its value.
    const double tError = 4.0 * u * t;
    const glm::dvec3 dError = u * glm::abs(d);
    // View-space march (screenMarchView): s = p + d t, then P (s, 1).
    glm::dvec3 sError;
    for (int c = 0; c < 3; ++c)
        sError[c] = std::abs(d[c]) * tError + dError[c] * t + u * std::abs(d[c] * t) + u * std::abs(s[c]);
    glm::dvec4 viewClip, textureClip;
    for (int r = 0; r < 4; ++r) {
        viewClip[r] = rowOfErrors(P, r, sError) + 4.0 * u * rowMagnitude(P, r, glm::dvec4(s, 1.0));
        // Texture-space march (screenRayOf, screenSampleAt): P (p, 1) + P (d, 0) t.
        const double delta = (P * glm::dvec4(d, 0.0))[r];
        textureClip[r] = 4.0 * u * rowMagnitude(P, r, glm::dvec4(p, 1.0)) +
                         (4.0 * u * rowMagnitude(P, r, glm::dvec4(d, 0.0)) + rowOfErrors(P, r, dError)) * t +
                         std::abs(delta) * tError + u * std::abs(delta * t) + u * std::abs(clip[r]);
    }
    const PathRounding view = pixelRounding(clip, viewClip, width, height);
    const PathRounding texture = pixelRounding(clip, textureClip, width, height);
    // The texture-space march's point: viewPositionFromUvZ(uv, z), z = p.z + d.z t as above,
    // xy = (uv * 2 - 1) A + B (A, B: the projection's inverse, each rounded to float).
    const glm::dvec2 A(rec.xyScale), B(rec.xyOffset);
    const double zError = sError.z;
    glm::dvec3 textureError(0.0, 0.0, zError);
    for (int a = 0; a < 2; ++a) {
        const double uv = clip[a] / clip.w * 0.5 + 0.5, centred = (uv * 2.0 - 1.0) * A[a], xy = centred + B[a];
        const double xyError = 2.0 * std::abs(A[a]) * texture.uv[a] + 3.0 * u * std::abs(centred) + 2.0 * u * std::abs(B[a]) +
                               u * std::abs(xy);
        textureError[a] = perspective ? std::abs(s.z) * xyError + std::abs(xy) * zError + u * std::abs(s[a]) : xyError;
    }
    MarchRounding m;
    m.pixel = glm::max(view.pixel, texture.pixel);
    m.w = std::max(viewClip.w, textureClip.w);
    m.point = std::max(glm::length(sError), glm::length(textureError));
    return m;
}

double depthStepOf(GLenum format) {
    switch (format) {
    case GL_DEPTH_COMPONENT16: return 1.0 / 65535.0;
    case GL_DEPTH_COMPONENT24:
    case GL_DEPTH24_STENCIL8: return 1.0 / 16777215.0;
    default: return 0.0; // float depth: an ulp of the value
    }
}

bool nearEdge(double x, double error, int size) {
    const double k = std::round(x);
    return k >= 0.0 && k <= size && std::abs(x - k) <= error;
}

} // namespace

ScreenMirror::ScreenMirror(Context& ctx, const GBufferView& view)
    : camera(view.camera), width(view.width), height(view.height), depth(readTexture(ctx, view.depth)),
      normals(readTexture(ctx, view.normal)), normalError(view.normalError), depthStep(depthStepOf(view.depth.internalFormat)) {
    if (view.backDepth) backDepth = readTexture(ctx, view.backDepth);
}

std::vector<ScreenMirror::Start> ScreenMirror::starts(glm::dvec3 from) const {
    const glm::dmat4 P(camera.projection);
    const glm::dvec4 clip = P * glm::dvec4(from, 1.0);
    glm::dvec4 clipError;
    for (int r = 0; r < 4; ++r) clipError[r] = 4.0 * u * rowMagnitude(P, r, glm::dvec4(from, 1.0));
    const glm::dvec2 error = pixelRounding(clip, clipError, width, height).pixel;
    const double X = (clip.x / clip.w * 0.5 + 0.5) * width, Y = (clip.y / clip.w * 0.5 + 0.5) * height;
    std::vector<Start> out;
    // The pixels the shader's float projection may put `from` in: those within its rounding.
    for (const double x : {X - error.x, X + error.x})
        for (const double y : {Y - error.y, Y + error.y}) {
            Start start{glm::dvec3(0.0), normalError};
            if (clip.w > 0.0 && x >= 0.0 && y >= 0.0 && x < width && y < height) {
                const int px = int(x), row = height - 1 - int(y);
                const float alpha = normals.at(px, row, 3);
                if (alpha > 0.0f) start = {texel3(normals, px, row), normalError * alpha};
            }
            if (std::none_of(out.begin(), out.end(), [&](const Start& s) { return s.normal == start.normal && s.error == start.error; }))
                out.push_back(start);
        }
    return out;
}

Verdict ScreenMirror::classify(glm::dvec3 from, glm::dvec3 d, int j, int steps, double jitter, double thickness,
                               ScreenThickness mode) const {
    const double t = (j + jitter) / steps;
    const glm::dvec3 s = from + d * t;
    const MarchRounding r = marchRounding(camera, width, height, from, d, t);
    const glm::dvec4 clip = glm::dmat4(camera.projection) * glm::dvec4(s, 1.0);
    if (std::abs(clip.w) <= r.w) return Verdict::Tie;
    if (clip.w <= 0.0) return Verdict::Visible; // behind the camera
    const double X = (clip.x / clip.w * 0.5 + 0.5) * width, Y = (clip.y / clip.w * 0.5 + 0.5) * height;
    if (nearEdge(X, r.pixel.x, width) || nearEdge(Y, r.pixel.y, height)) return Verdict::Tie;
    if (X < 0.0 || Y < 0.0 || X >= width || Y >= height) return Verdict::Visible; // the border policy
    const int px = int(X), row = height - 1 - int(Y);
    const DepthReconstruction rec = depthReconstruction(camera);
    const double z = depth.at(px, row, 0);
    if (z == rec.clearDepth) return Verdict::Visible;
    const glm::dvec2 ndc = pixelNdc(px, row, width, height);
    const glm::dvec3 o = viewPositionFromDepth(camera, ndc, z), n = texel3(normals, px, row);
    const double behind = -glm::dot(s - o, n);
    // screenHiddenAt's tolerance: depthReconstructionError twice, the normals' slack.
    const double step = std::max(depthStep, std::abs(z) * 0x1p-23);
    const double reconstruction = rec.kind == ProjectionKind::Perspective
                                      ? std::abs(o.z) / std::abs(double(rec.zScale)) * glm::length(o) * step
                                      : std::abs(double(rec.zScale)) * step;
    const double oError = normalError * normals.at(px, row, 3);
    const bool peeled = mode != ScreenThickness::Constant && !backDepth.pixels.empty();
    const double back = peeled ? backDepth.at(px, row, 0) : rec.clearDepth;
    // The verdict for one start pixel's normal error and one choice of the slack.
    const auto verdict = [&](double fromError, double slack) {
        const double tolerance = kPositionRounding * std::max(glm::length(o), glm::length(s)) + 2.0 * reconstruction + slack;
        // How far a march's behind - tolerance may lie from this one: its point's rounding,
        // through n and through the tolerance's terms in s; o's reconstruction (a division and
        // the xy terms, 10 ulp of |o|); the dot product's rounding; the tolerance's own sums.
        double dotRounding = 0.0;
        for (int c = 0; c < 3; ++c)
            dotRounding += (4.0 * u * std::abs(s[c] - o[c]) + u * (std::abs(s[c]) + std::abs(o[c]))) * std::abs(n[c]);
        const double margin = r.point * (glm::length(n) + kPositionRounding + fromError + oError) +
                              10.0 * u * glm::length(o) * (glm::length(n) + kPositionRounding + 2.0 * oError) +
                              dotRounding + 24.0 * u * tolerance;
        const bool planeTie = std::abs(behind - tolerance) <= margin;
        if (!planeTie && behind <= tolerance) return Verdict::Visible;
        const bool slab = behind <= thickness, slabTie = std::abs(behind - thickness) <= margin + u * thickness;
        bool inside = slab, insideTie = slabTie;
        if (back != rec.clearDepth) {
            // s.z against the back layer's view z (or o's): each within 10 ulp of its value.
            const double limit = std::min(viewPositionFromDepth(camera, ndc, back).z, o.z);
            const bool layer = s.z >= limit, layerTie = std::abs(s.z - limit) <= r.point + 10.0 * u * std::abs(limit);
            if (mode == ScreenThickness::DepthPeeling) {
                inside = layer;
                insideTie = layerTie;
            } else { // either: a certain yes of one decides, else a tie of either is a tie
                inside = slab || layer;
                insideTie = !((slab && !slabTie) || (layer && !layerTie)) && (slabTie || layerTie);
            }
        }
        if (!insideTie && !inside) return Verdict::Visible;
        return planeTie || insideTie ? Verdict::Tie : Verdict::Hidden;
    };
    // screenNormalSlack: only where o may lie on the start's plane. The test's own rounding
    // (o's reconstruction, the dot product, its limit's sums) may take it either way.
    std::vector<Verdict> verdicts;
    const glm::dvec3 toO = o - from;
    const double positionErrors = kPositionRounding * std::max(glm::length(o), glm::length(from)) + 2.0 * reconstruction;
    for (const Start& start : starts(from)) {
        const double offPlane = std::abs(glm::dot(toO, start.normal));
        const double limit = start.error * glm::length(toO) + positionErrors;
        // The integrators take the normal normalized (within 2^-10 of unit length stored).
        double gateRounding = 8.0 * u * limit + 10.0 * u * glm::length(o) * glm::length(start.normal) +
                              std::abs(1.0 - glm::length(start.normal)) * offPlane;
        for (int c = 0; c < 3; ++c)
            gateRounding += (4.0 * u * std::abs(toO[c]) + u * (std::abs(o[c]) + std::abs(from[c]))) * std::abs(start.normal[c]);
        const double slack = oError * glm::length(toO) + (start.error + oError) * glm::length(s - from);
        if (std::abs(offPlane - limit) > gateRounding) {
            verdicts.push_back(verdict(start.error, offPlane <= limit ? slack : 0.0));
        } else {
            verdicts.push_back(verdict(start.error, slack));
            verdicts.push_back(verdict(start.error, 0.0));
        }
    }
    const bool agree = std::all_of(verdicts.begin(), verdicts.end(), [&](Verdict v) { return v == verdicts.front(); });
    return agree ? verdicts.front() : Verdict::Tie;
}

} // namespace obscura::test

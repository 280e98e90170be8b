#pragma once
// A double-precision mirror of the screen-space classification (screen_march.glsl:
// screenHiddenAt over the samples t_j = (j + jitter) / steps of a segment), with first-order
// bounds on the float rounding of the view-space and texture-space marches. A sample whose
// exact classification lies within those bounds of a decision (a pixel edge, the camera
// plane, the tangent-plane tolerance, the thickness or the back layer) is a tie: either
// march may take it either way. Elsewhere both marches must classify it as the mirror does.
#include "obscura/obscura.hpp"

#include <glm/glm.hpp>

#include <vector>

namespace obscura::test {

enum class Verdict { Visible, Hidden, Tie };

struct ScreenMirror {
    Camera camera;
    int width = 0, height = 0;
    Image depth, normals, backDepth; // backDepth: empty with one depth layer
    double normalError = 0.0;        // GBufferView::normalError
    double depthStep = 0.0;          // the depth format's step (0 for float depth)

    //! Reads the view's depth, normals and back layer.
    ScreenMirror(Context& ctx, const GBufferView& view);

    //! Sample j of `steps` on from -> from + d, judged against `thickness` (world units), the
    //! back layer where there is one, or either, as `mode` says.
    Verdict classify(glm::dvec3 from, glm::dvec3 d, int j, int steps, double jitter, double thickness,
                     ScreenThickness mode) const;

    //! A ray's start as the marches take it: its pixel's stored normal and normal error
    //! (trace_screen's rayStartOf; the integrators' rays start in their own pixel), none and
    //! normalError off the geometry.
    struct Start {
        glm::dvec3 normal;
        double error;
    };
    //! The starts of the pixels the shader's float projection of `from` may fall in.
    std::vector<Start> starts(glm::dvec3 from) const;
};

} // namespace obscura::test

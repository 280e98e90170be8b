// The window within which the horizon AO shader's estimate (AoMethod::Horizon, GTAO-style)
// must lie at a floor pixel, for occluders made of planar faces seen from the camera: the
// slice integral the method estimates, bounded from both sides for what its discrete depth
// samples and its pixel rounding can find. Shared by the horizon tests (a wall, a disc).
//
// The shader's estimate, per slice: on each side, the largest cos(angle to v) among its depth
// samples that are above the floor's plane and within r gives the horizon; the arcs of the
// slice follow from it, the weight and g. For a floor point p, the samples above its plane are
// on the faces (the floor's are on the plane itself). Let a be a screen position's offset
// from p's pixel centre along the slice's direction and c across it (pixels). The ray through
// it meets a face's plane at o with o - p = V / w, where V, w and any affine function of o
// times w are affine in (a, c): a ray's origin and direction are affine in the screen position
// and one of them is constant (orthographic: the direction; perspective: the origin). A face
// is the part of its plane where some affine functions of o are >= 0 and, optionally, within a
// disc; w > 0 in front of the camera. The cosine is V.v / |V|, a function of V's direction only:
// - on c = 0, V stays in the slice's plane (it holds v and V(0, 0), which is parallel to v), so for
//   a > 0 its direction turns one way and the cosine is monotone in a;
// - {cos >= k}, k >= 0, is {V.v >= k |V|}: convex in (a, c), so on a rectangle where V.v >= 0
//   the least cosine is at a corner;
// - in the slice plane's coordinates (alpha, beta) = (V.e1, V.v), beta / |(alpha, beta)| is the
//   sine of an angle that is largest at a vertex of a parallelogram (the image of a rectangle)
//   lying at alpha > 0; the distance gamma = V.e3 from the plane only lowers a positive cosine
//   (a negative one it raises by at most gamma^2 / (2 |(alpha, beta)|^2)).
// A sample is taken at a_j = max((j + jitter) reach / steps, 1) and rounded to a pixel, which
// moves it by at most lambda (half a pixel's diagonal, with float rounding: 0.72) in a and in c.
// So, per face (horizonWindow):
// - the most any sample gives is at most the largest over the parallelogram of the a the
//   samples can reach with |c| <= lambda, feasibility relaxed by what c can change;
// - the least: where any rounding of the line's points keeps them on the face and within r, an
//   interval of a at least a sample spacing long within [1, reach] holds a sample (unclamped,
//   j < steps), near its end where the cosine is larger; its cosine is at least the least over
//   the rectangle it can be rounded into. Shorter, no sample need land there.
// Over several faces the horizon is the largest of theirs, so the window is the largest of
// each bound, as long as no sample counted as surely on a face may see something else there
// (a face's holes). The slice's occlusion is monotone in each side's horizon, so these give
// its window; the estimate (sum of occlusion over sum of open arcs over the slices) follows
// from those sums over the shader's own slices, at the pixel's offset from the noise texture
// (obliqueWindow, which also bounds the shader's float angles).
#pragma once
#include "ao_fixture.hpp"

#include "obscura/camera.hpp"

#include <glm/glm.hpp>

#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace obscura::test::horizon {

//! The horizon settings the window depends on; lambda in pixels.
struct Sampling {
    double radius = 1.0; // world units
    int slices = 128, steps = 128;
    double lambda = 0.72; // sqrt(1/2) and float rounding

    //! The horizon AO settings that sample so.
    AmbientOcclusionSettings settings() const {
        return {.method = AoMethod::Horizon, .radius = float(radius), .rays = 2 * slices, .steps = steps};
    }
};

//! An affine function of the screen offsets (a, c).
template <class T> struct Affine {
    T at, da, dc;
    T operator()(double a, double c) const { return at + a * da + c * dc; }
};

//! A planar occluder in view space: its plane (the normal faces the camera), cut to where
//! every bound's gradient . o + offset >= 0 and, when discRadius > 0, to the disc about
//! discCentre. A sample counts as surely on the face only `margin` (world units) inside a
//! bound: the shader's plane test needs the faces' points clear of the floor's plane.
struct Face {
    struct Bound {
        glm::dvec3 gradient;
        double offset = 0.0, margin = 0.0;
    };
    glm::dvec3 normal, point;
    std::vector<Bound> bounds;
    glm::dvec3 discCentre{0.0};
    double discInner = 0.0, discOuter = 0.0; // the disc's radius: surely inside, possibly inside
    //! Screen rectangles (GL pixels, min and max) where something nearer may hide the face:
    //! no sample counts as surely on it within a pixel of them.
    std::vector<std::pair<glm::dvec2, glm::dvec2>> holes;
};

//! The face of the plane through `point` with `normal` (world space, facing the camera), cut
//! by `bounds` (world space), in the view space of `view`.
Face viewFace(const glm::dmat4& view, glm::dvec3 normal, glm::dvec3 point, const std::vector<Face::Bound>& bounds);

//! A face seen from p along one side of one slice: V, w, the bounds and the balls' offsets
//! (w (o - centre), with their radii), affine in (a, c), and v.
struct FaceSide {
    struct Ball {
        Affine<glm::dvec3> X;
        double least, most;
    };
    Affine<glm::dvec3> V;
    Affine<double> w;
    std::vector<std::pair<Affine<double>, double>> bounds; // w f(o), margin
    std::vector<Ball> balls;
    std::vector<std::pair<double, double>> hidden; // the a where a hole may hide the face
    glm::dvec3 v;

    double cosine(double a, double c) const;
};

//! The camera's rays in view space, each affine in the screen position (GL pixels, y up).
struct ScreenRays {
    glm::dmat4 inverseProjection{1.0};
    bool perspective = false;
    glm::dvec2 size{0.0};

    ScreenRays(const Camera& camera, int width, int height);
    std::pair<glm::dvec3, glm::dvec3> ray(glm::dvec2 s) const; // origin, direction
    //! How far from `centre` along the unit `u` the screen stays at least `inset` pixels
    //! inside the image (negative inset: outside).
    double inside(glm::dvec2 centre, glm::dvec2 u, double inset) const;
    FaceSide side(const Face& face, glm::dvec3 p, glm::dvec3 v, double radius, glm::dvec2 centre, glm::dvec2 u) const;
};

//! One floor pixel: its view point and normal, v, its pixel centre (GL pixels) and the
//! radius in pixels there, and its slice offset, as the shader computes them.
struct FloorPixel {
    glm::dvec3 p, n, v;
    glm::dvec2 centre;
    double reach;
    double sliceOffset; // u of the shader's slice angles pi (k + u) / N, in [0, 1)
};

//! Floor pixel (x, y) of f's G-buffer (rows down) as the shader sees it; none off the floor
//! (y = 0 within 1 mm, normal up: a face's lowest pixels are within a few mm of the floor's
//! height too). `normals`: the G-buffer's normals read back.
std::optional<FloorPixel> floorPixel(const AoFixture& f, const Image& normals, int x, int y, double radius);

//! Checks that a face's V, w and bounds as seen from px are affine in (a, c): at a far screen
//! point they agree with that point's own ray meeting the face's plane.
void checkAffine(const ScreenRays& rays, const Face& face, const FloorPixel& px, double radius);

//! The shader's estimate lies in [lo, hi].
struct AoWindow {
    double lo = 1.0, hi = 1.0;
};

//! The window of a floor pixel's estimate among the faces, from the shader's slices.
AoWindow obliqueWindow(const FloorPixel& px, const std::vector<Face>& faces, const ScreenRays& rays, const Sampling& sampling);

//! Checks pixels' AO against their windows, plus the half float's rounding (to nearest), and
//! keeps what the tests report: the mean error from the windows' centres and the windows'
//! mean half-width over the occluded pixels (which must stay small, or a wrong horizon or arc
//! could pass unnoticed).
struct WindowTally {
    int checked = 0, occluded = 0;
    double meanError = 0.0, occludedWindow = 0.0;

    void check(double value, AoWindow w);
    double halfWidth() const { return occludedWindow / occluded; }
    std::string summary() const;
};

} // namespace obscura::test::horizon

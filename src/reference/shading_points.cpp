// Where references are evaluated: primary-ray hits (mode b) or the G-buffer's samples (mode a).
#include "obscura/error.hpp"
#include "obscura/reference.hpp"
#include "reference/ray_scene_impl.hpp"

#include <algorithm>
#include <cmath>

namespace obscura::reference {
namespace {

struct ViewRayMaker {
    glm::dmat4 toWorld;
    glm::dmat4 projection;
    bool perspective;
    ProjectionInfo info;

    explicit ViewRayMaker(const Camera& c)
        : toWorld(glm::inverse(glm::dmat4(c.view))), projection(c.projection), info(analyzeProjection(c)) {
        perspective = info.kind == ProjectionKind::Perspective;
    }

    // View ray of the pixel centre (x, y), row 0 at the top; the near and far planes as
    // distances along it (what the rasterizer keeps).
    void ray(int x, int y, int w, int h, ShadingPoint& s, double& tnear, double& tfar) const {
        const glm::dvec2 ndc((x + 0.5) / w * 2.0 - 1.0, 1.0 - (y + 0.5) / h * 2.0);
        const glm::dmat4& p = projection;
        glm::dvec3 o, d;
        if (perspective) {
            o = glm::dvec3(0.0);
            d = glm::dvec3((ndc.x + p[2][0]) / p[0][0], (ndc.y + p[2][1]) / p[1][1], -1.0);
        } else {
            o = glm::dvec3((ndc.x - p[3][0]) / p[0][0], (ndc.y - p[3][1]) / p[1][1], 0.0);
            d = glm::dvec3(0.0, 0.0, -1.0);
        }
        // Along the unit direction, view depth grows as 1/len per unit length (len = 1 for
        // orthographic rays), so the clip planes sit at near*len and far*len.
        const double len = glm::length(d);
        tnear = info.nearPlane * len;
        tfar = std::isinf(info.farPlane) ? kInfinity : info.farPlane * len;
        s.origin = glm::dvec3(toWorld * glm::dvec4(o, 1.0));
        s.direction = glm::normalize(glm::dmat3(toWorld) * (d / len));
    }
};

// Float error of a hit at parameter t (Embree computes t in float).
double hitUncertainty(double distance) { return std::ldexp(distance, -20); }

// Four quantization steps of the 32F depth that stores view depth z, as a distance along the
// view ray (the G-buffer reconstructs positions along it).
double depthUncertainty(const Camera& camera, const glm::dvec3& viewPosition, const glm::dvec2& ndc) {
    const glm::dvec4 clip = glm::dmat4(camera.projection) * glm::dvec4(viewPosition, 1.0);
    const double zn = clip.z / clip.w;
    const double d = camera.clipDepth == ClipDepth::ZeroToOne ? zn : 0.5 * zn + 0.5;
    const float df = static_cast<float>(std::clamp(d, 0.0, 1.0));
    const float next = std::nextafter(df, df < 1.0f ? 2.0f : -1.0f);
    const double step = std::abs(viewPositionFromDepth(camera, ndc, next).z - viewPositionFromDepth(camera, ndc, df).z);
    const double alongRay = std::abs(viewPosition.z) > 0.0 ? glm::length(viewPosition) / std::abs(viewPosition.z) : 1.0;
    return 4.0 * step * alongRay;
}

void shade(const RayScene::Impl& scene, const Hit& hit, ShadingPoint& s) {
    s.distance = hit.distance;
    s.normal = glm::dot(hit.normal, s.direction) > 0.0 ? -hit.normal : hit.normal;
    s.shadingNormal = scene.shadingNormal(hit, s.normal);
    s.albedo = scene.albedo(hit);
    s.emission = scene.emission(hit, -s.direction);
    s.uncertainty = hitUncertainty(hit.distance);
}

} // namespace

ShadingPoints fromCamera(const RayScene& scene, const Camera& camera, int width, int height) {
    if (width < 1 || height < 1)
        throw Error(ErrorCode::InvalidArgument, "fromCamera: size must be >= 1x1, got " + std::to_string(width) + "x" +
                                                    std::to_string(height));
    const ViewRayMaker maker(camera);
    ShadingPoints out{width, height, std::vector<ShadingPoint>(static_cast<std::size_t>(width) * height)};
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            ShadingPoint& s = out.points[static_cast<std::size_t>(y) * width + x];
            double tnear = 0, tfar = 0;
            maker.ray(x, y, width, height, s, tnear, tfar);
            if (auto hit = scene.impl().intersect(glm::vec3(s.origin), s.direction, tfar, tnear)) {
                shade(scene.impl(), *hit, s);
                s.position = s.origin + hit->distance * s.direction;
            }
        }
    return out;
}

ShadingPoints fromGBuffer(const RayScene& scene, const Camera& camera, const Image& viewPositions,
                          const Image& viewNormals) {
    if (viewPositions.channels != 4 || viewNormals.channels < 3 || viewPositions.width != viewNormals.width ||
        viewPositions.height != viewNormals.height)
        throw Error(ErrorCode::InvalidArgument, "fromGBuffer: needs RGBA positions and RGB(A) normals of the same size");
    const ViewRayMaker maker(camera);
    const int w = viewPositions.width, h = viewPositions.height;
    ShadingPoints out{w, h, std::vector<ShadingPoint>(static_cast<std::size_t>(w) * h)};
    const glm::dmat3 rotation(maker.toWorld);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            ShadingPoint& s = out.points[static_cast<std::size_t>(y) * w + x];
            double tnear = 0, tfar = 0;
            maker.ray(x, y, w, h, s, tnear, tfar);
            if (viewPositions.at(x, y, 3) <= 0.0f) continue;
            const glm::dvec3 pv(viewPositions.at(x, y, 0), viewPositions.at(x, y, 1), viewPositions.at(x, y, 2));
            const glm::dvec3 nv(viewNormals.at(x, y, 0), viewNormals.at(x, y, 1), viewNormals.at(x, y, 2));
            s.position = glm::dvec3(maker.toWorld * glm::dvec4(pv, 1.0));
            const glm::dvec3 toPoint = s.position - s.origin;
            s.distance = maker.perspective ? glm::length(toPoint) : glm::dot(toPoint, s.direction);
            if (maker.perspective && s.distance > 0.0) s.direction = toPoint / s.distance;
            const double nl = glm::length(nv);
            s.normal = nl > 0.0 ? rotation * (nv / nl) : -s.direction;
            const glm::dvec2 ndc((x + 0.5) / w * 2.0 - 1.0, 1.0 - (y + 0.5) / h * 2.0);
            s.uncertainty = depthUncertainty(camera, pv, ndc) + hitUncertainty(s.distance);
            // The surface the sample stands for: the triangle the view ray reaches at that
            // distance (within the sample's uncertainty plus a pixel's slack of 2^-10 of the
            // distance). The sample moves onto it: rasterizers may interpolate depth from
            // vertices snapped to their sub-pixel grid (NVIDIA does; 8 bits there), which puts
            // the rebuilt point off the surface by the depth's slope over 1/256 of a pixel,
            // far more than the depth's quantization (about 1e-4 of the model's size at 128x128
            // against 1e-6). Secondary rays lifted only by the quantization then started behind
            // the surface and hit it: shadowed and occluded where nothing is. Else (a silhouette
            // pixel whose centre misses the rasterized triangle) the point stays where the
            // G-buffer put it and takes the nearest triangle's material.
            s.shadingNormal = s.normal;
            const double slack = 4.0 * s.uncertainty + std::ldexp(s.distance, -10);
            auto hit = scene.impl().intersect(glm::vec3(s.origin), s.direction, s.distance + slack,
                                              std::max(tnear, s.distance - slack));
            if (hit) {
                s.distance = hit->distance;
                s.position = s.origin + hit->distance * s.direction;
                s.uncertainty = hitUncertainty(hit->distance);
            } else {
                hit = scene.impl().intersect(glm::vec3(s.origin), s.direction, kInfinity, tnear);
            }
            if (hit) {
                s.albedo = scene.impl().albedo(*hit);
                s.emission = scene.impl().emission(*hit, -s.direction);
                s.shadingNormal = scene.impl().shadingNormal(*hit, s.normal);
            }
        }
    return out;
}

Image surfaceMask(const ShadingPoints& points) {
    Image m;
    m.width = points.width;
    m.height = points.height;
    m.channels = 1;
    m.pixels.resize(points.points.size());
    for (std::size_t i = 0; i < points.points.size(); ++i) m.pixels[i] = points.points[i].surface() ? 1.0f : 0.0f;
    return m;
}

} // namespace obscura::reference

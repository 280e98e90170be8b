#include "shadows/shadow_lookup.hpp"

#include "core/context_impl.hpp"
#include "core/validate.hpp"
#include "obscura/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

namespace obscura::detail {
namespace {

// SHADOW_POISSON_TAPS points in the unit disc, none closer than 0.3 to another (dart
// throwing with a fixed seed, so every run and machine gets the same kernel), ordered by
// distance from the centre.
std::array<glm::vec2, SHADOW_POISSON_TAPS> makePoissonDisc() {
    std::array<glm::vec2, SHADOW_POISSON_TAPS> points{};
    std::minstd_rand random(12345);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    std::size_t count = 0;
    while (count < points.size()) {
        const glm::vec2 p(unit(random), unit(random));
        bool far = glm::dot(p, p) <= 1.0f;
        for (std::size_t i = 0; i < count && far; ++i) far = glm::distance(p, points[i]) >= 0.3f;
        if (far) points[count++] = p;
    }
    std::sort(points.begin(), points.end(), [](glm::vec2 a, glm::vec2 b) { return glm::dot(a, a) < glm::dot(b, b); });
    return points;
}

// The disc of PcfKernel::PoissonDisc (unit radius), made once.
const std::array<glm::vec2, SHADOW_POISSON_TAPS>& poissonDisc() {
    static const std::array<glm::vec2, SHADOW_POISSON_TAPS> disc = makePoissonDisc();
    return disc;
}

// The radius R that PCSS takes for the light's size: a rect's is that of the disc of its area.
float pcssLightRadius(const Light& light) {
    switch (light.type) {
    case LightType::Directional: return 0.0f;
    case LightType::Rect: return std::sqrt(light.size.x * light.size.y / 3.14159265f);
    default: return light.radius;
    }
}

float pcfKernelCode(PcfKernel kernel) {
    switch (kernel) {
    case PcfKernel::PoissonDisc: return SHADOW_PCF_POISSON;
    case PcfKernel::OptimizedGrid: return SHADOW_PCF_OPTIMIZED;
    case PcfKernel::Grid: break;
    }
    return SHADOW_PCF_GRID;
}

} // namespace

void validateShadowMask(const ShadowMaskSettings& s, const std::string& owner) {
    validateSettings(ShadowMaskSettings::table(), s, owner);
}

void requireMapsFor(const ShadowMapSet& maps, const Camera& camera, const std::string& owner) {
    const Camera& c = maps.camera;
    if (!(c.view == camera.view && c.projection == camera.projection && c.clipDepth == camera.clipDepth))
        throw Error(ErrorCode::InvalidArgument, owner + ": the shadow maps were fitted to another camera (render them "
                                                        "with the camera of the G-buffer)");
}

shader::ShadowParams shadowRecord(const ShadowMapInfo& info, const Camera& camera, const ShadowMaskSettings& s,
                                  int resolution) {
    shader::ShadowParams p{};
    const glm::dmat4 view(camera.view), viewToWorld = glm::inverse(view);
    for (int c = 0; c < info.layers; ++c) {
        const auto k = static_cast<std::size_t>(c);
        p.cascades[k].viewToLight = glm::mat4(glm::dmat4(info.worldToClip[k]) * viewToWorld);
        const float projection = info.paraboloid ? 2.0f : info.type == LightType::Directional ? 0.0f : 1.0f;
        p.cascades[k].sliceEnd = info.sliceEnd[k];
        p.cascades[k].texelSize = info.texelSize[k];
        p.cascades[k].layer = static_cast<float>(info.firstLayer + c);
        p.cascades[k].projection = projection;
        p.cascades[k].depthMapping = info.depthMapping[k];
    }
    const Light& light = info.source;
    const glm::vec3 position(view * glm::dvec4(glm::dvec3(light.position), 1.0));
    const glm::vec3 direction = glm::normalize(glm::vec3(view * glm::dvec4(glm::dvec3(light.direction), 0.0)));
    p.light = position;
    if (light.type == LightType::Point || light.type == LightType::Sphere) {
        p.lightType = SHADOW_LIGHT_POINT;
    } else if (light.type == LightType::Rect) {
        p.lightType = SHADOW_LIGHT_RECT;
        p.spotAxis = direction; // its front half-space, as a cone of 90 degrees
    } else if (light.type == LightType::Spot) {
        p.lightType = SHADOW_LIGHT_SPOT;
        p.spotAxis = direction;
        p.spotCosOuter = std::cos(light.outerAngle);
    } else {
        p.light = -direction;
        p.lightType = SHADOW_LIGHT_DIRECTIONAL;
    }
    p.constantBias = s.constantBias;
    p.slopeBias = s.slopeBias;
    p.normalOffset = s.normalOffset;
    p.cascadeBlend = s.cascadeBlend;
    p.minVariance = s.minVariance;
    p.lightBleedReduction = s.lightBleedReduction;
    p.exponent = s.exponent;
    p.negativeExponent = s.negativeExponent;
    p.contactLength = s.contactLength;
    p.contactSteps = static_cast<float>(s.contactSteps);
    p.contactThickness = s.contactThickness;
    p.firstSliceStart = info.sliceStart;
    p.mapCount = info.layers;
    p.receiverPlane = s.receiverPlane ? 1 : 0;
    p.pcfRadius = s.pcfRadius;
    p.resolution = resolution;
    p.pcfKernel = pcfKernelCode(s.pcfKernel);
    p.lightRadius = pcssLightRadius(light);
    p.pcssSearchScale = (1.0f - s.pcssBlockerFraction) / s.pcssBlockerFraction;
    const std::array<glm::vec2, SHADOW_POISSON_TAPS>& disc = poissonDisc();
    for (std::size_t i = 0; i < disc.size(); i += 2) p.poisson[i / 2] = glm::vec4(disc[i], disc[i + 1]);
    return p;
}

int shadowFilterCode(ShadowFilter filter) {
    switch (filter) {
    case ShadowFilter::Hard: return SHADOW_FILTER_HARD;
    case ShadowFilter::Pcf: return SHADOW_FILTER_PCF;
    case ShadowFilter::Vsm: return SHADOW_FILTER_VSM;
    case ShadowFilter::Esm: return SHADOW_FILTER_ESM;
    case ShadowFilter::Evsm2: return SHADOW_FILTER_EVSM2;
    case ShadowFilter::Evsm4: return SHADOW_FILTER_EVSM4;
    case ShadowFilter::Msm: return SHADOW_FILTER_MSM;
    case ShadowFilter::Pcss: return SHADOW_FILTER_PCSS;
    }
    return SHADOW_FILTER_HARD;
}

bool isMomentFilter(ShadowFilter filter) { return SHADOW_FILTER_MOMENTS(shadowFilterCode(filter)); }

std::string shadowFilterDefine(ShadowFilter filter) { return "FILTER=" + std::to_string(shadowFilterCode(filter)); }

std::vector<std::string> shadowMaskDefines(const ShadowMaskSettings& s) {
    std::vector<std::string> defines{shadowFilterDefine(s.filter)};
    if (isMomentFilter(s.filter) && s.momentPrecision == ShadowMomentPrecision::Bits16)
        defines.push_back(s.filter == ShadowFilter::Msm ? "MOMENTS_UNORM" : "MOMENTS_HALF");
    return defines;
}

GLenum shadowMomentFormat(const ShadowMaskSettings& s) {
    if (s.momentPrecision == ShadowMomentPrecision::Float32) return GL_RGBA32F;
    return s.filter == ShadowFilter::Msm ? GL_RGBA16 : GL_RGBA16F;
}

void ShadowBinding::bind(ContextImpl& ctx, GLuint maps, const std::vector<shader::ShadowParams>& records,
                         ShadowFilter filter) {
    if (!records_ || capacity_ < records.size()) {
        records_ = createBuffer(ctx, static_cast<GLsizeiptr>(records.size() * sizeof(shader::ShadowParams)), nullptr,
                                GL_DYNAMIC_STORAGE_BIT, "shadow.records");
        capacity_ = records.size();
    }
    ctx.gl.NamedBufferSubData(records_.get(), 0, static_cast<GLsizeiptr>(records.size() * sizeof(shader::ShadowParams)),
                              records.data());
    ctx.state.bindStorageBuffer(ctx, SHADOW_LIGHTS_SSBO, records_.get());
    const bool linear = filter == ShadowFilter::Pcf;
    Sampler& sampler = linear ? linear_ : nearest_;
    if (!sampler) {
        sampler = createSampler(ctx, linear ? GL_LINEAR : GL_NEAREST, GL_CLAMP_TO_EDGE,
                                linear ? "shadow.linear_compare" : "shadow.nearest_compare");
        // Reversed-Z: the receiver is lit when it is at least as near as the stored depth.
        ctx.gl.SamplerParameteri(sampler.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        ctx.gl.SamplerParameteri(sampler.get(), GL_TEXTURE_COMPARE_FUNC, GL_GEQUAL);
    }
    ctx.state.bindTexture(ctx, SHADOW_MAP_UNIT, maps);
    ctx.state.bindSampler(ctx, SHADOW_MAP_UNIT, sampler.get());
}

} // namespace obscura::detail

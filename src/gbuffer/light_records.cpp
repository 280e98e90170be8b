#include "gbuffer/light_records.hpp"

#include "core/context_impl.hpp"
#include "core/validate.hpp"
#include "shaders/gbuffer/gbuffer_bindings.h"

#include <algorithm>
#include <cmath>

namespace obscura::detail {
namespace {

shader::LightData toViewSpace(const Light& l, const glm::dmat4& view) {
    shader::LightData d{};
    const glm::dvec3 p = glm::dvec3(view * glm::dvec4(glm::dvec3(l.position), 1.0));
    const glm::dvec3 dir = glm::normalize(glm::dmat3(view) * glm::dvec3(l.direction));
    int type = GBUFFER_LIGHT_POINT;
    switch (l.type) {
    case LightType::Point: type = GBUFFER_LIGHT_POINT; break;
    case LightType::Spot: type = GBUFFER_LIGHT_SPOT; break;
    case LightType::Directional: type = GBUFFER_LIGHT_DIRECTIONAL; break;
    case LightType::Rect: type = GBUFFER_LIGHT_RECT; break;
    case LightType::Sphere: type = GBUFFER_LIGHT_SPHERE; break;
    }
    d.position = glm::vec3(p);
    d.type = static_cast<float>(type);
    d.direction = l.type == LightType::Point || l.type == LightType::Sphere ? glm::vec3(0.0f) : glm::vec3(dir);
    d.radius = l.radius;
    d.radiance = l.color * l.intensity;
    d.cosInner = std::cos(l.innerAngle);
    d.cosOuter = std::cos(l.outerAngle);
    if (l.type == LightType::Rect) {
        // Width axis made orthogonal to the normal, in view space.
        const glm::dvec3 t = glm::dvec3(l.tangent) - glm::dot(glm::dvec3(l.tangent), glm::normalize(glm::dvec3(l.direction))) *
                                                         glm::normalize(glm::dvec3(l.direction));
        const glm::dvec3 u = glm::normalize(glm::dmat3(view) * t);
        d.halfWidthAxis = glm::vec3(u * (0.5 * l.size.x));
        d.halfHeight = 0.5f * l.size.y;
    }
    return d;
}

} // namespace

void validateLightShadows(const ShadowMapSet& maps, const ShadowMaskSettings& filter, std::size_t lightCount,
                          const Camera& camera, const std::string& owner) {
    validateShadowMask(filter, owner + "::shadowFilter");
    if (filter.filter != ShadowFilter::Hard && filter.filter != ShadowFilter::Pcf)
        throw Error(ErrorCode::InvalidArgument, owner + "::shadowFilter: lighting passes look shadows up with Hard or Pcf; "
                                                        "the moment filters and PCSS are ShadowMaps::mask's");
    requireMapsFor(maps, camera, owner + "::shadows");
    for (const ShadowMapInfo& m : maps.maps)
        if (m.light >= lightCount)
            throw Error(ErrorCode::InvalidArgument, owner + "::shadows has maps of light " + std::to_string(m.light) +
                                                        " but the scene has " + std::to_string(lightCount) + " lights");
}

bool LightRecords::bindShadows(ContextImpl& ctx, std::span<const Light> lights, const Camera& camera,
                               const ShadowMapSet* maps, const ShadowMaskSettings& filter) {
    recordOf_.assign(lights.size(), -1);
    if (!maps || !maps->depth) return false;
    std::vector<shader::ShadowParams> records;
    for (std::size_t i = 0; i < lights.size(); ++i)
        if (const ShadowMapInfo* info = maps->find(i)) {
            recordOf_[i] = static_cast<int>(records.size());
            records.push_back(shadowRecord(*info, camera, filter, maps->resolution));
        }
    if (records.empty()) return false;
    shadows_.bind(ctx, maps->depth, records, filter.filter);
    return true;
}

void LightRecords::upload(ContextImpl& ctx, std::span<const Light> lights, const glm::dmat4& view, const char* label) {
    recordOf_.resize(lights.size(), -1);
    std::vector<shader::LightData> data;
    data.reserve(lights.size());
    for (std::size_t i = 0; i < lights.size(); ++i) {
        data.push_back(toViewSpace(lights[i], view));
        data.back().shadowRecord = static_cast<float>(recordOf_[i]);
    }
    const std::size_t needed = std::max<std::size_t>(1, data.size());
    if (!buffer_ || capacity_ < needed) {
        buffer_ = createBuffer(ctx, static_cast<GLsizeiptr>(needed * sizeof(shader::LightData)), nullptr,
                               GL_DYNAMIC_STORAGE_BIT, label);
        capacity_ = needed;
    }
    if (!data.empty())
        ctx.gl.NamedBufferSubData(buffer_.get(), 0, static_cast<GLsizeiptr>(data.size() * sizeof(data[0])), data.data());
    ctx.state.bindStorageBuffer(ctx, GBUFFER_LIGHTS_SSBO_BINDING, buffer_.get());
}

std::size_t LightRecords::memoryBytes() const { return capacity_ * sizeof(shader::LightData) + shadows_.memoryBytes(); }

} // namespace obscura::detail

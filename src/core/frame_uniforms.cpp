#include "core/frame_uniforms.hpp"

#include "shaders/common/common_bindings.h"
#include "core/context_impl.hpp"

#include <algorithm>
#include <cmath>

namespace obscura::detail {

glm::vec3 frameSampleShift(std::uint32_t index) {
    // 1 / phi3^k, phi3 = 1.2207440846... the real root of x^4 = x + 1.
    constexpr double alpha[3] = {0.8191725133961645, 0.6710436067037893, 0.5497004779019703};
    glm::vec3 shift;
    for (int k = 0; k < 3; ++k) {
        const double v = double(index) * alpha[k]; // < 2^32: the fraction keeps 20 bits or more
        shift[k] = std::min(static_cast<float>(v - std::floor(v)), 0.99999994f);
    }
    return shift;
}

void FrameUniforms::bind(ContextImpl& ctx, const Camera& camera, int width, int height, double depthStep, float normalError,
                         std::uint32_t frameIndex) {
    const DepthReconstruction r = depthReconstruction(camera);
    const ProjectionInfo info = analyzeProjection(camera);
    shader::FrameData data;
    data.view = camera.view;
    data.projection = camera.projection;
    data.viewInverse = glm::mat4(glm::inverse(glm::dmat4(camera.view)));
    data.depthXY = glm::vec4(r.xyScale, r.xyOffset);
    data.depthZ = glm::vec4(r.zScale, r.zBiasHi, r.zBiasLo, r.clearDepth);
    data.viewport = glm::ivec4(width, height,
                               r.kind == ProjectionKind::Perspective ? OBSCURA_PROJECTION_PERSPECTIVE
                                                                     : OBSCURA_PROJECTION_ORTHOGRAPHIC,
                               info.reversedZ ? 1 : 0);
    data.depthPrecision = glm::vec4(static_cast<float>(depthStep), normalError, r.farthestDepth, 0.0f);
    data.sampleShift = glm::vec4(frameSampleShift(frameIndex), 0.0f);
    if (!buffer_) buffer_ = createBuffer(ctx, sizeof data, nullptr, GL_DYNAMIC_STORAGE_BIT, "obscura.frame_uniforms");
    ctx.gl.NamedBufferSubData(buffer_.get(), 0, sizeof data, &data);
    ctx.state.bindUniformBuffer(ctx, OBSCURA_FRAME_UBO_BINDING, buffer_.get());
}

std::size_t FrameUniforms::memoryBytes() const { return buffer_ ? sizeof(shader::FrameData) : 0; }

} // namespace obscura::detail

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
    shader::FrameData data{};
    data.view = camera.view;
    data.projection = camera.projection;
    data.viewInverse = glm::mat4(glm::inverse(glm::dmat4(camera.view)));
    data.rayScale = r.xyScale;
    data.rayOffset = r.xyOffset;
    data.depthScale = r.zScale;
    data.depthBiasHi = r.zBiasHi;
    data.depthBiasLo = r.zBiasLo;
    data.clearDepth = r.clearDepth;
    data.size = glm::ivec2(width, height);
    data.projectionKind =
        r.kind == ProjectionKind::Perspective ? OBSCURA_PROJECTION_PERSPECTIVE : OBSCURA_PROJECTION_ORTHOGRAPHIC;
    data.reversedZ = info.reversedZ ? 1 : 0;
    data.depthStep = static_cast<float>(depthStep);
    data.normalError = normalError;
    data.farthestDepth = r.farthestDepth;
    data.sampleShift = frameSampleShift(frameIndex);
    uploadUniformBlock(ctx, buffer_, data, OBSCURA_FRAME_UBO_BINDING, "obscura.frame_uniforms");
}

std::size_t FrameUniforms::memoryBytes() const { return buffer_ ? sizeof(shader::FrameData) : 0; }

} // namespace obscura::detail

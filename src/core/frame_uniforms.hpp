#pragma once
// The per-frame uniform block (shaders/common/frame.glsl) filled from a Camera.
#include "core/gl_objects.hpp"
#include "obscura/camera.hpp"

#include <cstdint>

namespace obscura::detail {

struct ContextImpl;

//! The shift of frame `index` (sampling.glsl): point `index` of the R3 sequence, the fractional
//! parts of index times (1/phi3, 1/phi3^2, 1/phi3^3), phi3 the plastic-like root of x^4 = x + 1
//! (Roberts 2018): consecutive frames' shifts fill [0, 1)^3 evenly, so N frames average N
//! well-spread rotations of each pixel's point set. Index 0 is no shift.
glm::vec3 frameSampleShift(std::uint32_t index);

class FrameUniforms {
public:
    //! Uploads the camera and viewport and binds the block at OBSCURA_FRAME_UBO_BINDING.
    //! `depthStep`: one step of the depth buffer read with it (TextureInfo::depthStep; 0 for
    //! float depth), whose precision bounds what screen-space tests can resolve.
    //! `normalError`: GBufferView::normalError of the normals the pass reads (0: none).
    //! `frameIndex`: shifts every pixel's sampling pattern (sampleShift), 0: no shift.
    void bind(ContextImpl& ctx, const Camera& camera, int width, int height, double depthStep, float normalError = 0.0f,
              std::uint32_t frameIndex = 0);
    std::size_t memoryBytes() const;

private:
    Buffer buffer_;
};

} // namespace obscura::detail

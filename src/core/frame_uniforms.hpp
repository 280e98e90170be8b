#pragma once
// The per-frame uniform block (shaders/common/frame.glsl) filled from a Camera.
#include "core/gl_objects.hpp"
#include "obscura/camera.hpp"

namespace obscura::detail {

struct ContextImpl;

class FrameUniforms {
public:
    //! Uploads the camera and viewport and binds the block at OBSCURA_FRAME_UBO_BINDING.
    //! `depthStep`: one step of the depth buffer read with it (TextureInfo::depthStep; 0 for
    //! float depth), whose precision bounds what screen-space tests can resolve.
    //! `normalError`: GBufferView::normalError of the normals the pass reads (0: none).
    void bind(ContextImpl& ctx, const Camera& camera, int width, int height, double depthStep, float normalError = 0.0f);
    std::size_t memoryBytes() const;

private:
    Buffer buffer_;
};

} // namespace obscura::detail

#pragma once
// media.bounded's first two passes: the spot lights' lit volumes rebuilt from their shadow
// maps (shaders/media/media_volume.comp.glsl) and drawn from the camera into each pixel's
// nearest and farthest crossing (media_volume.{vert,frag}.glsl), for the march to sample
// between them.
#include "core/gl_objects.hpp"
#include "obscura/media.hpp"

#include <cstddef>

namespace obscura::detail {

struct ContextImpl;
class LightRecords;

//! Whether Bounded has a bound to take: every light a spot with a map in `maps`.
bool everyLightBounded(const MediaInputs& inputs);

class ShadowVolumes {
public:
    //! Builds and draws the volumes of every light (everyLightBounded must hold), with the
    //! frame uniforms, the lights' records and the shadow records bound; leaves the crossing
    //! images bound at MEDIA_NEAR_IMAGE and MEDIA_FAR_IMAGE for the march.
    void draw(ContextImpl& ctx, const MediaInputs& inputs, const LightRecords& records, int cellTexels, int width, int height);
    void release() noexcept;
    std::size_t memoryBytes() const;

private:
    Buffer vertices_;
    std::size_t vertexBytes_ = 0;
    SizedTexture nearest_, farthest_, cells_;
    Framebuffer fbo_;
};

} // namespace obscura::detail

#pragma once
// The scene's lights as the shaders read them (shaders/gbuffer/light_irradiance.glsl): view-
// space records in a storage buffer, each with its shadow record where a ShadowMapSet has
// maps for it. Shared by the G-buffer's lighting and SSDO's lights pass.
#include "core/gl_objects.hpp"
#include "obscura/camera.hpp"
#include "obscura/scene.hpp"
#include "obscura/shadow_maps.hpp"
#include "shadows/shadow_lookup.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace obscura::detail {

struct ContextImpl;

//! The checks of a ShadowMapSet a lighting pass reads (`owner` names it in messages): the
//! filter (Hard or Pcf: what shadow_sample.glsl's lookups take outside ShadowMaps::mask), the
//! maps against the camera, and lights that exist. Throws Error{InvalidArgument}.
void validateLightShadows(const ShadowMapSet& maps, const ShadowMaskSettings& filter, std::size_t lightCount,
                          const Camera& camera, const std::string& owner);

class LightRecords {
public:
    //! Binds the shadow records of the lights `maps` has maps for (none without maps); returns
    //! whether any light has one. Before upload().
    bool bindShadows(ContextImpl& ctx, std::span<const Light> lights, const Camera& camera, const ShadowMapSet* maps,
                     const ShadowMaskSettings& filter);
    //! Writes the lights, in view space, with the records bindShadows() found, and binds them.
    void upload(ContextImpl& ctx, std::span<const Light> lights, const glm::dmat4& view, const char* label);
    std::size_t memoryBytes() const;
    //! The shadow record (ShadowParams index) of light i, or -1 without maps.
    int recordOf(std::size_t i) const { return i < recordOf_.size() ? recordOf_[i] : -1; }

private:
    std::vector<int> recordOf_;
    ShadowBinding shadows_;
    Buffer buffer_;
    std::size_t capacity_ = 0;
};

} // namespace obscura::detail

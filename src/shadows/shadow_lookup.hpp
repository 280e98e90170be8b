#pragma once
// What a pass that looks shadows up (shaders/shadows/shadow_sample.glsl) needs on the host:
// the settings check, the per-light records and their binding with the maps.
#include "core/gl_objects.hpp"
#include "obscura/shadow_maps.hpp"
#include "shaders/shadows/shadow_bindings.h"

#include <string>
#include <vector>

namespace obscura::detail {

//! Throws Error{InvalidArgument} naming `owner` for settings out of range.
void validateShadowMask(const ShadowMaskSettings& s, const std::string& owner);

//! Throws Error{InvalidArgument} unless `maps` were fitted to `camera`.
void requireMapsFor(const ShadowMapSet& maps, const Camera& camera, const std::string& owner);

//! The record of `info`'s light, in `camera`'s view space.
shader::ShadowParams shadowRecord(const ShadowMapInfo& info, const Camera& camera, const ShadowMaskSettings& s,
                                  int resolution);

//! The shader's code of the filter (SHADOW_FILTER_*) and its define (FILTER=...).
int shadowFilterCode(ShadowFilter filter);
std::string shadowFilterDefine(ShadowFilter filter);
//! The mask and moment passes' defines: the filter's, and for a moment filter its storage
//! (MOMENTS_HALF, MOMENTS_UNORM; see shadow_bindings.h).
std::vector<std::string> shadowMaskDefines(const ShadowMaskSettings& s);
//! The moment maps' GL format for `s` (a moment filter).
GLenum shadowMomentFormat(const ShadowMaskSettings& s);
//! Vsm, Esm, Evsm2, Evsm4, Msm: looked up in prefiltered moments, not in the depth maps.
bool isMomentFilter(ShadowFilter filter);

//! Uploads records to SHADOW_LIGHTS_SSBO and binds the maps at SHADOW_MAP_UNIT with the
//! comparison sampler of the filter (nearest for Hard, linear for Pcf).
class ShadowBinding {
public:
    void bind(ContextImpl& ctx, GLuint maps, const std::vector<shader::ShadowParams>& records, ShadowFilter filter);
    std::size_t memoryBytes() const { return capacity_ * sizeof(shader::ShadowParams); }

private:
    Buffer records_;
    std::size_t capacity_ = 0;
    Sampler nearest_, linear_;
};

} // namespace obscura::detail

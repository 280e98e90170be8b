#pragma once
// Temporal accumulation of an integrator's result at the G-buffer's resolution
// (shaders/filters/temporal.comp.glsl): AO's and IndirectLight's TemporalSettings.
#include "core/gl_objects.hpp"
#include "obscura/ambient_occlusion.hpp"
#include "obscura/gbuffer.hpp"

#include <glm/glm.hpp>

#include <cstddef>
#include <string>

namespace obscura::detail {

struct ContextImpl;


class TemporalHistory {
public:
    //! Averages `value` (the view's size: GL_R16F, or GL_RGBA16F with `rgb`), in place, with
    //! the history of the last call, reprojected from its camera to the view's, and keeps the
    //! result as the next call's history. The caller has bound the frame block of the view's
    //! camera and its depth and normal (VIS_DEPTH_UNIT, VIS_NORMAL_UNIT). A history of another
    //! size or kind, or none, starts afresh. Pass `passName`.
    void accumulate(ContextImpl& ctx, const GBufferView& view, GLuint value, bool rgb, const TemporalSettings& s,
                    const char* passName);
    //! Forgets the history (and frees it): the next call starts afresh.
    void reset() noexcept;
    std::size_t memoryBytes() const;
    //! Compiles the program accumulate() uses, ahead of time.
    static void prepare(ContextImpl& ctx, bool rgb);

private:
    SizedTexture history_[2], geometry_[2];
    int latest_ = -1; //!< the index of the last call's history, -1: none
    bool rgb_ = false;
    glm::ivec2 size_{0};
    glm::dmat4 previousView_{1.0}, previousProjection_{1.0};
    DepthReconstruction previousRays_; //!< of the last call's camera: its view rays
    Buffer params_;
};

} // namespace obscura::detail

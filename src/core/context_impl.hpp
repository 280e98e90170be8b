#pragma once
#include "core/gl.hpp"
#include "core/gl_objects.hpp"
#include "core/state_guard.hpp"
#include "obscura/context.hpp"
#include "obscura/profiler.hpp"

#include <memory>

namespace obscura::detail {

class ShaderLibrary;

struct ContextImpl {
    GladGLContext gl{};
    ContextDesc desc;
    ContextInfo info;
    std::size_t liveObjects = 0; //!< incremented/decremented by every Handle
    StateTracker state;
    std::unique_ptr<ShaderLibrary> shaders;
    std::unique_ptr<Profiler> profiler;

    // Shared helpers, created on first use.
    VertexArray emptyVao;   //!< for attribute-less full-screen draws
    Sampler nearestClamp;
    Sampler linearClamp;
    Texture noise;          //!< the tiled random texture of shaders/common/sampling.glsl

    GLuint emptyVertexArray();
    GLuint nearestClampSampler();
    GLuint linearClampSampler();
    //! Binds the tiled random texture at OBSCURA_NOISE_TEXTURE_UNIT (created on first use).
    void bindNoiseTexture();

    explicit ContextImpl(const ContextDesc& d);
    ~ContextImpl();
};

} // namespace obscura::detail

#pragma once
// Saving and restoring the host's GL state around every public call (the list is in
// include/obscura/context.hpp). Global state is saved once on entry to the outermost
// scope; per-unit bindings (texture/sampler/image units, indexed UBO/SSBO points) are
// saved lazily, the first time a call binds something there, so a call pays only for
// the units it uses. Obscura code must bind units through StateTracker, never directly.
#include "core/gl.hpp"

#include <array>
#include <cstdint>
#include <map>
#include <memory>

namespace obscura::detail {

struct ContextImpl;

struct SavedGlobalState;

class StateTracker {
public:
    StateTracker();
    ~StateTracker();

    void enter(ContextImpl& ctx);
    void leave(ContextImpl& ctx) noexcept;
    bool active() const noexcept { return depth_ > 0; }

    // Binding helpers; each saves the unit's host bindings before the first change.
    void bindTexture(ContextImpl& ctx, GLuint unit, GLuint texture);
    void bindSampler(ContextImpl& ctx, GLuint unit, GLuint sampler);
    void bindImage(ContextImpl& ctx, GLuint unit, GLuint texture, GLint level, GLboolean layered, GLint layer,
                   GLenum access, GLenum format);
    void bindUniformBuffer(ContextImpl& ctx, GLuint index, GLuint buffer, GLintptr offset = 0, GLsizeiptr size = 0);
    void bindStorageBuffer(ContextImpl& ctx, GLuint index, GLuint buffer, GLintptr offset = 0, GLsizeiptr size = 0);

private:
    struct TextureUnit {
        std::array<GLint, 11> targets{};
        GLint sampler = 0;
        bool samplerOnly = false;
    };
    struct ImageUnit {
        GLint name = 0, level = 0, layer = 0, access = 0, format = 0;
        GLboolean layered = GL_FALSE;
    };
    struct BufferPoint {
        GLint64 buffer = 0, start = 0, size = 0;
    };

    void saveTextureUnit(ContextImpl& ctx, GLuint unit);
    void saveImageUnit(ContextImpl& ctx, GLuint unit);
    void saveBufferPoint(ContextImpl& ctx, GLenum target, GLuint index);
    void restoreUnits(ContextImpl& ctx) noexcept;
    void clearUnits(ContextImpl& ctx) noexcept;

    int depth_ = 0;
    bool preserving_ = false;
    std::unique_ptr<SavedGlobalState> global_; // pimpl: keeps the long list out of this header
    std::map<GLuint, TextureUnit> textureUnits_;
    std::map<GLuint, ImageUnit> imageUnits_;
    std::map<GLuint, BufferPoint> uniformPoints_;
    std::map<GLuint, BufferPoint> storagePoints_;
};

//! RAII: every public entry point that touches GL opens one before its first GL command.
class StateScope {
public:
    explicit StateScope(ContextImpl& ctx);
    ~StateScope();
    StateScope(const StateScope&) = delete;
    StateScope& operator=(const StateScope&) = delete;

private:
    ContextImpl& ctx_;
};

//! Fixed-function state a draw relies on. Every draw pass applies a full DrawState so that
//! nothing left by an earlier pass (or by the host under StatePolicy::Clobber) leaks in.
struct DrawState {
    bool depthTest = false;
    bool depthWrite = false;
    GLenum depthFunc = GL_LESS;
    bool cullBackFaces = false;
    bool framebufferSrgb = false;
    GLenum clipDepth = GL_NEGATIVE_ONE_TO_ONE;
    bool depthClamp = false;
    GLenum logicOp = GL_NONE; //!< GL_NONE: no logic op; else glLogicOp's mode (integer targets)
    bool multiplyBlend = false; //!< draw buffer 0: destination *= source (glBlendFunc(GL_DST_COLOR, GL_ZERO))
    bool writeAlpha = true;     //!< off: the destination's alpha is kept
};
void applyDrawState(ContextImpl& ctx, const DrawState& state);
//! Sets viewport index 0 only (glViewport would reset every index of the host).
void setViewport(ContextImpl& ctx, int x, int y, int width, int height);

} // namespace obscura::detail

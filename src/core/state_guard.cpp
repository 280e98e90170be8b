#include "core/state_guard.hpp"

#include "core/context_impl.hpp"
#include "core/extension_state.hpp"
#include "obscura/error.hpp"

#include <iterator>
#include <memory>
#include <vector>

namespace obscura::detail {
namespace {

constexpr GLenum kTextureTargets[11] = {
    GL_TEXTURE_1D,       GL_TEXTURE_1D_ARRAY, GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY, GL_TEXTURE_2D_MULTISAMPLE,
    GL_TEXTURE_2D_MULTISAMPLE_ARRAY, GL_TEXTURE_3D, GL_TEXTURE_CUBE_MAP, GL_TEXTURE_CUBE_MAP_ARRAY,
    GL_TEXTURE_RECTANGLE, GL_TEXTURE_BUFFER};
constexpr GLenum kTextureBindings[11] = {
    GL_TEXTURE_BINDING_1D,       GL_TEXTURE_BINDING_1D_ARRAY, GL_TEXTURE_BINDING_2D, GL_TEXTURE_BINDING_2D_ARRAY,
    GL_TEXTURE_BINDING_2D_MULTISAMPLE, GL_TEXTURE_BINDING_2D_MULTISAMPLE_ARRAY, GL_TEXTURE_BINDING_3D,
    GL_TEXTURE_BINDING_CUBE_MAP, GL_TEXTURE_BINDING_CUBE_MAP_ARRAY, GL_TEXTURE_BINDING_RECTANGLE,
    GL_TEXTURE_BINDING_BUFFER};

// Enables saved and reset as plain booleans (scissor test is indexed, blend per draw buffer).
constexpr GLenum kEnables[] = {
    GL_DEPTH_TEST,          GL_STENCIL_TEST,           GL_CULL_FACE,           GL_COLOR_LOGIC_OP,
    GL_PRIMITIVE_RESTART,   GL_PRIMITIVE_RESTART_FIXED_INDEX, GL_DEPTH_CLAMP,  GL_FRAMEBUFFER_SRGB,
    GL_POLYGON_OFFSET_FILL, GL_POLYGON_OFFSET_LINE,    GL_POLYGON_OFFSET_POINT, GL_RASTERIZER_DISCARD,
    GL_SAMPLE_ALPHA_TO_COVERAGE, GL_SAMPLE_COVERAGE,   GL_SAMPLE_MASK,         GL_PROGRAM_POINT_SIZE,
    GL_CLIP_DISTANCE0,      GL_CLIP_DISTANCE1,         GL_CLIP_DISTANCE2,      GL_CLIP_DISTANCE3,
    GL_CLIP_DISTANCE4,      GL_CLIP_DISTANCE5,         GL_CLIP_DISTANCE6,      GL_CLIP_DISTANCE7,
    GL_POLYGON_SMOOTH};
constexpr std::size_t kEnableCount = std::size(kEnables);

// Generic buffer bindings: target and its binding query.
constexpr GLenum kBufferTargets[13][2] = {
    {GL_ARRAY_BUFFER, GL_ARRAY_BUFFER_BINDING},
    {GL_COPY_READ_BUFFER, GL_COPY_READ_BUFFER_BINDING},
    {GL_COPY_WRITE_BUFFER, GL_COPY_WRITE_BUFFER_BINDING},
    {GL_PIXEL_PACK_BUFFER, GL_PIXEL_PACK_BUFFER_BINDING},
    {GL_PIXEL_UNPACK_BUFFER, GL_PIXEL_UNPACK_BUFFER_BINDING},
    {GL_DRAW_INDIRECT_BUFFER, GL_DRAW_INDIRECT_BUFFER_BINDING},
    {GL_DISPATCH_INDIRECT_BUFFER, GL_DISPATCH_INDIRECT_BUFFER_BINDING},
    {GL_QUERY_BUFFER, GL_QUERY_BUFFER_BINDING},
    {GL_TEXTURE_BUFFER, GL_TEXTURE_BUFFER_BINDING},
    {GL_UNIFORM_BUFFER, GL_UNIFORM_BUFFER_BINDING},
    {GL_SHADER_STORAGE_BUFFER, GL_SHADER_STORAGE_BUFFER_BINDING},
    {GL_ATOMIC_COUNTER_BUFFER, GL_ATOMIC_COUNTER_BUFFER_BINDING},
    {GL_TRANSFORM_FEEDBACK_BUFFER, GL_TRANSFORM_FEEDBACK_BUFFER_BINDING}};

// Pixel store parameters with their GL initial values.
constexpr GLenum kPixelStore[16][2] = {
    {GL_PACK_ALIGNMENT, 4},    {GL_PACK_ROW_LENGTH, 0},    {GL_PACK_IMAGE_HEIGHT, 0}, {GL_PACK_SKIP_PIXELS, 0},
    {GL_PACK_SKIP_ROWS, 0},    {GL_PACK_SKIP_IMAGES, 0},   {GL_PACK_SWAP_BYTES, 0},   {GL_PACK_LSB_FIRST, 0},
    {GL_UNPACK_ALIGNMENT, 4},  {GL_UNPACK_ROW_LENGTH, 0},  {GL_UNPACK_IMAGE_HEIGHT, 0}, {GL_UNPACK_SKIP_PIXELS, 0},
    {GL_UNPACK_SKIP_ROWS, 0},  {GL_UNPACK_SKIP_IMAGES, 0}, {GL_UNPACK_SWAP_BYTES, 0}, {GL_UNPACK_LSB_FIRST, 0}};

void setEnabled(GladGLContext& gl, GLenum cap, bool on) { on ? gl.Enable(cap) : gl.Disable(cap); }

void GLAD_API_PTR forwardDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei length,
                                      const GLchar* message, const void* user) {
    // Our own debug groups are navigation aids, not messages.
    if (type == GL_DEBUG_TYPE_PUSH_GROUP || type == GL_DEBUG_TYPE_POP_GROUP) return;
    const auto* ctx = static_cast<const ContextImpl*>(user);
    if (!ctx->desc.debugOutput) return;
    // Exceptions must not unwind through the driver's C frames.
    try {
        DebugMessage m{source, type, id, severity,
                       length >= 0 ? std::string(message, static_cast<std::size_t>(length)) : std::string(message)};
        ctx->desc.debugOutput(m);
    } catch (...) {
    }
}

} // namespace

struct SavedGlobalState {
    GLint program = 0, vao = 0, drawFbo = 0, readFbo = 0;
    GLfloat viewport[4]{};
    GLint scissor[4]{};
    GLdouble depthRange[2]{};
    GLboolean scissorTest0 = GL_FALSE;
    GLboolean enables[kEnableCount]{};
    struct DrawBuffer {
        GLboolean blend = GL_FALSE;
        GLint srcRgb = 0, dstRgb = 0, srcAlpha = 0, dstAlpha = 0, eqRgb = 0, eqAlpha = 0;
        GLboolean colorMask[4]{};
    };
    std::vector<DrawBuffer> drawBuffers;
    GLfloat blendColor[4]{};
    GLboolean depthMask = GL_TRUE;
    GLint stencil[2][6]{}; // func, ref, value mask, fail, depth fail, depth pass; front and back
    GLint stencilWriteMask[2]{};
    GLint depthFunc = 0, logicOp = 0, clipOrigin = 0, clipDepth = 0;
    GLint polygonMode[2]{};
    GLfloat offsetFactor = 0, offsetUnits = 0;
    GLint frontFace = 0, cullFaceMode = 0, activeTexture = 0, provokingVertex = 0, clampReadColor = 0;
    GLboolean dither = GL_TRUE;
    ExtensionState extensions; // vendor extensions' state, where the context has them
    GLint pixelStore[16]{};
    GLint buffers[13]{};
    bool debug = false;
    void* debugCallback = nullptr;
    void* debugUser = nullptr;
    GLboolean debugOutput = GL_FALSE, debugSync = GL_FALSE;
};

namespace {

void saveGlobal(ContextImpl& ctx, SavedGlobalState& s) {
    auto& gl = ctx.gl;
    gl.GetIntegerv(GL_CURRENT_PROGRAM, &s.program);
    // A program the host deleted while current lives only as long as it stays current: GL
    // deletes it as soon as another is bound (0, at once, under either policy; GL 4.5, 7.3),
    // and binding its name back would raise GL_INVALID_VALUE and leave ours current. 0 is
    // what the host then gets (also where another context keeps the program alive: its name
    // is then still valid, but this context had let it go).
    GLint deleted = GL_FALSE;
    if (s.program != 0) gl.GetProgramiv(static_cast<GLuint>(s.program), GL_DELETE_STATUS, &deleted);
    if (deleted) s.program = 0;
    gl.GetIntegerv(GL_VERTEX_ARRAY_BINDING, &s.vao);
    gl.GetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &s.drawFbo);
    gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &s.readFbo);
    gl.GetFloati_v(GL_VIEWPORT, 0, s.viewport);
    gl.GetIntegeri_v(GL_SCISSOR_BOX, 0, s.scissor);
    gl.GetDoublei_v(GL_DEPTH_RANGE, 0, s.depthRange);
    s.scissorTest0 = gl.IsEnabledi(GL_SCISSOR_TEST, 0);
    for (std::size_t i = 0; i < kEnableCount; ++i) s.enables[i] = gl.IsEnabled(kEnables[i]);
    s.drawBuffers.resize(static_cast<std::size_t>(ctx.info.maxDrawBuffers));
    for (GLuint i = 0; i < s.drawBuffers.size(); ++i) {
        auto& d = s.drawBuffers[i];
        d.blend = gl.IsEnabledi(GL_BLEND, i);
        gl.GetIntegeri_v(GL_BLEND_SRC_RGB, i, &d.srcRgb);
        gl.GetIntegeri_v(GL_BLEND_DST_RGB, i, &d.dstRgb);
        gl.GetIntegeri_v(GL_BLEND_SRC_ALPHA, i, &d.srcAlpha);
        gl.GetIntegeri_v(GL_BLEND_DST_ALPHA, i, &d.dstAlpha);
        gl.GetIntegeri_v(GL_BLEND_EQUATION_RGB, i, &d.eqRgb);
        gl.GetIntegeri_v(GL_BLEND_EQUATION_ALPHA, i, &d.eqAlpha);
        gl.GetBooleani_v(GL_COLOR_WRITEMASK, i, d.colorMask);
    }
    gl.GetFloatv(GL_BLEND_COLOR, s.blendColor);
    gl.GetBooleanv(GL_DEPTH_WRITEMASK, &s.depthMask);
    constexpr GLenum stencilQueries[2][6] = {
        {GL_STENCIL_FUNC, GL_STENCIL_REF, GL_STENCIL_VALUE_MASK, GL_STENCIL_FAIL, GL_STENCIL_PASS_DEPTH_FAIL,
         GL_STENCIL_PASS_DEPTH_PASS},
        {GL_STENCIL_BACK_FUNC, GL_STENCIL_BACK_REF, GL_STENCIL_BACK_VALUE_MASK, GL_STENCIL_BACK_FAIL,
         GL_STENCIL_BACK_PASS_DEPTH_FAIL, GL_STENCIL_BACK_PASS_DEPTH_PASS}};
    for (int f = 0; f < 2; ++f)
        for (int i = 0; i < 6; ++i) gl.GetIntegerv(stencilQueries[f][i], &s.stencil[f][i]);
    gl.GetIntegerv(GL_STENCIL_WRITEMASK, &s.stencilWriteMask[0]);
    gl.GetIntegerv(GL_STENCIL_BACK_WRITEMASK, &s.stencilWriteMask[1]);
    gl.GetIntegerv(GL_DEPTH_FUNC, &s.depthFunc);
    gl.GetIntegerv(GL_LOGIC_OP_MODE, &s.logicOp);
    gl.GetIntegerv(GL_CLIP_ORIGIN, &s.clipOrigin);
    gl.GetIntegerv(GL_CLIP_DEPTH_MODE, &s.clipDepth);
    gl.GetIntegerv(GL_POLYGON_MODE, s.polygonMode);
    gl.GetFloatv(GL_POLYGON_OFFSET_FACTOR, &s.offsetFactor);
    gl.GetFloatv(GL_POLYGON_OFFSET_UNITS, &s.offsetUnits);
    gl.GetIntegerv(GL_FRONT_FACE, &s.frontFace);
    gl.GetIntegerv(GL_CULL_FACE_MODE, &s.cullFaceMode);
    gl.GetIntegerv(GL_PROVOKING_VERTEX, &s.provokingVertex);
    gl.GetIntegerv(GL_CLAMP_READ_COLOR, &s.clampReadColor);
    s.dither = gl.IsEnabled(GL_DITHER);
    s.extensions.save(gl);
    gl.GetIntegerv(GL_ACTIVE_TEXTURE, &s.activeTexture);
    for (int i = 0; i < 16; ++i) gl.GetIntegerv(kPixelStore[i][0], &s.pixelStore[i]);
    for (int i = 0; i < 13; ++i) gl.GetIntegerv(kBufferTargets[i][1], &s.buffers[i]);
    s.debug = static_cast<bool>(ctx.desc.debugOutput);
    if (s.debug) {
        gl.GetPointerv(GL_DEBUG_CALLBACK_FUNCTION, &s.debugCallback);
        gl.GetPointerv(GL_DEBUG_CALLBACK_USER_PARAM, &s.debugUser);
        s.debugOutput = gl.IsEnabled(GL_DEBUG_OUTPUT);
        s.debugSync = gl.IsEnabled(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    }
}

void restoreGlobal(ContextImpl& ctx, const SavedGlobalState& s) {
    auto& gl = ctx.gl;
    gl.UseProgram(static_cast<GLuint>(s.program));
    gl.BindVertexArray(static_cast<GLuint>(s.vao));
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(s.drawFbo));
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(s.readFbo));
    gl.ViewportIndexedfv(0, s.viewport);
    gl.ScissorIndexedv(0, s.scissor);
    gl.DepthRangeIndexed(0, s.depthRange[0], s.depthRange[1]);
    s.scissorTest0 ? gl.Enablei(GL_SCISSOR_TEST, 0) : gl.Disablei(GL_SCISSOR_TEST, 0);
    for (std::size_t i = 0; i < kEnableCount; ++i) setEnabled(gl, kEnables[i], s.enables[i]);
    for (GLuint i = 0; i < s.drawBuffers.size(); ++i) {
        const auto& d = s.drawBuffers[i];
        d.blend ? gl.Enablei(GL_BLEND, i) : gl.Disablei(GL_BLEND, i);
        gl.BlendFuncSeparatei(i, static_cast<GLenum>(d.srcRgb), static_cast<GLenum>(d.dstRgb),
                              static_cast<GLenum>(d.srcAlpha), static_cast<GLenum>(d.dstAlpha));
        // An advanced equation (KHR_blend_equation_advanced) is set for RGB and alpha together,
        // and glBlendEquationSeparatei refuses it.
        if (d.eqRgb == d.eqAlpha) gl.BlendEquationi(i, static_cast<GLenum>(d.eqRgb));
        else gl.BlendEquationSeparatei(i, static_cast<GLenum>(d.eqRgb), static_cast<GLenum>(d.eqAlpha));
        gl.ColorMaski(i, d.colorMask[0], d.colorMask[1], d.colorMask[2], d.colorMask[3]);
    }
    gl.BlendColor(s.blendColor[0], s.blendColor[1], s.blendColor[2], s.blendColor[3]);
    gl.DepthMask(s.depthMask);
    constexpr GLenum faces[2] = {GL_FRONT, GL_BACK};
    for (int f = 0; f < 2; ++f) {
        gl.StencilFuncSeparate(faces[f], static_cast<GLenum>(s.stencil[f][0]), s.stencil[f][1],
                               static_cast<GLuint>(s.stencil[f][2]));
        gl.StencilOpSeparate(faces[f], static_cast<GLenum>(s.stencil[f][3]), static_cast<GLenum>(s.stencil[f][4]),
                             static_cast<GLenum>(s.stencil[f][5]));
        gl.StencilMaskSeparate(faces[f], static_cast<GLuint>(s.stencilWriteMask[f]));
    }
    gl.DepthFunc(static_cast<GLenum>(s.depthFunc));
    gl.LogicOp(static_cast<GLenum>(s.logicOp));
    gl.ClipControl(static_cast<GLenum>(s.clipOrigin), static_cast<GLenum>(s.clipDepth));
    gl.PolygonMode(GL_FRONT_AND_BACK, static_cast<GLenum>(s.polygonMode[0]));
    gl.PolygonOffset(s.offsetFactor, s.offsetUnits);
    gl.FrontFace(static_cast<GLenum>(s.frontFace));
    gl.CullFace(static_cast<GLenum>(s.cullFaceMode));
    gl.ProvokingVertex(static_cast<GLenum>(s.provokingVertex));
    gl.ClampColor(GL_CLAMP_READ_COLOR, static_cast<GLenum>(s.clampReadColor));
    setEnabled(gl, GL_DITHER, s.dither);
    s.extensions.restore(gl);
    for (int i = 0; i < 16; ++i) gl.PixelStorei(kPixelStore[i][0], s.pixelStore[i]);
    for (int i = 0; i < 13; ++i) gl.BindBuffer(kBufferTargets[i][0], static_cast<GLuint>(s.buffers[i]));
    gl.ActiveTexture(static_cast<GLenum>(s.activeTexture));
    if (s.debug) {
        gl.DebugMessageCallback(reinterpret_cast<GLDEBUGPROC>(s.debugCallback), s.debugUser);
        setEnabled(gl, GL_DEBUG_OUTPUT, s.debugOutput);
        setEnabled(gl, GL_DEBUG_OUTPUT_SYNCHRONOUS, s.debugSync);
    }
}

// The state every call starts from (and, under Clobber, ends with): GL initial values.
void applyBaseline(ContextImpl& ctx) {
    auto& gl = ctx.gl;
    gl.UseProgram(0);
    gl.BindVertexArray(0);
    gl.BindFramebuffer(GL_FRAMEBUFFER, 0);
    gl.DepthRangeIndexed(0, 0.0, 1.0);
    gl.Disablei(GL_SCISSOR_TEST, 0);
    for (GLenum cap : kEnables) gl.Disable(cap);
    gl.Disable(GL_BLEND);
    gl.BlendFunc(GL_ONE, GL_ZERO);
    gl.BlendEquation(GL_FUNC_ADD);
    gl.BlendColor(0, 0, 0, 0);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl.DepthMask(GL_TRUE);
    gl.StencilFunc(GL_ALWAYS, 0, 0xFF);
    gl.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    gl.StencilMask(0xFF);
    gl.DepthFunc(GL_LESS);
    gl.LogicOp(GL_COPY);
    gl.ClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    gl.PolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    gl.PolygonOffset(0, 0);
    gl.FrontFace(GL_CCW);
    gl.CullFace(GL_BACK);
    // Rasterizers may set up triangles from the provoking vertex: it changes depth by ulps.
    gl.ProvokingVertex(GL_LAST_VERTEX_CONVENTION);
    // TRUE would clamp float readbacks (readTexture) to [0,1].
    gl.ClampColor(GL_CLAMP_READ_COLOR, GL_FIXED_ONLY);
    gl.Enable(GL_DITHER);
    ExtensionState::applyBaseline(gl);
    for (const auto& p : kPixelStore) gl.PixelStorei(p[0], static_cast<GLint>(p[1]));
    for (const auto& b : kBufferTargets) gl.BindBuffer(b[0], 0);
    gl.ActiveTexture(GL_TEXTURE0);
}

void installDebugCallback(ContextImpl& ctx) {
    auto& gl = ctx.gl;
    gl.DebugMessageCallback(forwardDebugMessage, &ctx);
    gl.Enable(GL_DEBUG_OUTPUT);
    gl.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
}

void removeDebugCallback(ContextImpl& ctx) {
    auto& gl = ctx.gl;
    gl.DebugMessageCallback(nullptr, nullptr);
    gl.Disable(GL_DEBUG_OUTPUT);
    gl.Disable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
}

void requireNoActiveTransformFeedback(ContextImpl& ctx) {
    GLboolean active = GL_FALSE, paused = GL_FALSE;
    ctx.gl.GetBooleanv(GL_TRANSFORM_FEEDBACK_ACTIVE, &active);
    ctx.gl.GetBooleanv(GL_TRANSFORM_FEEDBACK_PAUSED, &paused);
    if (active && !paused)
        throw Error(ErrorCode::InvalidState,
                    "transform feedback is active: Obscura's draws would be captured. Pause or end it "
                    "(glPauseTransformFeedback) before calling Obscura");
}

} // namespace

StateTracker::StateTracker() : global_(std::make_unique<SavedGlobalState>()) {}
StateTracker::~StateTracker() = default;

void StateTracker::enter(ContextImpl& ctx) {
    if (depth_++ > 0) return;
    try {
        requireNoActiveTransformFeedback(ctx);
    } catch (...) {
        depth_ = 0;
        throw;
    }
    preserving_ = ctx.desc.statePolicy == StatePolicy::Preserve;
    if (preserving_) saveGlobal(ctx, *global_);
    applyBaseline(ctx);
    if (ctx.desc.debugOutput) installDebugCallback(ctx);
}

void StateTracker::leave(ContextImpl& ctx) noexcept {
    if (--depth_ > 0) return;
    if (preserving_) {
        restoreUnits(ctx);
        restoreGlobal(ctx, *global_);
    } else {
        clearUnits(ctx);
        applyBaseline(ctx);
        if (ctx.desc.debugOutput) removeDebugCallback(ctx);
    }
    textureUnits_.clear();
    imageUnits_.clear();
    uniformPoints_.clear();
    storagePoints_.clear();
}

void StateTracker::saveTextureUnit(ContextImpl& ctx, GLuint unit) {
    if (textureUnits_.count(unit)) return;
    TextureUnit& u = textureUnits_[unit];
    if (!preserving_) return;
    auto& gl = ctx.gl;
    gl.ActiveTexture(GL_TEXTURE0 + unit);
    for (std::size_t i = 0; i < 11; ++i) gl.GetIntegerv(kTextureBindings[i], &u.targets[i]);
    gl.GetIntegerv(GL_SAMPLER_BINDING, &u.sampler);
    gl.ActiveTexture(GL_TEXTURE0);
}

void StateTracker::saveImageUnit(ContextImpl& ctx, GLuint unit) {
    if (imageUnits_.count(unit)) return;
    ImageUnit& u = imageUnits_[unit];
    if (!preserving_) return;
    auto& gl = ctx.gl;
    gl.GetIntegeri_v(GL_IMAGE_BINDING_NAME, unit, &u.name);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_LEVEL, unit, &u.level);
    gl.GetBooleani_v(GL_IMAGE_BINDING_LAYERED, unit, &u.layered);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_LAYER, unit, &u.layer);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_ACCESS, unit, &u.access);
    gl.GetIntegeri_v(GL_IMAGE_BINDING_FORMAT, unit, &u.format);
}

void StateTracker::saveBufferPoint(ContextImpl& ctx, GLenum target, GLuint index) {
    auto& points = target == GL_UNIFORM_BUFFER ? uniformPoints_ : storagePoints_;
    if (points.count(index)) return;
    BufferPoint& p = points[index];
    if (!preserving_) return;
    auto& gl = ctx.gl;
    const bool ubo = target == GL_UNIFORM_BUFFER;
    gl.GetInteger64i_v(ubo ? GL_UNIFORM_BUFFER_BINDING : GL_SHADER_STORAGE_BUFFER_BINDING, index, &p.buffer);
    gl.GetInteger64i_v(ubo ? GL_UNIFORM_BUFFER_START : GL_SHADER_STORAGE_BUFFER_START, index, &p.start);
    gl.GetInteger64i_v(ubo ? GL_UNIFORM_BUFFER_SIZE : GL_SHADER_STORAGE_BUFFER_SIZE, index, &p.size);
}

void StateTracker::restoreUnits(ContextImpl& ctx) noexcept {
    auto& gl = ctx.gl;
    for (const auto& [unit, u] : textureUnits_) {
        gl.ActiveTexture(GL_TEXTURE0 + unit);
        for (std::size_t i = 0; i < 11; ++i) gl.BindTexture(kTextureTargets[i], static_cast<GLuint>(u.targets[i]));
        gl.BindSampler(unit, static_cast<GLuint>(u.sampler));
    }
    for (const auto& [unit, u] : imageUnits_)
        gl.BindImageTexture(unit, static_cast<GLuint>(u.name), u.level, u.layered, u.layer,
                            static_cast<GLenum>(u.access), static_cast<GLenum>(u.format));
    const auto restorePoints = [&](GLenum target, const std::map<GLuint, BufferPoint>& points) {
        for (const auto& [index, p] : points) {
            if (p.buffer != 0 && p.size > 0)
                gl.BindBufferRange(target, index, static_cast<GLuint>(p.buffer), static_cast<GLintptr>(p.start),
                                   static_cast<GLsizeiptr>(p.size));
            else
                gl.BindBufferBase(target, index, static_cast<GLuint>(p.buffer));
        }
    };
    restorePoints(GL_UNIFORM_BUFFER, uniformPoints_);
    restorePoints(GL_SHADER_STORAGE_BUFFER, storagePoints_);
}

void StateTracker::clearUnits(ContextImpl& ctx) noexcept {
    auto& gl = ctx.gl;
    for (const auto& entry : textureUnits_) {
        gl.BindTextureUnit(entry.first, 0);
        gl.BindSampler(entry.first, 0);
    }
    for (const auto& entry : imageUnits_) gl.BindImageTexture(entry.first, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R8);
    for (const auto& entry : uniformPoints_) gl.BindBufferBase(GL_UNIFORM_BUFFER, entry.first, 0);
    for (const auto& entry : storagePoints_) gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, entry.first, 0);
}

void StateTracker::bindTexture(ContextImpl& ctx, GLuint unit, GLuint texture) {
    saveTextureUnit(ctx, unit);
    ctx.gl.BindTextureUnit(unit, texture);
}

void StateTracker::bindSampler(ContextImpl& ctx, GLuint unit, GLuint sampler) {
    saveTextureUnit(ctx, unit);
    ctx.gl.BindSampler(unit, sampler);
}

void StateTracker::bindImage(ContextImpl& ctx, GLuint unit, GLuint texture, GLint level, GLboolean layered,
                             GLint layer, GLenum access, GLenum format) {
    saveImageUnit(ctx, unit);
    ctx.gl.BindImageTexture(unit, texture, level, layered, layer, access, format);
}

void StateTracker::bindUniformBuffer(ContextImpl& ctx, GLuint index, GLuint buffer, GLintptr offset,
                                     GLsizeiptr size) {
    saveBufferPoint(ctx, GL_UNIFORM_BUFFER, index);
    if (size > 0) ctx.gl.BindBufferRange(GL_UNIFORM_BUFFER, index, buffer, offset, size);
    else ctx.gl.BindBufferBase(GL_UNIFORM_BUFFER, index, buffer);
}

void StateTracker::bindStorageBuffer(ContextImpl& ctx, GLuint index, GLuint buffer, GLintptr offset,
                                     GLsizeiptr size) {
    saveBufferPoint(ctx, GL_SHADER_STORAGE_BUFFER, index);
    if (size > 0) ctx.gl.BindBufferRange(GL_SHADER_STORAGE_BUFFER, index, buffer, offset, size);
    else ctx.gl.BindBufferBase(GL_SHADER_STORAGE_BUFFER, index, buffer);
}

StateScope::StateScope(ContextImpl& ctx) : ctx_(ctx) { ctx_.state.enter(ctx_); }
StateScope::~StateScope() { ctx_.state.leave(ctx_); }

void applyDrawState(ContextImpl& ctx, const DrawState& s) {
    auto& gl = ctx.gl;
    setEnabled(gl, GL_DEPTH_TEST, s.depthTest);
    gl.DepthMask(s.depthWrite ? GL_TRUE : GL_FALSE);
    gl.DepthFunc(s.depthFunc);
    setEnabled(gl, GL_CULL_FACE, s.cullBackFaces);
    gl.CullFace(GL_BACK);
    gl.FrontFace(GL_CCW);
    setEnabled(gl, GL_FRAMEBUFFER_SRGB, s.framebufferSrgb);
    setEnabled(gl, GL_DEPTH_CLAMP, s.depthClamp);
    gl.ClipControl(GL_LOWER_LEFT, s.clipDepth);
    setEnabled(gl, GL_BLEND, s.multiplyBlend);
    gl.BlendEquation(GL_FUNC_ADD);
    gl.BlendFunc(s.multiplyBlend ? GL_DST_COLOR : GL_ONE, GL_ZERO);
    gl.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, s.writeAlpha ? GL_TRUE : GL_FALSE);
    // Dithering may perturb 8-bit targets (albedo): results must not depend on it.
    gl.Disable(GL_DITHER);
    setEnabled(gl, GL_COLOR_LOGIC_OP, s.logicOp != GL_NONE);
    gl.LogicOp(s.logicOp != GL_NONE ? s.logicOp : GL_COPY);
}

void setViewport(ContextImpl& ctx, int x, int y, int width, int height) {
    ctx.gl.ViewportIndexedf(0, static_cast<GLfloat>(x), static_cast<GLfloat>(y), static_cast<GLfloat>(width),
                            static_cast<GLfloat>(height));
}

} // namespace obscura::detail
